#include "frame_capture.hpp"

#include <filesystem>

#include "io/error.hpp"
#include "io/image_writer.hpp"
#include "preset_json.hpp"

namespace iblab::app {

StatusReport writeCapture(const Renderer& renderer, const std::string& path, const FrameSettings& settings,
                          const bake::BakeSettings& bakeSettings)
{
    // What the frame was drawn with, bake included: loaded as a preset, it draws the same.
    const std::string settingsJson = presetJsonText(settings, bakeSettings, path);
    const std::string extension = std::filesystem::path(path).extension().string();
    try {
        if (extension == ".png") {
            const DisplayReadback image = renderer.readDisplayImage();
            writePng8(path, image.width, image.height, 4, image.rgba, {.bottomUp = true, .settingsJson = settingsJson});
        } else if (extension == ".exr") {
            // Opaque: the frame's alpha is its MSAA coverage, not an opacity of the
            // (unpremultiplied) colour, and would make compositing tools cut the silhouettes.
            FrameReadback image = renderer.readHdrFrame();
            for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 1.0f;
            writeExr(path, image.width, image.height, 4, image.rgba, {.bottomUp = true, .settingsJson = settingsJson});
        } else {
            return {path + ": unknown screenshot format \"" + extension + "\" (use .png or .exr)", true};
        }
    } catch (const Error& e) {
        return {e.what(), true};
    }
    return {"saved " + path + " (+ " + path + ".json)", false};
}

} // namespace iblab::app
