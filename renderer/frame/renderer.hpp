#pragma once
// The frame renderer: environment, bake and scene in, tone-mapped frame out. Its public
// interface hides GL so that the UI and the app never issue GL calls; it needs a current
// 4.5 context. Inside it is a set of passes run by one coordinator (renderer.cpp says which
// pass reads and writes what) and a reference renderer (reference_renderer.hpp).
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "frame/frame_analysis.hpp"
#include "frame/readback.hpp"
#include "frame/reference_types.hpp"
#include "frame/settings.hpp"
#include "frame/split_view.hpp"
#include "ibl/image.hpp"

namespace iblab {

namespace gl {
class ShaderLibrary;
}
namespace bake {
struct BakeResult;
}
struct ModelData;

struct SceneInfo {
    std::size_t draws = 0;
    std::size_t gpuBytes = 0;
    glm::vec3 centre{0.0f};      // of the bounding box, for framing the camera
    glm::vec3 halfExtents{1.0f};
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
    // The bake's shading lights the fitted lobe sums (0 without), and what setBake spent
    // making the cube without them (the read-back, the residual, the upload).
    struct ShadingLightsInfo {
        int count = 0;
        double milliseconds = 0.0;
    };
    ShadingLightsInfo shadingLights() const;
    // A bake of builtin:white used by ViewMode::Furnace (the app makes it on demand).
    void setFurnaceBake(std::shared_ptr<const bake::BakeResult> bake);
    bool hasFurnaceBake() const;
    // After a frame: per-sphere readings of the HDR frame (the furnace view prints them).
    std::vector<SphereReading> measureSpheres(const FrameSettings& settings) const;
    // A loaded glTF model for SceneKind::Model (uploads meshes and textures).
    void setModel(const ModelData& model, const std::string& path);
    // Counts the calls above that change what a frame shows besides its settings
    // (setBake, setFurnaceBake, setModel, and setEnvironment while no bake is set: the
    // sky shows the bake's environment cube once there is one). Accumulation restarts when it
    // moves; the app may key its own "is this frame final" on it too.
    std::uint64_t contentRevision() const;

    // Renders the HDR frame and its tone-mapped display image at the given size. With the
    // split view, pixels from splitColumn on are rendered with view.compare as sampling.
    // ViewMode::Error shows the frame's error in false colour once advanceReference has
    // completed the reference of these settings and size, and the plain frame until then.
    // resolutionScale < 1 renders fewer pixels (the view is scaled up when presented), for
    // interaction with expensive settings; accumulate averages successive frames of the
    // same settings and content revision with rotated sample sets (progressive refinement
    // of the sampled method), except where keepsExactSampleCount holds (for both sides of
    // the split view): those frames stay one set of N samples per pixel. The lit frame is
    // drawn with ViewSettings::msaaSamples per pixel and resolved.
    struct Options {
        float resolutionScale = 1.0f;
        bool accumulate = false;
        // renderFrameSlice: the caller's estimate of the whole frame's time in milliseconds
        // (0: none), so that the first bands of a frame with new settings fit the budget.
        double expectedMs = 0.0;
    };
    void renderFrame(const FrameSettings& settings, int width, int height, const Options& options);
    void renderFrame(const FrameSettings& settings, int width, int height) { renderFrame(settings, width, height, Options{}); }
    // The same frame drawn over several calls, so that a frame that takes seconds on a
    // software renderer never holds the UI for longer than `budget`: each call draws bands of
    // rows until the budget is spent (glFinish after each, so that it is GPU time) and
    // returns true once the last band is in; then the frame is finished as renderFrame
    // finishes it. Until then the image on screen, the running mean and the readbacks stay
    // those of the last complete frame. A call with other settings, size, options or content
    // starts over; renderFrame abandons a frame under way.
    bool renderFrameSlice(const FrameSettings& settings, int width, int height, const Options& options, std::chrono::steady_clock::duration budget);
    // How much of the sliced frame under way is drawn (0 when none is).
    float sliceProgress() const;
    // The time the bands of the last complete sliced frame took together, in milliseconds.
    double lastSlicedFrameMs() const;
    // Frames averaged into the current image (1 without accumulation).
    int accumulatedFrames() const;
    // Whether the last frame drew anything with the sampled method and a sample set that
    // rotates under accumulation (so later frames differ); a frame without it is final
    // after one render.
    bool lastFrameWasSampled() const;
    // MSAA samples per pixel of the last frame: msaaSamples as the driver allocated it
    // (clamped to the most it supports, or raised to the next count it has); 1 for the
    // debug views of baked data.
    int frameSamples() const;

    // The reference renderer: the frame of these settings at this size with the full
    // integral over the (downsampled) environment's texels, no split sum and no N = V = R.
    // Starts it when the settings, size, slicing, environment or model changed (the mesh
    // pass fills a G-buffer at once), then runs slices until `budget` is spent (each
    // waits on a fence after the one before it, so the budget is GPU time) or it is complete; a complete reference is
    // resolved into an RGBA32F frame. Needs a bake, like any lit frame.
    ReferenceStatus advanceReference(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget,
                                     const ReferenceSlicing& slicing = {});
    ReferenceStatus referenceStatus(const FrameSettings& settings, int width, int height) const;
    FrameReadback readReferenceFrame() const; // of the last complete reference
    FrameReadback readReferenceLayer(ReferenceLayer layer) const;
    // Compares the last rendered frame with the reference (ViewSettings::errorSpace decides
    // linear HDR or display values); invalid unless the reference of that frame is complete.
    // Measures the pixels that the reference covers at their centre and the frame's
    // surfaces cover entirely (isMeasuredPixel): an MSAA edge pixel mixes in the sky, which
    // the single-sampled reference does not, so it is left out like the background.
    ErrorReport measureError(const FrameSettings& settings) const;

    SceneInfo sceneInfo(const FrameSettings& settings);
    std::vector<float> prefilterMipRoughness() const; // the roughness of each prefiltered mip; empty before the first bake
    // The scene's text anchors (grid axes) projected for a width x height frame.
    std::vector<ScreenLabel> sceneLabels(const FrameSettings& settings, int width, int height) const;

    // The texel of the debug view under pixel (x, y) (y up) of a width x height frame.
    TexelProbe probe(const FrameSettings& settings, int width, int height, float x, float y) const;

    // GL name of the display texture (RGBA8, sRGB-encoded) for ImGui::Image or a blit.
    unsigned int displayTexture() const;
    // Copies the display image into a rectangle (y up) of a framebuffer (0: the window's).
    void presentTo(unsigned int framebuffer, int x0, int y0, int x1, int y1) const;

    // Binds the display image as the draw framebuffer (viewport included), for overlays
    // drawn into it after renderFrame.
    void bindDisplayFramebuffer() const;

    FrameReadback readHdrFrame() const;
    DisplayReadback readDisplayImage() const;

    // The shader library, for passes that run outside a frame (the bake).
    gl::ShaderLibrary& shaders();
    // Recompiles shaders edited on disk; returns compile errors (the old shaders stay). A
    // shader that did change restarts the running mean and the reference.
    std::vector<std::string> reloadShaders();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace iblab
