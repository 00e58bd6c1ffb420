#pragma once
// What the GUI and the headless commands share: which environment is loaded (and what
// loading it found), and writing screenshots with their settings.
#include <optional>
#include <string>

#include "environment/environment.hpp"
#include "panels.hpp"
#include "renderer.hpp"

namespace iblab::app {

std::string defaultEnvironmentSpec();

class LabSession {
public:
    explicit LabSession(Renderer& renderer) : renderer_(renderer) {}

    // Loads spec (a path or builtin:NAME). On success the renderer gets it and
    // settings.environment.source is updated; on failure the current environment stays
    // and the returned status holds the one-line error.
    ui::StatusLine loadEnvironment(const std::string& spec, FrameSettings& settings);
    // Writes the last rendered frame: .png = tone-mapped sRGB, .exr = linear HDR, both with
    // the settings embedded and in a .json sidecar.
    ui::StatusLine capture(const std::string& path, const FrameSettings& settings) const;

    ui::EnvironmentCatalog catalog() const;
    const std::optional<Environment>& environment() const { return environment_; }

private:
    Renderer& renderer_;
    std::optional<Environment> environment_;
};

} // namespace iblab::app
