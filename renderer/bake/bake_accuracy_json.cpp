// The bake's error report as JSON (bake --json's "errors"), apart from the measurements
// (bake_accuracy.cpp) so that each stays one concern.
#include "bake/bake_accuracy.hpp"

#include <nlohmann/json.hpp>

namespace iblab::bake {
namespace {

nlohmann::ordered_json statsJson(const ErrorStats& s)
{
    return {{"mean_relative", s.mean}, {"max_relative", s.max}, {"directions", s.directions}};
}

} // namespace

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
    if (errors.shIrradianceWithLightsShaded) irrShaded["sh_with_lights"] = statsJson(*errors.shIrradianceWithLightsShaded);
    if (errors.shIrradianceWindowedWithLightsShaded)
        irrShaded["sh_windowed_with_lights"] = statsJson(*errors.shIrradianceWindowedWithLightsShaded);
    if (errors.irradianceCubeWithLightsShaded) irrShaded[cubeKey + "_with_lights"] = statsJson(*errors.irradianceCubeWithLightsShaded);
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
                  "irradiance_shaded: the same for each cube read bilinearly and seamlessly at the Fibonacci directions (*_with_lights, where the bake "
                  "found shading lights: as the fitted lobe shades it, the source less the lights plus each light's flux max(0, n.l)); references for roughness >= 0.5 and irradiance on the "
                  "environment halved to at most " +
                  std::to_string(options.maxReferenceWidthForWideLobes) + " wide; LUT: max abs error on a " +
                  std::to_string(options.lutGrid) + "x" + std::to_string(options.lutGrid) + " texel grid against " +
                  std::to_string(options.lutReferenceSamples) + "-sample CPU integration";
    j["milliseconds"] = errors.milliseconds;
    j["references"] = {{"from_cache", errors.referencesFromCache}, {"milliseconds", errors.referenceMilliseconds}};
    return j.dump();
}

} // namespace iblab::bake
