#pragma once
// The plain parameter structs that the UI edits, the CLI fills and the renderer reads.
// Everything a screenshot needs to be reproduced is in here and serialises to JSON.
#include <string>

#include "ibl/tonemap.hpp"

namespace iblab {

struct EnvironmentSettings {
    std::string source;       // a file path or builtin:NAME
    float yawDegrees = 0.0f;  // rotation about +Y; +90 brings what was at +X in front of the default camera
    float intensityEv = 0.0f; // radiance scale in stops
};

struct ToneMapSettings {
    ToneMapOperator op = ToneMapOperator::AcesHill;
    float exposureEv = 0.0f;
};

// An orbit camera around a target; at yaw = pitch = 0 it looks down -Z.
struct CameraSettings {
    float yawDegrees = 0.0f;    // positive turns right: +90 looks down +X
    float pitchDegrees = 0.0f;  // positive looks up
    float fovDegrees = 60.0f;   // vertical field of view
    float distance = 3.0f;
};

struct FrameSettings {
    EnvironmentSettings environment;
    ToneMapSettings toneMap;
    CameraSettings camera;
};

// JSON text of the settings (for screenshots' metadata and sidecars, and presets).
std::string toJsonText(const FrameSettings& settings, int indent = 2);
// Throws std::runtime_error naming the offending key.
FrameSettings frameSettingsFromJsonText(const std::string& text);

} // namespace iblab
