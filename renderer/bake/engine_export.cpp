#include "bake/engine_export.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "bake/bake_job.hpp"
#include "ibl/engine_sh.hpp"
#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/ktx_writer.hpp"

namespace iblab::bake {
namespace {

int log2Floor(int v)
{
    int e = 0;
    while ((v >> (e + 1)) > 0) ++e;
    return e;
}

// cmgen's sh.txt lines (outputSh): "(r, g, b); // L<l><m>, irradiance, pre-scaled base".
std::string shText(const FilamentSh& sh)
{
    static const char* names[] = {"L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22"};
    std::string out;
    char line[160];
    for (int i = 0; i < kSh9Count; ++i) {
        const glm::dvec3 c = sh[std::size_t(i)];
        std::snprintf(line, sizeof line, "(%18.15f, %18.15f, %18.15f); // %s, irradiance, pre-scaled base\n", c.x, c.y, c.z, names[i]);
        out += line;
    }
    return out;
}

// The KTX key "sh" as cmgen writes it (iblRoughnessPrefilter): "r g b\n" per coefficient.
std::string shKeyValue(const FilamentSh& sh)
{
    std::string out;
    char line[96];
    for (const glm::dvec3& c : sh) {
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", c.x, c.y, c.z);
        out += line;
    }
    return out;
}

ktx::KtxTexture lutToKtx(const BakedTexture& lut)
{
    const Image2D image = read2D(lut);
    ktx::KtxTexture t;
    t.size = image.size;
    t.faces = 1;
    std::vector<float> texels;
    texels.reserve(image.texels.size() * 4);
    for (const glm::vec4& v : image.texels) texels.insert(texels.end(), {v.x, v.y, v.z, 1.0f});
    t.levels.push_back(std::move(texels));
    return t;
}

} // namespace

EngineLayout engineLayout(EngineFormat format, int prefilterFaceSize)
{
    EngineLayout l;
    l.faceSize = prefilterFaceSize;
    const int baseExp = log2Floor(prefilterFaceSize);
    switch (format) {
    case EngineFormat::Filament: {
        // cmgen iblRoughnessPrefilter: levels (baseExp + 1) - log2(16), unless the face is
        // no larger than 16 (then every level down to 1^2).
        const int minLod = 4 < baseExp ? 4 : 0;
        l.levels = baseExp + 1 - minLod;
        l.roughness = RoughnessLayout::Quadratic;
        // cmgen reads the panorama with +Z at its centre and mirrors x (CubemapUtils::
        // equirectangularToCubemap, mirrorCubemap); iblab's centre is -Z: together a half
        // turn about +Y.
        l.engineToIblab = glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1));
        l.diffuseScale = 0.0; // Filament's diffuse is the SH
        break;
    }
    case EngineFormat::Khronos:
        // glTF-IBL-Sampler: floor(log2(resolution)) mips (down to 2^2), lod = roughness x
        // (levels - 1); its panorama lookup (filter.frag dirToUV) puts u = 0.5 at +X, growing
        // towards +Z: iblab direction (d.z, d.y, -d.x).
        l.levels = baseExp > 0 ? baseExp : 1;
        l.roughness = RoughnessLayout::Linear;
        l.engineToIblab = glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
        l.diffuseScale = 1.0 / std::numbers::pi;
        break;
    case EngineFormat::Bevy:
        // Bevy's environment_map shader samples both cubes at (x, y, -z) of its world
        // direction (right-handed, +Y up, like iblab's); mips as the IBL-Sampler makes them.
        l.levels = baseExp > 0 ? baseExp : 1;
        l.roughness = RoughnessLayout::Linear;
        l.engineToIblab = glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1));
        l.diffuseScale = 1.0 / std::numbers::pi;
        break;
    }
    return l;
}

BakeSettings engineBakeSettings(EngineFormat format, const BakeSettings& settings)
{
    const EngineLayout l = engineLayout(format, settings.prefilter.faceSize);
    BakeSettings s = settings;
    s.prefilter.faceSize = l.faceSize;
    s.prefilter.levels = l.levels;
    s.prefilter.layout = l.roughness;
    if (l.diffuseScale > 0.0 && s.irradiance == IrradianceMethod::None) s.irradiance = IrradianceMethod::Moments;
    // The Sample Viewer's LUT is the height-correlated Smith one (the IBL-Sampler's V_SmithGGXCorrelated).
    if (format == EngineFormat::Khronos) s.lut.heightCorrelatedSmith = true;
    return s;
}

