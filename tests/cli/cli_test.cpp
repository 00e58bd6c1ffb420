// The command line as users and scripts drive it: exit codes, one-line errors naming the
// file, the headless fallback of the bare `iblab`, and what lands on disk.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "cli_fixture.hpp"
#include "malformed_images.hpp"

namespace {

using namespace iblab::cli_testing;

TEST_F(Cli, BareCommandRendersHeadlessWithoutADisplay)
{
    const Result r = run("--env builtin:sky");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
    const fs::path expected = dir / "iblab-default.png";
    EXPECT_NE(r.out.find(expected.string()), std::string::npos) << "prints the path it wrote: " << r.out;
    EXPECT_TRUE(fs::exists(expected));
}

TEST_F(Cli, RenderWritesPngWithSettingsAndSidecar)
{
    const Result r = run("render --scene none --env builtin:white --tonemap none --width 32 --height 16 --env-yaw 12.5 -o white.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto input = OIIO::ImageInput::open((dir / "white.png").string());
    ASSERT_TRUE(input);
    const OIIO::ImageSpec& spec = input->spec();
    EXPECT_EQ(spec.width, 32);
    EXPECT_EQ(spec.height, 16);
    std::vector<unsigned char> pixels(std::size_t(spec.width * spec.height * spec.nchannels));
    ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()));
    for (unsigned char v : pixels) ASSERT_EQ(v, 255); // uniform radiance 1, clamp, sRGB(1) = 1
    const auto embedded = nlohmann::json::parse(spec.get_string_attribute("iblab:settings"));
    EXPECT_EQ(embedded["environment"]["source"], "builtin:white");
    EXPECT_FLOAT_EQ(embedded["environment"]["yaw_degrees"].get<float>(), 12.5f);
    std::ifstream sidecar(dir / "white.png.json");
    EXPECT_EQ(nlohmann::json::parse(sidecar), embedded);
}

