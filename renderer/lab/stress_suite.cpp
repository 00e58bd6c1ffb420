#include "lab/stress_suite.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>

#include "bake/bake_job.hpp"
#include "bake/baked_texture.hpp"
#include "ibl/prefilter_lod.hpp"
#include "frame/camera.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"
#include "gl/context_info.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/equirect.hpp"
#include "ibl/reference.hpp"
#include "ibl/tonemap.hpp"
#include "frame/renderer.hpp"

namespace iblab::stress {
namespace {

using Clock = std::chrono::steady_clock;

constexpr glm::dvec3 kLuminance{0.2126, 0.7152, 0.0722};
double luminance(glm::dvec3 c) { return glm::dot(c, kLuminance); }

// The background is drawn in this colour, which no lit pixel can have, so the sphere's
// pixels are known exactly (the tessellated silhouette is not the analytic one). Exactly
// representable in the half-float frame.
constexpr float kBackgroundSentinel = -1024.0f;

// Sub-texel lobes: below this alpha (in units of the environment's texel angle) the exact
// integral's midpoint rule is meaningless, and the surface is a mirror at that resolution.
constexpr double kMirrorLobeTexels = 2.0;
// The exact references of wide lobes sum over a copy of the map at most this wide: their
// lobes span tens of degrees, many texels of it (bake_accuracy.hpp does the same).
constexpr int kReferenceWidth = 64;
constexpr int kIrradianceReferenceWidth = 32;
// Top pixels of each render that always get a reference value, so that a firefly's own
// pixel is compared, not only the regular subset.
constexpr int kTopPixels = 16;
constexpr int kSubsetStride = 3;

std::string formatValue(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

ImageRGB32F downsampleTo(ImageRGB32F image, int maxWidth)
{
    while (image.width > maxWidth && image.width % 4 == 0)
        image = downsampleEquirect2x(image);
    return image;
}

double equirectPower(const ImageRGB32F& image)
{
    double power = 0.0;
    forEachEquirectTexel(image.width, image.height, [&](int x, int y, glm::dvec3, double dOmega) {
        power += luminance(glm::dvec3(image.at(x, y))) * dOmega;
    });
    return power;
}

// ---- Pixels of the sphere ---------------------------------------------------------------

struct SpherePixel {
    int index = 0; // into the frame, bottom row first
    glm::dvec3 n{0.0};
    glm::dvec3 v{0.0};
    double NdotV = 0.0;
};

// The exact sphere under each pixel centre: the camera ray against the scene's sphere.
std::vector<SpherePixel> spherePixels(const CameraSettings& camera, glm::vec3 centre, float radius, int size)
{
    const glm::mat4 inverse = glm::inverse(cameraProjection(camera, 1.0f) * cameraView(camera));
    const glm::dvec3 eye = cameraPosition(camera);
    std::vector<SpherePixel> pixels;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::vec2 ndc((float(x) + 0.5f) / float(size) * 2.0f - 1.0f, (float(y) + 0.5f) / float(size) * 2.0f - 1.0f);
            const glm::vec4 farPoint = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::dvec3 d = glm::normalize(glm::dvec3(farPoint) / double(farPoint.w) - eye);
            const glm::dvec3 oc = eye - glm::dvec3(centre);
            const double b = glm::dot(oc, d);
            const double disc = b * b - (glm::dot(oc, oc) - double(radius) * radius);
            if (disc < 0.0) continue;
            const glm::dvec3 hit = eye + d * (-b - std::sqrt(disc));
            SpherePixel p;
            p.index = y * size + x;
            p.n = glm::normalize(hit - glm::dvec3(centre));
            p.v = -d;
            p.NdotV = glm::dot(p.n, p.v);
            pixels.push_back(p);
        }
    return pixels;
}

bool inBin(const SpherePixel& p, ViewBin bin)
{
    if (bin == ViewBin::Normal) return p.NdotV >= kNormalMinNdotV;
    if (bin == ViewBin::Grazing) return p.NdotV <= kGrazingMaxNdotV;
    return true;
}

// ---- The exact outgoing radiance of the shading model -----------------------------------

struct MaterialModel {
    glm::dvec3 F0{1.0};
    double albedo = 0.0; // Lambert, weighted by the shader's kD = 1 - F_roughness
};

MaterialModel materialModel(StressMaterial material)
{
    if (material == StressMaterial::WhiteMetal) return {glm::dvec3(1.0), 0.0};
    return {glm::dvec3(0.04), 1.0}; // specular 0.5: F0 = 0.16 * 0.5^2
}

// Exact integrals of the material the shader evaluates, at the pixels asked for, memoised
// per pixel (a render's top pixels are mostly the same pixels for every method).
class Reference {
public:
    Reference(const ImageRGB32F& full, const ImageRGB32F& reduced, const ImageRGB32F& forIrradiance, MaterialModel material,
              float roughness, bool multiscatter, GeometryTerm term, int pixelCount)
        : full_(full), reduced_(reduced), forIrradiance_(forIrradiance), material_(material), roughness_(roughness),
          multiscatter_(multiscatter), term_(term), values_(std::size_t(pixelCount), std::numeric_limits<double>::quiet_NaN())
    {
        const double texelAngle = kPi / double(full.height);
        mirror_ = double(roughness) * roughness < kMirrorLobeTexels * texelAngle;
        for (std::size_t i = 0; i < full.texelCount(); ++i)
            peak_ = std::max(peak_, luminance(glm::dvec3(full.texels[i * 3], full.texels[i * 3 + 1], full.texels[i * 3 + 2])));
    }

