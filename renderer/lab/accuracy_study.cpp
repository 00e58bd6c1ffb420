// accuracy_study: how far real-time specular IBL methods are from the full integral, and the
// fit of the lobe table (issue #14; docs/accuracy-study.md). CPU only, no GL.
//
//   accuracy_study eval [--width 256] [--sphere 64] [--grid 128] [--set bundled,unseen,procedural]
//                       [--env PATH|builtin:SPEC ...] [--csv FILE] [--table FILE.inc ...]
//   accuracy_study fit  [--width 256] [--taps 1|2|3] [--frames 96] [--size 16] [--out FILE.inc]
//                       [--min-roughness 0.15] [--mixed-objective] [--init ONE_TAP.inc] [--seed 14]
//   (diagnostics for eval: --bins, --exact-prefilter, --roughness 0.2,0.3,...)
//
// eval renders, per environment, the bench's scenes as the GPU shades them -- a unit sphere
// from the default camera (fov 45, distance 3.5) in copper (metallic 1) and a dielectric
// (metallic 0, F0 0.04, copper base colour) at roughness 0.2 0.3 0.5 0.7 0.9, and the 7 x 7
// metallic x roughness grid framed as `iblab bench` frames it -- and measures each method's
// relative RMSE against the full integral with the bench's per-pixel measure
// (common/error_metrics.glsl: L1 difference over the reference's channel sum; RMSE over
// the surface pixels whose roughness the reference resolves). Specular + Lambert diffuse
// with kD = (1 - F_roughness(n.v))(1 - metallic) and exact irradiance, as combineLobes.
// The prefiltered cube is emulated (PrefilteredChain: exact prefilter per mip, 6 mips in
// the quadratic layout, trilinear) and the LUT is the bake's 128^2 x 2048, read bilinearly.
//
// fit refits the lobe table on the 8 bundled maps only and writes it as a C++ include; the
// committed table (renderer/ibl/specular_lobe_fit.inc) is reproduced by
//   accuracy_study fit --taps 1 --out /tmp/one-tap.inc
//   accuracy_study fit --taps 3 --mixed-objective --init /tmp/one-tap.inc
// (docs/accuracy-study.md). Caches: build/accuracy_cache (delete it to recompute).
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "io/environment.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/error_metrics.hpp"
#include "ibl/reference.hpp"
#include "ibl/specular_approximations.hpp"

namespace fs = std::filesystem;
using namespace iblab;

namespace {

constexpr GeometryTerm kTerm = GeometryTerm::HeightCorrelatedSmith; // SamplingSettings default
const glm::dvec3 kCopper(0.95, 0.64, 0.54);                        // MaterialSettings default base colour
constexpr double kDielectricF0 = 0.04;                              // 0.16 * 0.5^2

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

template <typename Fn>
void parallelFor(int count, const Fn& fn)
{
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 64u));
    std::atomic<int> next{0};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (int i = next++; i < count; i = next++) fn(i);
        });
    for (auto& th : pool) th.join();
}

// ---- The split-sum LUT as the GPU reads it ----------------------------------------------
struct Lut {
    int size = 128;
    std::vector<glm::vec3> table;
    glm::dvec3 sample(double NdotV, double roughness) const
    {
        auto axis = [&](double x, int& i0, int& i1, double& t) {
            const double f = std::clamp(x, 0.0, 1.0) * size - 0.5;
            const double fl = std::floor(f);
            t = f - fl;
            i0 = std::clamp(int(fl), 0, size - 1);
            i1 = std::clamp(int(fl) + 1, 0, size - 1);
        };
        int x0, x1, y0, y1;
        double tx, ty;
        axis(NdotV, x0, x1, tx);
        axis(roughness, y0, y1, ty);
        auto at = [&](int x, int y) { return glm::dvec3(table[std::size_t(y) * std::size_t(size) + std::size_t(x)]); };
        return (at(x0, y0) * (1.0 - tx) + at(x1, y0) * tx) * (1.0 - ty) + (at(x0, y1) * (1.0 - tx) + at(x1, y1) * tx) * ty;
    }
};

const Lut& lut()
{
    static const Lut l = [] {
        Lut x;
        x.table = computeBrdfLut(x.size, 2048, kTerm);
        return x;
    }();
    return l;
}

// ---- Environments --------------------------------------------------------------------------
struct EnvCase {
    std::string name;
    std::string set; // bundled, unseen, procedural
    ImageRGB32F image;
    std::shared_ptr<PrefilteredChain> chain;
    std::shared_ptr<ReferenceSums> sums;
    std::uint64_t hash = 0;
};

