#pragma once
// The A/B split: side A (the frame's sampling settings) over the whole frame, then side B
// (ViewSettings::compare as the sampling) over the columns from splitColumn on, confined by
// the scissor. Each side runs the same lit passes; the error measurement splits the same way.
#include <functional>

#include "frame/settings.hpp"

namespace iblab {

// The first pixel column that shows side B in the split view of a frame width wide.
int splitColumn(const ViewSettings& view, int width);

// The split view's right side: the frame's settings with the comparison's sampling.
FrameSettings compareSide(const FrameSettings& settings);

// Whether every side the frame shows keeps its exact sample count (keepsExactSampleCount):
// then accumulating more frames would only average copies.
bool everySideKeepsExactSampleCount(const FrameSettings& settings);

// Calls drawSide with side A's settings, then, with the split view, with side B's while the
// scissor confines drawing (and the depth clear before it) to B's columns. Leaves the
// scissor test off.
void drawSides(const FrameSettings& settings, int width, int height, const std::function<void(const FrameSettings&)>& drawSide);

} // namespace iblab