// The frame options the GUI also has reach the settings the image records.
TEST_F(Cli, MsaaAndFrozenSamplesAreRecordedInTheSidecar)
{
    const Result r = run("render --scene none --env builtin:white --width 8 --height 8 --msaa 2 --freeze-samples --b-freeze-samples -o a.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream sidecar(dir / "a.png.json");
    const auto settings = nlohmann::json::parse(sidecar);
    EXPECT_EQ(settings["view"]["msaa_samples"], 2);
    EXPECT_EQ(settings["sampling"]["freeze_sample_set"], true);
    EXPECT_EQ(settings["view"]["compare"]["freeze_sample_set"], true);
}

TEST_F(Cli, RenderWritesLinearExrBeforeToneMapping)
{
    const Result r = run("render --scene none --env builtin:white --env-intensity 2 --exposure -5 --width 8 --height 8 -o frame.exr");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto input = OIIO::ImageInput::open((dir / "frame.exr").string());
    ASSERT_TRUE(input);
    std::vector<float> pixels(std::size_t(8 * 8 * input->spec().nchannels));
    ASSERT_TRUE(input->read_image(0, 0, 0, input->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    // Intensity +2 EV scales the radiance to 4; exposure applies only to the display image.
    EXPECT_FLOAT_EQ(pixels[0], 4.0f);
}

TEST_F(Cli, MissingEnvironmentFailsWithOneLineNamingTheFile)
{
    const Result r = run("render --env no-such-map.exr -o out.png");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("no-such-map.exr"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST_F(Cli, WrongAspectFailsWithOneLine)
{
    // A 3:1 image written with OpenImageIO: valid file, wrong shape for an equirect map.
    const fs::path path = dir / "wide.exr";
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(48, 16, 3, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path.string(), spec));
    std::vector<float> pixels(48 * 16 * 3, 0.5f);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
    const Result r = run("render --env wide.exr -o out.png");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("wide.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("3:1"), std::string::npos) << r.err;
}

TEST_F(Cli, BadOptionsExitWithUsageError)
{
    for (const char* arguments : {"render --tonemap filmic -o a.png", "render -o a.jpg", "render", "render --width 0 -o a.png", "render --msaa 3 -o a.png"}) {
        const Result r = run(arguments);
        EXPECT_EQ(r.exitCode, 2) << arguments;
        EXPECT_EQ(lineCount(r.err), 1) << arguments << ": " << r.err;
    }
}

// A value outside a setting's range names the option once and says what it got: the range
// check's message repeated the option ("--metallic: --metallic: material.metallic: ...") and
// wrote NaN as JSON's "null".
TEST_F(Cli, OutOfRangeValuesNameTheOptionOnceAndTheValue)
{
    const std::pair<const char*, const char*> cases[] = {
        {"render --metallic -1 -o a.png", "iblab: --metallic: material.metallic: must be 0..1, got -1.0 (see --help)"},
        {"render --roughness nan -o a.png", "iblab: --roughness: material.roughness: must be 0..1, got nan (see --help)"},
        {"render --samples 0 -o a.png", "iblab: --samples: sampling.samples: must be 1..1024, got 0 (see --help)"},
    };
    for (const auto& [arguments, message] : cases) {
        const Result r = run(arguments);
        EXPECT_EQ(r.exitCode, 2) << arguments;
        EXPECT_EQ(r.err, std::string(message) + "\n") << arguments;
    }
}

TEST_F(Cli, UnwritableOutputFailsWithOneLine)
{
    const Result r = run("render --env builtin:white --width 8 --height 8 -o no/such/dir/a.png");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("no/such/dir/a.png"), std::string::npos) << r.err;
}

// Every view and scene the UI offers renders headless without a GL error (--gl-debug makes
// any KHR_debug error fail the command).
TEST_F(Cli, EveryViewAndSceneRendersWithoutGlErrors)
{
    const std::string common = " --env builtin:studio?width=128 --width 96 --height 64 --gl-debug -o out.png";
    for (const char* view : {"final", "prefilter-mips", "lut", "furnace", "irradiance", "error --reference-width 32"}) {
        const Result r = run(std::string("render --view ") + view + common);
        EXPECT_EQ(r.exitCode, 0) << view << ": " << r.err << " (stdout: " << r.out << ")";
    }
    for (const char* scene : {"sphere", "grid", "counting", "sweep", "none", IBLAB_SOURCE_DIR "/assets/models/material_spheres.glb"}) {
        const Result r = run(std::string("render --method sampled --samples 4 --scene ") + scene + common);
        EXPECT_EQ(r.exitCode, 0) << scene << ": " << r.err << " (stdout: " << r.out << ")";
    }
}

TEST_F(Cli, FurnaceReportsReflectedEnergyPerSphere)
{
    // A white metal reflects all of a uniform environment with the energy compensation the
    // default shading has, and loses energy at high roughness with --no-multiscatter.
    const Result r = run("render --view furnace --scene grid --base-color 1,1,1 --width 280 --height 280 --json -o f.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Result off = run("render --view furnace --scene grid --base-color 1,1,1 --no-multiscatter --width 280 --height 280 --json -o g.png");
    ASSERT_EQ(off.exitCode, 0) << off.err;
    const auto report = nlohmann::json::parse(r.out);
    const auto single = nlohmann::json::parse(off.out);
    ASSERT_EQ(report["furnace"].size(), 49u);
    ASSERT_EQ(single["furnace"].size(), 49u);
    for (std::size_t i = 0; i < report["furnace"].size(); ++i) {
        const auto& sphere = report["furnace"][i];
        if (sphere["metallic"].get<float>() != 1.0f) continue;
        // 3%: the default LUT (128^2, half floats) and the sphere's central disc, where n.v
        // runs from 1 down to 0.87.
        EXPECT_NEAR(sphere["reflected"][0].get<float>(), 1.0f, 0.03f) << "roughness " << sphere["roughness"];
        const float singleScatter = single["furnace"][i]["reflected"][0].get<float>();
        EXPECT_LE(singleScatter, sphere["reflected"][0].get<float>() + 1e-4f) << "roughness " << sphere["roughness"];
        // Single scattering keeps about a third at roughness 1 (E_ss = 1 - ln 2 = 0.31 at
        // n.v = 1, alpha = 1; measured 0.32 over the central disc).
        if (sphere["roughness"].get<float>() > 0.99f) {
            EXPECT_LT(singleScatter, 0.5f);
        }
    }
}

TEST_F(Cli, BadModelFailsWithOneLine)
{
    std::ofstream(dir / "broken.gltf") << "{ not json";
    const Result r = run("render --scene broken.gltf -o out.png");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("broken.gltf"), std::string::npos) << r.err;
}

// A model that loads with a texture missing still renders, and stderr names the file and the
// texture, one line a warning; stdout stays the output's path alone.
TEST_F(Cli, AModelsMissingTextureIsAWarningOnStderr)
{
    const fs::path model = IBLAB_SOURCE_DIR "/assets/models/material_spheres.glb";
    std::ofstream(dir / "textured.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA","byteLength":36}],)"
           R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
           R"("images":[{"uri":"nowhere.png"}],"textures":[{"source":0}],"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
    const Result r = run("render --scene textured.gltf --width 32 --height 32 -o out.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("iblab render: warning: textured.gltf: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nowhere.png"), std::string::npos) << r.err;
    const Result clean = run("render --scene " + model.string() + " --width 32 --height 32 -o clean.png");
    ASSERT_EQ(clean.exitCode, 0) << clean.err;
    EXPECT_EQ(clean.err.find("warning"), std::string::npos) << clean.err;
}

void writeImage(const fs::path& path, int width, int height, OIIO::TypeDesc type, const void* pixels)
{
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(width, height, 3, type);
    ASSERT_TRUE(out->open(path.string(), spec));
    ASSERT_TRUE(out->write_image(type, pixels));
    out->close();
}

TEST_F(Cli, HugeHeaderIsRefusedQuicklyWithoutAllocating)
{
    // A Radiance header claiming 65536 x 32768 (2^31 texels, 24 GiB as float RGB) and no data.
    std::ofstream(dir / "huge.hdr") << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32768 +X 65536\n";
    const auto start = std::chrono::steady_clock::now();
    const Result r = run("render --env huge.hdr --width 8 --height 8 -o out.png");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("huge.hdr"), std::string::npos) << r.err;
}

// Every malformed image of issue #6: a non-zero exit, one line on stderr naming the file and
// the problem, nothing written, and no crash (a signal would make exitCode -1).
TEST_F(Cli, MalformedImagesFailWithOneLineNamingFileAndProblem)
{
    for (const iblab::testing::MalformedImage& bad : iblab::testing::writeMalformedImages(dir)) {
        SCOPED_TRACE(bad.fileName);
        const Result r = run("render --env " + bad.fileName + " --width 8 --height 8 -o out.png");
        EXPECT_GT(r.exitCode, 0);
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(bad.fileName + ": "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(bad.problem), std::string::npos) << "expected \"" << bad.problem << "\" in: " << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png"));
    }
}

TEST_F(Cli, NanAndNegativeEnvironmentsRenderFinite)
{
    std::vector<float> nans(32 * 16 * 3, std::numeric_limits<float>::quiet_NaN());
    std::vector<float> negatives(32 * 16 * 3, -5.0f);
    writeImage(dir / "nan.exr", 32, 16, OIIO::TypeDesc::FLOAT, nans.data());
    writeImage(dir / "negative.exr", 32, 16, OIIO::TypeDesc::FLOAT, negatives.data());
    for (const char* name : {"nan.exr", "negative.exr"}) {
        const Result r = run(std::string("render --env ") + name + " --width 16 --height 16 --json -o out.exr");
        ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
        EXPECT_NE(nlohmann::json::parse(r.out)["environment"].get<std::string>().find("repaired"), std::string::npos) << r.out;
        auto input = OIIO::ImageInput::open((dir / "out.exr").string());
        ASSERT_TRUE(input);
        std::vector<float> pixels(std::size_t(16 * 16 * input->spec().nchannels));
        ASSERT_TRUE(input->read_image(0, 0, 0, input->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
        for (float v : pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << name;
    }
}

// `bake` says what the loader repaired, as the GUI and `render --json` do: on stderr, naming
// the map, and in the report's notes.
TEST_F(Cli, BakeReportsTheTexelsTheLoaderRepaired)
{
    std::vector<float> texels(32 * 16 * 3, 2.0f);
    texels[7] = std::numeric_limits<float>::quiet_NaN();
    texels[40] = std::numeric_limits<float>::infinity();
    writeImage(dir / "spoilt.exr", 32, 16, OIIO::TypeDesc::FLOAT, texels.data());
    const Result r = run("bake --env spoilt.exr --no-errors --json --prefilter-size 16 --prefilter-levels 3 --moments-size 8 --lut-size 16 --lut-samples 64");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("iblab bake: spoilt.exr: repaired 2 texel components"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("1 NaN; 1 +Inf"), std::string::npos) << r.err;
    const nlohmann::json notes = nlohmann::json::parse(r.out)["notes"];
    EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const nlohmann::json& n) { return n.get<std::string>().find("1 NaN") != std::string::npos; }))
        << notes;
}

TEST_F(Cli, LdrEnvironmentLoadsWithAWarning)
{
    std::vector<unsigned char> pixels(64 * 32 * 3, 128);
    writeImage(dir / "photo.png", 64, 32, OIIO::TypeDesc::UINT8, pixels.data());
    const Result r = run("render --env photo.png --width 16 --height 16 --json -o out.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string environment = nlohmann::json::parse(r.out)["environment"];
    EXPECT_NE(environment.find("dynamic range"), std::string::npos) << environment;
}

// A shader that does not compile (here: edited by a user, through IBLAB_ASSET_DIR) fails
// the command with one line naming the shader file and line, never a multi-line log.
TEST_F(Cli, BrokenShaderFailsWithOneLineNamingTheFile)
{
    const fs::path assets = dir / "assets";
    fs::create_directories(assets);
    fs::copy(IBLAB_SOURCE_DIR "/assets/shaders", assets / "shaders", fs::copy_options::recursive);
    std::ofstream(assets / "shaders" / "tonemap.frag", std::ios::app) << "\nthis is not glsl;\n";
    const Result r = run("render --env builtin:white --scene none --width 8 --height 8 -o out.png", "IBLAB_ASSET_DIR='" + assets.string() + "'");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("tonemap.frag:"), std::string::npos) << r.err;
}

TEST_F(Cli, HelpListsEveryRenderOption)
{
    const Result r = run("render --help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option : {"--env", "--env-yaw", "--env-intensity", "--exposure", "--tonemap", "--yaw", "--pitch", "--fov", "--width",
                               "--height", "--output", "--json", "--scene", "--method", "--samples", "--mip", "--metallic", "--roughness",
                               "--base-color", "--view", "--error-space", "--error-scale", "--reference-width", "--split", "--b-method",
                               "--b-samples", "--b-geometry", "--b-multiscatter", "--freeze-samples", "--b-freeze-samples", "--msaa"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option;
}

// `iblab stress --quick --json`: valid JSON on stdout naming every environment and
// method, each (environment, method) pair measured, and the three files in --out.
TEST_F(Cli, StressQuickJsonHasEveryEnvironmentAndMethod)
{
    const Result r = run("stress --quick --json --out report");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    std::vector<std::string> environments, methods;
    for (const auto& e : j.at("environments")) environments.push_back(e.at("name"));
    for (const auto& m : j.at("methods")) methods.push_back(m);
    for (const char* name : {"sun-1e2", "sun-1e3", "sun-1e4", "sun-1e5", "sun-1e6", "texel", "slits", "white", "studio", "black", "nan"})
        EXPECT_NE(std::find(environments.begin(), environments.end(), name), environments.end()) << name;
    for (const char* name : {"splitsum", "splitsum-sh9", "splitsum-sh9-windowed", "splitsum-irradiance-cube", "sampled-n1", "sampled-n16",
                             "sampled-n256", "sampled-n1-nopdf", "sampled-n16-nopdf", "sampled-n256-nopdf"})
        EXPECT_NE(std::find(methods.begin(), methods.end(), name), methods.end()) << name;
    std::set<std::pair<std::string, std::string>> measured;
    for (const auto& render : j.at("renders"))
        measured.insert({render.at("environment").get<std::string>(), render.at("method").get<std::string>()});
    EXPECT_EQ(measured.size(), environments.size() * methods.size());
    for (const auto& finding : j.at("findings")) {
        const std::string verdict = finding.at("verdict");
        EXPECT_TRUE(verdict == "pass" || verdict == "warn" || verdict == "fail") << verdict;
    }
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "report" / "stress.json")), j);
    std::ifstream markdown(dir / "report" / "stress.md");
    const std::string text((std::istreambuf_iterator<char>(markdown)), {});
    EXPECT_NE(text.find("## Where each method fails"), std::string::npos);
    auto png = OIIO::ImageInput::open((dir / "report" / "stress.png").string());
    ASSERT_TRUE(png);
    EXPECT_GT(png->spec().width, png->spec().height) << "columns (method x roughness) outnumber rows (environments)";
}

