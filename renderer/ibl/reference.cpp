#include "ibl/reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/equirect.hpp"

namespace iblab {

namespace {

struct Sums {
    glm::dvec3 weighted{0.0}; // sum L(w) * weight(w) * dOmega
    double weight = 0.0;      // sum weight(w) * dOmega
};

// Sums weightFn(direction) * {L, 1} * dOmega over all texels with weightFn(...) != 0.
// weightFn returns a per-channel weight (dvec3) so that Fresnel can differ by channel; the
// scalar `weight` sum uses its first channel.
template <typename WeightFn>
Sums sumOverTexels(const ImageRGB32F& env, const WeightFn& weightFn)
{
    auto sumRows = [&](int y0, int y1) {
        Sums s;
        for (int y = y0; y < y1; ++y) {
            const double dOmega = equirectTexelSolidAngle(y, env.width, env.height);
            Sums row;
            for (int x = 0; x < env.width; ++x) {
                const glm::dvec3 w = weightFn(equirectTexelDirection(x, y, env.width, env.height));
                if (w.x == 0.0 && w.y == 0.0 && w.z == 0.0)
                    continue;
                row.weighted += glm::dvec3(env.at(x, y)) * w;
                row.weight += w.x;
            }
            s.weighted += row.weighted * dOmega;
            s.weight += row.weight * dOmega;
        }
        return s;
    };

    // Threads pay off only above a few tens of thousands of texels (thread start ~ 20 us).
    constexpr std::size_t kTexelsPerThread = 1u << 15;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const int threads = int(std::min<std::size_t>({std::size_t(hw), std::size_t(env.height),
                                                   env.texelCount() / kTexelsPerThread}));
    if (threads <= 1)
        return sumRows(0, env.height);

    std::vector<Sums> partial(static_cast<std::size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
        const int y0 = env.height * t / threads;
        const int y1 = env.height * (t + 1) / threads;
        pool.emplace_back([&, t, y0, y1] { partial[std::size_t(t)] = sumRows(y0, y1); });
    }
    Sums total;
    for (int t = 0; t < threads; ++t) {
        pool[std::size_t(t)].join();
        total.weighted += partial[std::size_t(t)].weighted;
        total.weight += partial[std::size_t(t)].weight;
    }
    return total;
}

void requireEnvironment(const ImageRGB32F& env, const char* who)
{
    if (env.empty() || env.texels.size() != env.texelCount() * 3)
        throw std::invalid_argument(std::string(who) + ": empty or inconsistent environment (" +
                                    std::to_string(env.width) + "x" + std::to_string(env.height) + ")");
}

} // namespace

glm::dvec3 referenceIrradiance(const ImageRGB32F& env, glm::dvec3 n)
{
    requireEnvironment(env, "referenceIrradiance");
    return ZonalReference(env).irradiance(std::span(&n, 1)).front();
}

// Why this is what the LearnOpenGL prefilter computes. Its loop draws half vectors h from
// D(h) (n.h) (sampling.hpp), reflects v = n about h to get l, and accumulates
//   sum_i L(l_i) (n.l_i)  /  sum_i (n.l_i)       over samples with n.l_i > 0.
// Each l_i has the solid-angle density p(l) = D(h) (n.h) / (4 (v.h)) (the reflection
// Jacobian), and with v = n we have n.h = v.h, so p(l) = D(h) / 4. By the law of large
// numbers numerator and denominator, each divided by the sample count, converge to
//   integral L(l) (n.l) D(h)/4 dOmega_l    and    integral (n.l) D(h)/4 dOmega_l,
// the 1/4 cancels, and h = normalize(n + l) is the half vector between v = n and l. Note the
// weight is D(h) (n.l), not the BRDF: the split-sum's first factor is this normalised
// D-weighted average by construction (Karis 2013, "we found weighting by cos(theta_l) achieves
// better results").
glm::dvec3 referencePrefilteredRadiance(const ImageRGB32F& env, glm::dvec3 n, double roughness)
{
    requireEnvironment(env, "referencePrefilteredRadiance");
    if (roughness <= 0.0)
        return glm::dvec3(sampleEquirectBilinear(env, n));
    const ZonalReference::PrefilterQuery query{n, roughness};
    return ZonalReference(env).prefilteredRadiance(std::span(&query, 1)).front();
}

ZonalReference::ZonalReference(const ImageRGB32F& env)
    : env_(env), rowStride_((std::size_t(env.width) + kLanes - 1) / kLanes * kLanes)
{
    requireEnvironment(env, "ZonalReference");
    // Rows are padded to whole lanes with zero directions and radiance: weight 0, nothing added.
    const std::size_t size = rowStride_ * std::size_t(env.height);
    for (std::vector<double>* v : {&dirX_, &dirY_, &dirZ_}) v->assign(size, 0.0);
    for (std::vector<float>* v : {&red_, &green_, &blue_}) v->assign(size, 0.0f);
    for (std::vector<double>* v : {&rowSolidAngle_, &rowMinY_, &rowMaxY_, &rowMaxHorizontal_})
        v->resize(std::size_t(env.height));
    for (int y = 0; y < env.height; ++y) {
        rowSolidAngle_[std::size_t(y)] = equirectTexelSolidAngle(y, env.width, env.height);
        double minY = 1.0, maxY = -1.0, maxHorizontal = 0.0;
        for (int x = 0; x < env.width; ++x) {
            const std::size_t i = std::size_t(y) * rowStride_ + std::size_t(x);
            const glm::dvec3 w = equirectTexelDirection(x, y, env.width, env.height);
            dirX_[i] = w.x;
            dirY_[i] = w.y;
            dirZ_[i] = w.z;
            const glm::vec3 L = env.at(x, y);
            if (!std::isfinite(L.r) || !std::isfinite(L.g) || !std::isfinite(L.b))
                throw std::invalid_argument("ZonalReference: non-finite radiance at texel (" + std::to_string(x) + ", " +
                                            std::to_string(y) + "); the environment loader repairs these");
            red_[i] = L.r;
            green_[i] = L.g;
            blue_[i] = L.b;
            minY = std::min(minY, w.y);
            maxY = std::max(maxY, w.y);
            maxHorizontal = std::max(maxHorizontal, std::sqrt(w.x * w.x + w.z * w.z));
        }
        rowMinY_[std::size_t(y)] = minY;
        rowMaxY_[std::size_t(y)] = maxY;
        rowMaxHorizontal_[std::size_t(y)] = maxHorizontal;
    }
}

// Lanes are internal to this file, so the ABI of passing them (which -Wpsabi warns about
// when AVX is not the baseline) never crosses a translation unit.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {

// Four (query, texel) pairs at once in GCC/Clang vector extensions: SSE2 splits them in two
// registers, AVX in one. Lanes keep their own partial sums, added in a fixed order at the
// end (a compiler may not reorder one floating-point sum into lanes by itself), so results
// are the same on every machine and build.
constexpr int kLanes = ZonalReference::kLanes;
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
using FloatLanes = float __attribute__((vector_size(kLanes * sizeof(float))));

template <typename V, typename T>
V loadLanes(const T* p)
{
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

} // namespace

template <bool prefilter>
[[gnu::always_inline]] inline ZonalReference::RowSums sumLanes(const double* dx, const double* dy, const double* dz, const float* red,
                                                               const float* green, const float* blue, int count, glm::dvec3 n, double a2)
{
    Lanes sr = {}, sg = {}, sb = {}, sw = {};
    const Lanes zero = {};
    for (int i = 0; i < count; i += kLanes) {
        const Lanes c = n.x * loadLanes<Lanes>(dx + i) + n.y * loadLanes<Lanes>(dy + i) + n.z * loadLanes<Lanes>(dz + i);
        Lanes w = c > zero ? c : zero;
        if constexpr (prefilter) {
            // D(h) (n.w) up to the constant a2 / pi, which the ratio of the two sums cancels:
            // with (n.h)^2 = (1 + c) / 2, ggxD's cancellation-free denominator
            // a2 (n.h)^2 + (1 - n.h)(1 + n.h) is (a2 (1 + c) + (1 - c)) / 2, and the factor 4
            // of squaring the halves cancels too. d > 0 for every c in [-1, 1].
            const Lanes d = a2 * (1.0 + c) + (1.0 - c);
            w = w / (d * d);
        }
        // A zero weight times finite radiance is zero, so texels below the horizon add
        // nothing (the constructor refuses non-finite radiance, where 0 * inf would be NaN).
        sr += w * __builtin_convertvector(loadLanes<FloatLanes>(red + i), Lanes);
        sg += w * __builtin_convertvector(loadLanes<FloatLanes>(green + i), Lanes);
        sb += w * __builtin_convertvector(loadLanes<FloatLanes>(blue + i), Lanes);
        sw += w;
    }
    ZonalReference::RowSums sums;
    for (int lane = 0; lane < kLanes; ++lane) {
        sums.r += sr[lane];
        sums.g += sg[lane];
        sums.b += sb[lane];
        sums.weight += sw[lane];
    }
    return sums;
}

// Compiled twice, for x86-64's baseline and for AVX2 (chosen by CPU feature at load time): the
// division per texel is most of a reference's time, and AVX divides four lanes at once.
#if defined(__x86_64__)
#define IBLAB_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define IBLAB_VECTOR_CLONES
#endif

IBLAB_VECTOR_CLONES ZonalReference::RowSums prefilterRowSums(const double* dx, const double* dy, const double* dz, const float* red,
                                                             const float* green, const float* blue, int count, glm::dvec3 n, double a2)
{
    return sumLanes<true>(dx, dy, dz, red, green, blue, count, n, a2);
}

IBLAB_VECTOR_CLONES ZonalReference::RowSums irradianceRowSums(const double* dx, const double* dy, const double* dz, const float* red,
                                                              const float* green, const float* blue, int count, glm::dvec3 n, double a2)
{
    return sumLanes<false>(dx, dy, dz, red, green, blue, count, n, a2);
}

ZonalReference::RowSums ZonalReference::sumRow(Kernel kernel, const Query& query, int row) const
{
    const glm::dvec3 n = query.direction;
    // Every texel of the row has n.w <= n.y w.y + |n_xz| |w_xz| (Cauchy-Schwarz on the
    // horizontal parts); a row with that bound <= 0 adds nothing under either kernel.
    const std::size_t r = std::size_t(row);
    const double bound = (n.y >= 0.0 ? n.y * rowMaxY_[r] : n.y * rowMinY_[r]) + std::sqrt(n.x * n.x + n.z * n.z) * rowMaxHorizontal_[r];
    if (bound <= 0.0)
        return {};
    const std::size_t first = r * rowStride_;
    const auto sum = kernel == Kernel::Prefilter ? prefilterRowSums : irradianceRowSums;
    auto sumSpan = [&](int begin, int end) {
        const std::size_t at = first + std::size_t(begin);
        return sum(&dirX_[at], &dirY_[at], &dirZ_[at], &red_[at], &green_[at], &blue_[at], end - begin, n, query.alphaSquared);
    };
    const int stride = int(rowStride_);

    // The texels with n.w > 0 are one arc of the row. With w = (s sin phi, w.y, -s cos phi)
    // (conventions.glsl), n.w = n.y w.y + s rho sin(phi - psi), rho = |n_xz|,
    // psi = atan2(n.z, n.x): positive where phi is within acos(t) of psi + pi/2, with
    // t = -n.y w.y / (s rho). kSlack covers the texel directions' float rounding and their
    // small spread of w.y and s across the row (both ~1e-7) generously, the arc is widened
    // by a texel on each side and rounded out to whole lanes; outside it every weight is 0,
    // so skipping it changes no sum.
    constexpr double kSlack = 1e-5;
    const double rho = std::sqrt(n.x * n.x + n.z * n.z);
    const double highestVertical = n.y >= 0.0 ? n.y * rowMaxY_[r] : n.y * rowMinY_[r];
    const double amplitude = rho * rowMaxHorizontal_[r];
    const double t = amplitude > 0.0 ? -(highestVertical + kSlack) / amplitude : -2.0;
    if (t <= -1.0)
        return sumSpan(0, stride);
    const int width = env_.width;
    const double halfArc = std::acos(t);
    const double centre = std::atan2(n.z, n.x) + 0.5 * kPi;
    auto texelAt = [&](double phi) { return (phi / (2.0 * kPi) + 0.5) * width - 0.5; };
    const long lo = long(std::floor(texelAt(centre - halfArc))) - 1;
    const long hi = long(std::ceil(texelAt(centre + halfArc))) + 1; // inclusive
    if (hi - lo + 1 >= width)
        return sumSpan(0, stride);
    auto roundUpToLanes = [](int x) { return (x + kLanes - 1) / kLanes * kLanes; };
    const int start = int(((lo % width) + width) % width);
    const int stop = start + int(hi - lo + 1); // exclusive; past the row's end when the arc wraps
    const int begin = start / kLanes * kLanes;
    if (stop <= width)
        return sumSpan(begin, roundUpToLanes(stop));
    // The arc wraps around the seam: its part at the start of the row, then its part at the end.
    const int wrapped = roundUpToLanes(stop - width);
    if (wrapped >= begin)
        return sumSpan(0, stride);
    RowSums sums = sumSpan(0, wrapped);
    const RowSums tail = sumSpan(begin, stride);
    sums.r += tail.r;
    sums.g += tail.g;
    sums.b += tail.b;
    sums.weight += tail.weight;
    return sums;
}

// Per query, the sums of every row (rows.size() == queries.size() * height). Rows are spread
// over threads in interleaved bands, and every thread runs all of a chunk's queries over
// its row before the next, so a row's directions and radiance are read from cache once per
// chunk, not once per query.
std::vector<ZonalReference::RowSums> ZonalReference::sum(Kernel kernel, std::span<const Query> queries) const
{
    const std::size_t height = std::size_t(env_.height);
    std::vector<RowSums> rows(queries.size() * height);
    // Threads pay off only above a few tens of thousands of (query, texel) pairs (a thread
    // starts in ~20 us).
    constexpr std::size_t kPairsPerThread = 1u << 15;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const int threads = int(std::min<std::size_t>({std::size_t(hw), height, queries.size() * env_.texelCount() / kPairsPerThread}));
    constexpr int kBand = 4;
    auto work = [&](int thread, int threadCount) {
        for (int y0 = kBand * thread; y0 < env_.height; y0 += kBand * threadCount)
            for (int y = y0; y < std::min(y0 + kBand, env_.height); ++y)
                for (std::size_t q = 0; q < queries.size(); ++q) rows[q * height + std::size_t(y)] = sumRow(kernel, queries[q], y);
    };
    if (threads <= 1) {
        work(0, 1);
        return rows;
    }
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work, t, threads);
    for (std::thread& t : pool) t.join();
    return rows;
}

