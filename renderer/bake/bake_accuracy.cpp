#include "bake/bake_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <set>
#include <span>
#include <tuple>
#include <thread>

#include <glm/geometric.hpp>

#include "bake/bake_passes.hpp"
#include "bake/residual_irradiance.hpp"
#include "ibl/prefilter_lod.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/conventions.hpp"
#include "ibl/reference.hpp"
#include "io/atomic_file.hpp"
#include "io/hash.hpp"

namespace iblab::bake {
namespace {

ErrorStats relativeErrors(const std::vector<glm::dvec3>& baked, std::span<const glm::dvec3> reference)
{
    ErrorStats stats;
    for (std::size_t i = 0; i < baked.size(); ++i) {
        const double ref = glm::length(reference[i]);
        const double e = ref > 0.0 ? glm::length(baked[i] - reference[i]) / ref : glm::length(baked[i]);
        stats.mean += e;
        stats.max = std::max(stats.max, e);
    }
    stats.directions = int(baked.size());
    if (!baked.empty())
        stats.mean /= double(baked.size());
    return stats;
}

// sqrt(sum |baked - ref|^2 / sum |ref|^2) over directions and channels.
double relativeRmse(const std::vector<glm::dvec3>& baked, std::span<const glm::dvec3> reference)
{
    double sumErr2 = 0.0;
    double sumRef2 = 0.0;
    for (std::size_t i = 0; i < baked.size(); ++i) {
        const glm::dvec3 d = baked[i] - reference[i];
        sumErr2 += glm::dot(d, d);
        sumRef2 += glm::dot(reference[i], reference[i]);
    }
    return sumRef2 > 0.0 ? std::sqrt(sumErr2 / sumRef2) : std::sqrt(sumErr2);
}

// The width downsampleEquirectToWidth would give, without summing anything (for a report
// whose references come from the cache).
int reducedWidth(int width, int height, int maxWidth)
{
    while (width > maxWidth && width % 2 == 0 && height % 2 == 0) {
        width /= 2;
        height /= 2;
    }
    return width;
}

// Every exact value a bake's errors compare against, in one list: the measurement first
// asks for them (each request returns the first of its slots), then they are computed in
// batches, or read from the cache, since they depend only on the map and the list itself.
class ReferenceList {
public:
    std::size_t prefilter(const std::vector<glm::dvec3>& directions, double roughness, bool wide)
    {
        const std::size_t first = requests_.size();
        for (const glm::dvec3& d : directions) requests_.push_back({wide ? Kind::WidePrefilter : Kind::SharpPrefilter, d, roughness, {}});
        if (!wide && roughness > 0.0 && !directions.empty())
            smallestSharpRoughness_ = std::min(smallestSharpRoughness_, roughness);
        return first;
    }
    std::size_t irradiance(const std::vector<glm::dvec3>& normals)
    {
        const std::size_t first = requests_.size();
        for (const glm::dvec3& n : normals) requests_.push_back({Kind::Irradiance, n, 0.0, {}});
        return first;
    }
    std::size_t lut(double NdotV, double roughness, GeometryTerm term)
    {
        requests_.push_back({Kind::Lut, glm::dvec3(NdotV, roughness, 0.0), 0.0, term});
        return requests_.size() - 1;
    }

    // The requests' bytes, for the cache key.
    std::string digest() const
    {
        std::string bytes;
        for (const Request& r : requests_) {
            const double fields[] = {double(r.kind), r.direction.x, r.direction.y, r.direction.z, r.roughness, double(r.term)};
            bytes.append(reinterpret_cast<const char*>(fields), sizeof fields);
        }
        return bytes;
    }
    std::size_t size() const { return requests_.size(); }
    // The narrowest lobe summed over the full map: the resolution that map must have.
    double smallestSharpRoughness() const { return smallestSharpRoughness_; }