const fs::path kSource = IBLAB_SOURCE_DIR;

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
    if (sets.find("bundled") != std::string::npos) addDir(kSource / "assets" / "environments", "bundled");
    if (sets.find("unseen") != std::string::npos) addDir(kSource / ".." / "shared" / "assets" / "hdri" / "pmndrs", "unseen");
    if (sets.find("procedural") != std::string::npos)
        for (const char* spec : {"builtin:sun", "builtin:sky", "builtin:studio"}) out.emplace_back(spec, "procedural");
    for (const auto& e : extra) out.emplace_back(e, "extra");
    return out;
}

std::string shortName(const std::string& spec, const std::string& set)
{
    if (spec.rfind("builtin:", 0) == 0) return "builtin-" + spec.substr(8);
    const std::string stem = fs::path(spec).stem().string();
    return set == "unseen" ? "pmndrs-" + stem : stem;
}

std::shared_ptr<PrefilteredChain> cachedChain(const ImageRGB32F& image, std::uint64_t hash);
std::uint64_t imageHash(const ImageRGB32F& image);

EnvCase loadCase(const std::string& spec, const std::string& set, int width, bool withChain)
{
    EnvCase c;
    c.name = shortName(spec, set);
    c.set = set;
    c.image = downsampleEquirectToWidth(loadEnvironment(spec).image, width);
    c.hash = imageHash(c.image);
    if (withChain) c.chain = cachedChain(c.image, c.hash);
    c.sums = std::make_shared<ReferenceSums>(c.image);
    return c;
}

// ---- On-disk cache ----------------------------------------------------------------------------
// The expensive sums (the emulated prefilter chain, the full integral per pixel) depend only
// on the environment, its width and the query list; they are kept under build/accuracy_cache
// keyed by an FNV-1a hash of all of that, so re-running a method costs lookups only.
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

struct Query {
    glm::dvec3 n, v;
    double roughness;
};

// The full integral for every query (parallel), through the cache.
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

// ---- Scenes ----------------------------------------------------------------------------------
struct Pixel {
    glm::dvec3 n, v;
    double roughness = 0.0;
    double metallic = 0.0;
};

// A unit sphere at the origin from the default orbit camera: position (0, 0, 3.5), looking
// down -Z, vertical fov 45, square frame. Analytic normals.
std::vector<Pixel> spherePixels(int size)
{
    std::vector<Pixel> px;
    const double t = std::tan(glm::radians(22.5));
    const glm::dvec3 eye(0.0, 0.0, 3.5);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const glm::dvec3 d = glm::normalize(glm::dvec3((2.0 * (i + 0.5) / size - 1.0) * t, (2.0 * (j + 0.5) / size - 1.0) * t, -1.0));
            const double b = glm::dot(eye, d);
            const double disc = b * b - (glm::dot(eye, eye) - 1.0);
            if (disc < 0.0) continue;
            const double dist = -b - std::sqrt(disc);
            const glm::dvec3 p = eye + dist * d;
            px.push_back({glm::normalize(p), -d, 0.0, 0.0});
        }
    return px;
}

// The 7 x 7 grid (scene/sphere.cpp: metallic = row / 6 upwards, roughness = column / 6 to the
// right, spacing 2.5) with its labels' bounds, framed by frameBox (camera.cpp) at yaw = pitch
// = 0 and aspect 1, as gpu_scene.cpp and the bench do.
std::vector<Pixel> gridPixels(int size)
{
    const double spacing = 2.5;
    auto offset = [&](int i) { return (i - 3) * spacing; };
    glm::dvec3 lo(1e9), hi(-1e9);
    auto extend = [&](glm::dvec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); };
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) {
            extend(glm::dvec3(offset(c), offset(r), 0.0) - 1.0);
            extend(glm::dvec3(offset(c), offset(r), 0.0) + 1.0);
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

    std::vector<Pixel> px;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const glm::dvec3 d = glm::normalize(glm::dvec3((2.0 * (i + 0.5) / size - 1.0) * t, (2.0 * (j + 0.5) / size - 1.0) * t, -1.0));
            double best = 1e30;
            Pixel hit{};
            bool any = false;
            for (int r = 0; r < 7; ++r)
                for (int c = 0; c < 7; ++c) {
                    const glm::dvec3 o = eye - glm::dvec3(offset(c), offset(r), 0.0);
                    const double b = glm::dot(o, d);
                    const double disc = b * b - (glm::dot(o, o) - 1.0);
                    if (disc < 0.0) continue;
                    const double dist = -b - std::sqrt(disc);
                    if (dist <= 0.0 || dist >= best) continue;
                    best = dist;
                    any = true;
                    hit = {glm::normalize(o + dist * d), -d, c / 6.0, r / 6.0};
                }
            if (any) px.push_back(hit);
        }
    return px;
}

