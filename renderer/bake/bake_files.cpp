#include "bake/bake_files.hpp"

#include <bit>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/bake_passes.hpp"
#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_codec.hpp"
#include "io/image_codec_direct.hpp"
#include "io/image_writer.hpp"
#include "io/shading_lights_json.hpp"

namespace iblab::bake {
namespace {

std::string irradianceFileName(IrradianceMethod method) { return "irradiance_" + std::string(enumName(method)) + ".exr"; }

namespace fs = std::filesystem;
using nlohmann::ordered_json;

struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
};

RgbImage readExrRgb(const fs::path& path)
{
    if (!fs::exists(path))
        throw BakeFileError(path, "missing");
    std::string openError;
    const std::unique_ptr<ImageReader> in = imageCodec().openFile(path.string(), openError);
    if (!in)
        throw BakeFileError(path, "cannot open: " + oneLine(openError));
    const ImageHeader& spec = in->header();
    if (spec.channels < 3)
        throw BakeFileError(path, "has " + std::to_string(spec.channels) + " channels, expected RGB");
    RgbImage image{spec.width, spec.height, std::vector<float>(std::size_t(spec.width) * std::size_t(spec.height) * 3)};
    // A truncated file opens (the header is intact) and fails here.
    if (!in->readImage(3, PixelType::Float, image.rgb.data()))
        throw BakeFileError(path, "cannot read pixels: " + oneLine(in->takeError()));
    return image;
}

// RGB of the RGBA texels read back, a tile per face.
void writeCubeExr(const fs::path& path, const StoredCubeLevel& image, const BakeSnapshot& snapshot)
{
    writeExr(path.string(),
             ExrPixels{.width = image.size,
                       .height = 6 * image.size,
                       .channels = 3,
                       .pixelValues = 4,
                       .type = image.internalFormat == GL_RGBA16F ? ExrPixelType::Half : ExrPixelType::Float,
                       .data = image.bytes.get()},
             {.exrCompression = snapshot.exrCompression, .exrTileSize = image.size, .durability = snapshot.durability});
}

// A cube level as writeCubeExr stored it, into the texture format's own layout (RGB from the
// file, A = 1): uploaded as it is, with no conversion on either side.
StoredCubeLevel readStoredCubeExr(const fs::path& path, int expectedSize, GLenum internalFormat)
{
    if (!fs::exists(path))
        throw BakeFileError(path, "missing");
    StoredCubeLevel stored{expectedSize, internalFormat, nullptr};
    stored.bytes = std::make_unique_for_overwrite<std::byte[]>(stored.byteCount());
    const std::size_t texels = std::size_t(6) * std::size_t(expectedSize) * std::size_t(expectedSize);
    const bool halfTexels = internalFormat == GL_RGBA16F;
    if (halfTexels) {
        auto* values = reinterpret_cast<std::uint16_t*>(stored.bytes.get());
        for (std::size_t i = 0; i < texels; ++i)
            values[i * 4 + 3] = 0x3C00; // 1.0 as a half
    } else {
        auto* values = reinterpret_cast<float*>(stored.bytes.get());
        for (std::size_t i = 0; i < texels; ++i)
            values[i * 4 + 3] = 1.0f;
    }
    try {
        readExrDirect(path.string(), {.width = expectedSize,
                                      .height = 6 * expectedSize,
                                      .channels = 3,
                                      .pixelValues = 4,
                                      .type = halfTexels ? ExrPixelType::Half : ExrPixelType::Float,
                                      .data = stored.bytes.get()});
    } catch (const Error& e) {
        // Its message already names the file.
        std::string problem = e.what();
        if (const std::string named = path.string() + ": "; problem.rfind(named, 0) == 0)
            problem.erase(0, named.size());
        throw BakeFileError(path, problem);
    }
    return stored;
}

ordered_json shArray(const SH9Color& sh)
{
    ordered_json a = ordered_json::array();
    for (const glm::dvec3& c : sh.c)
        a.push_back({c.x, c.y, c.z});
    return a;
}

SH9Color shFromArray(const fs::path& file, const nlohmann::json& a)
{
    if (!a.is_array() || a.size() != std::size_t(kSh9Count))
        throw BakeFileError(file, "expected 9 RGB coefficients");
    SH9Color sh;
    for (std::size_t i = 0; i < sh.c.size(); ++i) {
        const auto& c = a[i];
        if (!c.is_array() || c.size() != 3 || !c[0].is_number() || !c[1].is_number() || !c[2].is_number())
            throw BakeFileError(file, "coefficient " + std::to_string(i) + " is not [r, g, b]");
        sh.c[i] = {c[0].get<double>(), c[1].get<double>(), c[2].get<double>()};
    }
    return sh;
}

nlohmann::json readJson(const fs::path& path)
{
    if (!fs::exists(path))
        throw BakeFileError(path, "missing");
    std::string text;
    try {
        text = readTextFile(path.string());
    } catch (const Error& e) {
        throw BakeFileError(path, e.what());
    }
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw BakeFileError(path, std::string("bad JSON: ") + oneLine(e.what()));
    }
}