    std::vector<glm::dvec3> evaluate(const ImageRGB32F& sharp, const ImageRGB32F& reduced, std::uint32_t lutSamples) const
    {
        std::vector<glm::dvec3> values(requests_.size());
        auto batch = [&](Kind kind, const ImageRGB32F& map) {
            std::vector<std::size_t> slots;
            std::vector<ZonalReference::PrefilterQuery> queries;
            std::vector<glm::dvec3> normals;
            for (std::size_t i = 0; i < requests_.size(); ++i)
                if (requests_[i].kind == kind) {
                    slots.push_back(i);
                    queries.push_back({requests_[i].direction, requests_[i].roughness});
                    normals.push_back(requests_[i].direction);
                }
            if (slots.empty())
                return;
            const ZonalReference sums(map);
            const std::vector<glm::dvec3> results = kind == Kind::Irradiance ? sums.irradiance(normals) : sums.prefilteredRadiance(queries);
            for (std::size_t k = 0; k < slots.size(); ++k) values[slots[k]] = results[k];
        };
        batch(Kind::SharpPrefilter, sharp);
        batch(Kind::WidePrefilter, reduced);
        batch(Kind::Irradiance, reduced);
        // The LUT's points are independent integrals: spread over threads.
        std::vector<std::size_t> lutSlots;
        for (std::size_t i = 0; i < requests_.size(); ++i)
            if (requests_[i].kind == Kind::Lut) lutSlots.push_back(i);
        const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(std::max<std::size_t>(lutSlots.size(), 1)));
        std::vector<std::thread> pool;
        for (unsigned t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
                for (std::size_t k = t; k < lutSlots.size(); k += threads) {
                    const Request& r = requests_[lutSlots[k]];
                    values[lutSlots[k]] = integrateSplitSumBrdf(r.direction.x, r.direction.y, lutSamples, r.term);
                }
            });
        for (std::thread& t : pool) t.join();
        return values;
    }

private:
    enum class Kind { SharpPrefilter, WidePrefilter, Irradiance, Lut };
    struct Request {
        Kind kind;
        glm::dvec3 direction; // for Lut: (n.v, roughness, 0)
        double roughness;
        GeometryTerm term;
    };
    std::vector<Request> requests_;
    double smallestSharpRoughness_ = 1.0;
};

// <dir>/<key>.bin: "iblabref", the value count (uint64), then the values as 3 doubles each,
// native byte order (a cache is per machine). Anything else is a miss, noted.
constexpr std::string_view kReferenceMagic = "iblabref";

std::optional<std::vector<glm::dvec3>> loadReferenceValues(const std::filesystem::path& path, std::size_t count,
                                                           std::vector<std::string>& notes)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        return std::nullopt;
    std::string bytes;
    try {
        bytes = readTextFile(path.string());
    } catch (const std::exception& e) {
        notes.push_back(e.what());
        return std::nullopt;
    }
    const std::size_t expected = kReferenceMagic.size() + sizeof(std::uint64_t) + count * sizeof(glm::dvec3);
    std::uint64_t stored = 0;
    if (bytes.size() == expected)
        std::memcpy(&stored, bytes.data() + kReferenceMagic.size(), sizeof stored);
    if (bytes.size() != expected || bytes.compare(0, kReferenceMagic.size(), kReferenceMagic) != 0 || stored != count) {
        notes.push_back(path.string() + ": not a reference cache entry of " + std::to_string(count) +
                        " values (corrupt or truncated); computed again");
        std::filesystem::remove(path, ec);
        return std::nullopt;
    }
    std::vector<glm::dvec3> values(count);
    std::memcpy(values.data(), bytes.data() + kReferenceMagic.size() + sizeof stored, count * sizeof(glm::dvec3));
    return values;
}

void storeReferenceValues(const std::filesystem::path& path, const std::vector<glm::dvec3>& values, std::vector<std::string>& notes)
{
    std::string bytes(kReferenceMagic);
    const std::uint64_t count = values.size();
    bytes.append(reinterpret_cast<const char*>(&count), sizeof count);
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(glm::dvec3));
    try {
        std::filesystem::create_directories(path.parent_path());
        writeTextFileAtomic(path.string(), bytes, Durability::NoFlush);
    } catch (const std::exception& e) {
        notes.push_back(std::string("reference cache not written: ") + e.what());
    }
}

} // namespace

