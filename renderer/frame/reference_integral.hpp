#pragma once
// The reference renderer's GPU side (internal to the renderer): the G-buffer the mesh pass
// fills, and the integral over the reference environment's texels in slices of one screen
// tile x one band of rows, so that a frame can spend a budget on it and the UI never stalls.
#include <array>
#include <cstdint>
#include <vector>

#include <epoxy/gl.h>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "gl/handles.hpp"
#include "gl/shader_library.hpp"
#include "ibl/brdf.hpp"
#include "ibl/image.hpp"
#include "frame/reference_types.hpp"

namespace iblab {

// pbr.frag's METHOD 2 outputs, one RGBA32F texture per ReferenceLayer, with a depth buffer.
class GBuffer {
public:
    void ensure(int width, int height);
    // Binds it as the draw framebuffer with coverage 0 everywhere and depth 1.
    void bindCleared() const;
    GLuint texture(ReferenceLayer layer) const { return layers_[std::size_t(layer)].id(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    std::array<gl::Texture, std::size_t(ReferenceLayer::Count)> layers_;
    gl::Renderbuffer depth_;
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

class ReferenceIntegral {
public:
    // Starts over: the environment to sum over, the frame's size, and which of its pixels
    // are surfaces (one byte per pixel, bottom row first); tiles without any are skipped.
    void start(const ImageRGB32F& environment, int width, int height, const std::vector<std::uint8_t>& coverage, const ReferenceSlicing& slicing);
    // Adds the next slice's rows to the sums. No-op when complete.
    void runSlice(gl::ShaderLibrary& shaders, const GBuffer& gbuffer, GeometryTerm geometry);
    bool complete() const { return nextSlice_ >= sliceCount(); }
    float progress() const { return sliceCount() == 0 ? 1.0f : float(nextSlice_) / float(sliceCount()); }
    // Slices run tile-major, so tiles [0, finishedTiles()) have every row of the
    // environment in their sums; the pixels outside every tile have no surface at all.
    int finishedTiles() const { return bands_ == 0 ? 0 : nextSlice_ / bands_; }
    // Pixel rectangle of tile i: x0, y0 (bottom row first), x1, y1 exclusive.
    glm::ivec4 tileRect(int i) const;
    // RGBA32F: specular radiance and E_ss; irradiance E (before the environment's intensity).
    GLuint specularSum() const { return specularSum_.id(); }
    GLuint irradianceSum() const { return irradianceSum_.id(); }
    int environmentWidth() const { return environmentWidth_; }
    int environmentHeight() const { return environmentHeight_; }

private:
    int sliceCount() const { return int(tiles_.size()) * bands_; }

    gl::Texture environment_;
    gl::Buffer rowSolidAngles_;
    gl::Texture specularSum_;
    gl::Texture irradianceSum_;
    std::vector<glm::ivec2> tiles_; // origins of the tiles with surface pixels
    int tileSize_ = 32;
    int rowsPerSlice_ = 1;
    int bands_ = 0;
    int nextSlice_ = 0;
    int width_ = 0;
    int height_ = 0;
    int environmentWidth_ = 0;
    int environmentHeight_ = 0;
};

} // namespace iblab