ordered_json textureJson(const BakedTexture& t)
{
    return {{"face_size", t.size}, {"levels", t.levels}, {"format", t.internalFormat == GL_RGBA16F ? "rgba16f" : "rgba32f"}};
}

std::string prefilterFile(int level) { return "prefiltered_mip" + std::to_string(level) + ".exr"; }

constexpr const char* kMirrorOfEnvironmentLevel = "mirror_of_environment_level";

// The format bake.json records for a cube (textureJson's), or the settings' where it records
// none: a half-precision bake of a map brighter than a half float is stored in floats.
GLenum storedFormat(const nlohmann::json& meta, const std::string& cube, GLenum settingsFormat, const fs::path& metaPath)
{
    if (!meta.contains(cube) || !meta[cube].is_object() || !meta[cube].contains("format"))
        return settingsFormat;
    const nlohmann::json& named = meta[cube]["format"];
    if (named != "rgba16f" && named != "rgba32f")
        throw BakeFileError(metaPath, cube + ".format is neither rgba16f nor rgba32f");
    return named == "rgba32f" ? GL_RGBA32F : GL_RGBA16F;
}

} // namespace

std::string shJsonText(const ShResult& sh, int indent)
{
    ordered_json j;
    j["basis"] = kSh9Convention;
    j["radiance"] = shArray(sh.radiance);
    j["irradiance"] = shArray(sh.irradiance);
    j["irradiance_windowed"] = shArray(sh.irradianceWindowed);
    j["window"] = enumName(sh.window);
    j["window_width"] = sh.windowWidth;
    return j.dump(indent);
}

BakeSnapshot snapshotBake(const BakeResult& result, const std::string& extraJson, MirrorFile mirror)
{
    BakeSnapshot snapshot;
    snapshot.cubes.push_back({"environment.exr", readStoredCubeLevel(result.environmentCube, 0)});
    if (result.irradianceCube)
        snapshot.cubes.push_back({irradianceFileName(result.settings.irradiance), readStoredCubeLevel(result.irradianceCube, 0)});
    std::optional<int> mirrorSource;
    for (int level = 0; level < result.prefiltered.levels; ++level) {
        const std::optional<int> source =
            BakePasses::mirrorSourceLevel(result.environmentCube, result.prefiltered, level, result.settings.prefilter);
        if (mirror == MirrorFile::FromEnvironment && source)
            mirrorSource = source;
        else
            snapshot.cubes.push_back({prefilterFile(level), readStoredCubeLevel(result.prefiltered, level)});
    }
    snapshot.shJson = shJsonText(result.sh) + "\n";

    ordered_json files = ordered_json::array();
    for (const auto& cube : snapshot.cubes)
        files.push_back(cube.name);
    files.push_back("sh.json");
    ordered_json meta;
    meta["format"] = kBakeFormatVersion;
    meta["source"] = result.source;
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(result.contentHash));
    meta["content_hash"] = hash;
    meta["source_size"] = {result.sourceWidth, result.sourceHeight};
    meta["settings"] = ordered_json::parse(toJsonText(result.settings));
    meta["environment_cube"] = textureJson(result.environmentCube);
    if (result.irradianceCube)
        meta["irradiance_" + std::string(enumName(result.settings.irradiance))] = textureJson(result.irradianceCube);
    meta["prefiltered"] = textureJson(result.prefiltered);
    ordered_json roughness = ordered_json::array();
    for (int level = 0; level < result.prefiltered.levels; ++level)
        roughness.push_back(prefilterMipRoughness(result.settings.prefilter, level));
    meta["prefiltered"]["roughness_per_mip"] = roughness;
    if (mirrorSource)
        meta["prefiltered"][kMirrorOfEnvironmentLevel] = *mirrorSource;
    if (result.settings.prefilter.shadingLights > 0)
        meta["shading_lights"] = shadingLightsJson(result.shadingLights);
    meta["cube_layout"] = "one EXR per level: width = face size, height = 6 x face size, faces +X,-X,+Y,-Y,+Z,-Z top to "
                          "bottom, each face's t = 0 row first";
    meta["files"] = files;
    ordered_json timings;
    for (const PhaseTiming& t : result.timings)
        timings[std::string(enumName(t.phase))] = t.milliseconds;
    timings["total"] = result.totalMilliseconds;
    meta["timings_ms"] = timings;
    if (!extraJson.empty()) {
        const ordered_json extra = ordered_json::parse(extraJson);
        for (const auto& [key, value] : extra.items())
            meta[key] = value;
    }
    snapshot.metaJson = meta.dump(2) + "\n";
    return snapshot;
}

