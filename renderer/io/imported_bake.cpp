// Other tools' bakes as environments (imported_bake.hpp). The orientations and the SH scaling
// are the tools' conventions, with their sources in docs/engine-import.md.
#include "io/imported_bake.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ibl/conventions.hpp"
#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_codec_direct.hpp"
#include "io/image_writer.hpp"
#include "io/ktx_cube.hpp"

namespace iblab {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() && lower(s.substr(s.size() - suffix.size())) == suffix;
}

// The texel of a cube strip in whose footprint direction d lies.
glm::vec3 nearestTexel(const ImageRGB32F& strip, glm::dvec3 d)
{
    const int size = strip.width;
    const glm::vec3 fst = directionToCubeFaceUv(glm::vec3(d));
    const int face = std::clamp(int(std::lround(fst.x)), 0, 5);
    const int x = std::clamp(int(std::floor(fst.y * float(size))), 0, size - 1);
    const int row = std::clamp(int(std::floor(fst.z * float(size))), 0, size - 1);
    return strip.at(x, face * size + row);
}

std::vector<ImageRGB32F> reorientLevels(const KtxCube& cube, const AxisMap& fileToWorld)
{
    std::vector<ImageRGB32F> levels;
    for (const ImageRGB32F& level : cube.levels)
        levels.push_back(reorientCubeStrip(level, fileToWorld));
    return levels;
}

void noteRepairs(const KtxCube& cube, const std::string& file, ImportedBake& bake)
{
    if (cube.repairedComponents > 0)
        bake.notes.push_back(file + ": " + std::to_string(cube.repairedComponents) + " NaN, infinite or negative components replaced by 0");
}

// Filament cmgen: NAME_ibl.ktx (prefiltered, `sh`), NAME_skybox.ktx beside it.
std::shared_ptr<ImportedBake> loadCmgen(const std::string& spec)
{
    auto bake = std::make_shared<ImportedBake>();
    bake->kind = ImportedBakeKind::Cmgen;
    const AxisMap toWorld = cmgenFileToWorld();
    const KtxCube ibl = readKtxCube(spec);
    if (ibl.version != 1) throw Error(spec, "a .ktx bake is read as cmgen's KTX 1.1 output, this file is KTX 2.0 (name it .ktx2)");
    bake->files.push_back(spec);
    noteRepairs(ibl, spec, *bake);
    bake->prefiltered = reorientLevels(ibl, toWorld);
    bake->roughnessLayout = 1;
    const std::string* sh = ibl.value("sh");
    if (sh)
        bake->shIrradiance = shFromFilament(parseFilamentSh(*sh, spec), toWorld);
    else
        bake->notes.push_back(spec + ": no `sh` key; SH irradiance is projected from the sky instead");

    std::string skyPath;
    const std::string name = fs::path(spec).filename().string();
    if (endsWith(name, "_ibl.ktx")) skyPath = (fs::path(spec).parent_path() / (name.substr(0, name.size() - 8) + "_skybox.ktx")).string();
    std::error_code ec;
    if (!skyPath.empty() && fs::is_regular_file(skyPath, ec)) {
        const KtxCube sky = readKtxCube(skyPath);
        noteRepairs(sky, skyPath, *bake);
        bake->files.push_back(skyPath);
        bake->sky = reorientCubeStrip(sky.levels.front(), toWorld);
    } else {
        bake->sky = bake->prefiltered.front();
        bake->notes.push_back(spec + ": no NAME_skybox.ktx beside it; the sky is the prefiltered mip 0 (roughness 0)");
    }
    return bake;
}

std::optional<std::pair<std::string, std::string>> khronosPairIn(const fs::path& dir)
{
    std::error_code ec;
    const std::pair<const char*, const char*> layouts[] = {{"specular.ktx2", "diffuse.ktx2"},
                                                           {"ggx/specular.ktx2", "lambertian/diffuse.ktx2"},
                                                           {"ggx.ktx2", "lambertian.ktx2"}};
    for (const auto& [specular, diffuse] : layouts)
        if (fs::is_regular_file(dir / specular, ec) && fs::is_regular_file(dir / diffuse, ec))
            return std::make_pair((dir / specular).string(), (dir / diffuse).string());
    return std::nullopt;
}

