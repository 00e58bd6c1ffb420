// How far a rendered pixel is from the reference, and the false colour that shows it. ONE
// definition, compiled both as GLSL (the error view) and as C++ (renderer/ibl/error_metrics.hpp:
// the numbers, and the colour bar the UI draws). Same rules as conventions.glsl: the common
// subset of GLSL and C++/glm, float literals with an f suffix, functions marked IBL_FN.

// Below this the reference is black and any relative error is noise over nothing; the
// floor keeps the ratio finite without hiding errors on dim but lit pixels (the dimmest
// lit pixels of the bundled maps sum to well above 1e-3).
const float IBL_ERROR_FLOOR = 1e-4f;

// Relative error of a pixel: the L1 colour difference over the reference's channel sum,
// so that a hue shift counts as much as a change of brightness and a saturated colour (a
// channel near 0) does not blow the ratio up.
IBL_FN float relativeError(vec3 value, vec3 reference)
{
    vec3 d = abs(value - reference);
    float referenceSum = reference.x + reference.y + reference.z;
    return (d.x + d.y + d.z) / max(referenceSum, IBL_ERROR_FLOOR);
}

// Whether the error measures a pixel: the reference's G-buffer covers its centre, and the
// frame's surfaces cover all of its MSAA samples (the frame's alpha is the covered
// fraction). A partially covered edge pixel averages surface and sky samples, which the
// single-sampled reference never does: measured, it would be an error of coverage, not of
// shading. Covered is exactly 1: the resolve averages samples of 1 exactly.
IBL_FN bool isMeasuredPixel(float frameCoverage, float referenceCoverage)
{
    return frameCoverage == 1.0f && referenceCoverage != 0.0f;
}

// A firefly: a pixel more than three times as bright as it should be (channel sums), the
// signature of a low-probability sample that hit a bright texel.
IBL_FN bool isFirefly(vec3 value, vec3 reference)
{
    return value.x + value.y + value.z > 3.0f * (reference.x + reference.y + reference.z);
}

// Turbo (Mikhailov 2019, Google), his degree-5 polynomial fit per channel: perceptually
// ordered like viridis but with more distinct steps, near black (0) through blue, green
// and yellow to dark red (1).
// Returns display (sRGB-encoded) values; t is clamped to [0, 1].
IBL_FN vec3 falseColour(float t)
{
    float x = clamp(t, 0.0f, 1.0f);
    const vec3 c0 = vec3(0.13572138f, 0.09140261f, 0.10667330f);
    const vec3 c1 = vec3(4.61539260f, 2.19418839f, 12.64194608f);
    const vec3 c2 = vec3(-42.66032258f, 4.84296658f, -60.58204836f);
    const vec3 c3 = vec3(132.13108234f, -14.18503333f, 110.36276771f);
    const vec3 c4 = vec3(-152.94239396f, 4.27729857f, -89.90310912f);
    const vec3 c5 = vec3(59.28637943f, 2.82956604f, 27.34824973f);
    return clamp(c0 + x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5)))), 0.0f, 1.0f);
}