    // An upper bound of the exact image's maximum that holds whatever the pixels sample:
    // a mirror reflects every direction somewhere on the sphere with F <= 1, so its exact
    // image peaks at the map's brightest texel, even where that texel is smaller than a
    // pixel and no pixel centre reflects it. 0 for wide lobes (their pixels are evaluated).
    double mirrorPeak() const { return mirror_ ? peak_ : 0.0; }

    double at(const SpherePixel& p)
    {
        double& value = values_[std::size_t(p.index)];
        if (std::isnan(value)) value = luminance(compute(p));
        return value;
    }

private:
    glm::dvec3 compute(const SpherePixel& p) const
    {
        const double NdotV = std::max(p.NdotV, 1e-4);
        glm::dvec3 specular;
        double singleScatter = 1.0; // E_ss at (n.v, roughness), for the compensation
        if (mirror_) {
            // A lobe narrower than a texel sees one radiance: F(n.v) L(R), the roughness 0 limit.
            const glm::dvec3 r = glm::reflect(-p.v, p.n);
            specular = fresnelSchlick(NdotV, material_.F0) * glm::dvec3(sampleEquirectBilinear(full_, r));
        } else {
            specular = referenceSpecular(reduced_, p.n, p.v, double(roughness_), material_.F0, term_);
        }
        if (multiscatter_) {
            if (!mirror_) singleScatter = integrateSplitSumBrdf(NdotV, double(roughness_), 512, term_).z;
            specular *= specularEnergyCompensation(material_.F0, singleScatter);
        }
        glm::dvec3 diffuse(0.0);
        if (material_.albedo > 0.0) {
            const glm::dvec3 kD = glm::dvec3(1.0) - fresnelSchlickRoughness(NdotV, material_.F0, double(roughness_));
            diffuse = kD * material_.albedo / kPi * referenceIrradiance(forIrradiance_, p.n);
        }
        return specular + diffuse;
    }