std::pair<std::string, std::string> khronosPair(const std::string& spec)
{
    const std::size_t comma = spec.find(',');
    if (comma != std::string::npos) return {spec.substr(0, comma), spec.substr(comma + 1)};
    std::error_code ec;
    if (fs::is_directory(spec, ec)) {
        if (auto pair = khronosPairIn(spec)) return *pair;
        throw Error(spec, "no specular.ktx2 + diffuse.ktx2 (or ggx/specular.ktx2 + lambertian/diffuse.ktx2) in this directory");
    }
    // SPECULAR.ktx2: its diffuse partner by the Sample Viewer's names.
    const fs::path path(spec);
    std::string name = path.filename().string();
    for (const auto& [from, to] : {std::pair{"specular", "diffuse"}, std::pair{"ggx", "lambertian"}}) {
        const std::size_t at = name.find(from);
        if (at == std::string::npos) continue;
        const fs::path diffuse = path.parent_path() / name.replace(at, std::string(from).size(), to);
        if (fs::is_regular_file(diffuse, ec)) return {spec, diffuse.string()};
    }
    throw Error(spec, "no diffuse cube beside it (name the pair: SPECULAR.ktx2,DIFFUSE.ktx2)");
}

// The glTF-IBL-Sampler's GGX specular and Lambertian diffuse cubes.
std::shared_ptr<ImportedBake> loadKhronos(const std::string& spec)
{
    auto bake = std::make_shared<ImportedBake>();
    bake->kind = ImportedBakeKind::Khronos;
    const AxisMap toWorld = khronosFileToWorld();
    const auto [specularPath, diffusePath] = khronosPair(spec);
    const KtxCube specular = readKtxCube(specularPath);
    const KtxCube diffuse = readKtxCube(diffusePath);
    noteRepairs(specular, specularPath, *bake);
    noteRepairs(diffuse, diffusePath, *bake);
    bake->files = {specularPath, diffusePath};
    bake->prefiltered = reorientLevels(specular, toWorld);
    bake->roughnessLayout = 0;
    bake->sky = bake->prefiltered.front();
    // The Sample Viewer's Lambertian cube holds the cosine-weighted mean of the radiance,
    // E / pi (filter.frag divides by the sample count); iblab's irradiance cubes hold E.
    ImageRGB32F irradiance = reorientCubeStrip(diffuse.levels.front(), toWorld);
    for (float& v : irradiance.texels)
        v *= float(kPi);
    bake->irradiance = std::move(irradiance);
    bake->notes.push_back(spec + ": no SH in a KTX2 pair; SH irradiance is projected from the specular mip 0");
    return bake;
}

// A cube level of an iblab bake directory: an RGB EXR strip of size x 6 size.
ImageRGB32F readIblabStrip(const fs::path& path, int size)
{
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw Error(path.string(), "missing (bake.json lists it)");
    ImageRGB32F strip(size, 6 * size);
    readExrDirect(path.string(), {.width = size, .height = 6 * size, .channels = 3, .pixelValues = 3, .type = ExrPixelType::Float, .data = strip.texels.data()});
    for (float& v : strip.texels)
        if (!std::isfinite(v) || v < 0.0f) throw Error(path.string(), "holds a NaN, infinite or negative texel");
    return strip;
}

nlohmann::json readJsonFile(const fs::path& path)
{
    nlohmann::json j = nlohmann::json::parse(readTextFile(path.string()), nullptr, false);
    if (j.is_discarded() || !j.is_object()) throw Error(path.string(), "not a JSON object");
    return j;
}

// A cube's face size from bake.json ({"face_size": n, ...}), checked.
int faceSizeOf(const nlohmann::json& meta, const std::string& key, const fs::path& file)
{
    const auto it = meta.find(key);
    if (it == meta.end() || !it->is_object() || !it->contains("face_size") || !(*it)["face_size"].is_number_integer())
        throw Error(file.string(), key + ".face_size is missing");
    const int size = (*it)["face_size"].get<int>();
    if (size < 1 || size > 8192) throw Error(file.string(), key + ".face_size " + std::to_string(size) + " is out of range");
    return size;
}

SH9Color shOf(const nlohmann::json& sh, const std::string& key, const fs::path& file)
{
    SH9Color out;
    const auto it = sh.find(key);
    if (it == sh.end() || !it->is_array() || it->size() != 9) throw Error(file.string(), key + " is not 9 RGB coefficients");
    for (std::size_t i = 0; i < 9; ++i) {
        const nlohmann::json& c = (*it)[i];
        if (!c.is_array() || c.size() != 3) throw Error(file.string(), key + " is not 9 RGB coefficients");
        for (int k = 0; k < 3; ++k) {
            if (!c[std::size_t(k)].is_number()) throw Error(file.string(), key + " is not 9 RGB coefficients");
            out.c[i][k] = c[std::size_t(k)].get<double>();
        }
    }
    return out;
}