namespace {

// The texels of a size^2 cube level that bilinear, seamless lookups at these directions can
// read: the nearest texel of each and its 8 neighbours, found by stepping a texel along the
// face plane (past an edge, that lands on the adjacent face's texels, which seamless
// filtering reads there).
std::vector<CubeTexelRef> texelsAround(int size, const std::vector<glm::dvec3>& directions)
{
    std::set<std::tuple<int, int, int>> seen;
    std::vector<CubeTexelRef> texels;
    const double step = 2.0 / size;
    for (const glm::dvec3& d : directions) {
        const glm::dvec3 a = glm::abs(d);
        const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        const glm::dvec3 onFace = d / a[axis];
        glm::dvec3 e1(0.0), e2(0.0);
        e1[(axis + 1) % 3] = 1.0;
        e2[(axis + 2) % 3] = 1.0;
        for (int du = -1; du <= 1; ++du)
            for (int dv = -1; dv <= 1; ++dv) {
                const glm::vec3 fst = directionToCubeFaceUv(glm::vec3(glm::normalize(onFace + step * (double(du) * e1 + double(dv) * e2))));
                const int face = int(fst.x);
                const int x = std::clamp(int(std::floor(fst.y * float(size))), 0, size - 1);
                const int row = std::clamp(int(std::floor(fst.z * float(size))), 0, size - 1);
                if (seen.insert({face, x, row}).second)
                    texels.push_back({face, x, row});
            }
    }
    return texels;
}

} // namespace

std::vector<CubeTexelRef> cubeTexelGrid(int size, int grid)
{
    std::vector<CubeTexelRef> texels;
    const int n = std::min(size, grid);
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                texels.push_back({face, (2 * i + 1) * size / (2 * n), (2 * j + 1) * size / (2 * n)});
    return texels;
}

std::vector<glm::dvec3> fibonacciSphere(int n)
{
    std::vector<glm::dvec3> directions;
    const double goldenAngle = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double y = 1.0 - (2.0 * i + 1.0) / n;
        const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        directions.emplace_back(r * std::cos(goldenAngle * i), y, r * std::sin(goldenAngle * i));
    }
    return directions;
}

namespace {

// Wide lobes against the reduced map (AccuracyOptions::maxReferenceWidthForWideLobes).
constexpr float kNarrowestWideLobe = 0.5f;
bool isWide(float roughness) { return roughness >= kNarrowestWideLobe; }

// Up to 16: a 64-wide map is summed 1024 wide, which resolves roughness 0.096.
constexpr int kMaxReferenceUpsample = 16;

// What one bake's errors measure, and where: every reference value is requested from one
// list, each group of points keeping the first of its slots.
struct MeasurePlan {
    ReferenceList references;
    int fullWidth = 0; // of the map the sharp lobes sum over
    int wideWidth = 0; // of the reduced map the wide lobes and the irradiance sum over
    struct Level {
        std::vector<CubeTexelRef> texels;
        std::vector<glm::dvec3> directions;
        float roughness = 0.0f;
        std::size_t first = 0;
    };
    std::vector<Level> levels;
    std::vector<glm::dvec3> shadedDirections;
    std::vector<float> shadedRoughness;
    std::vector<std::size_t> shadedFirst;
    // The floor (AccuracyOptions::shadedFloor): per level, the texels the shaded lookups read.
    std::vector<std::pair<std::vector<CubeTexelRef>, std::size_t>> floorTexels;
    std::vector<CubeTexelRef> irradianceTexels;
    std::vector<glm::dvec3> irradianceNormals;
    std::size_t irradianceFirst = 0;
    std::size_t shadedIrradianceFirst = 0;
    struct LutPoint {
        GeometryTerm term;
        int x, row;
        std::size_t slot;
    };
    std::vector<LutPoint> lutPoints;