// Diagnostics: read the exact prefilter at the requested roughness (O(texels) per read)
// instead of the emulated mip chain, to separate the chain's discrete levels from the lobe.
bool gExactPrefilter = false;
// fit --mixed-objective: also the dielectric's specular alone, so that a read that only
// the dielectric's diffuse hides (a dark dielectric would show it) is not rewarded.
bool gMixedObjective = false;
std::vector<double> gRoughnesses{0.2, 0.3, 0.5, 0.7, 0.9};

std::vector<double> parseList(const std::string& text)
{
    std::vector<double> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(std::stod(item));
    return out;
}

// ---- Methods ---------------------------------------------------------------------------------
struct Method {
    std::string name;
    std::function<glm::dvec3(const SpecularShadingInputs&, const PrefilteredLookup&)> specular;
};

std::vector<Method> methods(const std::vector<std::pair<std::string, LobeFitTable>>& tables)
{
    std::vector<Method> m;
    for (SpecularMethod s : {SpecularMethod::SplitSum, SpecularMethod::FrostbiteDominant, SpecularMethod::FrostbitePerceptual,
                             SpecularMethod::FilamentDominant, SpecularMethod::FittedLobe})
        m.push_back({std::string(specularMethodName(s)),
                     [s](const SpecularShadingInputs& in, const PrefilteredLookup& p) { return shadeSpecularApproximation(s, in, p); }});
    for (const auto& [name, table] : tables) {
        const LobeFitTable* t = &table;
        m.push_back({name, [t](const SpecularShadingInputs& in, const PrefilteredLookup& p) {
                         return shadeSpecularApproximation(SpecularMethod::FittedLobe, in, p, t);
                     }});
    }
    return m;
}

// ---- Evaluation ------------------------------------------------------------------------------
// One measured image: per method, the per-pixel relative errors of total and specular-only.
struct Errors {
    std::vector<double> total, specular;
    std::vector<double> NdotV; // per pixel, for --bins
};

double rmse(const std::vector<double>& e)
{
    double s = 0.0;
    for (double x : e) s += x * x;
    return e.empty() ? 0.0 : std::sqrt(s / double(e.size()));
}

double pixelError(glm::dvec3 value, glm::dvec3 reference)
{
    return double(relativeError(glm::vec3(value), glm::vec3(reference)));
}

struct Shaded {
    glm::dvec3 total, specular;
};

// Shades a pixel's diffuse and specular as combineLobes does, given the specular radiance.
Shaded combine(const Pixel& p, glm::dvec3 specular, glm::dvec3 irradiance, glm::dvec3 F0)
{
    const double NdotV = std::max(glm::dot(p.n, p.v), 1e-4);
    const glm::dvec3 F = fresnelSchlickRoughness(NdotV, F0, p.roughness);
    const glm::dvec3 kD = (glm::dvec3(1.0) - F) * (1.0 - p.metallic);
    return {kD * kCopper * irradiance / kPi + specular, specular};
}

// Evaluates `pixels` (roughness and metallic set) for every method; appends errors per method.
void evaluatePixels(const EnvCase& env, const std::vector<Pixel>& pixels, const std::vector<Method>& ms, std::vector<Errors>& out)
{
    const PrefilteredLookup lookup = [&](glm::dvec3 d, double r) {
        return gExactPrefilter ? referencePrefilteredRadiance(env.image, glm::normalize(d), r) : env.chain->lookup(d, r);
    };
    std::vector<Query> queries;
    for (const Pixel& p : pixels) queries.push_back({p.n, p.v, p.roughness});
    const std::vector<FullIntegral> refs = fullIntegrals(env, queries, true);
    std::vector<std::vector<std::pair<double, double>>> perPixel(pixels.size());
    parallelFor(int(pixels.size()), [&](int i) {
        const Pixel& p = pixels[std::size_t(i)];
        const glm::dvec3 F0 = glm::mix(glm::dvec3(kDielectricF0), kCopper, p.metallic);
        const FullIntegral& ref = refs[std::size_t(i)];
        const Shaded r = combine(p, ref.specular(F0), ref.irradiance, F0);
        SpecularShadingInputs in;
        in.n = p.n;
        in.v = p.v;
        in.roughness = p.roughness;
        in.F0 = F0;
        in.lut = lut().sample(std::max(glm::dot(p.n, p.v), 1e-4), p.roughness);
        auto& row = perPixel[std::size_t(i)];
        for (const Method& m : ms) {
            const Shaded a = combine(p, m.specular(in, lookup), ref.irradiance, F0);
            row.emplace_back(pixelError(a.total, r.total), pixelError(a.specular, r.specular));
        }
    });
    if (out.size() < ms.size()) out.resize(ms.size());
    for (const auto& row : perPixel)
        for (std::size_t m = 0; m < ms.size(); ++m) {
            out[m].total.push_back(row[m].first);
            out[m].specular.push_back(row[m].second);
        }
    for (std::size_t m = 0; m < ms.size(); ++m)
        for (const Pixel& p : pixels) out[m].NdotV.push_back(std::max(glm::dot(p.n, p.v), 0.0));
}

