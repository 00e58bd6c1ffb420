// accuracy_study's command line: the options into StudyOptions, then eval (evaluate.cpp) or
// fit (fit.cpp); kUsage is the synopsis that --help prints. The study itself:
// accuracy_study.hpp and docs/accuracy-study.md.
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "accuracy_study.hpp"

using namespace iblab::accuracy;

namespace iblab::accuracy {
namespace {

const char* const kUsage =
    "usage: accuracy_study eval [--width 256] [--sphere 64] [--grid 128] [--set bundled,unseen,procedural]\n"
    "                           [--env PATH|builtin:SPEC ...] [--csv FILE] [--table FILE.inc ...]\n"
    "                           [--bins] [--exact-prefilter] [--roughness 0.2,0.3,...]\n"
    "                           [--bench-scenes] [--bakes DIR] [--lights]\n"
    "       accuracy_study fit  [--width 256] [--taps 1|2|3|4] [--frames 96] [--size 16] [--out FILE.inc]\n"
    "                           [--min-roughness 0.15] [--mixed-objective] [--init TABLE.inc] [--seed 14] [--bakes DIR]\n"
    "                           [--per-map-ratio] [--smooth 0] [--smooth-passes 4] [--leave-out MAP] [--lights] [--read-floor]\n"
    "                           [--env PATH|builtin:SPEC ...]\n"
    "eval measures every method against the full integral on the bench's scenes (markdown on stdout);\n"
    "fit refits the lobe table on the 8 bundled maps (renderer/ibl/specular_lobe_fit.inc by default).\n"
    "--bench-scenes: the GPU measure's scenes (scripts/measure-lobe.sh): a copper sphere per --roughness, the grid.\n"
    "--bakes DIR: read each map's prefiltered cube from DIR/<map>/ (scripts/accuracy-bakes.sh writes them).\n"
    "--smooth W: after fitting each cell alone, --smooth-passes passes re-fit every cell with W times its\n"
    "squared distance from the lines through its neighbours added to its objective (no rings between cells).\n"
    "--lights: with --bakes, each bake's shading lights (bake.json) and its mips less them, as the renderer shades\n"
    "the fitted lobe; eval adds <method>+lights, fit fits the table that way.\n"
    "--leave-out MAP: fit on the bundled maps but MAP (leave-one-out; scripts/fit-lobe-loo.sh).\n"
    "--read-floor: fit reads no sharper than the lobe each stands for (read_floor.hpp: equal effective solid angle).\n"
    "fit --env: fit on these maps instead of the bundled ones (a diagnostic: the best the layout does on them).\n"
    "See docs/accuracy-study.md. Caches: <build>/accuracy_cache (delete it to recompute).\n";

std::vector<double> parseList(const std::string& text)
{
    std::vector<double> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(std::stod(item));
    return out;
}

} // namespace
} // namespace iblab::accuracy

int main(int argc, char** argv)
{
    StudyOptions a;
    if (argc < 2) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    a.command = argv[1];
    if (a.command == "--help" || a.command == "-h") {
        std::fputs(kUsage, stdout);
        return 0;
    }
    try {
        bool sphereGiven = false, roughnessGiven = false;
        for (int i = 2; i < argc; ++i) {
            const std::string k = argv[i];
            auto next = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error("missing value after " + k);
                return argv[++i];
            };
            if (k == "--width") a.width = std::stoi(next());
            else if (k == "--sphere") a.sphere = std::stoi(next()), sphereGiven = true;
            else if (k == "--grid") a.grid = std::stoi(next());
            else if (k == "--set") a.sets = next();
            else if (k == "--env") a.envs.push_back(next());
            else if (k == "--csv") a.csv = next();
            else if (k == "--table") a.tables.push_back(next());
            else if (k == "--taps") a.taps = std::stoi(next());
            else if (k == "--frames") a.frames = std::stoi(next());
            else if (k == "--size") a.size = std::stoi(next());
            else if (k == "--min-roughness") a.minRoughness = std::stod(next());
            else if (k == "--out") a.out = next();
            else if (k == "--init") a.init = next();
            else if (k == "--exact-prefilter") a.exactPrefilter = true;
            else if (k == "--bins") a.bins = true;
            else if (k == "--bench-scenes") a.benchScenes = true;
            else if (k == "--bakes") a.bakes = next();
            else if (k == "--lights") a.lights = true;
            else if (k == "--mixed-objective") a.mixedObjective = true;
            else if (k == "--per-map-ratio") a.perMapRatio = true;
            else if (k == "--no-multiscatter") a.multiscatter = false;
            else if (k == "--roughness") a.roughnesses = parseList(next()), roughnessGiven = true;
            else if (k == "--seed") a.seed = unsigned(std::stoul(next()));
            else if (k == "--smooth") a.smooth = std::stod(next());
            else if (k == "--smooth-passes") a.smoothPasses = std::stoi(next());
            else if (k == "--leave-out") a.leaveOut = next();
            else if (k == "--read-floor") a.readFloor = true;
            else {
                std::fprintf(stderr, "unknown option %s\n%s", k.c_str(), kUsage);
                return 2;
            }
        }
        // The GPU measure's frames are 128 x 128, its spheres the two roughnesses.
        if (a.benchScenes && !sphereGiven) a.sphere = 128;
        if (a.benchScenes && !roughnessGiven) a.roughnesses = {0.3, 0.6};
        if (a.command == "eval") return evalCommand(a);
        if (a.command == "fit") return fitCommand(a);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "accuracy_study: %s\n", e.what());
        return 1;
    }
    std::fprintf(stderr, "unknown command %s\n%s", a.command.c_str(), kUsage);
    return 2;
}
