#pragma once
// Screenshots: the last rendered frame written with the settings it was drawn with.
#include <string>

#include "bake/bake_settings.hpp"
#include "frame/renderer.hpp"
#include "status_report.hpp"

namespace iblab::app {

// Writes the renderer's last frame: .png = tone-mapped sRGB, .exr = linear HDR, both with
// the settings (bake included) embedded and in a .json sidecar.
StatusReport writeCapture(const Renderer& renderer, const std::string& path, const FrameSettings& settings,
                          const bake::BakeSettings& bakeSettings);

} // namespace iblab::app