    const ImageRGB32F& full_;
    const ImageRGB32F& reduced_;
    const ImageRGB32F& forIrradiance_;
    MaterialModel material_;
    float roughness_;
    bool multiscatter_;
    GeometryTerm term_;
    bool mirror_ = false;
    double peak_ = 0.0;
    std::vector<double> values_;
};

// ---- Measurements of one render ---------------------------------------------------------

RenderMeasurement measureRender(const FrameReadback& frame, const std::vector<SpherePixel>& pixels, Reference& reference,
                                double epsilon)
{
    RenderMeasurement m;
    std::vector<double> lum(std::size_t(frame.width) * std::size_t(frame.height), 0.0);
    std::vector<bool> covered(lum.size(), false);
    for (std::size_t i = 0; i < lum.size(); ++i) {
        const float* p = &frame.rgba[i * 4];
        if (p[0] == kBackgroundSentinel && p[1] == kBackgroundSentinel && p[2] == kBackgroundSentinel) continue;
        covered[i] = true;
        for (int c = 0; c < 3; ++c) {
            m.nanComponents += std::isnan(p[c]) ? 1 : 0;
            m.infComponents += std::isinf(p[c]) ? 1 : 0;
            m.negativeComponents += p[c] < 0.0f ? 1 : 0;
        }
        lum[i] = luminance(glm::dvec3(p[0], p[1], p[2]));
    }

    // The sphere's pixels that the rasteriser covered, brightest first (NaN sorts last).
    std::vector<const SpherePixel*> drawn;
    for (const SpherePixel& p : pixels)
        if (covered[std::size_t(p.index)]) drawn.push_back(&p);
    std::vector<const SpherePixel*> brightest = drawn;
    const auto brighter = [&](const SpherePixel* a, const SpherePixel* b) {
        const double la = lum[std::size_t(a->index)], lb = lum[std::size_t(b->index)];
        return std::isnan(lb) ? !std::isnan(la) : la > lb;
    };
    const std::size_t top = std::min<std::size_t>(kTopPixels, brightest.size());
    std::partial_sort(brightest.begin(), brightest.begin() + std::ptrdiff_t(top), brightest.end(), brighter);

    for (ViewBin bin : {ViewBin::All, ViewBin::Normal, ViewBin::Grazing}) {
        ViewReading r;
        r.bin = bin;
        double renderSum = 0.0, referenceSum = 0.0;
        int referenced = 0;
        for (std::size_t k = 0; k < drawn.size(); ++k) {
            const SpherePixel& p = *drawn[k];
            if (!inBin(p, bin)) continue;
            const double l = lum[std::size_t(p.index)];
            ++r.pixels;
            r.renderMax = std::isnan(l) || std::isnan(r.renderMax) ? std::numeric_limits<double>::quiet_NaN() : std::max(r.renderMax, l);
            renderSum += l;
            // Normal and grazing bins are small: every pixel gets its reference. All the
            // sphere: a regular subset plus the brightest pixels below.
            if (bin != ViewBin::All || k % kSubsetStride == 0) {
                const double ref = reference.at(p);
                r.referenceMax = std::max(r.referenceMax, ref);
                referenceSum += ref;
                ++referenced;
            }
        }
        if (bin == ViewBin::All) {
            for (std::size_t k = 0; k < top; ++k) r.referenceMax = std::max(r.referenceMax, reference.at(*brightest[k]));
            r.referenceMax = std::max(r.referenceMax, reference.mirrorPeak());
        }
        if (r.pixels > 0) {
            r.renderMean = renderSum / r.pixels;
            r.referenceMean = referenced > 0 ? referenceSum / referenced : 0.0;
        }
        // Against the exact maximum over the whole sphere: a firefly is a pixel brighter
        // than the exact image ever gets, wherever it is (a dark bin's own maximum can be ~0).
        const double sphereReferenceMax = m.views.empty() ? r.referenceMax : m.views.front().referenceMax;
        r.fireflyRatio = (r.renderMax + epsilon) / (sphereReferenceMax + epsilon);
        r.energyRatio = (r.renderMean + epsilon) / (r.referenceMean + epsilon);
        m.views.push_back(r);
    }
    return m;
}

// ---- Bake-level measurements -------------------------------------------------------------

void countInvalid(const std::vector<glm::vec4>& texels, BakeHealth& health)
{
    for (const glm::vec4& t : texels)
        for (int c = 0; c < 3; ++c) {
            health.nonFiniteTexels += std::isfinite(t[c]) ? 0 : 1;
            health.negativeTexels += t[c] < 0.0f ? 1 : 0;
        }
}

BakeHealth measureBakeHealth(const std::string& name, const bake::BakeResult& result, double equirectPowerValue)
{
    BakeHealth health;
    health.environment = name;
    for (const bake::BakedTexture* t : {&result.environmentCube, &result.prefiltered, &result.irradianceCube}) {
        if (!*t) continue;
        for (int level = 0; level < t->levels; ++level) countInvalid(bake::readCubeLevel(*t, level).texels, health);
    }
    for (const bake::BakedTexture& lut : result.brdfLut)
        if (lut) countInvalid(bake::read2D(lut).texels, health);
    for (const SH9Color* sh : {&result.sh.irradiance, &result.sh.irradianceWindowed})
        for (const glm::dvec3& c : sh->c)
            for (int k = 0; k < 3; ++k) health.nonFiniteTexels += std::isfinite(c[k]) ? 0 : 1;

    // Power of mip 0: each texel's radiance times its exact solid angle on the cube.
    const bake::CubeImage cube = bake::readCubeLevel(result.environmentCube, 0);
    double power = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < cube.size; ++row)
            for (int x = 0; x < cube.size; ++x)
                power += luminance(glm::dvec3(cube.rgb(face, x, row))) *
                         double(bake::cubeTexelSolidAngle(cube.texelDirection(face, x, row), float(cube.size)));
    health.energyKept = equirectPowerValue > 0.0 ? power / equirectPowerValue : (power > 0.0 ? 2.0 : 1.0);
    return health;
}

// The texel of `image` across the edge from (face, x, row) in direction (dx, drow): the
// direction of the virtual texel one step outside the face lands on the neighbouring face.
glm::vec3 texelAcross(const bake::CubeImage& image, int face, int x, int row, int dx, int drow)
{
    const glm::vec3 outside = cubeFaceUvToDirection(
        face, glm::vec2((float(x + dx) + 0.5f) / float(image.size), (float(row + drow) + 0.5f) / float(image.size)));
    return image.nearest(outside);
}

SeamReading measureSeams(const bake::CubeImage& image)
{
    SeamReading s;
    const int n = image.size;
    double jump = 0.0, step = 0.0, level = 0.0;
    int edgeTexels = 0;
    for (int face = 0; face < 6; ++face)
        for (int i = 0; i < n; ++i) {
            // The four edges: (x, row) on the edge, the inward step, the outward step.
            const int edges[4][6] = {{0, i, 1, 0, -1, 0}, {n - 1, i, -1, 0, 1, 0}, {i, 0, 0, 1, 0, -1}, {i, n - 1, 0, -1, 0, 1}};
            for (const auto& e : edges) {
                const double here = luminance(glm::dvec3(image.rgb(face, e[0], e[1])));
                const double inward = luminance(glm::dvec3(image.rgb(face, e[0] + e[2], e[1] + e[3])));
                const double across = luminance(glm::dvec3(texelAcross(image, face, e[0], e[1], e[4], e[5])));
                jump += std::abs(here - across);
                step += std::abs(here - inward);
                ++edgeTexels;
            }
        }
    for (const glm::vec4& t : image.texels) level += luminance(glm::dvec3(t));
    s.edgeJump = jump / edgeTexels;
    s.interiorStep = step / edgeTexels;
    s.meanLevel = level / double(image.texels.size());
    // A level with no variation anywhere has no seam (0 / 0).
    s.ratio = s.edgeJump <= 1e-6 * (s.meanLevel + 1e-12) ? 1.0 : s.edgeJump / std::max(s.interiorStep, 1e-12);
    return s;
}

// The minimum over the sphere of each channel of the SH irradiance relative to that
// channel's mean, worst channel: a negative red lobe must not hide under a bright green.
double shRelativeMinimum(const SH9Color& sh)
{
    const ShMinimum minimum = findMinimum(sh);
    const double y00 = sh9Basis(glm::dvec3(0.0, 1.0, 0.0))[0];
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double mean = sh.c[0][c] * y00;
        if (mean > 0.0) worst = std::min(worst, minimum.value[c] / mean);
        else if (minimum.value[c] < 0.0) worst = -std::numeric_limits<double>::infinity(); // negative with no light at all
    }
    return worst;
}