struct Args {
    std::string command;
    int width = 256;
    int sphere = 64;
    int grid = 128;
    std::string sets = "bundled,unseen,procedural";
    std::vector<std::string> envs;
    std::string csv;
    std::vector<std::string> tables;
    // fit
    int taps = 1;
    int frames = 96;
    int size = 16;
    double minRoughness = 0.15;
    std::string out;
    std::string init; // fit --taps 3: the one-tap table to start from
    unsigned seed = 14;
};

LobeFitTable readTable(const std::string& path)
{
    // The .inc format fit writes: three "constexpr int" lines, then the numbers.
    std::ifstream f(path);
    if (!f) throw std::runtime_error("cannot read " + path);
    std::stringstream ss;
    ss << f.rdbuf();
    std::string text = ss.str();
    LobeFitTable t;
    auto intAfter = [&](const std::string& key) {
        const auto at = text.find(key);
        if (at == std::string::npos) throw std::runtime_error(path + ": no " + key);
        return std::stoi(text.substr(text.find('=', at) + 1));
    };
    t.taps = intAfter("kLobeFitTaps");
    t.nvSize = intAfter("kLobeFitNvSize");
    t.roughnessSize = intAfter("kLobeFitRoughnessSize");
    std::string body = text.substr(text.find('{', text.find("kLobeFitCells")) + 1);
    for (char& c : body)
        if (c == 'f' || c == ',' || c == '}' || c == ';') c = ' ';
    std::istringstream in(body);
    std::vector<float> v;
    float x;
    while (in >> x) v.push_back(x);
    for (std::size_t i = 0; i + 3 < v.size(); i += 4) t.cells.emplace_back(v[i], v[i + 1], v[i + 2], v[i + 3]);
    if (t.cells.size() != std::size_t(t.nvSize) * std::size_t(t.roughnessSize)) throw std::runtime_error(path + ": wrong cell count");
    return t;
}

// --bins: the copper spheres' total relative RMSE by n.v band, to see where an error lives.
constexpr int kBins = 5;
using Bins = std::array<std::array<double, 2>, kBins>; // per band: sum of squares, count
std::map<std::string, std::vector<Bins>> bins;
bool gBins = false;

void addBins(std::vector<Bins>& perMethod, std::size_t methods, std::size_t m, const Errors& e)
{
    if (perMethod.size() < methods) perMethod.resize(methods, Bins{});
    for (std::size_t i = 0; i < e.total.size(); ++i) {
        const int b = std::clamp(int(e.NdotV[i] * kBins), 0, kBins - 1);
        perMethod[m][std::size_t(b)][0] += e.total[i] * e.total[i];
        perMethod[m][std::size_t(b)][1] += 1.0;
    }
}

