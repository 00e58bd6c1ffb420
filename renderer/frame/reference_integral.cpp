#include "frame/reference_integral.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "frame/texture_units.hpp"
#include "gl/uniform.hpp"
#include "ibl/equirect.hpp"

namespace iblab {
namespace {

gl::Texture createFloatTexture(GLenum internalFormat, int width, int height)
{
    gl::Texture texture = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), 1, internalFormat, width, height);
    // Every read is a texelFetch of one pixel's or one texel's own value.
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

// Roughly 10 ms of llvmpipe time on two cores per slice (measured: the 256 x 128 reference
// of the default sphere at 128 x 128 pixels, at most 16 tiles x 16 bands, took 2.2 s): small
// enough for a frame's budget, large enough that dispatch overhead is noise.
constexpr long kEvaluationsPerSlice = 1L << 21;

struct IntegralUniforms {
    explicit IntegralUniforms(const gl::ShaderProgram& p)
        : tileOrigin(p, "uTileOrigin"), tileEnd(p, "uTileEnd"), firstRow(p, "uFirstRow"), endRow(p, "uEndRow"), geometry(p, "uGeometry")
    {
    }
    gl::Uniform<glm::ivec2> tileOrigin;
    gl::Uniform<glm::ivec2> tileEnd;
    gl::Uniform<int> firstRow;
    gl::Uniform<int> endRow;
    gl::Uniform<int> geometry;
};

} // namespace

void GBuffer::ensure(int width, int height)
{
    if (framebuffer_ && width == width_ && height == height_) return;
    if (width <= 0 || height <= 0) throw std::invalid_argument("G-buffer size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
    gl::Framebuffer framebuffer = gl::createFramebuffer();
    std::array<GLenum, std::size_t(ReferenceLayer::Count)> drawBuffers{};
    for (std::size_t i = 0; i < layers_.size(); ++i) {
        layers_[i] = createFloatTexture(GL_RGBA32F, width, height);
        glNamedFramebufferTexture(framebuffer.id(), GLenum(GL_COLOR_ATTACHMENT0 + i), layers_[i].id(), 0);
        drawBuffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    }
    glNamedFramebufferDrawBuffers(framebuffer.id(), GLsizei(drawBuffers.size()), drawBuffers.data());
    depth_ = gl::createRenderbuffer();
    glNamedRenderbufferStorage(depth_.id(), GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferRenderbuffer(framebuffer.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) throw std::runtime_error("reference G-buffer is incomplete (status " + std::to_string(status) + ")");
    framebuffer_ = std::move(framebuffer);
    width_ = width;
    height_ = height;
}

void GBuffer::bindCleared() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width_, height_);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (GLint i = 0; i < GLint(layers_.size()); ++i) glClearBufferfv(GL_COLOR, i, zero);
    const float farDepth = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &farDepth);
}

void ReferenceIntegral::start(const ImageRGB32F& environment, int width, int height, const std::vector<std::uint8_t>& coverage,
                              const ReferenceSlicing& slicing)
{
    if (coverage.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("reference coverage has " + std::to_string(coverage.size()) + " pixels for " + std::to_string(width) + "x" +
                                    std::to_string(height));
    if (slicing.tileSize < 1 || slicing.rowsPerSlice < 0) throw std::invalid_argument("reference slicing: tile size >= 1 and rows per slice >= 0");
    if (environment.width != environmentWidth_ || environment.height != environmentHeight_ || !environment_) {
        environment_ = createFloatTexture(GL_RGB32F, environment.width, environment.height);
        // In double, as the CPU reference computes them, and only then rounded: the
        // difference of cosines near the poles loses most of its digits in float.
        std::vector<float> solidAngles;
        for (int y = 0; y < environment.height; ++y) solidAngles.push_back(float(equirectTexelSolidAngle(y, environment.width, environment.height)));
        rowSolidAngles_ = gl::createBufferWith<float>(solidAngles);
        environmentWidth_ = environment.width;
        environmentHeight_ = environment.height;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(environment_.id(), 0, 0, 0, environment.width, environment.height, GL_RGB, GL_FLOAT, environment.texels.data());

    if (width != width_ || height != height_ || !specularSum_) {
        specularSum_ = createFloatTexture(GL_RGBA32F, width, height);
        irradianceSum_ = createFloatTexture(GL_RGBA32F, width, height);
        width_ = width;
        height_ = height;
    }
    glClearTexImage(specularSum_.id(), 0, GL_RGBA, GL_FLOAT, nullptr);
    glClearTexImage(irradianceSum_.id(), 0, GL_RGBA, GL_FLOAT, nullptr);

    tileSize_ = slicing.tileSize;
    tiles_.clear();
    for (int y0 = 0; y0 < height; y0 += tileSize_)
        for (int x0 = 0; x0 < width; x0 += tileSize_) {
            bool anySurface = false;
            for (int y = y0; y < std::min(y0 + tileSize_, height) && !anySurface; ++y)
                for (int x = x0; x < std::min(x0 + tileSize_, width) && !anySurface; ++x) anySurface = coverage[std::size_t(y) * std::size_t(width) + std::size_t(x)] != 0;
            if (anySurface) tiles_.push_back({x0, y0});
        }
    const long autoRows = kEvaluationsPerSlice / (long(tileSize_) * long(tileSize_) * long(environment.width));
    rowsPerSlice_ = std::clamp(slicing.rowsPerSlice > 0 ? slicing.rowsPerSlice : int(std::max(1L, autoRows)), 1, environment.height);
    bands_ = (environment.height + rowsPerSlice_ - 1) / rowsPerSlice_;
    nextSlice_ = 0;
}

glm::ivec4 ReferenceIntegral::tileRect(int i) const
{
    const glm::ivec2 origin = tiles_.at(std::size_t(i));
    const glm::ivec2 end = glm::min(origin + tileSize_, glm::ivec2(width_, height_));
    return {origin.x, origin.y, end.x, end.y};
}

void ReferenceIntegral::runSlice(gl::ShaderLibrary& shaders, const GBuffer& gbuffer, GeometryTerm geometry)
{
    if (complete()) return;
    // Tile-major: a tile's pixels finish before the next tile starts.
    const glm::ivec4 tile = tileRect(nextSlice_ / bands_);
    const int band = nextSlice_ % bands_;
    const gl::ShaderProgram& p = shaders.program({"reference_integral.comp"});
    const IntegralUniforms& u = p.uniforms<IntegralUniforms>();
    glUseProgram(p.id());
    u.tileOrigin.set(glm::ivec2(tile.x, tile.y));
    u.tileEnd.set(glm::ivec2(tile.z, tile.w));
    u.firstRow.set(band * rowsPerSlice_);
    u.endRow.set(std::min((band + 1) * rowsPerSlice_, environmentHeight_));
    u.geometry.set(int(geometry));
    glBindTextureUnit(kUnitGNormal, gbuffer.texture(ReferenceLayer::Normal));
    glBindTextureUnit(kUnitGView, gbuffer.texture(ReferenceLayer::View));
    glBindTextureUnit(kUnitGSpecular, gbuffer.texture(ReferenceLayer::Specular));
    glBindTextureUnit(kUnitReferenceEnvironment, environment_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, rowSolidAngles_.id());
    glBindImageTexture(0, specularSum_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(1, irradianceSum_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    const GLuint groups = GLuint((tileSize_ + 7) / 8);
    glDispatchCompute(groups, groups, 1);
    // The next slice reads these sums with imageLoad, the resolve with texelFetch.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glUseProgram(0);
    ++nextSlice_;
}

} // namespace iblab
