#pragma once
// Each sub-command registers itself on the CLI11 app and returns how to run it, so that
// commands live in their own files and cli.cpp only dispatches.
#include <chrono>
#include <functional>

#include <CLI/CLI.hpp>

#include "frame/settings.hpp"

namespace iblab::app {

using ProcessClock = std::chrono::steady_clock;

struct Command {
    CLI::App* subcommand = nullptr;
    std::function<int()> run; // called after a successful parse when the sub-command was given
};

// The view options shared by the GUI and `render`: what a frame looks like.
void addFrameOptions(CLI::App& command, FrameSettings& settings);
// --convention NAME (conventions.hpp): how LearnOpenGL, Filament or the glTF Sample Viewer
// bake and shade; checked against the list at parse time.
void addConventionOption(CLI::App& command, std::string& convention);

Command addRenderCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addBakeCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addShCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addLutCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addStressCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addConventionsCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addBenchCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addCompareCommand(CLI::App& app, ProcessClock::time_point processStart);
Command addMeasureCommand(CLI::App& app, ProcessClock::time_point processStart);

} // namespace iblab::app
