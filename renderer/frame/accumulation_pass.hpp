#pragma once
// The accumulation pass (accumulate.frag): the running mean of successive frames of one
// FrameKey, each drawn with its own rotation of the sample set, so that the sampled method
// refines while nothing changes.
//   reads:  the resolved HDR frame
//   writes: the RGBA32F running mean (radiance blended in with weight 1 / (n + 1),
//           coverage replaced)
#include <optional>

#include <glm/vec2.hpp>

#include "frame/frame_key.hpp"
#include "frame/fullscreen_triangle.hpp"
#include "gl/render_target.hpp"
#include "gl/shader_library.hpp"

namespace iblab {

class AccumulationPass {
public:
    AccumulationPass(gl::ShaderLibrary& shaders, const FullscreenTriangle& triangle) : shaders_(shaders), triangle_(triangle) {}

    // Before drawing a frame: continues the running mean when key is the one it holds, else
    // starts over (std::nullopt: no accumulation, the frame stands alone). Returns the
    // Cranley-Patterson rotation of this frame's sample set: none for the first frame.
    glm::vec2 begin(std::optional<FrameKey> key);
    // After drawing it: adds frame to the running mean and returns the mean, or, without
    // accumulation, returns frame itself.
    const gl::RenderTarget& add(const gl::RenderTarget& frame);
    // Frames averaged into the current image (1 without accumulation).
    int frames() const { return frames_; }

private:
    gl::ShaderLibrary& shaders_;
    const FullscreenTriangle& triangle_;
    gl::RenderTarget mean_;         // RGBA32F
    std::optional<FrameKey> key_;   // what the running mean belongs to
    int frames_ = 0;
};

} // namespace iblab
