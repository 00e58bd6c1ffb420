#include "lab_session.hpp"

#include <filesystem>

#include "asset_paths.hpp"
#include "environment/builtin_environments.hpp"
#include "environment/error.hpp"
#include "environment/image_writer.hpp"

namespace iblab::app {

std::string defaultEnvironmentSpec() { return defaultEnvironmentPath(assetDirectory().string()); }

ui::StatusLine LabSession::loadEnvironment(const std::string& spec, FrameSettings& settings)
{
    try {
        Environment loaded = iblab::loadEnvironment(spec);
        renderer_.setEnvironment(loaded.image);
        std::string text = loaded.source + ": " + std::to_string(loaded.image.width) + "x" + std::to_string(loaded.image.height);
        // Repairs, downsampling and LDR input are all among the loader's warnings.
        for (const auto& warning : loaded.warnings) text += "; " + warning;
        environment_ = std::move(loaded);
        settings.environment.source = spec;
        return {text, false};
    } catch (const Error& e) {
        return {e.what(), true};
    }
}

ui::StatusLine LabSession::capture(const std::string& path, const FrameSettings& settings) const
{
    const std::string settingsJson = toJsonText(settings);
    const std::string extension = std::filesystem::path(path).extension().string();
    try {
        if (extension == ".png") {
            const DisplayReadback image = renderer_.readDisplayImage();
            writePng8(path, image.width, image.height, 4, image.rgba, {.bottomUp = true, .settingsJson = settingsJson});
        } else if (extension == ".exr") {
            const FrameReadback image = renderer_.readHdrFrame();
            writeExr(path, image.width, image.height, 4, image.rgba, {.bottomUp = true, .settingsJson = settingsJson});
        } else {
            return {path + ": unknown screenshot format \"" + extension + "\" (use .png or .exr)", true};
        }
    } catch (const Error& e) {
        return {e.what(), true};
    }
    return {"saved " + path + " (+ " + path + ".json)", false};
}

ui::EnvironmentCatalog LabSession::catalog() const
{
    ui::EnvironmentCatalog catalog;
    catalog.gallery = galleryEnvironments(assetDirectory().string());
    for (const auto& name : builtinEnvironmentNames()) catalog.builtins.push_back("builtin:" + name);
    return catalog;
}

} // namespace iblab::app