int evalCommand(const Args& a, const std::vector<std::pair<std::string, LobeFitTable>>& extraTables)
{
    const auto t0 = Clock::now();
    std::vector<std::pair<std::string, LobeFitTable>> tables = extraTables;
    for (const auto& path : a.tables) tables.emplace_back(fs::path(path).stem().string(), readTable(path));
    const std::vector<Method> ms = methods(tables);
    const double minResolved = referenceMinResolvedRoughness(a.width);
    const std::vector<Pixel> sphere = spherePixels(a.sphere);
    std::vector<Pixel> grid;
    for (const Pixel& p : gridPixels(a.grid))
        if (p.roughness >= minResolved) grid.push_back(p);
    std::fprintf(stderr, "reference %d wide, resolved roughness >= %.3f; sphere %zu pixels, grid %zu pixels\n", a.width, minResolved,
                 sphere.size(), grid.size());

    std::ofstream csv;
    if (!a.csv.empty()) {
        csv.open(a.csv);
        csv << "environment,set,scene,material,roughness,method,relative_rmse,specular_relative_rmse,pixels\n";
    }
    const std::vector<double> roughnesses = gRoughnesses;
    // Summary: per environment, per method: spheres total, spheres specular, grid total, grid specular.
    struct Row {
        std::string env, set;
        std::vector<std::array<double, 4>> values;
    };
    std::vector<Row> rows;
    for (const auto& [spec, set] : environmentList(a.sets, a.envs)) {
        const auto te = Clock::now();
        const EnvCase env = loadCase(spec, set, a.width, true);
        std::vector<Errors> spheres, gridErr;
        for (double metallic : {1.0, 0.0})
            for (double r : roughnesses) {
                std::vector<Pixel> px = sphere;
                for (Pixel& p : px) p.roughness = r, p.metallic = metallic;
                std::vector<Errors> one;
                evaluatePixels(env, px, ms, one);
                if (spheres.size() < ms.size()) spheres.resize(ms.size());
                for (std::size_t m = 0; m < ms.size(); ++m) {
                    spheres[m].total.insert(spheres[m].total.end(), one[m].total.begin(), one[m].total.end());
                    spheres[m].specular.insert(spheres[m].specular.end(), one[m].specular.begin(), one[m].specular.end());
                    if (metallic > 0.5) addBins(bins[env.name], ms.size(), m, one[m]);
                    if (csv)
                        csv << env.name << ',' << set << ",sphere," << (metallic > 0.5 ? "copper" : "dielectric") << ',' << r << ',' << ms[m].name
                            << ',' << rmse(one[m].total) << ',' << rmse(one[m].specular) << ',' << one[m].total.size() << '\n';
                }
            }
        evaluatePixels(env, grid, ms, gridErr);
        Row row{env.name, set, {}};
        for (std::size_t m = 0; m < ms.size(); ++m) {
            row.values.push_back({rmse(spheres[m].total), rmse(spheres[m].specular), rmse(gridErr[m].total), rmse(gridErr[m].specular)});
            if (csv)
                csv << env.name << ',' << set << ",grid,all,all," << ms[m].name << ',' << rmse(gridErr[m].total) << ',' << rmse(gridErr[m].specular)
                    << ',' << gridErr[m].total.size() << '\n';
        }
        rows.push_back(row);
        std::fprintf(stderr, "%-20s %6.1f s\n", env.name.c_str(), secondsSince(te));
    }

    // Tables: one per measure, rows = environments, columns = methods (value and ratio to split-sum).
    const char* measures[4] = {"spheres, specular + diffuse", "spheres, specular only", "grid (roughness >= resolved), specular + diffuse",
                               "grid, specular only"};
    for (int k = 0; k < 4; ++k) {
        std::printf("\n### Relative RMSE: %s (ratio to split-sum in brackets)\n\n| environment | set |", measures[k]);
        for (const Method& m : ms) std::printf(" %s |", m.name.c_str());
        std::printf("\n|---|---|");
        for (std::size_t m = 0; m < ms.size(); ++m) std::printf("---|");
        std::printf("\n");
        std::map<std::string, std::vector<double>> worst;
        for (const Row& r : rows) {
            std::printf("| %s | %s |", r.env.c_str(), r.set.c_str());
            const double base = r.values[0][std::size_t(k)];
            for (std::size_t m = 0; m < ms.size(); ++m) {
                const double v = r.values[m][std::size_t(k)];
                if (m == 0) std::printf(" %.3f |", v);
                else std::printf(" %.3f (%.2f) |", v, v / base);
            }
            std::printf("\n");
        }
        std::printf("| **worst ratio** | |");
        for (std::size_t m = 0; m < ms.size(); ++m) {
            double w = 0.0;
            for (const Row& r : rows) w = std::max(w, r.values[m][std::size_t(k)] / r.values[0][std::size_t(k)]);
            std::printf(" %.2f |", w);
        }
        std::printf("\n");
    }
    if (gBins) {
        std::printf("\n### Copper spheres (all roughnesses), relative RMSE by n.v band\n\n| environment | method |");
        for (int b = 0; b < kBins; ++b) std::printf(" n.v %.1f-%.1f |", double(b) / kBins, double(b + 1) / kBins);
        std::printf("\n|---|---|");
        for (int b = 0; b < kBins; ++b) std::printf("---|");
        std::printf("\n");
        for (const Row& r : rows)
            for (std::size_t m = 0; m < ms.size(); ++m) {
                std::printf("| %s | %s |", r.env.c_str(), ms[m].name.c_str());
                for (const auto& band : bins[r.env][m]) std::printf(" %.3f |", band[1] > 0.0 ? std::sqrt(band[0] / band[1]) : 0.0);
                std::printf("\n");
            }
    }
    std::fprintf(stderr, "eval took %.1f s\n", secondsSince(t0));
    return 0;
}