void writeBakeSnapshot(const fs::path& directory, const BakeSnapshot& snapshot)
{
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec)
        throw Error(directory.string(), "cannot create the directory: " + ec.message());
    for (const auto& cube : snapshot.cubes)
        writeCubeExr(directory / cube.name, cube.image, snapshot);
    writeTextFileAtomic((directory / "sh.json").string(), snapshot.shJson, snapshot.durability);
    // Last: an entry without bake.json is incomplete and reads as a miss.
    writeTextFileAtomic((directory / "bake.json").string(), snapshot.metaJson, snapshot.durability);
}

void writeBakeDirectory(const fs::path& directory, const BakeResult& result, const std::string& extraJson)
{
    writeBakeSnapshot(directory, snapshotBake(result, extraJson));
}

bool hasBakeDirectory(const fs::path& directory) { return fs::exists(directory / "bake.json"); }

void readBakeDirectory(const fs::path& directory, BakeResult& result, const MipBuilder& buildMips)
{
    const fs::path metaPath = directory / "bake.json";
    const nlohmann::json meta = readJson(metaPath);
    if (!meta.is_object() || meta.value("format", 0) != kBakeFormatVersion)
        throw BakeFileError(metaPath, "not a bake of format " + std::to_string(kBakeFormatVersion));
    const BakeSettings& s = result.settings;
    const GLenum format = s.precision == Precision::Half ? GL_RGBA16F : GL_RGBA32F;

    const int face = bakeEnvironmentFaceSize(s, result.sourceWidth, result.sourceHeight);
    const int levels = std::bit_width(unsigned(face));
    const GLenum environmentFormat = storedFormat(meta, "environment_cube", format, metaPath);
    result.environmentCube = createCubeTexture(environmentFormat, face, levels);
    uploadStoredCubeLevel(result.environmentCube, 0, readStoredCubeExr(directory / "environment.exr", face, environmentFormat));
    buildMips(result.environmentCube);

    if (s.irradiance != IrradianceMethod::None) {
        const int irradianceFace = irradianceFaceSize(s);
        const GLenum irradianceFormat = storedFormat(meta, "irradiance_" + std::string(enumName(s.irradiance)), format, metaPath);
        result.irradianceCube = createCubeTexture(irradianceFormat, irradianceFace, 1);
        uploadStoredCubeLevel(result.irradianceCube, 0,
                              readStoredCubeExr(directory / irradianceFileName(s.irradiance), irradianceFace, irradianceFormat));
    }
    const GLenum prefilteredFormat = storedFormat(meta, "prefiltered", format, metaPath);
    result.prefiltered = createCubeTexture(prefilteredFormat, s.prefilter.faceSize, s.prefilter.levels);
    int mirrorSource = -1;
    if (meta.contains("prefiltered") && meta["prefiltered"].is_object() && meta["prefiltered"].contains(kMirrorOfEnvironmentLevel)) {
        const nlohmann::json& level = meta["prefiltered"][kMirrorOfEnvironmentLevel];
        if (!level.is_number_integer())
            throw BakeFileError(metaPath, std::string("prefiltered.") + kMirrorOfEnvironmentLevel + " is not a level");
        mirrorSource = level.get<int>();
    }
    for (int level = 0; level < s.prefilter.levels; ++level) {
        // Stored once, as the environment's level (snapshotBake): the same texels again. (A
        // bake.json that names a level the settings would not copy: the file is missing.)
        if (mirrorSource >= 0 && BakePasses::mirrorSourceLevel(result.environmentCube, result.prefiltered, level, s.prefilter) == mirrorSource) {
            copyCubeRows(result.environmentCube, mirrorSource, result.prefiltered, level, 0, 6, 0, result.prefiltered.levelSize(level));
            continue;
        }
        uploadStoredCubeLevel(result.prefiltered, level, readStoredCubeExr(directory / prefilterFile(level), result.prefiltered.levelSize(level), prefilteredFormat));
    }

    if (s.prefilter.shadingLights > 0) {
        if (!meta.contains("shading_lights"))
            throw BakeFileError(metaPath, "no shading_lights, though the settings ask for " + std::to_string(s.prefilter.shadingLights));
        try {
            result.shadingLights = shadingLightsFromJson(meta["shading_lights"], "shading_lights");
        } catch (const Error& e) {
            throw BakeFileError(metaPath, e.what());
        }
        // The residual scales whole texels of the mirror per group (mirrorBlock).
        const int grid = result.shadingLights.grid;
        if (grid > s.prefilter.faceSize || s.prefilter.faceSize % grid != 0)
            throw BakeFileError(metaPath, "shading_lights: a grid of " + std::to_string(grid) + " does not divide the prefiltered face of " +
                                              std::to_string(s.prefilter.faceSize));
    }

    const fs::path shPath = directory / "sh.json";
    const nlohmann::json sh = readJson(shPath);
    if (!sh.is_object() || !sh.contains("radiance") || !sh.contains("irradiance") || !sh.contains("irradiance_windowed"))
        throw BakeFileError(shPath, "expected radiance, irradiance and irradiance_windowed");
    result.sh.radiance = shFromArray(shPath, sh["radiance"]);
    result.sh.irradiance = shFromArray(shPath, sh["irradiance"]);
    result.sh.irradianceWindowed = shFromArray(shPath, sh["irradiance_windowed"]);
    result.sh.window = parseEnum<ShWindow>(sh.value("window", std::string("none"))).value_or(ShWindow::None);
    result.sh.windowWidth = sh.value("window_width", 0.0);
}