// iblab's own `bake --out` directory (bake/bake_files.hpp). The roughness layout is told
// from bake.json's roughness_per_mip, which states what each mip holds.
std::shared_ptr<ImportedBake> loadIblabDirectory(const std::string& spec)
{
    const fs::path dir(spec);
    const fs::path metaPath = dir / "bake.json";
    const nlohmann::json meta = readJsonFile(metaPath);
    auto bake = std::make_shared<ImportedBake>();
    bake->kind = ImportedBakeKind::Iblab;
    bake->files.push_back(metaPath.string());
    const int prefilterSize = faceSizeOf(meta, "prefiltered", metaPath);
    const nlohmann::json& roughness = meta["prefiltered"].value("roughness_per_mip", nlohmann::json::array());
    const int levels = int(roughness.size());
    if (levels < 1 || levels > int(std::bit_width(unsigned(prefilterSize))))
        throw Error(metaPath.string(), "prefiltered.roughness_per_mip lists " + std::to_string(levels) + " mips for a " + std::to_string(prefilterSize) + "^2 cube");
    bool linear = true, quadratic = true;
    for (int m = 0; m < levels; ++m) {
        if (!roughness[std::size_t(m)].is_number()) throw Error(metaPath.string(), "prefiltered.roughness_per_mip holds a non-number");
        const double r = roughness[std::size_t(m)].get<double>();
        const double t = levels > 1 ? double(m) / double(levels - 1) : 0.0;
        linear = linear && std::abs(r - t) < 1e-4;
        quadratic = quadratic && std::abs(r - (1.0 - std::sqrt(1.0 - t))) < 1e-4;
    }
    if (!linear && !quadratic) throw Error(metaPath.string(), "prefiltered.roughness_per_mip follows neither the linear nor the quadratic layout");
    bake->roughnessLayout = quadratic && !linear ? 1 : 0;
    for (int m = 0; m < levels; ++m) {
        const fs::path file = dir / ("prefiltered_mip" + std::to_string(m) + ".exr");
        bake->prefiltered.push_back(readIblabStrip(file, std::max(prefilterSize >> m, 1)));
        bake->files.push_back(file.string());
    }
    bake->sky = readIblabStrip(dir / "environment.exr", faceSizeOf(meta, "environment_cube", metaPath));
    bake->files.push_back((dir / "environment.exr").string());
    for (const auto& [key, value] : meta.items())
        if (key.rfind("irradiance_", 0) == 0 && value.is_object()) {
            const fs::path file = dir / (key + ".exr");
            bake->irradiance = readIblabStrip(file, faceSizeOf(meta, key, metaPath));
            bake->files.push_back(file.string());
            break;
        }
    const fs::path shPath = dir / "sh.json";
    const nlohmann::json sh = readJsonFile(shPath);
    bake->shIrradiance = shOf(sh, "irradiance", shPath);
    ImportedBake::WindowedSh windowed{shOf(sh, "irradiance_windowed", shPath), ShWindow::None, sh.value("window_width", 0.0)};
    windowed.window = parseEnum<ShWindow>(sh.value("window", std::string("none"))).value_or(ShWindow::None);
    bake->shWindowed = windowed;
    bake->files.push_back(shPath.string());
    return bake;
}

} // namespace

AxisMap AxisMap::inverse() const
{
    AxisMap inv;
    for (int k = 0; k < 3; ++k) {
        inv.axis[axis[k]] = k;
        inv.sign[axis[k]] = sign[k];
    }
    return inv;
}

// Measured with cmgen 1.9.25 (Debian libfilament-tools) on a map whose colour is its
// direction (tests/cpu/imported_bake_test.cpp, CmgenOrientation): the texel of cmgen's cube
// at GL direction (x, y, z) holds iblab's direction (-x, y, -z), a half turn about +Y. Its
// `sh` is in the same frame.
AxisMap cmgenFileToWorld() { return {{0, 1, 2}, {-1.0, 1.0, -1.0}}; }

