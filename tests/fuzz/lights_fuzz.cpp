// libFuzzer target: any bytes as bake.json's shading_lights (io/shading_lights_json.hpp), the
// JSON parse and then the reader. It must return lights of the form it promises (at most
// kMaxShadingLights groups on the grid, unit directions, flux >= 0, keep in [0, 1]) or throw
// iblab::Error; anything else is a bug.
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "io/error.hpp"
#include "io/shading_lights_json.hpp"

namespace {

void checkLight(const iblab::ShadingLight& l)
{
    if (!(std::abs(glm::length(l.direction) - 1.0f) <= 1e-3f)) __builtin_trap();
    if (!(l.flux.r >= 0.0f && l.flux.g >= 0.0f && l.flux.b >= 0.0f)) __builtin_trap();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const nlohmann::json json = nlohmann::json::parse(data, data + size, nullptr, false);
    if (json.is_discarded()) return 0;
    try {
        const iblab::ShadingLights lights = iblab::shadingLightsFromJson(json, "fuzz.json");
        if (lights.grid < 1 || lights.groups.size() > std::size_t(iblab::kMaxShadingLights)) __builtin_trap();
        for (const iblab::ShadingLightGroup& g : lights.groups) {
            if (g.face < 0 || g.face > 5 || g.x < 0 || g.x >= lights.grid || g.row < 0 || g.row >= lights.grid) __builtin_trap();
            if (!(g.keep >= 0.0f && g.keep <= 1.0f)) __builtin_trap();
            checkLight(g.light);
            for (const iblab::ShadingLight& p : g.points) checkLight(p);
        }
    } catch (const iblab::Error&) {
    }
    return 0;
}
