#include "frame/display_passes.hpp"

#include <algorithm>

#include "frame/texture_units.hpp"

namespace iblab {
namespace {

struct ToneMapUniforms {
    explicit ToneMapUniforms(const gl::ShaderProgram& p) : exposureEv(p, "uExposureEv"), toneMapOperator(p, "uToneMapOperator") {}
    gl::Uniform<float> exposureEv;
    gl::Uniform<int> toneMapOperator;
};

struct ErrorViewUniforms {
    explicit ErrorViewUniforms(const gl::ShaderProgram& p)
        : exposureEv(p, "uExposureEv"), toneMapOperator(p, "uToneMapOperator"), displaySpace(p, "uDisplaySpace"), errorScale(p, "uErrorScale")
    {
    }
    gl::Uniform<float> exposureEv;
    gl::Uniform<int> toneMapOperator;
    gl::Uniform<bool> displaySpace;
    gl::Uniform<float> errorScale;
};

} // namespace

void ToneMapPass::draw(GLuint hdrFrame, const ToneMapSettings& toneMap, bool dataOnly)
{
    const gl::ShaderProgram& program = shaders_.program({"fullscreen.vert", "tonemap.frag"});
    const ToneMapUniforms& u = program.uniforms<ToneMapUniforms>();
    glUseProgram(program.id());
    u.exposureEv.set(dataOnly ? 0.0f : toneMap.exposureEv);
    u.toneMapOperator.set(int(dataOnly ? ToneMapOperator::None : toneMap.op));
    glBindTextureUnit(kUnitHdrFrame, hdrFrame);
    triangle_.draw();
}

void ErrorViewPass::draw(GLuint hdrFrame, GLuint referenceFrame, GLuint referenceNormals, const FrameSettings& settings)
{
    const gl::ShaderProgram& program = shaders_.program({"fullscreen.vert", "error_view.frag"});
    const ErrorViewUniforms& u = program.uniforms<ErrorViewUniforms>();
    glUseProgram(program.id());
    u.exposureEv.set(settings.toneMap.exposureEv);
    u.toneMapOperator.set(int(settings.toneMap.op));
    u.displaySpace.set(settings.view.errorSpace == ErrorSpace::Display);
    u.errorScale.set(std::max(settings.view.errorScale, 1e-6f));
    glBindTextureUnit(kUnitHdrFrame, hdrFrame);
    glBindTextureUnit(kUnitReferenceFrame, referenceFrame);
    glBindTextureUnit(kUnitGNormal, referenceNormals);
    triangle_.draw();
}

} // namespace iblab