// ---- Fit -------------------------------------------------------------------------------------
// Nelder-Mead on a box (parameters clamped into it before every evaluation).
std::vector<double> nelderMead(const std::function<double(const std::vector<double>&)>& f, std::vector<double> x0, const std::vector<double>& step,
                               int iterations)
{
    const std::size_t n = x0.size();
    std::vector<std::vector<double>> s(n + 1, x0);
    for (std::size_t i = 0; i < n; ++i) s[i + 1][i] += step[i];
    std::vector<double> fs(n + 1);
    for (std::size_t i = 0; i <= n; ++i) fs[i] = f(s[i]);
    for (int it = 0; it < iterations; ++it) {
        std::vector<std::size_t> order(n + 1);
        for (std::size_t i = 0; i <= n; ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return fs[a] < fs[b]; });
        std::vector<std::vector<double>> s2;
        std::vector<double> f2;
        for (std::size_t i : order) s2.push_back(s[i]), f2.push_back(fs[i]);
        s = s2, fs = f2;
        std::vector<double> c(n, 0.0);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j) c[j] += s[i][j] / double(n);
        auto along = [&](double k) {
            std::vector<double> x(n);
            for (std::size_t j = 0; j < n; ++j) x[j] = c[j] + k * (s[n][j] - c[j]);
            return x;
        };
        const std::vector<double> xr = along(-1.0);
        const double fr = f(xr);
        if (fr < fs[0]) {
            const std::vector<double> xe = along(-2.0);
            const double fe = f(xe);
            if (fe < fr) s[n] = xe, fs[n] = fe;
            else s[n] = xr, fs[n] = fr;
        } else if (fr < fs[n - 1]) {
            s[n] = xr, fs[n] = fr;
        } else {
            const std::vector<double> xc = along(fr < fs[n] ? -0.5 : 0.5);
            const double fc = f(xc);
            if (fc < std::min(fr, fs[n])) {
                s[n] = xc, fs[n] = fc;
            } else {
                for (std::size_t i = 1; i <= n; ++i) {
                    for (std::size_t j = 0; j < n; ++j) s[i][j] = s[0][j] + 0.5 * (s[i][j] - s[0][j]);
                    fs[i] = f(s[i]);
                }
            }
        }
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i <= n; ++i)
        if (fs[i] < fs[best]) best = i;
    return s[best];
}

struct FitSample {
    const EnvCase* env;
    glm::dvec3 n, v;
    glm::dvec3 refCopper, refDielectric; // specular; the dielectric's with its diffuse added
    glm::dvec3 diffuseDielectric;
};