    int referenceWidth(float roughness) const { return isWide(roughness) ? wideWidth : fullWidth; }
};

std::vector<glm::dvec3> texelDirections(const CubeImage& geometry, const std::vector<CubeTexelRef>& texels)
{
    std::vector<glm::dvec3> directions;
    for (const CubeTexelRef& t : texels)
        directions.push_back(glm::normalize(glm::dvec3(geometry.texelDirection(t.face, t.x, t.row))));
    return directions;
}

MeasurePlan planMeasurements(const BakeResult& result, const ImageRGB32F& environment, const AccuracyOptions& options)
{
    MeasurePlan plan;
    ReferenceList& references = plan.references;
    const BakedTexture& pre = result.prefiltered;
    plan.fullWidth = environment.width;
    // The wide lobes' map: halved down to the option's width, or, a map too coarse for the
    // narrowest wide lobe (roughness 0.5: 38 texels), its bilinear upsample as below.
    const int wideUpsample = referenceUpsampleFactor(environment.width, kNarrowestWideLobe, kMaxReferenceUpsample);
    plan.wideWidth = wideUpsample > 1 ? environment.width * wideUpsample
                                      : reducedWidth(environment.width, environment.height, options.maxReferenceWidthForWideLobes);
    for (int level = 0; level < pre.levels; ++level) {
        MeasurePlan::Level l;
        const CubeImage geometry(std::max(pre.size >> level, 1));
        l.texels = cubeTexelGrid(geometry.size, options.texelsPerFaceEdge);
        l.directions = texelDirections(geometry, l.texels);
        l.roughness = prefilterMipRoughness(result.settings.prefilter, level);
        l.first = references.prefilter(l.directions, l.roughness, isWide(l.roughness));
        plan.levels.push_back(std::move(l));
    }
    plan.shadedDirections = fibonacciSphere(options.shadedDirections);
    for (int i = 0; i <= options.shadedRoughnessSteps; ++i) {
        plan.shadedRoughness.push_back(float(i) / float(std::max(options.shadedRoughnessSteps, 1)));
        plan.shadedFirst.push_back(references.prefilter(plan.shadedDirections, plan.shadedRoughness.back(), isWide(plan.shadedRoughness.back())));
    }
    if (options.shadedFloor)
        for (int level = 0; level < pre.levels; ++level) {
            std::vector<glm::dvec3> reading; // the shaded directions whose lookups read this level
            for (float roughness : plan.shadedRoughness) {
                const float lod = prefilterMipFromRoughness(roughness, float(pre.levels), int(result.settings.prefilter.layout));
                if (level == int(std::floor(lod)) || level == int(std::ceil(lod)))
                    reading.insert(reading.end(), plan.shadedDirections.begin(), plan.shadedDirections.end());
            }
            const CubeImage geometry(pre.levelSize(level));
            std::vector<CubeTexelRef> texels = texelsAround(geometry.size, reading);
            const std::vector<glm::dvec3> directions = texelDirections(geometry, texels);
            const float roughness = plan.levels[std::size_t(level)].roughness;
            plan.floorTexels.emplace_back(std::move(texels), references.prefilter(directions, roughness, isWide(roughness)));
        }
    // Irradiance at texel centres: each cube at the grid texels of its own size, the SH at
    // those of the shading cube (or of a 32^2 one when there is none).
    const int irradianceSize = result.irradianceCube ? result.irradianceCube.size : 32;
    plan.irradianceTexels = cubeTexelGrid(irradianceSize, options.texelsPerFaceEdge);
    plan.irradianceNormals = texelDirections(CubeImage(irradianceSize), plan.irradianceTexels);
    plan.irradianceFirst = references.irradiance(plan.irradianceNormals);
    plan.shadedIrradianceFirst = references.irradiance(plan.shadedDirections);
    for (GeometryTerm term : kGeometryTerms) {
        const BakedTexture& lut = result.lut(term);
        if (!lut)
            continue;
        const int n = std::min(lut.size, options.lutGrid);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int x = (2 * i + 1) * lut.size / (2 * n);
                const int row = (2 * j + 1) * lut.size / (2 * n);
                plan.lutPoints.push_back({term, x, row, references.lut((x + 0.5) / lut.size, (row + 0.5) / lut.size, term)});
            }
    }
    // A map too coarse for the narrowest lobe is summed as its bilinear upsample, the map the
    // bake and the sky read: its texel centres alone would leave a lobe narrower than a texel
    // between them (builtin:sun 160 wide read 0.116 at mip 1 against them).
    plan.fullWidth = environment.width * referenceUpsampleFactor(environment.width, references.smallestSharpRoughness(), kMaxReferenceUpsample);
    return plan;
}