LutBanding measureLut(const bake::BakedTexture& lut, int samples, GeometryTerm term)
{
    LutBanding b;
    b.geometry = std::string(enumName(term));
    b.size = lut.size;
    const bake::Image2D baked = bake::read2D(lut);
    const std::vector<glm::vec3> cpu = computeBrdfLut(lut.size, std::uint32_t(samples), term);
    const auto code = [](double hdr) {
        return int(std::lround(255.0 * double(displayEncode(glm::vec3(float(hdr)), 0.0f, ToneMapOperator::AcesHill).g)));
    };
    for (int row = 0; row < lut.size; ++row)
        for (int x = 0; x < lut.size; ++x) {
            const glm::vec3 exact = cpu[std::size_t(row) * std::size_t(lut.size) + std::size_t(x)];
            const glm::vec4 gpu = baked.at(x, row);
            for (int c = 0; c < 2; ++c) {
                b.maxAbsVsCpu = std::max(b.maxAbsVsCpu, double(std::abs(gpu[c] - exact[c])));
                const float half = glm::unpackHalf1x16(glm::packHalf1x16(exact[c]));
                b.maxAbsQuantisation = std::max(b.maxAbsQuantisation, double(std::abs(half - exact[c])));
            }
            // A white metal under radiance 1 shows A + B: its 8-bit code after the default
            // tone curve, from the baked LUT and from the float one.
            const int step = std::abs(code(double(gpu.r) + gpu.g) - code(double(exact.x) + exact.y));
            b.maxDisplayStep = std::max(b.maxDisplayStep, step);
            b.texelsWithDisplayStep += step > 0 ? 1 : 0;
        }
    return b;
}

// ---- Classification ------------------------------------------------------------------------

Verdict classify(double value, double warnAbove, double failAbove)
{
    if (!(value <= failAbove)) return Verdict::Fail; // NaN fails
    return value > warnAbove ? Verdict::Warn : Verdict::Pass;
}

std::string thresholdText(double warnAbove, double failAbove, const char* what)
{
    return std::string(what) + ": pass <= " + formatValue(warnAbove) + ", warn <= " + formatValue(failAbove) + ", fail above";
}

void addFinding(std::vector<Finding>& findings, Finding f, double warnAbove, double failAbove, const char* what)
{
    f.verdict = classify(f.value, warnAbove, failAbove);
    f.threshold = thresholdText(warnAbove, failAbove, what);
    findings.push_back(std::move(f));
}

// Thresholds, with why. Fireflies: the references of wide lobes sum over a 64-wide copy of
// the map and only at a subset of pixels, which costs them up to ~25% against a sharp
// light; twice the exact maximum is a visible firefly.
constexpr double kFireflyWarn = 1.25, kFireflyFail = 2.0;
// Furnace: the README's 2% (LUT and half-float rounding), 5% before it is visibly off.
constexpr double kFurnaceWarn = 0.02, kFurnaceFail = 0.05;
// Seams: a step across an edge up to twice the step between neighbours inside a face is
// what the texel geometry alone gives (edge texels are smaller); four times is a visible seam.
constexpr double kSeamWarn = 2.0, kSeamFail = 4.0;
// SH: irradiance below 0 by more than 1e-6 of the mean is ringing; 1% of it is visible.
constexpr double kShWarn = 1e-6, kShFail = 1e-2;
// The bake's power: 1% for the cube's footprint filter, 10% lost is a visible change.
constexpr double kEnergyWarn = 0.01, kEnergyFail = 0.1;
// LUT: one 8-bit code is rounding; two is a band.
constexpr double kLutStepWarn = 1.0, kLutStepFail = 2.0;