namespace {

// Query chunks bound the row-sum buffer (a chunk's queries x rows) for large batches.
constexpr std::size_t kQueriesPerChunk = 64;

} // namespace

std::vector<glm::dvec3> ZonalReference::irradiance(std::span<const glm::dvec3> normals) const
{
    std::vector<glm::dvec3> result;
    result.reserve(normals.size());
    for (std::size_t first = 0; first < normals.size(); first += kQueriesPerChunk) {
        std::vector<Query> chunk;
        for (std::size_t i = first; i < std::min(normals.size(), first + kQueriesPerChunk); ++i) chunk.push_back({normals[i]});
        const std::vector<RowSums> rows = sum(Kernel::Irradiance, chunk);
        for (std::size_t q = 0; q < chunk.size(); ++q) {
            glm::dvec3 E(0.0);
            for (int y = 0; y < env_.height; ++y) {
                const RowSums& s = rows[q * std::size_t(env_.height) + std::size_t(y)];
                E += glm::dvec3(s.r, s.g, s.b) * rowSolidAngle_[std::size_t(y)];
            }
            result.push_back(E);
        }
    }
    return result;
}

std::vector<glm::dvec3> ZonalReference::prefilteredRadiance(std::span<const PrefilterQuery> queries) const
{
    std::vector<glm::dvec3> result;
    result.reserve(queries.size());
    for (std::size_t first = 0; first < queries.size(); first += kQueriesPerChunk) {
        // At roughness 0 the lobe is a delta: the bilinear lookup, no sum.
        std::vector<Query> chunk;
        std::vector<std::size_t> summed; // index into queries of each chunk entry
        const std::size_t last = std::min(queries.size(), first + kQueriesPerChunk);
        for (std::size_t i = first; i < last; ++i)
            if (queries[i].roughness > 0.0) {
                const double alpha = queries[i].roughness * queries[i].roughness;
                chunk.push_back({queries[i].direction, alpha * alpha});
                summed.push_back(i);
            }
        const std::vector<RowSums> rows = sum(Kernel::Prefilter, chunk);
        std::size_t next = 0;
        for (std::size_t i = first; i < last; ++i) {
            const glm::dvec3 n = queries[i].direction;
            if (next == summed.size() || summed[next] != i) {
                result.emplace_back(sampleEquirectBilinear(env_, n));
                continue;
            }
            glm::dvec3 weighted(0.0);
            double weight = 0.0;
            for (int y = 0; y < env_.height; ++y) {
                const RowSums& s = rows[next * std::size_t(env_.height) + std::size_t(y)];
                weighted += glm::dvec3(s.r, s.g, s.b) * rowSolidAngle_[std::size_t(y)];
                weight += s.weight * rowSolidAngle_[std::size_t(y)];
            }
            ++next;
            // The lobe can fall between texel centres when it is much narrower than a texel;
            // then no texel carries weight and the bilinear lookup is the limit the sum
            // would approach.
            result.push_back(weight > 0.0 ? weighted / weight : glm::dvec3(sampleEquirectBilinear(env_, n)));
        }
    }
    return result;
}

