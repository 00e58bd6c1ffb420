// The accuracy study's inputs, everything a measurement reads: the environments (bundled,
// unseen, procedural), the split-sum LUT and the prefiltered chain as the GPU would read
// them, the full integral per (n, v, roughness) with an on-disk cache, the pixels of the
// bench's scenes, and how a pixel's specular and diffuse combine as combineLobes does.
#include "accuracy_study.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "ibl/brdf_lut.hpp"
#include "ibl/error_metrics.hpp"
#include "ibl/reference.hpp"
#include "ibl/table_sampling.hpp"
#include "io/shading_lights_json.hpp"
#include "io/environment.hpp"

namespace iblab::accuracy {

namespace fs = std::filesystem;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// ---- The split-sum LUT as the GPU reads it ----------------------------------------------
glm::dvec3 Lut::sample(double NdotV, double roughness) const
{
    return sampleTableBilinear(NdotV, roughness, size, size, [&](int x, int y) {
        return glm::dvec3(table[std::size_t(y) * std::size_t(size) + std::size_t(x)]);
    });
}

const Lut& lut()
{
    static const Lut l = [] {
        Lut x;
        x.table = computeBrdfLut(x.size, 2048, kTerm);
        return x;
    }();
    return l;
}

// ---- On-disk cache ----------------------------------------------------------------------------
// The expensive sums (the emulated prefilter chain, the full integral per pixel) depend only
// on the environment, its width and the query list; they are kept under build/accuracy_cache
// keyed by an FNV-1a hash of all of that, so re-running a method costs lookups only.
namespace {

fs::path cacheDir()
{
    const fs::path d = fs::path(IBLAB_BINARY_DIR) / "accuracy_cache";
    fs::create_directories(d);
    return d;
}

std::uint64_t fnv(const void* data, std::size_t bytes, std::uint64_t h = 14695981039346656037ull)
{
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

std::uint64_t imageHash(const ImageRGB32F& image)
{
    std::uint64_t h = fnv(&image.width, sizeof image.width);
    h = fnv(&image.height, sizeof image.height, h);
    return fnv(image.texels.data(), image.texels.size() * sizeof(float), h);
}

template <typename T>
bool readCache(const fs::path& path, std::vector<T>& out, std::size_t count)
{
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    out.resize(count);
    f.read(reinterpret_cast<char*>(out.data()), std::streamsize(count * sizeof(T)));
    return bool(f) && f.peek() == std::char_traits<char>::eof();
}

template <typename T>
void writeCache(const fs::path& path, const std::vector<T>& data)
{
    const fs::path tmp = path.string() + ".tmp";
    std::ofstream(tmp, std::ios::binary).write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size() * sizeof(T)));
    fs::rename(tmp, path);
}

// PrefilteredChain's mips, cached (mip 1 of a 256-wide map alone is 10^9 texel terms).
std::shared_ptr<PrefilteredChain> cachedChain(const ImageRGB32F& image, std::uint64_t hash)
{
    char name[64];
    std::snprintf(name, sizeof name, "chain-%016llx.bin", static_cast<unsigned long long>(hash));
    const fs::path path = cacheDir() / name;
    const int levels = 6;
    std::vector<ImageRGB32F> mips{image};
    std::size_t floats = 0;
    for (int m = 1; m < levels; ++m) {
        const int w = std::max(32, std::min(image.width, 256 >> (m - 1)));
        mips.emplace_back(w, w / 2);
        floats += mips.back().texels.size();
    }
    std::vector<float> data;
    if (readCache(path, data, floats)) {
        std::size_t at = 0;
        for (int m = 1; m < levels; ++m) {
            auto& t = mips[std::size_t(m)].texels;
            std::copy(data.begin() + std::ptrdiff_t(at), data.begin() + std::ptrdiff_t(at + t.size()), t.begin());
            at += t.size();
        }
        return std::make_shared<PrefilteredChain>(PrefilteredChain::fromMips(std::move(mips), PREFILTER_LAYOUT_QUADRATIC));
    }
    auto chain = std::make_shared<PrefilteredChain>(image, levels, PREFILTER_LAYOUT_QUADRATIC);
    for (int m = 1; m < levels; ++m) data.insert(data.end(), chain->mip(m).texels.begin(), chain->mip(m).texels.end());
    writeCache(path, data);
    return chain;
}

std::string shortName(const std::string& spec, const std::string& set)
{
    if (spec.rfind("builtin:", 0) == 0) return "builtin-" + spec.substr(8);
    const std::string stem = fs::path(spec).stem().string();
    return set == "unseen" ? "pmndrs-" + stem : stem;
}

} // namespace