std::string conditionText(float roughness, ViewBin bin, bool multiscatter)
{
    std::string text = "roughness " + formatValue(roughness) + ", " + std::string(viewBinName(bin));
    if (multiscatter) text += ", multiscatter";
    return text;
}

void classifyRender(const RenderMeasurement& m, const StressMethod& method, bool furnace, std::vector<Finding>& findings)
{
    const std::string where = conditionText(m.roughness, ViewBin::All, m.multiscatter);
    addFinding(findings, {"non-finite", m.environment, m.method, where, double(m.nanComponents + m.infComponents), "", Verdict::Pass}, 0.0, 0.0,
               "NaN or Inf components in the frame");
    addFinding(findings, {"negative", m.environment, m.method, where, double(m.negativeComponents), "", Verdict::Pass}, 0.0, 0.0,
               "negative components in the frame");
    for (const ViewReading& v : m.views)
        addFinding(findings, {"fireflies", m.environment, m.method, conditionText(m.roughness, v.bin, m.multiscatter), v.fireflyRatio, "", Verdict::Pass},
                   kFireflyWarn, kFireflyFail, "render max / exact max");
    if (!furnace || method.material != StressMaterial::WhiteMetal) return;
    for (const ViewReading& v : m.views) {
        if (v.bin == ViewBin::All) continue;
        // The environment's radiance is 1: the mean radiance is the reflected energy.
        const std::string condition = conditionText(m.roughness, v.bin, m.multiscatter);
        if (m.multiscatter)
            addFinding(findings, {"furnace", m.environment, m.method, condition, std::abs(v.renderMean - 1.0), "", Verdict::Pass}, kFurnaceWarn,
                       kFurnaceFail, "|reflected energy - 1| with compensation");
        else
            // Without compensation single scattering loses energy by design: a loss is a
            // warning (what compensation is for), a gain a failure.
            addFinding(findings, {"furnace", m.environment, m.method, condition, 1.0 - v.renderMean, "", Verdict::Pass}, kFurnaceWarn, 1.0,
                       "energy lost without compensation, 1 - reflected");
    }
}

// ---- The grid ----------------------------------------------------------------------------

constexpr int kGridLabelWidth = 120;
constexpr int kGridHeaderHeight = 34;

void pasteThumbnail(StressGrid& grid, const DisplayReadback& image, int cell, int left, int top)
{
    // Box filter of the (bottom-up) display image down to cell x cell.
    for (int y = 0; y < cell; ++y)
        for (int x = 0; x < cell; ++x) {
            const int x0 = x * image.width / cell, x1 = std::max(x0 + 1, (x + 1) * image.width / cell);
            const int y0 = y * image.height / cell, y1 = std::max(y0 + 1, (y + 1) * image.height / cell);
            int sum[3] = {0, 0, 0};
            for (int sy = y0; sy < y1; ++sy)
                for (int sx = x0; sx < x1; ++sx)
                    for (int c = 0; c < 3; ++c)
                        sum[c] += image.rgba[(std::size_t(image.height - 1 - sy) * std::size_t(image.width) + std::size_t(sx)) * 4 + std::size_t(c)];
            const int n = (x1 - x0) * (y1 - y0);
            std::uint8_t* out = &grid.rgba[(std::size_t(top + y) * std::size_t(grid.width) + std::size_t(left + x)) * 4];
            for (int c = 0; c < 3; ++c) out[c] = std::uint8_t(sum[c] / n);
            out[3] = 255;
        }
}

} // namespace

std::string_view verdictName(Verdict verdict)
{
    switch (verdict) {
    case Verdict::Pass: return "pass";
    case Verdict::Warn: return "warn";
    case Verdict::Fail: return "fail";
    }
    return "?";
}

std::string_view viewBinName(ViewBin bin)
{
    switch (bin) {
    case ViewBin::All: return "all";
    case ViewBin::Normal: return "normal";
    case ViewBin::Grazing: return "grazing";
    }
    return "?";
}

const ViewReading& RenderMeasurement::view(ViewBin bin) const
{
    for (const ViewReading& v : views)
        if (v.bin == bin) return v;
    throw std::logic_error("RenderMeasurement::view: no reading for " + std::string(viewBinName(bin)));
}

int StressReport::count(Verdict verdict) const
{
    return int(std::count_if(findings.begin(), findings.end(), [verdict](const Finding& f) { return f.verdict == verdict; }));
}

