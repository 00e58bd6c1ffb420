#include "renderer.hpp"

#include <cmath>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "camera.hpp"
#include "gl/handles.hpp"
#include "gl/render_target.hpp"
#include "gl/shader_library.hpp"

namespace iblab {

struct Renderer::Impl {
    gl::ShaderLibrary shaders;
    gl::VertexArray emptyVertexArray = gl::createVertexArray();
    gl::Texture equirect;
    gl::RenderTarget hdrFrame;     // RGBA16F: the linear frame the tone mapper reads
    gl::RenderTarget displayFrame; // RGBA8: exposure, tone curve and sRGB applied

    explicit Impl(std::filesystem::path shaderDirectory) : shaders(std::move(shaderDirectory)) {}

    void drawFullscreenTriangle() const
    {
        glBindVertexArray(emptyVertexArray.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
};

Renderer::Renderer(std::filesystem::path shaderDirectory) : impl_(std::make_unique<Impl>(std::move(shaderDirectory))) {}
Renderer::~Renderer() = default;

void Renderer::setEnvironment(const ImageRGB32F& image)
{
    const int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
    gl::Texture texture = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), levels, GL_RGB32F, image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGB, GL_FLOAT, image.texels.data());
    glGenerateTextureMipmap(texture.id());
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    impl_->equirect = std::move(texture);
}

void Renderer::renderFrame(const FrameSettings& settings, int width, int height)
{
    Impl& r = *impl_;
    r.hdrFrame.ensure(GL_RGBA16F, width, height);
    r.displayFrame.ensure(GL_RGBA8, width, height);

    // Sky: rotation-only view so that the background sits at infinity.
    const float aspect = float(width) / float(height);
    const glm::mat4 viewRotation = glm::mat4(glm::mat3(cameraView(settings.camera)));
    const glm::mat4 inverseViewProjection = glm::inverse(cameraProjection(settings.camera, aspect) * viewRotation);

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER, r.hdrFrame.framebuffer());
    glViewport(0, 0, width, height);
    const gl::ShaderProgram& sky = r.shaders.program({"fullscreen.vert", "sky.frag"});
    glUseProgram(sky.id());
    sky.set("uInverseViewProjection", inverseViewProjection);
    sky.set("uEnvironmentYaw", glm::radians(settings.environment.yawDegrees));
    sky.set("uEnvironmentIntensity", std::exp2(settings.environment.intensityEv));
    sky.set("uEquirect", 0);
    glBindTextureUnit(0, r.equirect.id());
    r.drawFullscreenTriangle();

    glBindFramebuffer(GL_FRAMEBUFFER, r.displayFrame.framebuffer());
    const gl::ShaderProgram& tonemap = r.shaders.program({"fullscreen.vert", "tonemap.frag"});
    glUseProgram(tonemap.id());
    tonemap.set("uHdrFrame", 0);
    tonemap.set("uExposureEv", settings.toneMap.exposureEv);
    tonemap.set("uToneMapOperator", int(settings.toneMap.op));
    glBindTextureUnit(0, r.hdrFrame.texture());
    r.drawFullscreenTriangle();

    glBindTextureUnit(0, 0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

unsigned int Renderer::displayTexture() const { return impl_->displayFrame.texture(); }

void Renderer::presentToDefaultFramebuffer(int framebufferWidth, int framebufferHeight) const
{
    const gl::RenderTarget& display = impl_->displayFrame;
    glBlitNamedFramebuffer(display.framebuffer(), 0, 0, 0, display.width(), display.height(), 0, 0, framebufferWidth,
                           framebufferHeight, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

FrameReadback Renderer::readHdrFrame() const
{
    const gl::RenderTarget& hdr = impl_->hdrFrame;
    FrameReadback result{hdr.width(), hdr.height(), {}};
    result.rgba.resize(std::size_t(hdr.width()) * std::size_t(hdr.height()) * 4);
    glGetTextureImage(hdr.texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(result.rgba.size() * sizeof(float)), result.rgba.data());
    return result;
}

DisplayReadback Renderer::readDisplayImage() const
{
    const gl::RenderTarget& display = impl_->displayFrame;
    DisplayReadback result{display.width(), display.height(), {}};
    result.rgba.resize(std::size_t(display.width()) * std::size_t(display.height()) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(display.texture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(result.rgba.size()), result.rgba.data());
    return result;
}

std::vector<std::string> Renderer::reloadShaders() { return impl_->shaders.reloadChanged(); }

} // namespace iblab