// ---- Environments --------------------------------------------------------------------------
std::vector<std::pair<std::string, std::string>> environmentList(const std::string& sets, const std::vector<std::string>& extra)
{
    std::vector<std::pair<std::string, std::string>> out; // (spec, set)
    auto addDir = [&](const fs::path& dir, const std::string& set) {
        std::vector<std::string> files;
        if (fs::exists(dir))
            for (const auto& e : fs::directory_iterator(dir))
                if (e.path().extension() == ".exr") files.push_back(e.path().string());
        std::sort(files.begin(), files.end());
        for (const auto& f : files) out.emplace_back(f, set);
    };
    if (sets.find("bundled") != std::string::npos) addDir(kSourceDir / "assets" / "environments", "bundled");
    if (sets.find("unseen") != std::string::npos) addDir(kSourceDir / ".." / "shared" / "assets" / "hdri" / "pmndrs", "unseen");
    if (sets.find("procedural") != std::string::npos)
        for (const char* spec : {"builtin:sun", "builtin:sky", "builtin:studio"}) out.emplace_back(spec, "procedural");
    for (const auto& e : extra) out.emplace_back(e, "extra");
    return out;
}

void splitShadingLightsOf(EnvCase& env, const std::string& bakes)
{
    if (!env.bake) throw std::runtime_error("--lights reads the lights a bake found: give --bakes DIR");
    const fs::path meta = fs::path(bakes) / env.name / "bake.json";
    std::ifstream in(meta);
    const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
    if (json.is_discarded() || !json.contains("shading_lights"))
        throw std::runtime_error(meta.string() + ": no shading_lights (bake again with --prefilter-shading-lights above 0)");
    const ShadingLights lights = shadingLightsFromJson(json["shading_lights"], meta.string());
    env.residualBake = std::make_shared<CubeChain>(env.bake->withoutShadingLights(lights));
    env.lights = std::make_shared<ReferenceSums>(lights.lights());
    env.lightsMinRoughness = std::sqrt(double(lights.minAlpha()));
}

EnvCase loadCase(const std::string& spec, const std::string& set, int width, bool withChain, const std::string& bakes)
{
    EnvCase c;
    c.name = shortName(spec, set);
    c.set = set;
    c.image = downsampleEquirectToWidth(loadEnvironment(spec).image, width);
    c.hash = imageHash(c.image);
    if (withChain && !bakes.empty()) c.bake = std::make_shared<CubeChain>(CubeChain::fromBake(fs::path(bakes) / c.name, PREFILTER_LAYOUT_QUADRATIC));
    else if (withChain) c.chain = cachedChain(c.image, c.hash);
    c.sums = std::make_shared<ReferenceSums>(c.image);
    return c;
}


std::vector<FullIntegral> fullIntegrals(const EnvCase& env, const std::vector<Query>& queries, bool withIrradiance)
{
    std::uint64_t h = env.hash;
    h = fnv(queries.data(), queries.size() * sizeof(Query), h);
    const int flag = withIrradiance ? 1 : 0;
    h = fnv(&flag, sizeof flag, h);
    char name[64];
    std::snprintf(name, sizeof name, "full-%016llx.bin", static_cast<unsigned long long>(h));
    const fs::path path = cacheDir() / name;
    std::vector<FullIntegral> out;
    if (readCache(path, out, queries.size())) return out;
    out.resize(queries.size());
    parallelFor(int(queries.size()), [&](int i) {
        const Query& q = queries[std::size_t(i)];
        out[std::size_t(i)] = env.sums->evaluate(q.n, q.v, q.roughness, kTerm, withIrradiance);
    });
    writeCache(path, out);
    return out;
}

