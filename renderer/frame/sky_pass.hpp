#pragma once
// The sky pass (sky.frag): the background behind whatever the mesh pass drew. One view ray
// per pixel from the inverse camera, drawn at the far plane with the depth test on and
// depth writes off, so that only uncovered pixels are shaded.
//   reads:  the camera, ViewSettings (background, mip, solid colour; the irradiance and
//           furnace view modes), and the bake (its environment cube is the background, so
//           that sky and lighting change together), or the loaded map before a bake exists
//   writes: radiance, and coverage 0 in alpha, into the bound framebuffer
#include "frame/fullscreen_triangle.hpp"
#include "frame/lighting.hpp"

namespace iblab {

class SkyPass {
public:
    SkyPass(gl::ShaderLibrary& shaders, const FullscreenTriangle& triangle) : shaders_(shaders), triangle_(triangle) {}
    void draw(const FrameSettings& settings, const Lighting& lighting, float aspect);

private:
    gl::ShaderLibrary& shaders_;
    const FullscreenTriangle& triangle_;
};

} // namespace iblab
