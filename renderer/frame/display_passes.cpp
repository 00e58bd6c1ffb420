#include "frame/display_passes.hpp"

#include <algorithm>

#include "frame/texture_units.hpp"

namespace iblab {
namespace {

struct ToneMapUniforms {
    explicit ToneMapUniforms(const gl::ShaderProgram& p) : exposureEv(p, "uExposureEv") {}
    gl::Uniform<float> exposureEv;
};

struct ErrorViewUniforms {
    explicit ErrorViewUniforms(const gl::ShaderProgram& p)
        : exposureEv(p, "uExposureEv"), displaySpace(p, "uDisplaySpace"), errorScale(p, "uErrorScale")
    {
    }
    gl::Uniform<float> exposureEv;
    gl::Uniform<bool> displaySpace;
    gl::Uniform<float> errorScale;
};

// The operator is compiled in (tonemap.frag says why): one program per operator used.
gl::ShaderDefines toneMapDefines(ToneMapOperator op) { return {{"TONEMAP_OPERATOR", std::to_string(int(op))}}; }

} // namespace

void ToneMapPass::draw(GLuint hdrFrame, const ToneMapSettings& toneMap, bool dataOnly)
{
    const gl::ShaderProgram& program =
        shaders_.program({"fullscreen.vert", "tonemap.frag"}, toneMapDefines(dataOnly ? ToneMapOperator::None : toneMap.op));
    const ToneMapUniforms& u = program.uniforms<ToneMapUniforms>();
    glUseProgram(program.id());
    u.exposureEv.set(dataOnly ? 0.0f : toneMap.exposureEv);
    glBindTextureUnit(kUnitHdrFrame, hdrFrame);
    triangle_.draw();
}

void ErrorViewPass::draw(GLuint hdrFrame, GLuint referenceFrame, GLuint referenceNormals, const FrameSettings& settings)
{
    const gl::ShaderProgram& program = shaders_.program({"fullscreen.vert", "error_view.frag"}, toneMapDefines(settings.toneMap.op));
    const ErrorViewUniforms& u = program.uniforms<ErrorViewUniforms>();
    glUseProgram(program.id());
    u.exposureEv.set(settings.toneMap.exposureEv);
    u.displaySpace.set(settings.view.errorSpace == ErrorSpace::Display);
    u.errorScale.set(std::max(settings.view.errorScale, 1e-6f));
    glBindTextureUnit(kUnitHdrFrame, hdrFrame);
    glBindTextureUnit(kUnitReferenceFrame, referenceFrame);
    glBindTextureUnit(kUnitGNormal, referenceNormals);
    triangle_.draw();
}

} // namespace iblab