// ---- Scenes: unit spheres, ray-traced per pixel --------------------------------------------
namespace {

// 4x MSAA's standard sample positions within a pixel (the D3D / GL pattern llvmpipe uses).
constexpr std::array<glm::dvec2, 4> kMsaaSamples{{{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}}};

// The view ray through (x, y) in pixels of a size x size frame, vertical fov 45, looking down -Z.
glm::dvec3 viewRay(int size, double x, double y)
{
    const double t = std::tan(glm::radians(22.5));
    return glm::normalize(glm::dvec3((2.0 * x / size - 1.0) * t, (2.0 * y / size - 1.0) * t, -1.0));
}

// The GPU's spheres are scene/sphere.cpp's makeUvSphere(1, segments, rings), 64 x 32 for the
// sphere scene and 32 x 16 for the grid's (gpu_scene.cpp): flat triangles between vertices
// at (sin t sin p, cos t, sin t cos p), t = pi j / rings, p = 2 pi i / segments, each
// vertex's normal its position. At a point of a triangle the interpolated normal is then the
// normalised point itself. Where a sphere is a few pixels wide (the grid), the grazing
// pixels' n.v and which edge pixels are covered at all follow the mesh, not the sphere, and
// the split sum's error lives in those pixels.
struct UvSphereMesh {
    int segments, rings;
    glm::dvec3 vertex(int ring, int segment) const
    {
        const double t = kPi * ring / rings, p = 2.0 * kPi * segment / segments;
        return {std::sin(t) * std::sin(p), std::cos(t), std::sin(t) * std::cos(p)};
    }
};
constexpr UvSphereMesh kSphereSceneMesh{64, 32}, kGridMesh{32, 16};

// Ray (origin o, direction d) against triangle (a, b, c), Moller-Trumbore: the distance, or
// a negative value on a miss.
double rayTriangle(glm::dvec3 o, glm::dvec3 d, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c)
{
    const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
    const double det = glm::dot(e1, q);
    if (std::abs(det) < 1e-14) return -1.0;
    const glm::dvec3 s = o - a;
    const double u = glm::dot(s, q) / det;
    const glm::dvec3 r = glm::cross(s, e1);
    const double v = glm::dot(d, r) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) return -1.0;
    return glm::dot(e2, r) / det;
}

// The nearest hit of the ray with the mesh of a unit sphere at the origin (o relative to its
// centre): the distance, negative on a miss. The mesh lies inside the sphere, so only rays
// that hit the sphere are tried, against the quads around the sphere's hit point.
double rayUvSphere(const UvSphereMesh& mesh, glm::dvec3 o, glm::dvec3 d)
{
    const double b = glm::dot(o, d);
    const double disc = b * b - (glm::dot(o, o) - 1.0);
    if (disc < 0.0) return -1.0;
    const glm::dvec3 p = o + (-b - std::sqrt(disc)) * d;
    const int ring = std::clamp(int(std::acos(std::clamp(p.y, -1.0, 1.0)) / kPi * mesh.rings), 0, mesh.rings - 1);
    double phi = std::atan2(p.x, p.z);
    if (phi < 0.0) phi += 2.0 * kPi;
    const int segment = int(phi / (2.0 * kPi) * mesh.segments);
    double best = -1.0;
    for (int j = std::max(ring - 1, 0); j <= std::min(ring + 1, mesh.rings - 1); ++j)
        for (int i = segment - 1; i <= segment + 1; ++i) {
            const glm::dvec3 v00 = mesh.vertex(j, i), v01 = mesh.vertex(j, i + 1), v10 = mesh.vertex(j + 1, i), v11 = mesh.vertex(j + 1, i + 1);
            for (const double t : {rayTriangle(o, d, v00, v10, v11), rayTriangle(o, d, v00, v11, v01)})
                if (t > 0.0 && (best < 0.0 || t < best)) best = t;
        }
    return best;
}

// The nearest sphere mesh hit by the ray from eye along d: (index into centres, distance),
// index -1 when none.
std::pair<int, double> nearestSphere(const UvSphereMesh& mesh, glm::dvec3 eye, glm::dvec3 d, const std::vector<glm::dvec3>& centres)
{
    std::pair<int, double> best{-1, 1e30};
    for (std::size_t k = 0; k < centres.size(); ++k) {
        const double dist = rayUvSphere(mesh, eye - centres[k], d);
        if (dist > 0.0 && dist < best.second) best = {int(k), dist};
    }
    return best;
}

