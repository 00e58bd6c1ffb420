#include "bake/standalone_passes.hpp"

#include <chrono>

#include <epoxy/gl.h>

#include "bake/bake_passes.hpp"

namespace iblab::bake {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

TimedSh9 projectSh9OnGpu(gl::ShaderLibrary& shaders, const ImageRGB32F& equirect)
{
    BakePasses passes(shaders);
    passes.compileFor(BakeSettings{}, 0, /*lut=*/false);
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    const gl::Texture texture = passes.uploadEquirect(equirect);
    TimedSh9 result;
    result.radiance = passes.projectSh9(texture.id(), equirect.width, equirect.height);
    result.ms = millisecondsSince(start);
    return result;
}

TimedLut bakeBrdfLut(gl::ShaderLibrary& shaders, int size, int samples, GeometryTerm term)
{
    BakePasses passes(shaders);
    passes.compileFor(BakeSettings{}, 0, /*lut=*/true);
    const auto start = std::chrono::steady_clock::now();
    TimedLut result{create2DTexture(GL_RGBA16F, size)};
    passes.brdfLut(result.lut, 0, size, samples, term);
    glFinish();
    result.ms = millisecondsSince(start);
    return result;
}

} // namespace iblab::bake