// `iblab bench --quick`: the three files in --out (JSON on stdout equal to bench.json, the
// CSV with a row per point, pareto.png of one chart at the asked size with something drawn
// on it), and a missing environment failing in one line that names it.
TEST_F(Cli, BenchQuickWritesCsvJsonAndChart)
{
    const Result r = run("bench --quick --json --out b --chart-width 400 --chart-height 300");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "b" / "bench.json")), j);
    ASSERT_FALSE(j.at("points").empty());
    EXPECT_EQ(j.at("references").size(), 1u);

    std::ifstream csv(dir / "b" / "bench.csv");
    std::string header, line;
    ASSERT_TRUE(std::getline(csv, header));
    EXPECT_EQ(header.rfind("environment,family,series,label,", 0), 0u) << header;
    EXPECT_NE(header.find(",cost_ms,relative_rmse,"), std::string::npos) << header;
    std::size_t rows = 0;
    while (std::getline(csv, line)) ++rows;
    EXPECT_EQ(rows, j.at("points").size());

    auto png = OIIO::ImageInput::open((dir / "b" / "pareto.png").string());
    ASSERT_TRUE(png);
    const OIIO::ImageSpec spec = png->spec();
    EXPECT_EQ(spec.width, 400);
    EXPECT_EQ(spec.height, 300);
    std::vector<std::uint8_t> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
    ASSERT_TRUE(png->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()));
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i + 2 < pixels.size(); i += std::size_t(spec.nchannels))
        colours.insert(std::uint32_t(pixels[i]) << 16 | std::uint32_t(pixels[i + 1]) << 8 | pixels[i + 2]);
    EXPECT_GT(colours.size(), 20u) << "axes, text and coloured points, not a blank image";

    const Result missing = run("bench --quick --env nosuch.exr --out m");
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_EQ(lineCount(missing.err), 1) << missing.err;
    EXPECT_NE(missing.err.find("nosuch.exr"), std::string::npos) << missing.err;
}

