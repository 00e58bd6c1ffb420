#include "settings.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

namespace iblab {

std::string toJsonText(const FrameSettings& s, int indent)
{
    nlohmann::ordered_json j;
    j["environment"] = {{"source", s.environment.source}, {"yaw_degrees", s.environment.yawDegrees}, {"intensity_ev", s.environment.intensityEv}};
    j["tone_map"] = {{"operator", std::string(toneMapOperatorName(s.toneMap.op))}, {"exposure_ev", s.toneMap.exposureEv}};
    j["camera"] = {{"yaw_degrees", s.camera.yawDegrees},
                   {"pitch_degrees", s.camera.pitchDegrees},
                   {"fov_degrees", s.camera.fovDegrees},
                   {"distance", s.camera.distance}};
    return j.dump(indent);
}

FrameSettings frameSettingsFromJsonText(const std::string& text)
{
    const nlohmann::json j = nlohmann::json::parse(text);
    FrameSettings s;
    auto read = [](const nlohmann::json& object, const char* key, auto& target) {
        if (object.contains(key)) target = object.at(key).get<std::remove_reference_t<decltype(target)>>();
    };
    if (j.contains("environment")) {
        const auto& e = j["environment"];
        read(e, "source", s.environment.source);
        read(e, "yaw_degrees", s.environment.yawDegrees);
        read(e, "intensity_ev", s.environment.intensityEv);
    }
    if (j.contains("tone_map")) {
        const auto& t = j["tone_map"];
        if (t.contains("operator")) {
            const auto op = parseToneMapOperator(t["operator"].get<std::string>());
            if (!op) throw std::runtime_error("tone_map.operator: unknown operator \"" + t["operator"].get<std::string>() + "\"");
            s.toneMap.op = *op;
        }
        read(t, "exposure_ev", s.toneMap.exposureEv);
    }
    if (j.contains("camera")) {
        const auto& c = j["camera"];
        read(c, "yaw_degrees", s.camera.yawDegrees);
        read(c, "pitch_degrees", s.camera.pitchDegrees);
        read(c, "fov_degrees", s.camera.fovDegrees);
        read(c, "distance", s.camera.distance);
    }
    return s;
}

} // namespace iblab
