#include "bake/bake_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "bake/bake_passes.hpp"
#include "ibl/prefilter_lod.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/conventions.hpp"
#include "ibl/reference.hpp"

namespace iblab::bake {
namespace {

ImageRGB32F reduceTo(const ImageRGB32F& env, int maxWidth)
{
    ImageRGB32F out = env;
    while (out.width > maxWidth && out.width % 2 == 0 && out.height % 2 == 0)
        out = downsampleEquirect2x(out);
    return out;
}

ErrorStats relativeErrors(const std::vector<glm::dvec3>& baked, const std::vector<glm::dvec3>& reference)
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

ErrorStats cubeIrradianceErrors(const BakedTexture& cube, const std::vector<CubeTexelRef>& texels,
                                const std::vector<glm::dvec3>& reference)
{
    const CubeImage image = readCubeLevel(cube, 0);
    std::vector<glm::dvec3> baked;
    for (const CubeTexelRef& t : texels)
        baked.emplace_back(image.rgb(t.face, t.x, t.row));
    return relativeErrors(baked, reference);
}

nlohmann::ordered_json statsJson(const ErrorStats& s)
{
    return {{"mean_relative", s.mean}, {"max_relative", s.max}, {"directions", s.directions}};
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
    const ImageRGB32F reduced = reduceTo(environment, options.maxReferenceWidthForWideLobes);
    const ZonalReference fullSums(environment);
    const ZonalReference reducedSums(reduced);

    // Wide lobes against the reduced map (AccuracyOptions::maxReferenceWidthForWideLobes).
    auto referenceMap = [&](float roughness) -> const ZonalReference& { return roughness >= 0.5f ? reducedSums : fullSums; };
    // sqrt(sum |baked - ref|^2 / sum |ref|^2) of baked values against the prefiltered reference
    // at `roughness` in the given directions.
    auto prefilterRelativeRmse = [&](const std::vector<glm::dvec3>& baked, const std::vector<glm::dvec3>& directions, float roughness) {
        std::vector<ZonalReference::PrefilterQuery> queries;
        for (const glm::dvec3& d : directions) queries.push_back({d, double(roughness)});
        const std::vector<glm::dvec3> references = referenceMap(roughness).prefilteredRadiance(queries);
        double sumErr2 = 0.0;
        double sumRef2 = 0.0;
        for (std::size_t i = 0; i < directions.size(); ++i) {
            const glm::dvec3& ref = references[i];
            const glm::dvec3 d = baked[i] - ref;
            sumErr2 += glm::dot(d, d);
            sumRef2 += glm::dot(ref, ref);
        }
        return sumRef2 > 0.0 ? std::sqrt(sumErr2 / sumRef2) : std::sqrt(sumErr2);
    };

    const BakedTexture& pre = result.prefiltered;
    for (int level = 0; level < pre.levels; ++level) {
        const CubeImage image = readCubeLevel(pre, level);
        const float roughness = prefilterMipRoughness(result.settings.prefilter, level);
        std::vector<glm::dvec3> directions;
        std::vector<glm::dvec3> baked;
        for (const CubeTexelRef& t : cubeTexelGrid(image.size, options.texelsPerFaceEdge)) {
            directions.push_back(glm::normalize(glm::dvec3(image.texelDirection(t.face, t.x, t.row))));
            baked.emplace_back(image.rgb(t.face, t.x, t.row));
        }
        errors.prefilter.push_back(
            {level, roughness, prefilterRelativeRmse(baked, directions, roughness), int(directions.size()), referenceMap(roughness).width()});
    }

    const std::vector<glm::dvec3> shadedDirections = fibonacciSphere(options.shadedDirections);
    std::vector<float> shadedRoughness;
    for (int i = 0; i <= options.shadedRoughnessSteps; ++i)
        shadedRoughness.push_back(float(i) / float(std::max(options.shadedRoughnessSteps, 1)));
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
        const double rmse = prefilterRelativeRmse(baked, shadedDirections, roughness);
        errors.prefilterShaded.push_back({roughness, prefilterMipFromRoughness(roughness, float(pre.levels), int(result.settings.prefilter.layout)),
                                          rmse, int(shadedDirections.size()), referenceMap(roughness).width()});
        sumSquares += rmse * rmse;
    }
    if (!errors.prefilterShaded.empty())
        errors.prefilterShadedRms = std::sqrt(sumSquares / double(errors.prefilterShaded.size()));