// The reference values, computed or read from the cache: they depend on nothing but the map's
// pixels and the list (the bake's sizes and layout decide the directions).
std::vector<glm::dvec3> referenceValues(const MeasurePlan& plan, const BakeResult& result, const ImageRGB32F& environment,
                                        const AccuracyOptions& options, BakeErrors& errors)
{
    std::filesystem::path cached;
    if (!options.referenceCacheDirectory.empty()) {
        // 3: a coarse map's upsample keeps its texels' flux (fluxConservingRowBlends).
        const std::string key = hex16(fnv1a(plan.references.digest(), fnv1a("iblab-reference-3|" + std::to_string(result.contentHash) + "|" +
                                                                             std::to_string(plan.fullWidth) + "|" + std::to_string(plan.wideWidth) + "|" +
                                                                             std::to_string(options.lutReferenceSamples))));
        cached = options.referenceCacheDirectory / (key + ".bin");
        if (auto loaded = loadReferenceValues(cached, plan.references.size(), errors.notes)) {
            errors.referencesFromCache = true;
            return std::move(*loaded);
        }
    }
    const int upsample = plan.fullWidth / environment.width, wideUpsample = plan.wideWidth / environment.width;
    std::vector<glm::dvec3> values = plan.references.evaluate(
        upsample > 1 ? upsampleEquirectBilinear(environment, upsample) : environment,
        wideUpsample > 1 ? upsampleEquirectBilinear(environment, wideUpsample) : downsampleEquirectToWidth(environment, options.maxReferenceWidthForWideLobes),
        options.lutReferenceSamples);
    if (!cached.empty()) storeReferenceValues(cached, values, errors.notes);
    return values;
}

// The prefiltered cube against its references: at texel centres per level, as shaded (read
// where and how shading reads it), and with the floor, an exact cube read the same way.
void comparePrefilter(const MeasurePlan& plan, std::span<const glm::dvec3> values, const BakeResult& result, gl::ShaderLibrary& shaders,
                      const AccuracyOptions& options, BakeErrors& errors)
{
    const BakedTexture& pre = result.prefiltered;
    for (int level = 0; level < pre.levels; ++level) {
        const MeasurePlan::Level& l = plan.levels[std::size_t(level)];
        const CubeImage image = readCubeLevel(pre, level);
        std::vector<glm::dvec3> baked;
        for (const CubeTexelRef& t : l.texels) baked.emplace_back(image.rgb(t.face, t.x, t.row));
        errors.prefilter.push_back({level, l.roughness, relativeRmse(baked, values.subspan(l.first, baked.size())), int(baked.size()),
                                    plan.referenceWidth(l.roughness)});
    }

    const std::vector<glm::dvec3>& directions = plan.shadedDirections;
    std::vector<glm::vec4> queries;
    for (float roughness : plan.shadedRoughness)
        for (const glm::dvec3& d : directions)
            queries.emplace_back(glm::vec3(d), roughness);
    const std::vector<glm::vec3> shaded = BakePasses(shaders).samplePrefiltered(pre, result.settings.prefilter.layout, queries);
    double sumSquares = 0.0;
    for (std::size_t r = 0; r < plan.shadedRoughness.size(); ++r) {
        const float roughness = plan.shadedRoughness[r];
        const auto first = shaded.begin() + std::ptrdiff_t(r * directions.size());
        const std::vector<glm::dvec3> baked(first, first + std::ptrdiff_t(directions.size()));
        const double rmse = relativeRmse(baked, values.subspan(plan.shadedFirst[r], baked.size()));
        errors.prefilterShaded.push_back({roughness, prefilterMipFromRoughness(roughness, float(pre.levels), int(result.settings.prefilter.layout)),
                                          rmse, int(directions.size()), plan.referenceWidth(roughness)});
        sumSquares += rmse * rmse;
    }
    if (!errors.prefilterShaded.empty())
        errors.prefilterShadedRms = std::sqrt(sumSquares / double(errors.prefilterShaded.size()));
    if (!options.shadedFloor)
        return;

    const BakedTexture exact = createCubeTexture(pre.internalFormat, pre.size, pre.levels);
    for (int level = 0; level < pre.levels; ++level) {
        CubeImage image(pre.levelSize(level));
        const auto& [texels, first] = plan.floorTexels[std::size_t(level)];
        for (std::size_t i = 0; i < texels.size(); ++i)
            image.at(texels[i].face, texels[i].x, texels[i].row) = glm::vec4(glm::vec3(values[first + i]), 1.0f);
        uploadCubeLevel(exact, level, image);
    }
    const std::vector<glm::vec3> read = BakePasses(shaders).samplePrefiltered(exact, result.settings.prefilter.layout, queries);
    double floorSquares = 0.0;
    for (std::size_t r = 0; r < plan.shadedRoughness.size(); ++r) {
        const auto first = read.begin() + std::ptrdiff_t(r * directions.size());
        const std::vector<glm::dvec3> exactRead(first, first + std::ptrdiff_t(directions.size()));
        ShadedRoughnessError e = errors.prefilterShaded[r];
        e.relativeRmse = relativeRmse(exactRead, values.subspan(plan.shadedFirst[r], exactRead.size()));
        errors.prefilterShadedFloor.push_back(e);
        floorSquares += e.relativeRmse * e.relativeRmse;
    }
    errors.prefilterShadedFloorRms = std::sqrt(floorSquares / double(errors.prefilterShadedFloor.size()));
}