int fitCommand(const Args& a)
{
    const auto t0 = Clock::now();
    std::vector<EnvCase> envs;
    for (const auto& [spec, set] : environmentList("bundled", {})) envs.push_back(loadCase(spec, set, a.width, true));
    std::fprintf(stderr, "fit on %zu bundled maps at %d wide (%.1f s to load and prefilter)\n", envs.size(), a.width, secondsSince(t0));

    LobeFitTable initTable;
    if (!a.init.empty()) {
        initTable = readTable(a.init);
        if (initTable.taps != 1) throw std::runtime_error("--init needs a one-tap table");
    }
    LobeFitTable table;
    table.taps = a.taps;
    table.nvSize = a.size;
    table.roughnessSize = a.size;
    table.cells.assign(std::size_t(a.size) * std::size_t(a.size), glm::vec4(0.0f));
    for (int row = 0; row < a.size; ++row)
        for (int col = 0; col < a.size; ++col) {
            const float r = (float(row) + 0.5f) / float(a.size);
            table.at(col, row) = a.taps == 1 ? glm::vec4(0.0f, r, 0.0f, 0.0f) : a.taps == 2 ? glm::vec4(0.0f, 0.0f, r, 0.0f) : glm::vec4(0.0f, r, 0.0f, r);
        }
    std::vector<std::array<double, 2>> gain(table.cells.size(), {0.0, 0.0}); // split-sum objective, fitted objective
    std::mutex print;
    parallelFor(int(table.cells.size()), [&](int idx) {
        const int col = idx % a.size, row = idx / a.size;
        const double NdotV = (col + 0.5) / a.size, roughness = (row + 0.5) / a.size;
        if (roughness < a.minRoughness) return;
        std::mt19937 rng(a.seed * 7919u + unsigned(idx));
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::vector<FitSample> samples;
        for (const EnvCase& env : envs) {
            std::vector<Query> queries;
            for (int k = 0; k < a.frames; ++k) {
                const double z = 2.0 * u(rng) - 1.0, phi = 2.0 * kPi * u(rng);
                const glm::dvec3 n(std::sqrt(1.0 - z * z) * std::cos(phi), std::sqrt(1.0 - z * z) * std::sin(phi), z);
                const glm::dvec3 helper = std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
                const glm::dvec3 t = glm::normalize(glm::cross(helper, n)), b = glm::cross(n, t);
                const double psi = 2.0 * kPi * u(rng), s = std::sqrt(1.0 - NdotV * NdotV);
                queries.push_back({n, NdotV * n + s * (std::cos(psi) * t + std::sin(psi) * b), roughness});
            }
            const std::vector<FullIntegral> refs = fullIntegrals(env, queries, true);
            for (std::size_t k = 0; k < queries.size(); ++k) {
                // The dielectric as combineLobes shades it (metallic 0, copper base colour).
                const Pixel p{queries[k].n, queries[k].v, roughness, 0.0};
                const glm::dvec3 diffuse = combine(p, glm::dvec3(0.0), refs[k].irradiance, glm::dvec3(kDielectricF0)).total;
                samples.push_back({&env, queries[k].n, queries[k].v, refs[k].specular(kCopper), refs[k].specular(glm::dvec3(kDielectricF0)) + diffuse, diffuse});
            }
        }
        const glm::dvec3 ab = lut().sample(NdotV, roughness);
        const glm::dvec3 albedoCopper = kCopper * ab.x + ab.y, albedoDielectric = glm::dvec3(kDielectricF0 * ab.x + ab.y);
        auto objective = [&](const glm::vec4& p) {
            double e = 0.0;
            for (const FitSample& s : samples) {
                const glm::dvec3 R = 2.0 * glm::dot(s.n, s.v) * s.n - s.v;
                if (table.taps == 3) {
                    // Fresnel split: F0 A read_A + B read_B.
                    const glm::dvec3 preA = s.env->chain->lookup(glm::mix(R, s.n, double(p.x)), p.y);
                    const glm::dvec3 preB = s.env->chain->lookup(glm::mix(R, s.n, double(p.z)), p.w);
                    const double ec = pixelError(kCopper * ab.x * preA + ab.y * preB, s.refCopper);
                    const glm::dvec3 specD = kDielectricF0 * ab.x * preA + ab.y * preB;
                    const double ed = pixelError(specD + s.diffuseDielectric, s.refDielectric);
                    const double es = gMixedObjective ? pixelError(specD, s.refDielectric - s.diffuseDielectric) : 0.0;
                    e += ec * ec + ed * ed + es * es;
                    continue;
                }
                glm::dvec3 pre(0.0);
                for (int k = 0; k < table.taps; ++k) {
                    const glm::dvec3 d = glm::mix(R, s.n, double(shared::lobeTapTowardsNormal(p, table.taps, k)));
                    pre += double(shared::lobeTapWeight(p, table.taps, k)) * s.env->chain->lookup(d, shared::lobeTapRoughness(p, table.taps, k));
                }
                const double ec = pixelError(pre * albedoCopper, s.refCopper);
                const double ed = pixelError(pre * albedoDielectric + s.diffuseDielectric, s.refDielectric);
                const double es = gMixedObjective ? pixelError(pre * albedoDielectric, s.refDielectric - s.diffuseDielectric) : 0.0;
                e += ec * ec + ed * ed + es * es;
            }
            return e / double(samples.size());
        };
        auto clampParams = [&](const std::vector<double>& x) {
            if (table.taps == 1) return glm::vec4(float(std::clamp(x[0], -0.5, 1.0)), float(std::clamp(x[1], 0.0, 1.0)), 0.0f, 0.0f);
            if (table.taps == 3)
                return glm::vec4(float(std::clamp(x[0], -0.5, 1.0)), float(std::clamp(x[1], 0.0, 1.0)), float(std::clamp(x[2], -0.5, 1.0)),
                                 float(std::clamp(x[3], 0.0, 1.0)));
            return glm::vec4(float(std::clamp(x[0], -1.0, 1.0)), float(std::clamp(x[1], -1.0, 1.0)), float(std::clamp(x[2], 0.0, 1.0)),
                             float(std::clamp(x[3], 0.0, 1.0)));
        };
        auto f = [&](const std::vector<double>& x) { return objective(clampParams(x)); };
        const glm::vec4 identity = table.at(col, row);
        const double base = objective(identity);
        glm::vec4 best = identity;
        double bestValue = base;
        if (table.taps == 3) {
            // Start from the one-tap table of --init (both reads where it reads) and from the split sum.
            const glm::dvec4 one = initTable.empty() ? glm::dvec4(0.0, roughness, 0.0, 0.0) : initTable.sample(NdotV, roughness);
            for (const std::vector<double>& x0 : {std::vector<double>{one.x, one.y, one.x, one.y}, std::vector<double>{0.0, roughness, 0.0, roughness}}) {
                const std::vector<double> x = nelderMead(f, x0, {0.15, 0.1, 0.15, 0.1}, 200);
                const double v = f(x);
                if (v < bestValue) bestValue = v, best = clampParams(x);
            }
        } else if (table.taps == 1) {
            for (double t0s : {0.0, 0.3, 0.6}) {
                const std::vector<double> x = nelderMead(f, {t0s, roughness}, {0.15, 0.1}, 80);
                const double v = f(x);
                if (v < bestValue) bestValue = v, best = clampParams(x);
            }
        } else {
            for (double spread : {0.2, 0.5})
                for (double t0s : {0.0, 0.4}) {
                    const std::vector<double> x = nelderMead(f, {t0s - spread, t0s + spread, roughness * 0.8, 0.5}, {0.15, 0.15, 0.1, 0.2}, 160);
                    const double v = f(x);
                    if (v < bestValue) bestValue = v, best = clampParams(x);
                }
        }
        table.at(col, row) = best;
        gain[std::size_t(idx)] = {base, bestValue};
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "n.v %.3f r %.3f: rms %.3f -> %.3f  (%.3f %.3f %.3f %.3f)\n", NdotV, roughness, std::sqrt(base), std::sqrt(bestValue),
                     best.x, best.y, best.z, best.w);
    });

    std::ostringstream o;
    o << "// Generated by `accuracy_study fit --taps " << a.taps << " --width " << a.width << " --frames " << a.frames << " --size " << a.size
      << " --min-roughness " << a.minRoughness << (gMixedObjective ? " --mixed-objective" : "")
      << (a.init.empty() ? std::string() : " --init " + fs::path(a.init).filename().string()) << "` on the 8 bundled maps\n"
      << "// (assets/environments), " << a.frames << " random (n, v) per map and cell; objective: the mean squared per-pixel\n"
      << "// relative error (common/error_metrics.glsl) of copper's specular plus that of a dielectric's specular + diffuse\n"
      << "// (F0 0.04, copper base colour)" << (gMixedObjective ? " and of the dielectric's specular alone (--mixed-objective)" : "")
      << ". Do not edit: refit.\n"
      << "// Layout: specular_approximations.hpp, LobeFitTable; rows = roughness (i + 0.5) / size, columns = n.v.\n"
      << "constexpr int kLobeFitTaps = " << a.taps << ";\n"
      << "constexpr int kLobeFitNvSize = " << a.size << ";\n"
      << "constexpr int kLobeFitRoughnessSize = " << a.size << ";\n"
      << "constexpr float kLobeFitCells[] = {\n";
    char buf[64];
    for (int row = 0; row < a.size; ++row) {
        o << "    ";
        for (int col = 0; col < a.size; ++col) {
            const glm::vec4 p = table.at(col, row);
            for (int k = 0; k < 4; ++k) {
                std::snprintf(buf, sizeof buf, "%.4ff,%s", double(p[k]), (col == a.size - 1 && k == 3) ? "" : " ");
                o << buf;
            }
        }
        o << "\n";
    }
    o << "};\n";
    const std::string outPath = a.out.empty() ? (kSource / "renderer" / "ibl" / "specular_lobe_fit.inc").string() : a.out;
    std::ofstream(outPath) << o.str();
    double sb = 0.0, sf = 0.0;
    for (const auto& g : gain) sb += g[0], sf += g[1];
    std::fprintf(stderr, "wrote %s; mean objective %.4f -> %.4f; fit took %.1f s\n", outPath.c_str(), sb / double(gain.size()), sf / double(gain.size()),
                 secondsSince(t0));
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    Args a;
    if (argc < 2) {
        std::fprintf(stderr, "usage: accuracy_study eval|fit [options] (see tools/accuracy_study.cpp)\n");
        return 2;
    }
    a.command = argv[1];
    for (int i = 2; i < argc; ++i) {
        const std::string k = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error("missing value after " + k);
            return argv[++i];
        };
        if (k == "--width") a.width = std::stoi(next());
        else if (k == "--sphere") a.sphere = std::stoi(next());
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
        else if (k == "--exact-prefilter") gExactPrefilter = true;
        else if (k == "--bins") gBins = true;
        else if (k == "--mixed-objective") gMixedObjective = true;
        else if (k == "--roughness") gRoughnesses = parseList(next());
        else if (k == "--seed") a.seed = unsigned(std::stoul(next()));
        else {
            std::fprintf(stderr, "unknown option %s\n", k.c_str());
            return 2;
        }
    }
    try {
        if (a.command == "eval") return evalCommand(a, {});
        if (a.command == "fit") return fitCommand(a);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "accuracy_study: %s\n", e.what());
        return 1;
    }
    std::fprintf(stderr, "unknown command %s\n", a.command.c_str());
    return 2;
}
