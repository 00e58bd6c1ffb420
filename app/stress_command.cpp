// `iblab stress`: the stability suite (renderer/lab/stress_suite.hpp), headless. Writes
// stress.md, stress.json and the labelled image grid stress.png to --out, prints the path
// of the Markdown (or the JSON itself with --json), and exits 0 whatever the findings: a
// failing method is the report's content, not the command's failure.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <imgui.h>

#include "asset_paths.hpp"
#include "command_support.hpp"
#include "commands.hpp"
#include "io/atomic_file.hpp"
#include "io/image_writer.hpp"
#include "frame/renderer.hpp"
#include "lab/stress_suite.hpp"

namespace iblab::app {
namespace {

struct StressCommandOptions {
    std::string out = "stress";
    bool json = false;
    bool quick = false;
};

// Dear ImGui's built-in font, rasterised by its atlas on the CPU: labels for an image that
// never passes through a window.
class LabelFont {
public:
    LabelFont() : font_(atlas_.AddFontDefault())
    {
        atlas_.GetTexDataAsAlpha8(&pixels_, &width_, &height_);
    }

    // White text with its top-left at (x, y), alpha-blended over RGBA8 top-down pixels.
    void draw(stress::StressGrid& grid, int x, int y, const std::string& text) const
    {
        float pen = float(x);
        for (char c : text) {
            const ImFontGlyph* glyph = font_->FindGlyph(ImWchar(static_cast<unsigned char>(c)));
            if (!glyph) continue;
            const int u0 = int(glyph->U0 * float(width_) + 0.5f), v0 = int(glyph->V0 * float(height_) + 0.5f);
            const int w = int(glyph->X1 - glyph->X0), h = int(glyph->Y1 - glyph->Y0);
            for (int gy = 0; gy < h; ++gy)
                for (int gx = 0; gx < w; ++gx) {
                    const int px = int(pen + glyph->X0) + gx, py = y + int(glyph->Y0) + gy;
                    if (px < 0 || py < 0 || px >= grid.width || py >= grid.height) continue;
                    const int alpha = pixels_[std::size_t(v0 + gy) * std::size_t(width_) + std::size_t(u0 + gx)];
                    std::uint8_t* out = &grid.rgba[(std::size_t(py) * std::size_t(grid.width) + std::size_t(px)) * 4];
                    for (int k = 0; k < 3; ++k) out[k] = std::uint8_t((out[k] * (255 - alpha) + 255 * alpha) / 255);
                }
            pen += glyph->AdvanceX;
        }
    }

private:
    ImFontAtlas atlas_;
    ImFont* font_;
    unsigned char* pixels_ = nullptr;
    int width_ = 0;
    int height_ = 0;
};

int runStress(const StressCommandOptions& o)
{
    try {
        HeadlessGl gl(/*debugContext=*/true);
        Renderer renderer(shaderDirectory());
        stress::StressOptions options = stress::defaultStressOptions(o.quick);
        options.progress = [](const std::string& line) { std::fprintf(stderr, "iblab stress: %s\n", line.c_str()); };
        stress::StressReport report = stress::runStressSuite(renderer, options);
        if (gl.debug.errorCount() > 0) return failCommand("stress", std::to_string(gl.debug.errorCount()) + " GL error(s), the first: " + gl.debug.firstError());

        const std::filesystem::path dir(o.out);
        std::filesystem::create_directories(dir);
        const std::string json = stress::stressJsonText(report);
        writeTextFileAtomic((dir / "stress.json").string(), json);
        writeTextFileAtomic((dir / "stress.md").string(), stress::stressMarkdown(report));
        const LabelFont font;
        for (const stress::StressGrid::Label& label : report.grid.labels) font.draw(report.grid, label.x, label.y, label.text);
        writePng8((dir / "stress.png").string(), report.grid.width, report.grid.height, 4, report.grid.rgba);

        if (o.json) std::printf("%s\n", json.c_str());
        else std::printf("%s\n", (dir / "stress.md").string().c_str());
        return 0;
    } catch (const std::exception& e) {
        return failCommand("stress", e.what());
    }
}

} // namespace

Command addStressCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<StressCommandOptions>();
    CLI::App* c = app.add_subcommand("stress", "Stability suite: environments made to break IBL methods, every method at roughness 0, 0.05, "
                                               "0.5, 1 and grazing views; writes stress.md, stress.json and stress.png");
    c->add_option("--out", o->out, "Directory for stress.md, stress.json and stress.png")->capture_default_str();
    c->add_flag("--json", o->json, "Print the JSON report on stdout instead of the Markdown's path");
    c->add_flag("--quick", o->quick, "Small environments, frames and bakes (seconds; for tests)");
    return {c, [o] { return runStress(*o); }};
}

} // namespace iblab::app
