#pragma once
// What the stress suite measures (runStressSuite, stress_suite.hpp, puts it together): a
// render of the sphere against the exact integrals of the shading model at its pixels, and
// the health of a bake (invalid texels, power, seams across cube faces, SH ringing, the LUT's
// precision). Internal to the lab layer; needs a current GL context for the bake's textures.
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bake/bake_result.hpp"
#include "frame/renderer.hpp"
#include "ibl/brdf.hpp"
#include "ibl/image.hpp"
#include "ibl/luminance.hpp"
#include "ibl/sh.hpp"
#include "lab/stress_suite.hpp"

namespace iblab::stress {

using iblab::luminance;

// The background is drawn in this colour, which no lit pixel can have, so the sphere's
// pixels are known exactly (the tessellated silhouette is not the analytic one). Exactly
// representable in the half-float frame.
inline constexpr float kBackgroundSentinel = -1024.0f;

// The power of an equirect map: luminance times each texel's solid angle.
double equirectPower(const ImageRGB32F& image);

// ---- A render of the sphere -----------------------------------------------------------------

struct SpherePixel {
    int index = 0; // into the frame, bottom row first
    glm::dvec3 n{0.0};
    glm::dvec3 v{0.0};
    double NdotV = 0.0;
};

// The exact sphere under each pixel centre of a size x size frame: the camera ray against the
// scene's sphere.
std::vector<SpherePixel> spherePixels(const CameraSettings& camera, glm::vec3 centre, float radius, int size);

// The environment as the exact references read it: the full map for lobes too narrow for a
// copy, small copies for wide lobes and for the irradiance. Keeps a reference to `full`.
struct ReferenceMaps {
    explicit ReferenceMaps(const ImageRGB32F& full);
    const ImageRGB32F& full;
    ImageRGB32F reduced;       // for wide specular lobes
    ImageRGB32F forIrradiance; // for the diffuse layer's irradiance
    double peak = 0.0;         // the brightest texel's luminance
};

// The exact outgoing radiance (luminance) of one material under the environment at the
// sphere's pixels, as the shading model defines it (ibl/brdf.hpp's combineLobes over
// ibl/reference.hpp's integrals), memoised per pixel: a render's top pixels are mostly the
// same pixels for every method.
class ExactSphere {
public:
    ExactSphere(const ReferenceMaps& maps, const SurfaceMaterial& material, bool multiscatter, GeometryTerm term, int pixelCount);

    // An upper bound of the exact image's maximum that holds whatever the pixels sample:
    // a mirror reflects every direction somewhere on the sphere with F <= 1, so its exact
    // image peaks at the map's brightest texel, even where that texel is smaller than a
    // pixel and no pixel centre reflects it. 0 for wide lobes (their pixels are evaluated).
    double mirrorPeak() const { return mirror_ ? maps_.peak : 0.0; }
    double at(const SpherePixel& p);

private:
    glm::dvec3 compute(const SpherePixel& p) const;

    const ReferenceMaps& maps_;
    SurfaceMaterial material_;
    bool multiscatter_;
    GeometryTerm term_;
    bool mirror_ = false;
    std::vector<double> values_;
};

// NaN, Inf and negative components over the frame's lit pixels, and per view bin the render's
// and the exact image's maximum and mean luminance.
RenderMeasurement measureRender(const FrameReadback& frame, const std::vector<SpherePixel>& pixels, ExactSphere& reference, double epsilon);

// ---- The bake -------------------------------------------------------------------------------

// Invalid components over every texture and SH set of the bake, and the power its
// environment cube keeps of the map's (equirectPowerValue).
BakeHealth measureBakeHealth(const std::string& name, const bake::BakeResult& result, double equirectPowerValue);
// The mean jump across the cube's edges against the mean step inside its faces.
SeamReading measureSeams(const bake::CubeImage& image);
// The minimum over the sphere of each channel of the SH irradiance relative to that
// channel's mean, worst channel: a negative red lobe must not hide under a bright green.
double shRelativeMinimum(const SH9Color& sh);
// The baked RGBA16F LUT against the float CPU LUT of the same samples.
LutBanding measureLut(const bake::BakedTexture& lut, int samples, GeometryTerm term);

} // namespace iblab::stress
