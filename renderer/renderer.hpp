#pragma once
// The frame renderer: environment, bake and scene in, tone-mapped frame out. Its public
// interface hides GL so that the UI and the app never issue GL calls; it needs a current
// 4.5 context.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ibl/image.hpp"
#include "settings.hpp"

namespace iblab {

namespace gl {
class ShaderLibrary;
}
namespace bake {
struct BakeResult;
}
struct ModelData;

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

struct SceneInfo {
    std::size_t draws = 0;
    std::size_t gpuBytes = 0;
    glm::vec3 centre{0.0f};      // of the bounding box, for framing the camera
    glm::vec3 halfExtents{1.0f};
};

// What the texel under the cursor of a debug view holds.
struct TexelProbe {
    bool valid = false;
    std::string text; // "mip 2 (roughness 0.50), face +Z, texel (12, 30): 0.412 0.380 0.301"
};

// The mean radiance over the central disc of one sphere of a procedural scene.
struct SphereReading {
    glm::vec2 pixel{0.0f}; // projected centre, y up
    glm::vec3 radiance{0.0f};
    float metallic = 0.0f;  // the draw's own factors (the grid's), else the sliders'
    float roughness = 0.0f;
};

struct ScreenLabel {
    glm::vec2 pixel{0.0f}; // y up
    std::string text;
    bool title = false;
};

class Renderer {
public:
    explicit Renderer(std::filesystem::path shaderDirectory);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads an equirect environment (with mips) for the background. The previous one
    // stays until this returns.
    void setEnvironment(const ImageRGB32F& equirect);
    // The baked IBL that lit surfaces use; until one is set only the background is drawn.
    void setBake(std::shared_ptr<const bake::BakeResult> bake);
    bool hasBake() const;
    // A bake of builtin:white used by ViewMode::Furnace (the app makes it on demand).
    void setFurnaceBake(std::shared_ptr<const bake::BakeResult> bake);
    bool hasFurnaceBake() const;
    // After a frame: per-sphere readings of the HDR frame (the furnace view prints them).
    std::vector<SphereReading> measureSpheres(const FrameSettings& settings) const;
    // A loaded glTF model for SceneKind::Model (uploads meshes and textures).
    void setModel(const ModelData& model, const std::string& path);

    // Renders the HDR frame and its tone-mapped display image at the given size.
    // resolutionScale < 1 renders fewer pixels (the view is scaled up when presented), for
    // interaction with expensive settings; accumulate averages successive frames of the
    // same settings with rotated sample sets (progressive refinement of the sampled method).
    struct Options {
        float resolutionScale = 1.0f;
        bool accumulate = false;
    };
    void renderFrame(const FrameSettings& settings, int width, int height, const Options& options);
    void renderFrame(const FrameSettings& settings, int width, int height) { renderFrame(settings, width, height, Options{}); }
    // Frames averaged into the current image (1 without accumulation).
    int accumulatedFrames() const;
    // Whether the last frame drew anything with the sampled method (whose frames differ
    // under accumulation); a frame without it is final after one render.
    bool lastFrameWasSampled() const;

    SceneInfo sceneInfo(const FrameSettings& settings);
    int prefilterLevels() const; // 0 before the first bake
    // The scene's text anchors (grid axes) projected for a width x height frame.
    std::vector<ScreenLabel> sceneLabels(const FrameSettings& settings, int width, int height) const;

    // The texel of the debug view under pixel (x, y) (y up) of a width x height frame.
    TexelProbe probe(const FrameSettings& settings, int width, int height, float x, float y) const;

    // GL name of the display texture (RGBA8, sRGB-encoded) for ImGui::Image or a blit.
    unsigned int displayTexture() const;
    // Copies the display image into a rectangle of the default framebuffer (y up).
    void presentToDefaultFramebuffer(int x0, int y0, int x1, int y1) const;

    // Binds the display image as the draw framebuffer (viewport included), for overlays
    // drawn into it after renderFrame.
    void bindDisplayFramebuffer() const;

    FrameReadback readHdrFrame() const;
    DisplayReadback readDisplayImage() const;

    // The shader library, for passes that run outside a frame (the bake).
    gl::ShaderLibrary& shaders();
    // Recompiles shaders edited on disk; returns compile errors (the old shaders stay).
    std::vector<std::string> reloadShaders();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace iblab
