#pragma once
// Where to start: the Help window (F1) lists the mouse, the keys and the panel's sections;
// the first run's one-line hint points at it.
namespace iblab::ui {

// The hint shown at the top of the panel on the first run.
inline constexpr const char* kFirstRunHint = "Drag the view to orbit; try Sampling > Method > reference; F1 for help";

// The Help window while `open`; its close button (and Esc, handled by the app) clears it.
void drawHelpWindow(bool& open);

} // namespace iblab::ui