StressOptions defaultStressOptions(bool quick)
{
    StressOptions o;
    o.quick = quick;
    o.bake = bake::defaultPreset();
    o.bake.preset = quick ? "stress-quick" : "stress";
    // The default's moment cube is what shading reads (until this change an importance cube
    // was baked beside it and never read).
    o.bake.irradiance = bake::IrradianceMethod::Moments;
    if (quick) {
        o.environmentWidth = 64;
        o.frameSize = 32;
        o.gridCell = 32;
        o.bake.prefilter = {.faceSize = 16, .levels = 5, .samples = 32, .sampleGrowth = 2.0f, .mipFiltering = true, .mipBias = 0.0f};
        // The LUT clamps roughness 1 to its last texel centre, 1 - 0.5 / size: at 32 that alone
        // moves the rough furnace by 5%, at 128 by about 1%. 128^2 x 256 costs ~0.1 s.
        o.bake.lut = {.size = 128, .samples = 256, .schlickGgx = false, .heightCorrelatedSmith = true};
    } else {
        o.bake.prefilter = {.faceSize = 64, .levels = 5, .samples = 64, .sampleGrowth = 2.0f, .mipFiltering = true, .mipBias = 0.0f};
        o.bake.lut = {.size = 128, .samples = 1024, .schlickGgx = false, .heightCorrelatedSmith = true};
    }
    return o;
}

double sunIntensityForPeakToMean(double peakToMean, double sizeDegrees, double sky)
{
    // peak = sky + I, mean = sky + I Omega / (4 pi)  =>  I = sky (R - 1) / (1 - R Omega / (4 pi)).
    const double omega = 2.0 * kPi * (1.0 - std::cos(0.5 * sizeDegrees * kPi / 180.0));
    const double share = peakToMean * omega / (4.0 * kPi);
    if (share >= 1.0)
        throw Error("builtin:sun", "a disc of " + formatValue(sizeDegrees) + " degrees cannot reach peak / mean " + formatValue(peakToMean) +
                                       " (at most " + formatValue(4.0 * kPi / omega) + ")");
    return sky * (peakToMean - 1.0) / (1.0 - share);
}

std::vector<StressEnvironment> stressEnvironments(int width)
{
    const std::string w = "width=" + std::to_string(width);
    std::vector<StressEnvironment> list;
    // A 0.2 degree sun (a 0.53 degree one cannot exceed 1.9e5) on a sky of 1, placed where
    // the sphere reflects it near normal incidence.
    for (int decade = 2; decade <= 6; ++decade) {
        const double ratio = std::pow(10.0, decade);
        list.push_back({"sun-1e" + std::to_string(decade),
                        "builtin:sun?" + w + "&elevation=30&azimuth=160&size=0.2&sky=1&intensity=" +
                            formatValue(sunIntensityForPeakToMean(ratio, 0.2, 1.0)),
                        "dynamic range: a sub-texel sun with peak / mean 1e" + std::to_string(decade)});
    }
    list.push_back({"texel", "builtin:texel?" + w + "&intensity=1e4", "one lit texel next to a cube edge: fireflies, seams"});
    list.push_back({"slits", "builtin:slits?" + w, "48 slits narrower than a texel: aliasing, moire"});
    list.push_back({"white", "builtin:white?" + w, "the white furnace: energy conservation"});
    list.push_back({"studio", "builtin:studio?" + w, "saturated coloured lights: per-channel ringing and clipping"});
    list.push_back({"black", "builtin:black?" + w, "no light: any output is an error"});
    list.push_back({"nan", "builtin:nan?" + w, "NaN, Inf and negative texels: the repair, and NaN anywhere after it"});
    return list;
}

std::vector<StressMethod> stressMethods()
{
    std::vector<StressMethod> methods;
    SamplingSettings splitSum;
    splitSum.method = ShadingMethod::SplitSum;
    methods.push_back({"splitsum", splitSum, true, StressMaterial::WhiteMetal});
    methods.push_back({"splitsum-sh9", splitSum, false, StressMaterial::WhitePlastic});
    methods.push_back({"splitsum-sh9-windowed", splitSum, true, StressMaterial::WhitePlastic});
    SamplingSettings cube = splitSum;
    cube.diffuse = DiffuseSource::IrradianceCube;
    methods.push_back({"splitsum-irradiance-cube", cube, true, StressMaterial::WhitePlastic});
    for (bool pdf : {true, false})
        for (int n : {1, 16, 256}) {
            SamplingSettings sampled;
            sampled.method = ShadingMethod::Sampled;
            sampled.samples = n;
            sampled.pdfMipFiltering = pdf;
            methods.push_back({"sampled-n" + std::to_string(n) + (pdf ? "" : "-nopdf"), sampled, true, StressMaterial::WhiteMetal});
        }
    return methods;
}