glm::dvec3 referenceSpecular(const ImageRGB32F& env, glm::dvec3 n, glm::dvec3 v, double roughness, glm::dvec3 F0,
                             GeometryTerm term)
{
    requireEnvironment(env, "referenceSpecular");
    const double NdotV = glm::dot(n, v);
    if (NdotV <= 0.0)
        return glm::dvec3(0.0);
    const double alpha = roughness * roughness;
    return sumOverTexels(env, [&](glm::dvec3 w) {
               const double NdotL = glm::dot(n, w);
               if (NdotL <= 0.0)
                   return glm::dvec3(0.0);
               const glm::dvec3 h = glm::normalize(v + w);
               const double NdotH = std::max(0.0, glm::dot(n, h));
               const double VdotH = std::max(0.0, glm::dot(v, h));
               const double DV = ggxSpecularBrdf(term, NdotH, NdotV, NdotL, alpha);
               return fresnelSchlick(VdotH, F0) * (DV * NdotL);
           })
        .weighted;
}

ImageRGB32F downsampleEquirect2x(const ImageRGB32F& env)
{
    if (env.empty() || env.width % 2 != 0 || env.height % 2 != 0)
        throw std::invalid_argument("downsampleEquirect2x: dimensions must be even and non-zero, got " +
                                    std::to_string(env.width) + "x" + std::to_string(env.height));
    ImageRGB32F out(env.width / 2, env.height / 2);
    for (int y = 0; y < out.height; ++y) {
        const double w0 = equirectTexelSolidAngle(2 * y, env.width, env.height);
        const double w1 = equirectTexelSolidAngle(2 * y + 1, env.width, env.height);
        for (int x = 0; x < out.width; ++x) {
            const glm::dvec3 top = glm::dvec3(env.at(2 * x, 2 * y)) + glm::dvec3(env.at(2 * x + 1, 2 * y));
            const glm::dvec3 bottom =
                glm::dvec3(env.at(2 * x, 2 * y + 1)) + glm::dvec3(env.at(2 * x + 1, 2 * y + 1));
            out.set(x, y, glm::vec3((top * w0 + bottom * w1) / (2.0 * (w0 + w1))));
        }
    }
    return out;
}