// The surface pixels of the unit sphere meshes at `centres` seen from `eye`, shaded at the
// pixel centre; with msaaCoverage only those whose four MSAA samples all hit a sphere, as the
// bench measures (isMeasuredPixel: an edge pixel mixes in the sky). `material(k)` gives
// sphere k's (roughness, metallic).
template <typename Material>
std::vector<Pixel> tracePixels(const UvSphereMesh& mesh, int size, glm::dvec3 eye, const std::vector<glm::dvec3>& centres, bool msaaCoverage,
                               const Material& material)
{
    std::vector<Pixel> px;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const glm::dvec3 d = viewRay(size, i + 0.5, j + 0.5);
            const auto [k, dist] = nearestSphere(mesh, eye, d, centres);
            if (k < 0) continue;
            if (msaaCoverage && std::any_of(kMsaaSamples.begin(), kMsaaSamples.end(), [&](glm::dvec2 s) {
                    return nearestSphere(mesh, eye, viewRay(size, i + s.x, j + s.y), centres).first < 0;
                }))
                continue;
            const auto [roughness, metallic] = material(k);
            px.push_back({glm::normalize(eye + dist * d - centres[std::size_t(k)]), -d, roughness, metallic});
        }
    return px;
}

} // namespace

std::vector<Pixel> spherePixels(int size, double distance, bool msaaCoverage)
{
    return tracePixels(kSphereSceneMesh, size, glm::dvec3(0.0, 0.0, distance), {glm::dvec3(0.0)}, msaaCoverage, [](int) { return std::pair{0.0, 0.0}; });
}

// The 7 x 7 grid (scene/sphere.cpp: metallic = row / 6 upwards, roughness = column / 6 to the
// right, spacing 2.5) with its labels' bounds, framed by frameBox (camera.cpp) at yaw = pitch
// = 0 and aspect 1, as gpu_scene.cpp and the bench do.
std::vector<Pixel> gridPixels(int size, bool msaaCoverage)
{
    const double spacing = 2.5;
    auto offset = [&](int i) { return (i - 3) * spacing; };
    glm::dvec3 lo(1e9), hi(-1e9);
    auto extend = [&](glm::dvec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); };
    std::vector<glm::dvec3> centres;
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) {
            centres.emplace_back(offset(c), offset(r), 0.0);
            extend(centres.back() - 1.0);
            extend(centres.back() + 1.0);
        }
    const double left = offset(0), bottom = offset(0);
    // Labels: axis titles at 1.5 spacings (the metallic title one unit further left, half
    // width 2), ticks at 0.75 spacings (half width 0.6), all +-0.4 high.
    auto label = [&](glm::dvec3 p, double halfWidth) {
        extend(p - glm::dvec3(halfWidth, 0.4, 0.0));
        extend(p + glm::dvec3(halfWidth, 0.4, 0.0));
    };
    label({left - 1.5 * spacing - 1.0, 0.0, 0.0}, 2.0);
    label({0.0, bottom - 1.5 * spacing, 0.0}, 2.0);
    for (int r = 0; r < 7; ++r) label({left - 0.75 * spacing, offset(r), 0.0}, 0.6);
    for (int c = 0; c < 7; ++c) label({offset(c), bottom - 0.75 * spacing, 0.0}, 0.6);
    const glm::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const double t = std::tan(glm::radians(22.5));
    const double distance = 1.08 * std::max(half.x / t, half.y / t) + half.z;
    const glm::dvec3 eye = centre + glm::dvec3(0.0, 0.0, distance);
    return tracePixels(kGridMesh, size, eye, centres, msaaCoverage, [](int k) { return std::pair{(k % 7) / 6.0, (k / 7) / 6.0}; });
}

double pixelError(glm::dvec3 value, glm::dvec3 reference)
{
    return double(relativeError(glm::vec3(value), glm::vec3(reference)));
}

// Shades a pixel's diffuse and specular as combineLobes does, given the specular radiance.
Shaded combine(const Pixel& p, glm::dvec3 specular, glm::dvec3 irradiance, glm::dvec3 F0)
{
    const double NdotV = std::max(glm::dot(p.n, p.v), 1e-4);
    const SurfaceMaterial material{.baseColor = kCopper, .metallic = p.metallic, .roughness = p.roughness, .F0 = F0};
    return {combineLobes(material, NdotV, irradiance, specular), specular};
}

} // namespace iblab::accuracy