// The fitted lobe's diffuse as shaded, where the bake found shading lights: each source less
// the lights, read as shading reads it, plus the lights' own terms (residual_irradiance.hpp).
void compareIrradianceWithLights(const MeasurePlan& plan, std::span<const glm::dvec3> shadedReference, const BakeResult& result,
                                 gl::ShaderLibrary& shaders, BakeErrors& errors)
{
    if (result.shadingLights.groups.empty())
        return;
    const std::vector<ShadingLight> lights = result.shadingLights.lights();
    const SH9Color lightsSh = shadingLightsShIrradiance(lights);
    const SH9Color lightsShWindowed = applyWindow(lightsSh, result.sh.window, result.sh.windowWidth);
    std::vector<glm::dvec3> lit, sh, shWindowed;
    for (const glm::dvec3& d : plan.shadedDirections) {
        lit.push_back(shadingLightsIrradiance(lights, d));
        sh.push_back(evaluate(result.sh.irradiance, d) - evaluate(lightsSh, d) + lit.back());
        shWindowed.push_back(evaluate(result.sh.irradianceWindowed, d) - evaluate(lightsShWindowed, d) + lit.back());
    }
    errors.shIrradianceWithLightsShaded = relativeErrors(sh, shadedReference);
    errors.shIrradianceWindowedWithLightsShaded = relativeErrors(shWindowed, shadedReference);
    if (!result.irradianceCube)
        return;
    std::vector<glm::vec4> queries;
    for (const glm::dvec3& d : plan.shadedDirections) queries.emplace_back(glm::vec3(d), 0.0f);
    const BakedTexture residual = residualIrradianceCube(result.irradianceCube, lights);
    const std::vector<glm::vec3> read = BakePasses(shaders).samplePrefiltered(residual, RoughnessLayout::Linear, queries);
    std::vector<glm::dvec3> cube;
    for (std::size_t i = 0; i < read.size(); ++i) cube.push_back(glm::dvec3(read[i]) + lit[i]);
    errors.irradianceCubeWithLightsShaded = relativeErrors(cube, shadedReference);
}

