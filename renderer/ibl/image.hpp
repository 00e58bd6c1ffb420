#pragma once
// A linear-light RGB float image in memory: the one currency between the environment
// loader, the CPU math and the GPU upload. Row 0 is the top scanline (see
// assets/shaders/common/conventions.glsl for what that means for an equirect map).
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace iblab {

struct ImageRGB32F {
    int width = 0;
    int height = 0;
    std::vector<float> texels; // width * height * 3, interleaved RGB, row-major

    ImageRGB32F() = default;
    ImageRGB32F(int w, int h) : width(w), height(h), texels(std::size_t(w) * std::size_t(h) * 3, 0.0f) {}

    bool empty() const { return width <= 0 || height <= 0; }
    std::size_t texelCount() const { return std::size_t(width) * std::size_t(height); }
    std::size_t offset(int x, int y) const { return (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3; }

    glm::vec3 at(int x, int y) const
    {
        const float* p = &texels[offset(x, y)];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, glm::vec3 rgb)
    {
        float* p = &texels[offset(x, y)];
        p[0] = rgb.r;
        p[1] = rgb.g;
        p[2] = rgb.b;
    }
};

} // namespace iblab
