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

void drawSides(const FrameSettings& settings, int width, int height, const std::function<void(const FrameSettings&)>& drawSide)
{
    drawSide(settings);
    if (!settings.view.split) return;
    const int x0 = splitColumn(settings.view, width);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, 0, width - x0, height);
    glClear(GL_DEPTH_BUFFER_BIT);
    drawSide(compareSide(settings));
    glDisable(GL_SCISSOR_TEST);
}

} // namespace iblab