// `iblab bench --quick --auto`: one auto choice for the quick sky, marked on exactly one
// measured point, the two presets measured beside it, and its section in bench.md. A target
// of 255 steps (the whole display range) admits every candidate, so the choice must be the
// cheapest candidate; a hundredth of a step admits none, so it must be the most accurate,
// and the command says the target is out of reach instead of claiming it.
TEST_F(Cli, BenchQuickAutoChoosesTheCheapestWithinTheTarget)
{
    struct Measured {
        std::size_t chosen = 0, presets = 0;
        double cheapest = 1e300, lowestError = 1e300;
        const nlohmann::json* chosenPoint = nullptr;
    };
    const auto measure = [](const nlohmann::json& j) {
        Measured m;
        for (const nlohmann::json& p : j.at("points")) {
            if (p.value("auto_chosen", false)) ++m.chosen, m.chosenPoint = &p;
            if (p.at("family") == "preset") {
                ++m.presets;
                continue;
            }
            m.lowestError = std::min(m.lowestError, p.at("display_error").at("p99_steps").get<double>());
            m.cheapest = std::min(m.cheapest, p.at("cost_ms").get<double>());
        }
        return m;
    };
    const std::string common = "bench --quick --auto --width 32 --height 32 --repeats 1";

    const Result loose = run(common + " --auto-target 255 --json --out a");
    ASSERT_EQ(loose.exitCode, 0) << loose.err;
    const nlohmann::json j = nlohmann::json::parse(loose.out);
    ASSERT_EQ(j.at("auto").size(), 1u);
    const nlohmann::json& choice = j.at("auto").at(0);
    EXPECT_EQ(choice.at("environment"), "sky");
    ASSERT_TRUE(choice.at("meets_target").get<bool>());
    EXPECT_GT(choice.at("candidates_measured").get<int>(), 10);
    EXPECT_EQ(choice.at("candidates_meeting"), choice.at("candidates_measured"));
    EXPECT_FALSE(choice.at("reasons").empty());
    const Measured all = measure(j);
    EXPECT_EQ(all.presets, 2u);
    ASSERT_EQ(all.chosen, 1u);
    EXPECT_EQ(all.chosenPoint->at("label"), choice.at("chosen"));
    EXPECT_NE(all.chosenPoint->at("family"), "preset");
    EXPECT_EQ(all.chosenPoint->at("cost_ms").get<double>(), all.cheapest);
    std::ifstream markdown(dir / "a" / "bench.md");
    const std::string text((std::istreambuf_iterator<char>(markdown)), {});
    EXPECT_NE(text.find("## Auto quality"), std::string::npos);
    EXPECT_NE(text.find("preset tutorial"), std::string::npos);

    const Result strict = run(common + " --auto-target 0.01 --out s");
    ASSERT_EQ(strict.exitCode, 0) << strict.err;
    EXPECT_NE(strict.out.find("auto sky: out of reach (target 0.01 steps)"), std::string::npos) << strict.out;
    const nlohmann::json js = nlohmann::json::parse(std::ifstream(dir / "s" / "bench.json"));
    const Measured none = measure(js);
    ASSERT_EQ(none.chosen, 1u);
    EXPECT_EQ(none.chosenPoint->at("display_error").at("p99_steps").get<double>(), none.lowestError);
    EXPECT_FALSE(js.at("auto").at(0).at("meets_target").get<bool>());
}