ImageRGB32F downsampleEquirectToWidth(const ImageRGB32F& env, int maxWidth)
{
    ImageRGB32F out = env;
    while (out.width > maxWidth && out.width % 2 == 0 && out.height % 2 == 0) out = downsampleEquirect2x(out);
    return out;
}

double referenceMinResolvedRoughness(int width)
{
    return std::sqrt(1.5 * 2.0 * kPi / double(std::max(width, 1)));
}

std::vector<EquirectRowBlend> fluxConservingRowBlends(int height, int factor)
{
    const int rows = height * factor;
    std::vector<EquirectRowBlend> blends(static_cast<std::size_t>(rows));
    for (int k = 0; k < rows; ++k) {
        // The bilinear read's rows: row k's centre in the source's continuous row coordinate
        // (centres at integers), clamped at the poles.
        const double y = (double(k) + 0.5) / double(factor) - 0.5;
        const double y0 = std::floor(y);
        EquirectRowBlend& b = blends[std::size_t(k)];
        b.first = std::clamp(int(y0), 0, height - 1);
        b.second = std::clamp(int(y0) + 1, 0, height - 1);
        b.weight = b.first == b.second ? 0.0 : y - y0;
    }
    // A ring's solid angle; the columns divide every ring alike, so rings compare as texels do.
    auto source = [&](int r) { return equirectTexelSolidAngle(r, 1, height); };
    auto fine = [&](int k) { return equirectTexelSolidAngle(k, 1, rows); };
    // From the north pole down, each source row's flux made its own: the rows that blend it
    // with the row below get its weight scaled so that the flux it lends them, with what the
    // rows above already lend it, is its ring's. Up to the two rows either side of the equator,
    // which then hold the rest, the same by symmetry; the south half is the north's mirror.
    const int exactRows = (height - 1) / 2;
    int k = 0;
    for (int r = 0; r < exactRows; ++r) {
        double fixed = 0.0, adjustable = 0.0;
        const int firstAdjustable = k;
        for (; k < rows / 2 && blends[std::size_t(k)].first <= r; ++k) {
            const EquirectRowBlend& b = blends[std::size_t(k)];
            if (b.first == r && b.second == r) fixed += fine(k);
            else if (b.first == r) adjustable += fine(k) * (1.0 - b.weight);
        }
        // The rows that read r as their second were set when r - 1 was.
        for (int j = firstAdjustable - 1; j >= 0 && blends[std::size_t(j)].second == r && blends[std::size_t(j)].first == r - 1; --j)
            fixed += fine(j) * blends[std::size_t(j)].weight;
        if (adjustable <= 0.0) continue;
        double scale = std::max(0.0, (source(r) - fixed) / adjustable);
        for (int j = firstAdjustable; j < k; ++j)
            if (blends[std::size_t(j)].first == r && blends[std::size_t(j)].second == r + 1)
                scale = std::min(scale, 1.0 / (1.0 - blends[std::size_t(j)].weight));
        for (int j = firstAdjustable; j < k; ++j) {
            EquirectRowBlend& b = blends[std::size_t(j)];
            if (b.first == r && b.second == r + 1) b.weight = 1.0 - (1.0 - b.weight) * scale;
        }
    }
    for (int j = rows / 2; j < rows; ++j) {
        const EquirectRowBlend& north = blends[std::size_t(rows - 1 - j)];
        EquirectRowBlend& b = blends[std::size_t(j)];
        b.first = height - 1 - north.second;
        b.second = height - 1 - north.first;
        b.weight = b.first == b.second ? 0.0 : 1.0 - north.weight;
    }
    return blends;
}

