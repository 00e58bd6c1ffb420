#include "frame/split_view.hpp"

#include <algorithm>
#include <cmath>

#include <epoxy/gl.h>

namespace iblab {

// The divider is a pixel column; positions are clamped so that both sides can be empty.
int splitColumn(const ViewSettings& view, int width)
{
    return std::clamp(int(std::lround(double(view.splitPosition) * double(width))), 0, width);
}

FrameSettings compareSide(const FrameSettings& settings)
{
    FrameSettings b = settings;
    b.sampling = settings.view.compare;
    return b;
}

bool everySideKeepsExactSampleCount(const FrameSettings& settings)
{
    return keepsExactSampleCount(settings) && (!settings.view.split || keepsExactSampleCount(compareSide(settings)));
}

std::optional<FrameSettings> referenceMethodSide(const FrameSettings& settings)
{
    // The reference integrates the loaded environment under the frame's own sky: the furnace
    // (lit by builtin:white), the irradiance background and the views of baked data are not that.
    if (settings.view.mode != ViewMode::Final && settings.view.mode != ViewMode::Error) return std::nullopt;
    if (settings.sampling.method == ShadingMethod::Reference) return settings;
    if (settings.view.split && settings.view.compare.method == ShadingMethod::Reference) return compareSide(settings);
    return std::nullopt;
}

bool showsReference(const FrameSettings& settings) { return settings.view.mode == ViewMode::Error || referenceMethodSide(settings); }

FrameSettings referenceSubject(const FrameSettings& settings) { return referenceMethodSide(settings).value_or(settings); }

void forEachVisibleSide(const FrameSettings& settings, int width, const std::function<void(const FrameSettings&, int x0, int x1)>& show)
{
    if (!settings.view.split) {
        show(settings, 0, width);
        return;
    }
    const int divider = splitColumn(settings.view, width);
    show(settings, 0, divider);
    show(compareSide(settings), divider, width);
}

void drawSides(const FrameSettings& settings, int width, int height, const std::function<void(const FrameSettings&)>& drawSide, int y0, int y1)
{
    if (y1 < 0) y1 = height;
    const bool band = y0 > 0 || y1 < height;
    if (band) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, y0, width, y1 - y0);
    }
    drawSide(settings);
    if (!settings.view.split) {
        glDisable(GL_SCISSOR_TEST);
        return;
    }
    const int x0 = splitColumn(settings.view, width);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, y0, width - x0, y1 - y0);
    glClear(GL_DEPTH_BUFFER_BIT);
    drawSide(compareSide(settings));
    glDisable(GL_SCISSOR_TEST);
}

} // namespace iblab
