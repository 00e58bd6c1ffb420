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
#include <nlohmann/json.hpp>

#include "bake/bake_passes.hpp"
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

nlohmann::ordered_json statsJson(const ErrorStats& s)
{
    return {{"mean_relative", s.mean}, {"max_relative", s.max}, {"directions", s.directions}};
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

    std::vector<glm::dvec3> evaluate(const ImageRGB32F& environment, const ImageRGB32F& reduced, std::uint32_t lutSamples) const
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
        batch(Kind::SharpPrefilter, environment);
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

BakeErrors measureBakeErrors(const BakeResult& result, const ImageRGB32F& environment, gl::ShaderLibrary& shaders,
                             const AccuracyOptions& options)
{
    const auto start = std::chrono::steady_clock::now();
    BakeErrors errors;
    const BakedTexture& pre = result.prefiltered;
    // Wide lobes against the reduced map (AccuracyOptions::maxReferenceWidthForWideLobes).
    auto isWide = [](float roughness) { return roughness >= 0.5f; };
    const int wideWidth = reducedWidth(environment.width, environment.height, options.maxReferenceWidthForWideLobes);
    auto referenceWidth = [&](float roughness) { return isWide(roughness) ? wideWidth : environment.width; };

    // What is measured where: first every reference value is requested...
    ReferenceList references;
    struct LevelPlan {
        std::vector<CubeTexelRef> texels;
        std::vector<glm::dvec3> directions;
        float roughness = 0.0f;
        std::size_t first = 0;
    };
    std::vector<LevelPlan> levels;
    for (int level = 0; level < pre.levels; ++level) {
        LevelPlan plan;
        const CubeImage geometry(std::max(pre.size >> level, 1));
        plan.texels = cubeTexelGrid(geometry.size, options.texelsPerFaceEdge);
        for (const CubeTexelRef& t : plan.texels)
            plan.directions.push_back(glm::normalize(glm::dvec3(geometry.texelDirection(t.face, t.x, t.row))));
        plan.roughness = prefilterMipRoughness(result.settings.prefilter, level);
        plan.first = references.prefilter(plan.directions, plan.roughness, isWide(plan.roughness));
        levels.push_back(std::move(plan));
    }
    const std::vector<glm::dvec3> shadedDirections = fibonacciSphere(options.shadedDirections);
    std::vector<float> shadedRoughness;
    std::vector<std::size_t> shadedFirst;
    for (int i = 0; i <= options.shadedRoughnessSteps; ++i) {
        shadedRoughness.push_back(float(i) / float(std::max(options.shadedRoughnessSteps, 1)));
        shadedFirst.push_back(references.prefilter(shadedDirections, shadedRoughness.back(), isWide(shadedRoughness.back())));
    }
    // The floor (AccuracyOptions::shadedFloor): per level, the texels the shaded lookups read.
    std::vector<std::pair<std::vector<CubeTexelRef>, std::size_t>> floorTexels;
    if (options.shadedFloor)
        for (int level = 0; level < pre.levels; ++level) {
            std::vector<glm::dvec3> reading; // the shaded directions whose lookups read this level
            for (float roughness : shadedRoughness) {
                const float lod = prefilterMipFromRoughness(roughness, float(pre.levels), int(result.settings.prefilter.layout));
                if (level == int(std::floor(lod)) || level == int(std::ceil(lod)))
                    reading.insert(reading.end(), shadedDirections.begin(), shadedDirections.end());
            }
            const CubeImage geometry(pre.levelSize(level));
            std::vector<CubeTexelRef> texels = texelsAround(geometry.size, reading);
            std::vector<glm::dvec3> directions;
            for (const CubeTexelRef& t : texels)
                directions.push_back(glm::normalize(glm::dvec3(geometry.texelDirection(t.face, t.x, t.row))));
            const float roughness = levels[std::size_t(level)].roughness;
            floorTexels.emplace_back(std::move(texels), references.prefilter(directions, roughness, isWide(roughness)));
        }
    // Irradiance at texel centres: each cube at the grid texels of its own size, the SH at
    // those of the shading cube (or of a 32^2 one when there is none).
    const int irradianceSize = result.irradianceCube ? result.irradianceCube.size : 32;
    const std::vector<CubeTexelRef> irradianceTexels = cubeTexelGrid(irradianceSize, options.texelsPerFaceEdge);
    std::vector<glm::dvec3> irradianceNormals;
    const CubeImage irradianceGeometry(irradianceSize);
    for (const CubeTexelRef& t : irradianceTexels)
        irradianceNormals.push_back(glm::normalize(glm::dvec3(irradianceGeometry.texelDirection(t.face, t.x, t.row))));
    const std::size_t irradianceFirst = references.irradiance(irradianceNormals);
    const std::size_t shadedIrradianceFirst = references.irradiance(shadedDirections);
    struct LutPoint {
        GeometryTerm term;
        int x, row;
        std::size_t slot;
    };
    std::vector<LutPoint> lutPoints;
    for (GeometryTerm term : kGeometryTerms) {
        const BakedTexture& lut = result.lut(term);
        if (!lut)
            continue;
        const int n = std::min(lut.size, options.lutGrid);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int x = (2 * i + 1) * lut.size / (2 * n);
                const int row = (2 * j + 1) * lut.size / (2 * n);
                lutPoints.push_back({term, x, row, references.lut((x + 0.5) / lut.size, (row + 0.5) / lut.size, term)});
            }
    }

    // ... then computed, or read from the cache: they depend on nothing but the map's
    // pixels and the list (the bake's sizes and layout decide the directions).
    std::vector<glm::dvec3> values;
    std::filesystem::path cached;
    if (!options.referenceCacheDirectory.empty()) {
        const std::string key = hex16(fnv1a(references.digest(), fnv1a("iblab-reference-1|" + std::to_string(result.contentHash) + "|" +
                                                                        std::to_string(wideWidth) + "|" +
                                                                        std::to_string(options.lutReferenceSamples))));
        cached = options.referenceCacheDirectory / (key + ".bin");
        if (auto loaded = loadReferenceValues(cached, references.size(), errors.notes)) {
            values = std::move(*loaded);
            errors.referencesFromCache = true;
        }
    }
    if (!errors.referencesFromCache) {
        values = references.evaluate(environment, downsampleEquirectToWidth(environment, options.maxReferenceWidthForWideLobes),
                                     options.lutReferenceSamples);
        if (!cached.empty()) storeReferenceValues(cached, values, errors.notes);
    }
    errors.referenceMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    auto slice = [&](std::size_t first, std::size_t count) { return std::span<const glm::dvec3>(values).subspan(first, count); };

    for (int level = 0; level < pre.levels; ++level) {
        const LevelPlan& plan = levels[std::size_t(level)];
        const CubeImage image = readCubeLevel(pre, level);
        std::vector<glm::dvec3> baked;
        for (const CubeTexelRef& t : plan.texels) baked.emplace_back(image.rgb(t.face, t.x, t.row));
        errors.prefilter.push_back({level, plan.roughness, relativeRmse(baked, slice(plan.first, baked.size())),
                                    int(baked.size()), referenceWidth(plan.roughness)});
    }

    std::vector<glm::vec4> queries;
    for (float roughness : shadedRoughness)
        for (const glm::dvec3& d : shadedDirections)
            queries.emplace_back(glm::vec3(d), roughness);
    const std::vector<glm::vec3> shaded = BakePasses(shaders).samplePrefiltered(pre, result.settings.prefilter.layout, queries);
    double sumSquares = 0.0;
    for (std::size_t r = 0; r < shadedRoughness.size(); ++r) {
        const float roughness = shadedRoughness[r];
        const auto first = shaded.begin() + std::ptrdiff_t(r * shadedDirections.size());
        const std::vector<glm::dvec3> baked(first, first + std::ptrdiff_t(shadedDirections.size()));
        const double rmse = relativeRmse(baked, slice(shadedFirst[r], baked.size()));
        errors.prefilterShaded.push_back({roughness, prefilterMipFromRoughness(roughness, float(pre.levels), int(result.settings.prefilter.layout)),
                                          rmse, int(shadedDirections.size()), referenceWidth(roughness)});
        sumSquares += rmse * rmse;
    }
    if (!errors.prefilterShaded.empty())
        errors.prefilterShadedRms = std::sqrt(sumSquares / double(errors.prefilterShaded.size()));

    if (options.shadedFloor) {
        const BakedTexture exact = createCubeTexture(pre.internalFormat, pre.size, pre.levels);
        for (int level = 0; level < pre.levels; ++level) {
            CubeImage image(pre.levelSize(level));
            const auto& [texels, first] = floorTexels[std::size_t(level)];
            for (std::size_t i = 0; i < texels.size(); ++i)
                image.at(texels[i].face, texels[i].x, texels[i].row) = glm::vec4(glm::vec3(values[first + i]), 1.0f);
            uploadCubeLevel(exact, level, image);
        }
        const std::vector<glm::vec3> read = BakePasses(shaders).samplePrefiltered(exact, result.settings.prefilter.layout, queries);
        double floorSquares = 0.0;
        for (std::size_t r = 0; r < shadedRoughness.size(); ++r) {
            const auto first = read.begin() + std::ptrdiff_t(r * shadedDirections.size());
            const std::vector<glm::dvec3> exactRead(first, first + std::ptrdiff_t(shadedDirections.size()));
            ShadedRoughnessError e = errors.prefilterShaded[r];
            e.relativeRmse = relativeRmse(exactRead, slice(shadedFirst[r], exactRead.size()));
            errors.prefilterShadedFloor.push_back(e);
            floorSquares += e.relativeRmse * e.relativeRmse;
        }
        errors.prefilterShadedFloorRms = std::sqrt(floorSquares / double(errors.prefilterShadedFloor.size()));
    }

    const auto irradianceReference = slice(irradianceFirst, irradianceNormals.size());
    std::vector<glm::dvec3> sh;
    std::vector<glm::dvec3> shWindowed;
    for (const glm::dvec3& n : irradianceNormals) {
        sh.push_back(evaluate(result.sh.irradiance, n));
        shWindowed.push_back(evaluate(result.sh.irradianceWindowed, n));
    }
    errors.shIrradiance = relativeErrors(sh, irradianceReference);
    errors.shIrradianceWindowed = relativeErrors(shWindowed, irradianceReference);
    errors.irradianceReferenceWidth = wideWidth;
    errors.irradianceMethod = result.settings.irradiance;
    if (result.irradianceCube) {
        const CubeImage image = readCubeLevel(result.irradianceCube, 0);
        std::vector<glm::dvec3> baked;
        for (const CubeTexelRef& t : irradianceTexels) baked.emplace_back(image.rgb(t.face, t.x, t.row));
        errors.irradianceCube = relativeErrors(baked, irradianceReference);
    }

    // Irradiance as shaded: each cube read where shading reads it (bilinear, seamless) at the
    // Fibonacci directions, which counts the interpolation between texel centres that the
    // texel-centre numbers above leave out, and compares cubes of different sizes on the
    // same directions. A one-level cube read at roughness 0 is read at lod 0.
    const auto shadedReference = slice(shadedIrradianceFirst, shadedDirections.size());
    std::vector<glm::dvec3> shShaded;
    for (const glm::dvec3& d : shadedDirections)
        shShaded.push_back(evaluate(result.sh.irradiance, d));
    errors.shIrradianceShaded = relativeErrors(shShaded, shadedReference);
    if (result.irradianceCube) {
        std::vector<glm::vec4> irradianceQueries;
        for (const glm::dvec3& d : shadedDirections) irradianceQueries.emplace_back(glm::vec3(d), 0.0f);
        const std::vector<glm::vec3> read =
            BakePasses(shaders).samplePrefiltered(result.irradianceCube, RoughnessLayout::Linear, irradianceQueries);
        errors.irradianceCubeShaded = relativeErrors(std::vector<glm::dvec3>(read.begin(), read.end()), shadedReference);
    }

    for (GeometryTerm term : kGeometryTerms) {
        const BakedTexture& lut = result.lut(term);
        if (!lut)
            continue;
        const Image2D image = read2D(lut);
        double worst = 0.0;
        for (const LutPoint& p : lutPoints)
            if (p.term == term) {
                const glm::dvec3 d = glm::abs(glm::dvec3(glm::vec3(image.at(p.x, p.row))) - values[p.slot]);
                worst = std::max({worst, d.x, d.y, d.z});
            }
        errors.lutMaxAbs[std::size_t(term)] = worst;
    }
    errors.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return errors;
}