// glTF-IBL-Sampler lib/shaders/filter.frag: panoramaToCubeMap writes face texel uv (fragment
// rows from the top, uv.y = 2 t - 1) with uvToXYZ(face, uv), which is GL's direction d with y
// negated, and reads the panorama at dirToUV: u = 0.5 + atan(z, x) / (2 pi),
// v = 1 - acos(y) / pi; filterCubeMap negates y again before filtering. Equal longitude and
// latitude in iblab's equirect (u = 0.5 + atan(x, -z) / (2 pi), v = acos(y) / pi) give world
// direction (d.z, d.y, -d.x): a quarter turn about +Y.
AxisMap khronosFileToWorld() { return {{2, 1, 0}, {1.0, 1.0, -1.0}}; }

ImageRGB32F reorientCubeStrip(const ImageRGB32F& strip, const AxisMap& fileToWorld)
{
    const int size = strip.width;
    const AxisMap worldToFile = fileToWorld.inverse();
    ImageRGB32F out(size, 6 * size);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x) {
                const glm::vec2 st((float(x) + 0.5f) / float(size), (float(row) + 0.5f) / float(size));
                const glm::dvec3 d(cubeFaceUvToDirection(face, st));
                out.set(x, face * size + row, nearestTexel(strip, worldToFile.apply(d)));
            }
    return out;
}

ImageRGB32F cubeStripToEquirect(const ImageRGB32F& strip, int width)
{
    ImageRGB32F out(width, width / 2);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec2 uv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(out.height));
            out.set(x, y, nearestTexel(strip, glm::dvec3(equirectUvToDirection(uv))));
        }
    return out;
}

std::array<glm::dvec3, 9> parseFilamentSh(const std::string& text, const std::string& file)
{
    std::istringstream in(text);
    std::array<glm::dvec3, 9> c{};
    for (int i = 0; i < 9; ++i)
        for (int k = 0; k < 3; ++k)
            if (!(in >> c[std::size_t(i)][k]) || !std::isfinite(c[std::size_t(i)][k]))
                throw Error(file, "the `sh` key holds fewer than 27 finite numbers (9 RGB coefficients)");
    return c;
}

SH9Color shFromFilament(const std::array<glm::dvec3, 9>& c, const AxisMap& fileToWorld)
{
    // E is a polynomial of degree 2 on the sphere, so its projection onto iblab's basis is
    // exact up to the quadrature: a spherical Fibonacci lattice of 16384 points integrates
    // products of degree-2 polynomials to ~1e-6 relative.
    const AxisMap worldToFile = fileToWorld.inverse();
    const int n = 16384;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    SH9Color out;
    for (int i = 0; i < n; ++i) {
        const double y = 1.0 - (2.0 * i + 1.0) / n;
        const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        const glm::dvec3 world(r * std::cos(golden * i), y, r * std::sin(golden * i));
        const glm::dvec3 f = worldToFile.apply(world);
        const double p[9] = {1.0, f.y, f.z, f.x, f.x * f.y, f.y * f.z, 3.0 * f.z * f.z - 1.0, f.z * f.x, f.x * f.x - f.y * f.y};
        glm::dvec3 e(0.0);
        for (int k = 0; k < 9; ++k)
            e += c[std::size_t(k)] * p[k];
        e *= kPi;
        const std::array<double, 9> basis = sh9Basis(world);
        for (int k = 0; k < 9; ++k)
            out.c[std::size_t(k)] += e * basis[std::size_t(k)] * (4.0 * kPi / n);
    }
    return out;
}

const char* importedBakeFormat(ImportedBakeKind kind)
{
    switch (kind) {
    case ImportedBakeKind::Cmgen: return "Filament cmgen bake (KTX1)";
    case ImportedBakeKind::Khronos: return "glTF-IBL-Sampler bake (KTX2 pair)";
    case ImportedBakeKind::Iblab: return "iblab bake (bake.json)";
    }
    return "bake";
}

bool isImportedBakeSpec(const std::string& spec)
{
    if (endsWith(spec, ".ktx") || endsWith(spec, ".ktx2")) return true;
    std::error_code ec;
    return fs::is_directory(spec, ec) && (khronosPairIn(spec).has_value() || fs::is_regular_file(fs::path(spec) / "bake.json", ec));
}

std::shared_ptr<const ImportedBake> loadImportedBake(const std::string& spec, ImageRGB32F& equirect)
{
    std::error_code ec;
    std::shared_ptr<ImportedBake> bake = endsWith(spec, ".ktx")                                  ? loadCmgen(spec)
                                         : fs::is_regular_file(fs::path(spec) / "bake.json", ec) ? loadIblabDirectory(spec)
                                                                                                 : loadKhronos(spec);
    equirect = cubeStripToEquirect(bake->sky, 4 * bake->sky.width);
    return bake;
}

} // namespace iblab