// SH9 and the irradiance cube against the irradiance references: at texel centres, then as
// shaded.
void compareIrradiance(const MeasurePlan& plan, std::span<const glm::dvec3> values, const BakeResult& result, gl::ShaderLibrary& shaders,
                       BakeErrors& errors)
{
    const auto irradianceReference = values.subspan(plan.irradianceFirst, plan.irradianceNormals.size());
    std::vector<glm::dvec3> sh;
    std::vector<glm::dvec3> shWindowed;
    for (const glm::dvec3& n : plan.irradianceNormals) {
        sh.push_back(evaluate(result.sh.irradiance, n));
        shWindowed.push_back(evaluate(result.sh.irradianceWindowed, n));
    }
    errors.shIrradiance = relativeErrors(sh, irradianceReference);
    errors.shIrradianceWindowed = relativeErrors(shWindowed, irradianceReference);
    errors.irradianceReferenceWidth = plan.wideWidth;
    errors.irradianceMethod = result.settings.irradiance;
    if (result.irradianceCube) {
        const CubeImage image = readCubeLevel(result.irradianceCube, 0);
        std::vector<glm::dvec3> baked;
        for (const CubeTexelRef& t : plan.irradianceTexels) baked.emplace_back(image.rgb(t.face, t.x, t.row));
        errors.irradianceCube = relativeErrors(baked, irradianceReference);
    }

    // Irradiance as shaded: each cube read where shading reads it (bilinear, seamless) at the
    // Fibonacci directions, which counts the interpolation between texel centres that the
    // texel-centre numbers above leave out, and compares cubes of different sizes on the
    // same directions. A one-level cube read at roughness 0 is read at lod 0.
    const auto shadedReference = values.subspan(plan.shadedIrradianceFirst, plan.shadedDirections.size());
    std::vector<glm::dvec3> shShaded;
    for (const glm::dvec3& d : plan.shadedDirections)
        shShaded.push_back(evaluate(result.sh.irradiance, d));
    errors.shIrradianceShaded = relativeErrors(shShaded, shadedReference);
    if (result.irradianceCube) {
        std::vector<glm::vec4> irradianceQueries;
        for (const glm::dvec3& d : plan.shadedDirections) irradianceQueries.emplace_back(glm::vec3(d), 0.0f);
        const std::vector<glm::vec3> read =
            BakePasses(shaders).samplePrefiltered(result.irradianceCube, RoughnessLayout::Linear, irradianceQueries);
        errors.irradianceCubeShaded = relativeErrors(std::vector<glm::dvec3>(read.begin(), read.end()), shadedReference);
    }
    compareIrradianceWithLights(plan, shadedReference, result, shaders, errors);
}

// Each BRDF LUT's largest absolute difference from its references over the grid of points.
void compareLuts(const MeasurePlan& plan, std::span<const glm::dvec3> values, const BakeResult& result, BakeErrors& errors)
{
    for (GeometryTerm term : kGeometryTerms) {
        const BakedTexture& lut = result.lut(term);
        if (!lut)
            continue;
        const Image2D image = read2D(lut);
        double worst = 0.0;
        for (const MeasurePlan::LutPoint& p : plan.lutPoints)
            if (p.term == term) {
                const glm::dvec3 d = glm::abs(glm::dvec3(glm::vec3(image.at(p.x, p.row))) - values[p.slot]);
                worst = std::max({worst, d.x, d.y, d.z});
            }
        errors.lutMaxAbs[std::size_t(term)] = worst;
    }
}

} // namespace

BakeErrors measureBakeErrors(const BakeResult& result, const ImageRGB32F& environment, gl::ShaderLibrary& shaders,
                             const AccuracyOptions& options)
{
    const auto start = std::chrono::steady_clock::now();
    BakeErrors errors;
    // First every reference value is requested, then they are computed (or read from the
    // cache) in one go, then the bake is read and compared with them.
    const MeasurePlan plan = planMeasurements(result, environment, options);
    const std::vector<glm::dvec3> values = referenceValues(plan, result, environment, options, errors);
    errors.referenceMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    comparePrefilter(plan, values, result, shaders, options, errors);
    compareIrradiance(plan, values, result, shaders, errors);
    compareLuts(plan, values, result, errors);
    errors.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return errors;
}

} // namespace iblab::bake