ImageRGB32F upsampleEquirectBilinear(const ImageRGB32F& env, int factor)
{
    requireEnvironment(env, "upsampleEquirectBilinear");
    if (factor < 1 || std::int64_t(env.width) * factor > (1 << 16))
        throw std::invalid_argument("upsampleEquirectBilinear: factor " + std::to_string(factor) + " out of range for a " +
                                    std::to_string(env.width) + " wide map");
    if (factor == 1)
        return env;
    ImageRGB32F out(env.width * factor, env.height * factor);
    const std::vector<EquirectRowBlend> blends = fluxConservingRowBlends(env.height, factor);
    for (int y = 0; y < out.height; ++y) {
        const EquirectRowBlend& b = blends[std::size_t(y)];
        for (int x = 0; x < out.width; ++x) {
            // Output texel x's centre in the source's continuous column coordinate, which wraps.
            const double fx = (double(x) + 0.5) / double(factor) - 0.5;
            const glm::dvec3 first(equirectBilinearAt(env, fx, double(b.first)));
            const glm::dvec3 second(equirectBilinearAt(env, fx, double(b.second)));
            out.set(x, y, glm::vec3(first * (1.0 - b.weight) + second * b.weight));
        }
    }
    return out;
}

int referenceUpsampleFactor(int width, double roughness, int maxFactor)
{
    int factor = 1;
    while (factor < maxFactor && referenceMinResolvedRoughness(width * factor) > roughness) factor *= 2;
    return factor;
}

double ggxPrefilterNormalization(double roughness)
{
    // With v = n, dOmega_l = 4 (n.h) dOmega_h, so Z = 4 E[max(0, n.l)] for h drawn with
    // density D(h) (n.h), whose inverse CDF is cos^2(theta_h) = (1 - u) / (1 + (alpha^2 - 1) u);
    // n.l = 2 cos^2(theta_h) - 1. The integrand is smooth in u: the midpoint rule with 2^16
    // points is exact to well under 1e-6.
    const double a2 = roughness * roughness * roughness * roughness;
    constexpr int kSteps = 1 << 16;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        const double u = (i + 0.5) / kSteps;
        const double cos2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u);
        sum += std::max(0.0, 2.0 * cos2 - 1.0);
    }
    return 4.0 * sum / kSteps;
}

} // namespace iblab