std::string errorsJsonText(const BakeErrors& errors, const AccuracyOptions& options)
{
    nlohmann::ordered_json j;
    nlohmann::ordered_json pre = nlohmann::ordered_json::array();
    for (const PrefilterLevelError& e : errors.prefilter)
        pre.push_back({{"mip", e.level},
                       {"roughness", e.roughness},
                       {"relative_rmse", e.relativeRmse},
                       {"directions", e.directions},
                       {"reference_width", e.referenceWidth}});
    j["prefilter"] = pre;
    nlohmann::ordered_json shaded = nlohmann::ordered_json::array();
    for (const ShadedRoughnessError& e : errors.prefilterShaded)
        shaded.push_back({{"roughness", e.roughness},
                          {"lod", e.lod},
                          {"relative_rmse", e.relativeRmse},
                          {"directions", e.directions},
                          {"reference_width", e.referenceWidth}});
    j["prefilter_shaded"] = shaded;
    j["prefilter_shaded_rms"] = errors.prefilterShadedRms;
    if (!errors.prefilterShadedFloor.empty()) {
        nlohmann::ordered_json floor = nlohmann::ordered_json::array();
        for (const ShadedRoughnessError& e : errors.prefilterShadedFloor)
            floor.push_back({{"roughness", e.roughness}, {"relative_rmse", e.relativeRmse}});
        j["prefilter_shaded_floor"] = floor;
        j["prefilter_shaded_floor_rms"] = errors.prefilterShadedFloorRms;
    }
    nlohmann::ordered_json irr;
    irr["sh"] = statsJson(errors.shIrradiance);
    irr["sh_windowed"] = statsJson(errors.shIrradianceWindowed);
    const std::string cubeKey = "cube_" + std::string(enumName(errors.irradianceMethod));
    if (errors.irradianceCube) irr[cubeKey] = statsJson(*errors.irradianceCube);
    irr["reference_width"] = errors.irradianceReferenceWidth;
    j["irradiance"] = irr;
    nlohmann::ordered_json irrShaded;
    irrShaded["sh"] = statsJson(errors.shIrradianceShaded);
    if (errors.irradianceCubeShaded) irrShaded[cubeKey] = statsJson(*errors.irradianceCubeShaded);
    j["irradiance_shaded"] = irrShaded;
    nlohmann::ordered_json lut = nlohmann::ordered_json::object();
    for (GeometryTerm term : kGeometryTerms)
        if (errors.lutMaxAbs[std::size_t(term)])
            lut[std::string(enumName(term))] = *errors.lutMaxAbs[std::size_t(term)];
    j["lut_max_abs"] = lut;
    j["method"] = "exact references of renderer/ibl (sums over every texel) at the texel centres of a " +
                  std::to_string(options.texelsPerFaceEdge) + "x" + std::to_string(options.texelsPerFaceEdge) +
                  " texel grid per cube face; prefilter: relative RMSE = sqrt(sum|baked-ref|^2 / sum|ref|^2); "
                  "prefilter_shaded: the same for what split-sum shading reads (textureLod at the layout's lod, seamless "
                  "trilinear) at " + std::to_string(options.shadedDirections) + " Fibonacci-lattice directions at roughness 0 to 1 in steps of 1/" +
                  std::to_string(options.shadedRoughnessSteps) + ", "
                  "prefilter_shaded_rms their root mean square; "
                  "irradiance: per-direction |baked-ref|/|ref| at the texel grid of each cube (SH: of the shading cube); "
                  "irradiance_shaded: the same for each cube read bilinearly and seamlessly at the Fibonacci directions; references for roughness >= 0.5 and irradiance on the "
                  "environment halved to at most " +
                  std::to_string(options.maxReferenceWidthForWideLobes) + " wide; LUT: max abs error on a " +
                  std::to_string(options.lutGrid) + "x" + std::to_string(options.lutGrid) + " texel grid against " +
                  std::to_string(options.lutReferenceSamples) + "-sample CPU integration";
    j["milliseconds"] = errors.milliseconds;
    j["references"] = {{"from_cache", errors.referencesFromCache}, {"milliseconds", errors.referenceMilliseconds}};
    return j.dump();
}

} // namespace iblab::bake
