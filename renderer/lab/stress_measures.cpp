#include "lab/stress_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>

#include "bake/baked_texture.hpp"
#include "frame/camera.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/equirect.hpp"
#include "ibl/prefilter_lod.hpp"
#include "ibl/reference.hpp"
#include "ibl/tonemap.hpp"

namespace iblab::stress {
namespace {

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

bool inBin(const SpherePixel& p, ViewBin bin)
{
    if (bin == ViewBin::Normal) return p.NdotV >= kNormalMinNdotV;
    if (bin == ViewBin::Grazing) return p.NdotV <= kGrazingMaxNdotV;
    return true;
}

void countInvalid(const std::vector<glm::vec4>& texels, BakeHealth& health)
{
    for (const glm::vec4& t : texels)
        for (int c = 0; c < 3; ++c) {
            health.nonFiniteTexels += std::isfinite(t[c]) ? 0 : 1;
            health.negativeTexels += t[c] < 0.0f ? 1 : 0;
        }
}

// The texel of `image` across the edge from (face, x, row) in direction (dx, drow): the
// direction of the virtual texel one step outside the face lands on the neighbouring face.
glm::vec3 texelAcross(const bake::CubeImage& image, int face, int x, int row, int dx, int drow)
{
    const glm::vec3 outside = cubeFaceUvToDirection(
        face, glm::vec2((float(x + dx) + 0.5f) / float(image.size), (float(row + drow) + 0.5f) / float(image.size)));
    return image.nearest(outside);
}

} // namespace

double equirectPower(const ImageRGB32F& image)
{
    double power = 0.0;
    forEachEquirectTexel(image.width, image.height, [&](int x, int y, glm::dvec3, double dOmega) {
        power += luminance(glm::dvec3(image.at(x, y))) * dOmega;
    });
    return power;
}

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

ReferenceMaps::ReferenceMaps(const ImageRGB32F& map)
    : full(map), reduced(downsampleEquirectToWidth(map, kReferenceWidth)), forIrradiance(downsampleEquirectToWidth(map, kIrradianceReferenceWidth))
{
    for (std::size_t i = 0; i < full.texelCount(); ++i)
        peak = std::max(peak, luminance(glm::dvec3(full.texels[i * 3], full.texels[i * 3 + 1], full.texels[i * 3 + 2])));
}

ExactSphere::ExactSphere(const ReferenceMaps& maps, const SurfaceMaterial& material, bool multiscatter, GeometryTerm term, int pixelCount)
    : maps_(maps), material_(material), multiscatter_(multiscatter), term_(term), values_(std::size_t(pixelCount), std::numeric_limits<double>::quiet_NaN())
{
    const double texelAngle = kPi / double(maps.full.height);
    mirror_ = material.roughness * material.roughness < kMirrorLobeTexels * texelAngle;
}

double ExactSphere::at(const SpherePixel& p)
{
    double& value = values_[std::size_t(p.index)];
    if (std::isnan(value)) value = luminance(compute(p));
    return value;
}

glm::dvec3 ExactSphere::compute(const SpherePixel& p) const
{
    const double NdotV = std::max(p.NdotV, 1e-4);
    const double roughness = material_.roughness;
    glm::dvec3 specular;
    double singleScatter = 1.0; // E_ss at (n.v, roughness), for the compensation
    if (mirror_) {
        // A lobe narrower than a texel sees one radiance: F(n.v) L(R), the roughness 0 limit.
        const glm::dvec3 r = glm::reflect(-p.v, p.n);
        specular = fresnelSchlick(NdotV, material_.F0) * glm::dvec3(sampleEquirectBilinear(maps_.full, r));
    } else {
        specular = referenceSpecular(maps_.reduced, p.n, p.v, roughness, material_.F0, term_);
    }
    if (multiscatter_) {
        if (!mirror_) singleScatter = integrateSplitSumBrdf(NdotV, roughness, 512, term_).z;
        specular *= specularEnergyCompensation(material_.F0, singleScatter);
    }
    // A metal has no diffuse layer: its irradiance, a sum over the map per pixel, is not needed.
    const glm::dvec3 irradiance = material_.metallic < 1.0 ? referenceIrradiance(maps_.forIrradiance, p.n) : glm::dvec3(0.0);
    return combineLobes(material_, NdotV, irradiance, specular);
}

RenderMeasurement measureRender(const FrameReadback& frame, const std::vector<SpherePixel>& pixels, ExactSphere& reference, double epsilon)
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
                         double(cubeTexelSolidAngle(cube.texelDirection(face, x, row), float(cube.size)));
    health.energyKept = equirectPowerValue > 0.0 ? power / equirectPowerValue : (power > 0.0 ? 2.0 : 1.0);
    return health;
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

} // namespace iblab::stress
