#pragma once
// The frame renderer: environment in, tone-mapped frame out. Its public interface hides
// GL so that the UI and the app never issue GL calls; it needs a current 4.5 context.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ibl/image.hpp"
#include "settings.hpp"

namespace iblab {

struct FrameReadback {
    int width = 0;
    int height = 0;
    std::vector<float> rgba; // linear HDR before exposure and tone mapping, bottom row first
};

struct DisplayReadback {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // sRGB-encoded 8-bit, bottom row first
};

class Renderer {
public:
    explicit Renderer(std::filesystem::path shaderDirectory);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads an equirect environment (with mips). The previous one stays until this returns.
    void setEnvironment(const ImageRGB32F& equirect);

    // Renders the HDR frame and its tone-mapped display image at the given size.
    void renderFrame(const FrameSettings& settings, int width, int height);

    // GL name of the display texture (RGBA8, sRGB-encoded) for ImGui::Image or a blit.
    unsigned int displayTexture() const;
    // Copies the display image to the default framebuffer, scaled to fill it.
    void presentToDefaultFramebuffer(int framebufferWidth, int framebufferHeight) const;

    FrameReadback readHdrFrame() const;
    DisplayReadback readDisplayImage() const;

    // Recompiles shaders edited on disk; returns compile errors (the old shaders stay).
    std::vector<std::string> reloadShaders();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace iblab
