#pragma once
// The A/B split: side A (the frame's sampling settings) over the whole frame, then side B
// (ViewSettings::compare as the sampling) over the columns from splitColumn on, confined by
// the scissor. Each side runs the same lit passes; the error measurement splits the same way.
#include <functional>
#include <optional>

#include "frame/settings.hpp"

namespace iblab {

// The first pixel column that shows side B in the split view of a frame width wide.
int splitColumn(const ViewSettings& view, int width);

// The split view's right side: the frame's settings with the comparison's sampling.
FrameSettings compareSide(const FrameSettings& settings);

// Whether every side the frame shows keeps its exact sample count (keepsExactSampleCount):
// then accumulating more frames would only average copies.
bool everySideKeepsExactSampleCount(const FrameSettings& settings);

// The side drawn with ShadingMethod::Reference (A before B), if any, in the views that show
// the lit frame (final and error): the frame shows that side's reference wherever it is
// finished. Elsewhere, as before it finishes, the split sum stands in for it.
std::optional<FrameSettings> referenceMethodSide(const FrameSettings& settings);
// Whether the frame needs the reference renderer: a side drawn with the reference method,
// or the error view.
bool showsReference(const FrameSettings& settings);
// The settings whose reference the frame needs: the reference method's side, else side A
// (whose reference the error view compares both sides with).
FrameSettings referenceSubject(const FrameSettings& settings);

// Calls show with each side the frame shows and the pixel columns [x0, x1) where it is
// visible: A's before the divider (all of them without the split), B's from it on.
void forEachVisibleSide(const FrameSettings& settings, int width, const std::function<void(const FrameSettings&, int x0, int x1)>& show);

// Calls drawSide with side A's settings, then, with the split view, with side B's while the
// scissor confines drawing (and the depth clear before it) to B's columns. Rows [y0, y1)
// (y up) confine both sides to a band of the frame (a frame drawn over several calls);
// y1 < 0 means every row. Leaves the scissor test off.
void drawSides(const FrameSettings& settings, int width, int height, const std::function<void(const FrameSettings&)>& drawSide, int y0 = 0,
               int y1 = -1);

} // namespace iblab