CubeImage reorientCube(const CubeImage& level, const glm::dmat3& engineToIblab)
{
    CubeImage out(level.size);
    const glm::mat3 m(engineToIblab);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < level.size; ++row)
            for (int x = 0; x < level.size; ++x)
                out.at(face, x, row) = glm::vec4(level.nearest(m * out.texelDirection(face, x, row)), 1.0f);
    return out;
}

ktx::KtxTexture cubeToKtx(const BakedTexture& cube, int levels, const glm::dmat3& engineToIblab, float scale)
{
    ktx::KtxTexture t;
    t.size = cube.size;
    t.faces = 6;
    for (int m = 0; m < levels; ++m) {
        const CubeImage level = reorientCube(readCubeLevel(cube, m), engineToIblab);
        std::vector<float> texels;
        texels.reserve(level.texels.size() * 4);
        for (const glm::vec4& v : level.texels) texels.insert(texels.end(), {v.x * scale, v.y * scale, v.z * scale, 1.0f});
        t.levels.push_back(std::move(texels));
    }
    return t;
}

ExportReport exportForEngine(gl::ShaderLibrary& shaders, const Environment& environment, const BakeResult& bake, EngineFormat format,
                             const std::filesystem::path& directory)
{
    const auto start = std::chrono::steady_clock::now();
    ExportReport report;
    // The directory first: a path that cannot be written fails before a new prefilter is paid for.
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec) throw Error(directory.string(), "cannot create the directory: " + ec.message());
    const BakeSettings wanted = engineBakeSettings(format, bake.settings);
    BakeResult rebaked;
    const BakeResult* use = &bake;
    if (!(wanted == bake.settings) || (wanted.irradiance != IrradianceMethod::None && !bake.irradianceCube)) {
        if (environment.image.width == 0) throw Error(bake.source, "the export needs a new prefilter, and the environment's pixels are not loaded");
        BakeSettings s = wanted;
        s.samplesPerStep = kUnslicedBake;
        rebaked = BakeJob(shaders, environment, s).runToCompletion();
        use = &rebaked;
        report.reprefiltered = true;
    }
    const EngineLayout layout = engineLayout(format, wanted.prefilter.faceSize);
    const auto write1 = [&](const std::filesystem::path& p, const ktx::KtxTexture& t) {
        report.clippedToHalf = report.clippedToHalf || t.clipsToHalf();
        ktx::writeKtx1(p.string(), t);
        report.files.push_back(p);
    };
    const auto write2 = [&](const std::filesystem::path& p, const ktx::KtxTexture& t) {
        std::filesystem::create_directories(p.parent_path(), ec);
        if (ec) throw Error(p.parent_path().string(), "cannot create the directory: " + ec.message());
        report.clippedToHalf = report.clippedToHalf || t.clipsToHalf();
        ktx::writeKtx2(p.string(), t);
        report.files.push_back(p);
    };
    // cmgen names its files after the deploy directory; so do the other layouts here.
    std::string name = std::filesystem::absolute(directory).lexically_normal().filename().string();
    if (name.empty()) name = std::filesystem::absolute(directory).lexically_normal().parent_path().filename().string();

    switch (format) {
    case EngineFormat::Filament: {
        const FilamentSh sh = filamentShaderSh(use->sh.irradiance, layout.engineToIblab);
        ktx::KtxTexture ibl = cubeToKtx(use->prefiltered, layout.levels, layout.engineToIblab);
        ibl.keyValues.emplace_back("sh", shKeyValue(sh));
        write1(directory / (name + "_ibl.ktx"), ibl);
        write1(directory / (name + "_skybox.ktx"), cubeToKtx(use->environmentCube, 1, layout.engineToIblab));
        writeTextFileAtomic((directory / "sh.txt").string(), shText(sh));
        report.files.push_back(directory / "sh.txt");
        break;
    }
    case EngineFormat::Khronos:
        write2(directory / "ggx" / "specular.ktx2", cubeToKtx(use->prefiltered, layout.levels, layout.engineToIblab));
        write2(directory / "lambertian" / "diffuse.ktx2",
               cubeToKtx(use->irradianceCube, 1, layout.engineToIblab, float(layout.diffuseScale)));
        write2(directory / "lut_ggx.ktx2", lutToKtx(use->lut(GeometryTerm::HeightCorrelatedSmith)));
        break;
    case EngineFormat::Bevy:
        write2(directory / (name + "_specular.ktx2"), cubeToKtx(use->prefiltered, layout.levels, layout.engineToIblab));
        write2(directory / (name + "_diffuse.ktx2"), cubeToKtx(use->irradianceCube, 1, layout.engineToIblab, float(layout.diffuseScale)));
        break;
    }
    report.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return report;
}

} // namespace iblab::bake
