#pragma once

namespace iblab::app {
// Parses the command line and runs the GUI or a sub-command; returns the exit status.
int runCommandLine(int argc, char** argv);
}
