// Rec. 709 luminance, the weights of renderer/ibl/luminance.hpp's kLuminanceWeights in GLSL:
// the bake's bright-texel clamp, the irradiance moments' spread and the error view's grey
// background weigh colour as the C++ does. bake_shared_glsl_gltest's
// LuminanceAgreesWithCore holds the two copies equal.
const vec3 kLuminanceWeights = vec3(0.2126, 0.7152, 0.0722);

float rec709Luminance(vec3 rgb)
{
    return dot(rgb, kLuminanceWeights);
}
