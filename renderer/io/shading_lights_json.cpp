#include "io/shading_lights_json.hpp"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "io/error.hpp"

namespace iblab {
namespace {

nlohmann::ordered_json vec3Json(glm::vec3 v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); }

struct Reader {
    const std::string& file;
    [[noreturn]] void fail(const std::string& what) const { throw Error(file, what); }
    // Finite and within float's range: the lights are floats, and a larger double would not
    // convert to one.
    double number(const nlohmann::json& j, const std::string& what) const
    {
        if (!j.is_number() || !std::isfinite(j.get<double>()) || std::abs(j.get<double>()) > double(std::numeric_limits<float>::max()))
            fail(what + " is not a finite number");
        return j.get<double>();
    }
    int integer(const nlohmann::json& j, const char* key, int lo, int hi) const
    {
        if (!j.contains(key) || !j[key].is_number_integer() || j[key].get<int>() < lo || j[key].get<int>() > hi)
            fail(std::string(key) + " is not an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return j[key].get<int>();
    }
    glm::vec3 vec3(const nlohmann::json& j, std::size_t first, const std::string& what) const
    {
        if (!j.is_array() || j.size() < first + 3) fail(what + " is not 3 numbers");
        return glm::vec3(float(number(j[first], what)), float(number(j[first + 1], what)), float(number(j[first + 2], what)));
    }
    ShadingLight light(const nlohmann::json& direction, std::size_t d, const nlohmann::json& flux, std::size_t f) const
    {
        const ShadingLight l{vec3(direction, d, "a direction"), vec3(flux, f, "a flux")};
        if (std::abs(glm::length(l.direction) - 1.0f) > 1e-3f) fail("a direction is not a unit vector");
        if (l.flux.r < 0.0f || l.flux.g < 0.0f || l.flux.b < 0.0f) fail("a flux is negative");
        return l;
    }
};

} // namespace

nlohmann::ordered_json shadingLightsJson(const ShadingLights& lights)
{
    nlohmann::ordered_json groups = nlohmann::ordered_json::array();
    for (const ShadingLightGroup& g : lights.groups) {
        nlohmann::ordered_json points = nlohmann::ordered_json::array();
        for (const ShadingLight& p : g.points) points.push_back({p.direction.x, p.direction.y, p.direction.z, p.flux.r, p.flux.g, p.flux.b});
        groups.push_back({{"face", g.face}, {"x", g.x}, {"row", g.row}, {"keep", g.keep}, {"direction", vec3Json(g.light.direction)},
                          {"flux", vec3Json(g.light.flux)}, {"points", points}});
    }
    return {{"grid", lights.grid}, {"groups", groups}};
}

ShadingLights shadingLightsFromJson(const nlohmann::json& json, const std::string& file)
{
    const Reader r{file};
    if (!json.is_object() || !json.contains("groups") || !json["groups"].is_array()) r.fail("expected an object with grid and groups");
    ShadingLights lights;
    lights.grid = r.integer(json, "grid", 1, 4096);
    if (json["groups"].size() > std::size_t(kMaxShadingLights)) r.fail("more than " + std::to_string(kMaxShadingLights) + " groups");
    for (const nlohmann::json& g : json["groups"]) {
        if (!g.is_object() || !g.contains("direction") || !g.contains("flux") || !g.contains("points") || !g["points"].is_array() ||
            !g.contains("keep"))
            r.fail("a group lacks direction, flux, keep or points");
        ShadingLightGroup group;
        group.face = r.integer(g, "face", 0, 5);
        group.x = r.integer(g, "x", 0, lights.grid - 1);
        group.row = r.integer(g, "row", 0, lights.grid - 1);
        group.keep = float(r.number(g["keep"], "keep"));
        if (group.keep < 0.0f || group.keep > 1.0f) r.fail("keep is not in [0, 1]");
        group.light = r.light(g["direction"], 0, g["flux"], 0);
        for (const nlohmann::json& p : g["points"]) {
            if (!p.is_array() || p.size() != 6) r.fail("a point is not 6 numbers");
            group.points.push_back(r.light(p, 0, p, 3));
        }
        lights.groups.push_back(std::move(group));
    }
    return lights;
}

} // namespace iblab