// `iblab bench --scene sphere` (the material's roughness 0.3) on a map wide enough measures
// the sphere: the reference is widened for it. Given a reference too narrow for it, the
// command still writes its files, but says in one line why nothing was measured and what
// would be, shows no error instead of 0, and fails.
TEST_F(Cli, BenchOnASphereMeasuresItOrFailsSayingWhy)
{
    const std::string common = "bench --quick --scene sphere --env builtin:sky?width=256 --width 32 --height 32 --repeats 1";
    const Result wide = run(common + " --out wide");
    ASSERT_EQ(wide.exitCode, 0) << wide.err;
    const nlohmann::json measured = nlohmann::json::parse(std::ifstream(dir / "wide" / "bench.json"));
    ASSERT_FALSE(measured.at("points").empty());
    for (const nlohmann::json& p : measured.at("points")) {
        EXPECT_GT(p.at("error").at("pixels").get<int>(), 0) << p.at("label");
        EXPECT_GT(p.at("error").at("relative_rmse").get<double>(), 0.0) << p.at("label");
    }

    const Result narrow = run(common + " --reference-width 64 --out narrow");
    EXPECT_EQ(narrow.exitCode, 1);
    EXPECT_EQ(lineCount(narrow.err), 2) << "the environment's name as it starts, then why: " << narrow.err;
    EXPECT_NE(narrow.err.find("iblab bench: sky: not measured: no surface pixel has roughness >= 0.384, the smallest the 64-wide reference resolves; "
                              "the roughest is 0.3 (the sphere"),
              std::string::npos)
        << narrow.err;
    EXPECT_NE(narrow.err.find("(--reference-width 128)"), std::string::npos) << narrow.err;
    const nlohmann::json unmeasured = nlohmann::json::parse(std::ifstream(dir / "narrow" / "bench.json"));
    ASSERT_FALSE(unmeasured.at("points").empty());
    for (const nlohmann::json& p : unmeasured.at("points")) {
        EXPECT_EQ(p.at("error").at("pixels"), 0) << p.at("label");
        EXPECT_TRUE(p.at("error").at("relative_rmse").is_null()) << p.at("label");
    }
}

