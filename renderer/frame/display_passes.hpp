#pragma once
// The last pass of a frame, into the bound RGBA8 display target, one of:
// - the tone map pass (tonemap.frag): exposure, the tone curve and the sRGB encoding;
//     reads the resolved HDR frame (or the running mean) and ToneMapSettings
// - the error view pass (error_view.frag): the per-pixel relative error against the
//     reference in false colour, on linear HDR or display values;
//     reads the resolved HDR frame, the reference frame, the reference's coverage
//     (ReferenceLayer::Normal) and ToneMapSettings, ViewSettings::errorSpace / errorScale
#include <epoxy/gl.h>

#include "frame/fullscreen_triangle.hpp"
#include "frame/settings.hpp"
#include "gl/uniform.hpp"

namespace iblab {

class ToneMapPass {
public:
    ToneMapPass(gl::ShaderLibrary& shaders, const FullscreenTriangle& triangle) : shaders_(shaders), triangle_(triangle) {}
    // dataOnly: the frame holds data in [0, 1] (the LUT view), shown with the display
    // encoding alone, no exposure and no tone curve.
    void draw(GLuint hdrFrame, const ToneMapSettings& toneMap, bool dataOnly);

private:
    gl::ShaderLibrary& shaders_;
    const FullscreenTriangle& triangle_;
};

class ErrorViewPass {
public:
    ErrorViewPass(gl::ShaderLibrary& shaders, const FullscreenTriangle& triangle) : shaders_(shaders), triangle_(triangle) {}
    void draw(GLuint hdrFrame, GLuint referenceFrame, GLuint referenceNormals, const FrameSettings& settings);

private:
    gl::ShaderLibrary& shaders_;
    const FullscreenTriangle& triangle_;
};

} // namespace iblab
