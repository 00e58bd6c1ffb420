#pragma once
// Status lines in the panel: a line in green (or red for an error) with its notes under it,
// in an area of fixed height, so that the controls below never move under the mouse when a
// status appears, grows or goes.
#include "ui/panels.hpp"

namespace iblab::ui {

// One status line and its notes, wrapped at the panel's edge (nothing when it is empty).
void drawStatus(const StatusLine& status);

// The statuses (and a background activity's progress bar, when given and running) in an area
// `lines` text lines high, whatever they say: what does not fit scrolls inside the area
// (the wheel still scrolls the panel), and hovering it shows everything in a tooltip.
void drawStatusArea(const char* id, std::initializer_list<const StatusLine*> statuses, int lines, const Activity* activity = nullptr);

} // namespace iblab::ui
