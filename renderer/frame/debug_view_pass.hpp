#pragma once
// The debug views of baked data (debug_views.frag), drawn over the whole frame in place of
// the lit passes: ViewMode::PrefilterMips (each prefiltered mip as a labelled cube cross)
// and ViewMode::Lut (both BRDF LUTs), in the tiles debug_layout.hpp places.
//   reads:  the bake's prefiltered cube and LUTs, the environment's intensity
//   writes: every pixel of the bound framebuffer (single-sampled)
// The furnace and irradiance views are not passes of their own: the furnace view lights
// the lit passes with the furnace bake and the sky pass shows its uniform radiance; the
// irradiance view is a background of the sky pass.
#include "frame/frame_analysis.hpp"
#include "frame/fullscreen_triangle.hpp"
#include "frame/lighting.hpp"

namespace iblab {

class DebugViewPass {
public:
    DebugViewPass(gl::ShaderLibrary& shaders, const FullscreenTriangle& triangle) : shaders_(shaders), triangle_(triangle) {}
    // lighting.bake must be set.
    void draw(const FrameSettings& settings, const Lighting& lighting, int width, int height);

private:
    gl::ShaderLibrary& shaders_;
    const FullscreenTriangle& triangle_;
};

// The texel of the bake under pixel (x, y) (y up) of a width x height frame of the debug
// view settings.view.mode shows, read back from the bake's texture.
TexelProbe probeDebugView(const FrameSettings& settings, const bake::BakeResult& bake, int width, int height, float x, float y);

} // namespace iblab