    // Irradiance at texel centres: each cube at the grid texels of its own size, the SH at
    // those of the shading cube (or of a 32^2 one when there is none).
    auto texelGridErrors = [&](const BakedTexture& cube, int size) {
        const auto texels = cubeTexelGrid(size, options.texelsPerFaceEdge);
        const CubeImage directions(size);
        std::vector<glm::dvec3> normals;
        for (const CubeTexelRef& t : texels)
            normals.push_back(glm::normalize(glm::dvec3(directions.texelDirection(t.face, t.x, t.row))));
        const std::vector<glm::dvec3> reference = reducedSums.irradiance(normals);
        if (!cube) {
            std::vector<glm::dvec3> sh;
            std::vector<glm::dvec3> shWindowed;
            for (const glm::dvec3& n : normals) {
                sh.push_back(evaluate(result.sh.irradiance, n));
                shWindowed.push_back(evaluate(result.sh.irradianceWindowed, n));
            }
            errors.shIrradiance = relativeErrors(sh, reference);
            errors.shIrradianceWindowed = relativeErrors(shWindowed, reference);
            return ErrorStats{};
        }
        return cubeIrradianceErrors(cube, texels, reference);
    };
    texelGridErrors({}, result.irradianceCube ? result.irradianceCube.size : 32);
    errors.irradianceReferenceWidth = reduced.width;
    errors.irradianceMethod = result.settings.irradiance;
    if (result.irradianceCube) errors.irradianceCube = texelGridErrors(result.irradianceCube, result.irradianceCube.size);

    // Irradiance as shaded: each cube read where shading reads it (bilinear, seamless) at the
    // Fibonacci directions, which counts the interpolation between texel centres that the
    // texel-centre numbers above leave out, and compares cubes of different sizes on the
    // same directions. A one-level cube read at roughness 0 is read at lod 0.
    std::vector<glm::vec4> irradianceQueries;
    for (const glm::dvec3& d : shadedDirections) irradianceQueries.emplace_back(glm::vec3(d), 0.0f);
    const std::vector<glm::dvec3> shadedReference = reducedSums.irradiance(shadedDirections);
    auto shadedIrradianceErrors = [&](const BakedTexture& cube) {
        const std::vector<glm::vec3> read = BakePasses(shaders).samplePrefiltered(cube, RoughnessLayout::Linear, irradianceQueries);
        return relativeErrors(std::vector<glm::dvec3>(read.begin(), read.end()), shadedReference);
    };
    std::vector<glm::dvec3> shShaded;
    for (const glm::dvec3& d : shadedDirections)
        shShaded.push_back(evaluate(result.sh.irradiance, d));
    errors.shIrradianceShaded = relativeErrors(shShaded, shadedReference);
    if (result.irradianceCube) errors.irradianceCubeShaded = shadedIrradianceErrors(result.irradianceCube);

    for (GeometryTerm term : kGeometryTerms) {
        const BakedTexture& lut = result.lut(term);
        if (!lut)
            continue;
        const Image2D image = read2D(lut);
        const int n = std::min(lut.size, options.lutGrid);
        double worst = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int x = (2 * i + 1) * lut.size / (2 * n);
                const int row = (2 * j + 1) * lut.size / (2 * n);
                const glm::dvec3 ref = integrateSplitSumBrdf((x + 0.5) / lut.size, (row + 0.5) / lut.size,
                                                             options.lutReferenceSamples, term);
                const glm::dvec3 d = glm::abs(glm::dvec3(glm::vec3(image.at(x, row))) - ref);
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
    return j.dump();
}

} // namespace iblab::bake