void writeLutExr(const fs::path& path, const Image2D& lut, int samples, GeometryTerm term, bool multiscatterChannel, bool halfPixels,
                 const std::string& exrCompression, Durability durability)
{
    std::vector<float> rgb;
    rgb.reserve(lut.texels.size() * 3);
    for (const glm::vec4& t : lut.texels) {
        rgb.push_back(t.r);
        rgb.push_back(t.g);
        rgb.push_back(multiscatterChannel ? t.b : 0.0f);
    }
    // Rows in texture order, top-down writing: the file's first scanline is row 0, roughness
    // near 0 (a viewer shows the LUT upside down compared with Karis's figure; the data
    // order is what a loader uploading row 0 first expects).
    writeExr(path.string(), lut.size, lut.size, 3, rgb,
             {.settingsJson = lutJsonText(lut.size, samples, term, multiscatterChannel),
              .exrPixelType = halfPixels ? ExrPixelType::Half : ExrPixelType::Float,
              .exrCompression = exrCompression,
              .durability = durability});
}

Image2D readLutExr(const fs::path& path, int expectedSize)
{
    const RgbImage rgb = readExrRgb(path);
    if (rgb.width != expectedSize || rgb.height != expectedSize)
        throw BakeFileError(path, "is " + std::to_string(rgb.width) + "x" + std::to_string(rgb.height) + ", expected " +
                                      std::to_string(expectedSize) + "x" + std::to_string(expectedSize));
    Image2D image{expectedSize, std::vector<glm::vec4>(std::size_t(expectedSize) * std::size_t(expectedSize))};
    for (std::size_t i = 0; i < image.texels.size(); ++i)
        image.texels[i] = glm::vec4(rgb.rgb[i * 3], rgb.rgb[i * 3 + 1], rgb.rgb[i * 3 + 2], 1.0f);
    return image;
}

} // namespace iblab::bake
