#include "frame/accumulation_pass.hpp"

#include <cmath>

#include "frame/texture_units.hpp"

namespace iblab {
namespace {

// The n-th point of the R2 sequence (Roberts 2018): a low-discrepancy sequence of
// Cranley-Patterson rotations, so frame n's sample set fills the gaps of frames 0..n-1.
glm::vec2 r2Rotation(int n)
{
    constexpr double g = 1.32471795724474602596; // the plastic number
    return glm::vec2(float(std::fmod(double(n) / g, 1.0)), float(std::fmod(double(n) / (g * g), 1.0)));
}

} // namespace

glm::vec2 AccumulationPass::begin(std::optional<FrameKey> key)
{
    if (!key || key != key_) frames_ = 0;
    key_ = std::move(key);
    return frames_ == 0 ? glm::vec2(0.0f) : r2Rotation(frames_);
}

const gl::RenderTarget& AccumulationPass::add(const gl::RenderTarget& frame)
{
    if (!key_) {
        frames_ = 1;
        return frame;
    }
    mean_.ensure(GL_RGBA32F, frame.width(), frame.height());
    glBindFramebuffer(GL_FRAMEBUFFER, mean_.framebuffer());
    glViewport(0, 0, frame.width(), frame.height());
    const gl::ShaderProgram& program = shaders_.program({"fullscreen.vert", "accumulate.frag"});
    glUseProgram(program.id());
    glBindTextureUnit(kUnitHdrFrame, frame.texture());
    glEnable(GL_BLEND);
    // Radiance into the running mean; coverage replaced, because a blend of equal
    // coverages is not always bit-exact and "fully covered" means exactly 1.
    glBlendFuncSeparate(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_ONE, GL_ZERO);
    glBlendColor(0.0f, 0.0f, 0.0f, 1.0f / float(frames_ + 1));
    triangle_.draw();
    glDisable(GL_BLEND);
    ++frames_;
    return mean_;
}

} // namespace iblab