// The error view's numbers in the JSON report: one block for the frame, or one per side of
// the split; the reference's environment size and the roughness it resolves with it.
TEST_F(Cli, ErrorViewReportsMetricsAsJson)
{
    const std::string common = " --env builtin:studio?width=128 --reference-width 64 --width 40 --height 40 --gl-debug --json";
    const Result r = run("render --view error --error-space display" + common + " -o error.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "error.png"));
    const auto report = nlohmann::json::parse(r.out);
    const auto& error = report["error"];
    EXPECT_EQ(error["space"], "display");
    EXPECT_EQ(error["reference_environment"]["width"], 64);
    EXPECT_EQ(error["reference_environment"]["height"], 32);
    EXPECT_GT(error["frame"]["pixels"].get<int>(), 200);
    const double rmse = error["frame"]["relative_rmse"].get<double>();
    EXPECT_TRUE(std::isfinite(rmse) && rmse > 0.0) << rmse;
    EXPECT_GE(error["frame"]["max_relative"].get<double>(), error["frame"]["p99_relative"].get<double>());

    const Result split = run("render --view error --split 0.5 --b-method sampled --b-samples 1" + common + " -o split.png");
    ASSERT_EQ(split.exitCode, 0) << split.err;
    const auto sides = nlohmann::json::parse(split.out)["error"];
    EXPECT_GT(sides["a"]["pixels"].get<int>(), 100);
    EXPECT_GT(sides["b"]["pixels"].get<int>(), 100);
}

// --split shows A (the frame's options) left of the divider and B (--b-*) from it on.
TEST_F(Cli, SplitViewShowsAOnTheLeftAndBOnTheRight)
{
    const std::string common = " --env builtin:studio?width=128 --width 40 --height 40 --roughness 0.4 --gl-debug";
    ASSERT_EQ(run("render --method splitsum" + common + " -o a.exr").exitCode, 0);
    ASSERT_EQ(run("render --method sampled --samples 1" + common + " -o b.exr").exitCode, 0);
    const Result r = run("render --method splitsum --split 0.25 --b-method sampled --b-samples 1" + common + " -o split.exr");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    int width = 0;
    const std::vector<float> a = readExr(dir / "a.exr", width), b = readExr(dir / "b.exr", width), both = readExr(dir / "split.exr", width);
    ASSERT_EQ(width, 40);
    ASSERT_EQ(both.size(), a.size());
    int differing = 0;
    for (std::size_t i = 0; i < both.size(); ++i) {
        const int x = int(i / 4 % std::size_t(width));
        ASSERT_EQ(both[i], x < 10 ? a[i] : b[i]) << "pixel column " << x;
        differing += x >= 10 && std::abs(a[i] - b[i]) > 1e-3f;
    }
    EXPECT_GT(differing, 50) << "A and B must differ right of the divider for this to prove anything";
}

// Two conventions side by side: one row each (frame + error view), the choices that differ,
// and each one's error against the exact integral of its own BRDF.
TEST_F(Cli, ConventionsRendersEachPresetWithItsError)
{
    const Result r = run("conventions --env builtin:studio?width=128 --reference-width 64 --width 48 --height 32 --only filament --only iblab "
                         "--json -o conventions.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto report = nlohmann::json::parse(r.out);
    ASSERT_EQ(report["conventions"].size(), 2u);
    EXPECT_EQ(report["conventions"][0]["name"], "filament");
    EXPECT_NE(report["conventions"][0]["choices"]["source-mip bias"], report["conventions"][1]["choices"]["source-mip bias"]);
    for (const auto& c : report["conventions"]) {
        const double rmse = c["error"]["relative_rmse"].get<double>();
        EXPECT_TRUE(std::isfinite(rmse) && rmse > 0.0) << c["name"];
        EXPECT_GT(c["error"]["pixels"].get<int>(), 50) << c["name"];
    }
    auto input = OIIO::ImageInput::open((dir / "conventions.png").string());
    ASSERT_TRUE(input);
    EXPECT_EQ(input->spec().width, 2 * 48);
    EXPECT_EQ(input->spec().height, 2 * 32);

    const Result unknown = run("render --convention unreal -o x.png");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("unknown convention \"unreal\""), std::string::npos) << unknown.err;
}

// The reference beside two real-time methods on two maps: one row per map (reference, then
// each method's frame and error view), each method measured against that row's reference.
TEST_F(Cli, CompareShowsTheReferenceBesideEachMethodPerMap)
{
    const Result r = run("compare --env builtin:studio?width=128 --env builtin:sky?width=128 --reference-width 64 --roughness 0.5 --size 48 "
                         "--methods splitsum,fitted-lobe --json -o compare.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto report = nlohmann::json::parse(r.out);
    ASSERT_EQ(report["environments"].size(), 2u);
    for (const auto& environment : report["environments"]) {
        ASSERT_EQ(environment["methods"].size(), 2u);
        EXPECT_EQ(environment["methods"][0]["method"], "splitsum");
        EXPECT_EQ(environment["methods"][1]["method"], "fitted-lobe");
        for (const auto& m : environment["methods"]) {
            const double rmse = m["error"]["relative_rmse"].get<double>();
            EXPECT_TRUE(std::isfinite(rmse) && rmse > 0.0) << environment["environment"] << " " << m["method"];
            EXPECT_GT(m["error"]["pixels"].get<int>(), 50) << environment["environment"] << " " << m["method"];
        }
    }
    EXPECT_NE(report["environments"][0]["methods"][0]["error"]["relative_rmse"], report["environments"][1]["methods"][0]["error"]["relative_rmse"])
        << "each map is measured against its own reference";
    auto input = OIIO::ImageInput::open((dir / "compare.png").string());
    ASSERT_TRUE(input);
    EXPECT_EQ(input->spec().width, 5 * 48);
    EXPECT_EQ(input->spec().height, 2 * 48);

    const Result truth = run("compare --methods reference -o x.png");
    EXPECT_EQ(truth.exitCode, 2);
    EXPECT_NE(truth.err.find("not a real-time method"), std::string::npos) << truth.err;
}

} // namespace