StressReport runStressSuite(Renderer& renderer, const StressOptions& options)
{
    const auto start = Clock::now();
    StressReport report;
    report.options = options;
    report.renderer = gl::describeCurrentContext();
    const std::vector<StressEnvironment> environments = stressEnvironments(options.environmentWidth);
    const std::vector<StressMethod> methods = stressMethods();
    for (const StressMethod& m : methods) report.methods.push_back(m.name);

    const int size = options.frameSize;
    const int cell = options.gridCell;
    const int columns = int(methods.size() * options.roughnesses.size());
    StressGrid& grid = report.grid;
    grid.width = kGridLabelWidth + columns * cell;
    grid.height = kGridHeaderHeight + int(environments.size()) * cell;
    grid.rgba.assign(std::size_t(grid.width) * std::size_t(grid.height) * 4, 0);
    for (std::size_t i = 3; i < grid.rgba.size(); i += 4) grid.rgba[i] = 255;
    for (std::size_t m = 0; m < methods.size(); ++m) {
        const int left = kGridLabelWidth + int(m * options.roughnesses.size()) * cell;
        grid.labels.push_back({left + 2, 2, methods[m].name});
        for (std::size_t r = 0; r < options.roughnesses.size(); ++r)
            grid.labels.push_back({left + int(r) * cell + 2, 18, "r " + formatValue(options.roughnesses[r])});
    }

    FrameSettings base;
    base.scene.kind = SceneKind::Sphere;
    base.view.mode = ViewMode::Final;
    base.view.background = BackgroundMode::SolidColour;
    base.view.solidColour = glm::vec3(kBackgroundSentinel);
    // Pixels are compared with the CPU reference at their centres and the background is
    // found by its sentinel value: both need one sample per pixel, not an MSAA resolve that
    // mixes the sentinel into silhouette pixels.
    base.view.msaaSamples = 1;
    base.material.baseColor = glm::vec3(1.0f);
    base.material.specular = 0.5f;
    base.toneMap.op = ToneMapOperator::AcesHill;
    const SceneInfo scene = renderer.sceneInfo(base);
    frameBox(base.camera, scene.centre, scene.halfExtents, 1.0f);
    const std::vector<SpherePixel> pixels = spherePixels(base.camera, scene.centre, scene.halfExtents.x, size);

    // The LUT depends on no environment: baked with the first one, handed on to the next.
    std::array<bake::BakedTexture, 2> lut;
    for (std::size_t e = 0; e < environments.size(); ++e) {
        const StressEnvironment& env = environments[e];
        if (options.progress) options.progress(env.name + " (" + std::to_string(e + 1) + "/" + std::to_string(environments.size()) + ")");
        const Environment loaded = loadEnvironment(env.spec);
        EnvironmentSummary summary{env.name, loaded.source, env.breaks};
        const double power = equirectPower(loaded.image);
        summary.meanLuminance = power / (4.0 * kPi);
        for (std::size_t i = 0; i < loaded.image.texelCount(); ++i)
            summary.peakLuminance = std::max(summary.peakLuminance, luminance(glm::dvec3(loaded.image.at(int(i % std::size_t(loaded.image.width)),
                                                                                                          int(i / std::size_t(loaded.image.width))))));
        summary.repair = loaded.repair.summary();
        summary.repairedComponents = loaded.repair.repairedComponents();

        bake::BakeSettings bakeSettings = options.bake;
        if (lut[std::size_t(GeometryTerm::HeightCorrelatedSmith)]) bakeSettings.lut.schlickGgx = bakeSettings.lut.heightCorrelatedSmith = false;
        auto result = std::make_shared<bake::BakeResult>(bake::BakeJob(renderer.shaders(), loaded, bakeSettings).runToCompletion());
        summary.bakeMilliseconds = result->totalMilliseconds;
        if (lut[std::size_t(GeometryTerm::HeightCorrelatedSmith)]) result->brdfLut = std::move(lut);
        renderer.setEnvironment(loaded.image);
        renderer.setBake(result);

        if (e == 0)
            report.lut = measureLut(result->lut(GeometryTerm::HeightCorrelatedSmith), options.bake.lut.samples, GeometryTerm::HeightCorrelatedSmith);
        BakeHealth health = measureBakeHealth(env.name, *result, power);
        addFinding(report.findings, {"bake", env.name, "", "cubes, LUT and SH", double(health.nonFiniteTexels + health.negativeTexels), "", Verdict::Pass},
                   0.0, 0.0, "NaN, Inf or negative components in the bake");
        addFinding(report.findings, {"bake", env.name, "", "power kept by the environment cube", std::abs(1.0 - health.energyKept), "", Verdict::Pass},
                   kEnergyWarn, kEnergyFail, "|1 - cube power / map power|");
        report.bakes.push_back(health);

        ShRinging ringing{env.name, luminance(result->sh.irradiance.c[0]) * sh9Basis(glm::dvec3(0, 1, 0))[0],
                          shRelativeMinimum(result->sh.irradiance), shRelativeMinimum(result->sh.irradianceWindowed), result->sh.windowWidth};
        addFinding(report.findings, {"sh-ringing", env.name, "splitsum-sh9", "plain SH9, minimum over the sphere", -ringing.plainMinimum, "", Verdict::Pass},
                   kShWarn, kShFail, "-(minimum / mean irradiance), worst channel");
        addFinding(report.findings, {"sh-ringing", env.name, "splitsum-sh9-windowed", "windowed SH9, minimum over the sphere", -ringing.windowedMinimum, "",
                                     Verdict::Pass},
                   kShWarn, kShFail, "-(minimum / mean irradiance), worst channel");
        report.sh.push_back(ringing);

        for (int level = 0; level < result->prefiltered.levels; ++level) {
            if (result->prefiltered.levelSize(level) < 4) continue; // no interior to compare with
            SeamReading seam = measureSeams(bake::readCubeLevel(result->prefiltered, level));
            seam.environment = env.name;
            seam.texture = "prefiltered";
            seam.level = level;
            seam.roughness = bake::prefilterMipRoughness(result->settings.prefilter, level);
            addFinding(report.findings, {"seams", env.name, "splitsum", "prefiltered mip " + std::to_string(level), seam.ratio, "", Verdict::Pass},
                       kSeamWarn, kSeamFail, "jump across cube edges / step inside faces");
            report.seams.push_back(seam);
        }
        if (result->irradianceCube) {
            SeamReading seam = measureSeams(bake::readCubeLevel(result->irradianceCube, 0));
            seam.environment = env.name;
            seam.texture = "irradiance";
            addFinding(report.findings, {"seams", env.name, "splitsum-irradiance-cube", "irradiance cube", seam.ratio, "", Verdict::Pass}, kSeamWarn,
                       kSeamFail, "jump across cube edges / step inside faces");
            report.seams.push_back(seam);
        }

        // References at sub-texel lobes read the full map, wide lobes a small copy.
        const ImageRGB32F reduced = downsampleTo(loaded.image, kReferenceWidth);
        const ImageRGB32F forIrradiance = downsampleTo(loaded.image, kIrradianceReferenceWidth);
        const double epsilon = 1e-4 * summary.meanLuminance + 1e-6;
        const bool furnace = env.name == "white";
        // Exposure that puts the environment's mean near mid-grey in the thumbnails.
        const float exposure = summary.meanLuminance > 0.0 ? float(std::clamp(std::log2(0.4 / summary.meanLuminance), -12.0, 12.0)) : 0.0f;
        for (std::size_t r = 0; r < options.roughnesses.size(); ++r) {
            const float roughness = options.roughnesses[r];
            for (bool multiscatter : furnace ? std::vector<bool>{false, true} : std::vector<bool>{false}) {
                std::optional<Reference> references[2];
                for (std::size_t m = 0; m < methods.size(); ++m) {
                    const StressMethod& method = methods[m];
                    std::optional<Reference>& reference = references[int(method.material)];
                    if (!reference)
                        reference.emplace(loaded.image, reduced, forIrradiance, materialModel(method.material), roughness, multiscatter,
                                          base.sampling.geometry, size * size);
                    FrameSettings settings = base;
                    settings.sampling = method.sampling;
                    settings.sampling.multiscatter = multiscatter;
                    settings.material.metallic = method.material == StressMaterial::WhiteMetal ? 1.0f : 0.0f;
                    settings.material.roughness = roughness;
                    settings.toneMap.exposureEv = exposure;
                    // Plain SH9 is the same bake with the window off: windowed = applyWindow(E, None) = E.
                    const SH9Color windowed = result->sh.irradianceWindowed;
                    if (!method.windowedSh) result->sh.irradianceWindowed = result->sh.irradiance;
                    renderer.renderFrame(settings, size, size);
                    result->sh.irradianceWindowed = windowed;

                    RenderMeasurement measured = measureRender(renderer.readHdrFrame(), pixels, *reference, epsilon);
                    measured.environment = env.name;
                    measured.method = method.name;
                    measured.roughness = roughness;
                    measured.multiscatter = multiscatter;
                    classifyRender(measured, method, furnace, report.findings);
                    report.renders.push_back(std::move(measured));
                    if (!multiscatter)
                        pasteThumbnail(grid, renderer.readDisplayImage(), cell, kGridLabelWidth + int(m * options.roughnesses.size() + r) * cell,
                                       kGridHeaderHeight + int(e) * cell);
                }
            }
        }
        grid.labels.push_back({4, kGridHeaderHeight + int(e) * cell + cell / 2 - 6, env.name});
        report.environments.push_back(summary);
        lut = std::move(result->brdfLut);
        renderer.setBake(nullptr);
    }
    addFinding(report.findings, {"lut", "", "splitsum", "RGBA16F LUT vs float CPU LUT, 8-bit display codes", double(report.lut.maxDisplayStep), "", Verdict::Pass},
               kLutStepWarn, kLutStepFail, "largest step in 8-bit codes after ACES (Hill)");
    report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return report;
}

} // namespace iblab::stress
