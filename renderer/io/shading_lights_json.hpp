#pragma once
// The shading lights (ibl/shading_lights.hpp) as bake.json stores them, so that a bake read
// back (the cache, `iblab bake --out`, the accuracy study) shades with the lights it was made
// with:
//   {"grid": 64, "groups": [{"face": f, "x": x, "row": r, "keep": k,
//                            "direction": [x, y, z], "flux": [r, g, b],
//                            "points": [[x, y, z, r, g, b], ...]}, ...]}
#include <string>

#include <nlohmann/json.hpp>

#include "ibl/shading_lights.hpp"

namespace iblab {

nlohmann::ordered_json shadingLightsJson(const ShadingLights& lights);
// Throws Error(subject, what is wrong) on anything but the form above with finite numbers,
// unit directions, non-negative flux, keep in [0, 1] and groups on the grid.
ShadingLights shadingLightsFromJson(const nlohmann::json& json, const std::string& subject);

} // namespace iblab
