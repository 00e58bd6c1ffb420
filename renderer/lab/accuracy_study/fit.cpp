// accuracy_study fit refits the lobe table on the 8 bundled maps only and writes it as a C++
// include (report.cpp). Per (n.v, roughness) cell, random (n, v) pairs on every map give the
// full integral for copper and for a dielectric; Nelder-Mead then moves the cell's reads
// (direction towards the normal, roughness; two of each for the Fresnel split) to minimise
// the mean squared per-pixel relative error of both, starting from the split sum and, for
// the Fresnel split, from --init's one-tap table. Seeded per cell, so the result does not
// depend on the threads. The committed table (renderer/ibl/specular_lobe_fit.inc) is
// reproduced by
//   accuracy_study fit --taps 1 --out /tmp/one-tap.inc
//   accuracy_study fit --taps 3 --mixed-objective --init /tmp/one-tap.inc
// (docs/accuracy-study.md).
#include "accuracy_study.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <mutex>
#include <random>
#include <stdexcept>

namespace iblab::accuracy {
namespace {

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
    std::size_t envIndex;
    glm::dvec3 n, v;
    glm::dvec3 refCopper, refDielectric; // specular; the dielectric's with its diffuse added
    glm::dvec3 diffuseDielectric;
};

} // namespace

int fitCommand(const StudyOptions& a)
{
    const auto t0 = Clock::now();
    std::vector<EnvCase> envs;
    for (const auto& [spec, set] : environmentList("bundled", {})) envs.push_back(loadCase(spec, set, a.width, true, a.bakes));
    std::fprintf(stderr, "fit on %zu bundled maps at %d wide (%.1f s to load and prefilter)\n", envs.size(), a.width, secondsSince(t0));

    LobeFitTable initTable;
    if (!a.init.empty()) {
        initTable = readLobeTable(a.init);
        if (initTable.taps != 1 && !(a.taps >= 3 && initTable.taps >= 3))
            throw std::runtime_error("--init needs a one-tap table (or, for --taps 3 and 4, a Fresnel-split one to refine)");
    }
    LobeFitTable table;
    table.taps = a.taps;
    table.nvSize = a.size;
    table.roughnessSize = a.size;
    const int cellCount = a.size * a.size;
    table.cells.assign(std::size_t(cellCount) * std::size_t(table.planes()), glm::vec4(0.0f));
    for (int row = 0; row < a.size; ++row)
        for (int col = 0; col < a.size; ++col) {
            const float r = (float(row) + 0.5f) / float(a.size);
            table.at(col, row) = a.taps == 1 ? glm::vec4(0.0f, r, 0.0f, 0.0f) : a.taps == 2 ? glm::vec4(0.0f, 0.0f, r, 0.0f) : glm::vec4(0.0f, r, 0.0f, r);
            if (table.planes() > 1) table.at(col, row, 1) = glm::vec4(0.0f, r, 0.0f, 0.0f); // second A read, weight 0
        }
    std::vector<std::array<double, 2>> gain(std::size_t(cellCount), {0.0, 0.0}); // split-sum objective, fitted objective
    std::mutex print;
    parallelFor(cellCount, [&](int idx) {
        const int col = idx % a.size, row = idx / a.size;
        const double NdotV = (col + 0.5) / a.size, roughness = (row + 0.5) / a.size;
        if (roughness < a.minRoughness) return;
        std::mt19937 rng(a.seed * 7919u + unsigned(idx));
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::vector<FitSample> samples;
        for (std::size_t envIndex = 0; envIndex < envs.size(); ++envIndex) {
            const EnvCase& env = envs[envIndex];
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
                samples.push_back({&env, envIndex, queries[k].n, queries[k].v, refs[k].specular(kCopper), refs[k].specular(glm::dvec3(kDielectricF0)) + diffuse, diffuse});
            }
        }
        const glm::dvec3 ab = lut().sample(NdotV, roughness);
        const glm::dvec3 albedoCopper = kCopper * ab.x + ab.y, albedoDielectric = glm::dvec3(kDielectricF0 * ab.x + ab.y);
        // The squared errors summed per map; the objective is their total over the samples,
        // or (--per-map-ratio) the mean over the maps of each map's sum relative to the split
        // sum's in this cell: the bar is a ratio per map, so a map where the split sum is
        // already close (city, night) weighs as much as one where it is far off (sunrise).
        // A cell's texels: the first plane's, and layout 4's second (ignored by the others).
        using Cell = std::array<glm::vec4, 2>;
        auto perMapErrors = [&](const Cell& cell) {
            const glm::vec4& p = cell[0];
            const glm::vec4& q = cell[1];
            std::vector<double> perMap(envs.size(), 0.0);
            for (const FitSample& s : samples) {
                double& e = perMap[s.envIndex];
                const glm::dvec3 R = 2.0 * glm::dot(s.n, s.v) * s.n - s.v;
                if (table.taps >= 3) {
                    // Fresnel split: F0 A read_A + B read_B; layout 4 mixes a second read into read_A.
                    glm::dvec3 preA = s.env->prefiltered(glm::mix(R, s.n, double(p.x)), p.y);
                    if (table.taps == 4)
                        preA = glm::mix(preA, s.env->prefiltered(glm::mix(R, s.n, double(shared::lobeSecondATowardsNormal(q))), shared::lobeSecondARoughness(q)),
                                        double(shared::lobeSecondAWeight(q)));
                    const glm::dvec3 preB = s.env->prefiltered(glm::mix(R, s.n, double(p.z)), p.w);
                    const double ec = pixelError(kCopper * ab.x * preA + ab.y * preB, s.refCopper);
                    const glm::dvec3 specD = kDielectricF0 * ab.x * preA + ab.y * preB;
                    const double ed = pixelError(specD + s.diffuseDielectric, s.refDielectric);
                    const double es = a.mixedObjective ? pixelError(specD, s.refDielectric - s.diffuseDielectric) : 0.0;
                    e += ec * ec + ed * ed + es * es;
                    continue;
                }
                glm::dvec3 pre(0.0);
                for (int k = 0; k < table.taps; ++k) {
                    const glm::dvec3 d = glm::mix(R, s.n, double(shared::lobeTapTowardsNormal(p, table.taps, k)));
                    pre += double(shared::lobeTapWeight(p, table.taps, k)) * s.env->prefiltered(d, shared::lobeTapRoughness(p, table.taps, k));
                }
                const double ec = pixelError(pre * albedoCopper, s.refCopper);
                const double ed = pixelError(pre * albedoDielectric + s.diffuseDielectric, s.refDielectric);
                const double es = a.mixedObjective ? pixelError(pre * albedoDielectric, s.refDielectric - s.diffuseDielectric) : 0.0;
                e += ec * ec + ed * ed + es * es;
            }
            return perMap;
        };
        const Cell identity{table.at(col, row), table.planes() > 1 ? table.at(col, row, 1) : glm::vec4(0.0f)};
        const std::vector<double> splitSumPerMap = perMapErrors(identity);
        auto objective = [&](const Cell& cell) {
            const std::vector<double> perMap = perMapErrors(cell);
            double e = 0.0;
            if (!a.perMapRatio) {
                for (double x : perMap) e += x;
                return e / double(samples.size());
            }
            for (std::size_t m = 0; m < perMap.size(); ++m) e += perMap[m] / std::max(splitSumPerMap[m], 1e-12);
            return e / double(perMap.size());
        };
        auto clampParams = [&](const std::vector<double>& x) {
            auto towards = [](double t) { return float(std::clamp(t, -0.5, 1.0)); };
            auto unit = [](double v) { return float(std::clamp(v, 0.0, 1.0)); };
            if (table.taps == 1) return Cell{glm::vec4(towards(x[0]), unit(x[1]), 0.0f, 0.0f), glm::vec4(0.0f)};
            if (table.taps == 3) return Cell{glm::vec4(towards(x[0]), unit(x[1]), towards(x[2]), unit(x[3])), glm::vec4(0.0f)};
            if (table.taps == 4)
                return Cell{glm::vec4(towards(x[0]), unit(x[1]), towards(x[2]), unit(x[3])), glm::vec4(towards(x[4]), unit(x[5]), unit(x[6]), 0.0f)};
            return Cell{glm::vec4(float(std::clamp(x[0], -1.0, 1.0)), float(std::clamp(x[1], -1.0, 1.0)), unit(x[2]), unit(x[3])), glm::vec4(0.0f)};
        };
        auto f = [&](const std::vector<double>& x) { return objective(clampParams(x)); };
        const double base = objective(identity);
        Cell best = identity;
        double bestValue = base;
        if (table.taps == 4) {
            // From --init's Fresnel split (its A read kept, the second A read at weight 1/4):
            // once beside it along the plane of N and V at the same width (a stretched lobe),
            // once at its direction and wider (a peak with tails). A layout 4 --init is
            // refined from where it is.
            const glm::dvec4 p = initTable.empty() ? glm::dvec4(0.0, roughness, 0.0, roughness) : initTable.sample(NdotV, roughness);
            std::vector<std::vector<double>> starts;
            if (initTable.taps == 4) {
                const glm::dvec4 q = initTable.sample(NdotV, roughness, 1);
                starts.push_back({p.x, p.y, p.z, p.w, q.x, q.y, q.z});
            } else {
                starts.push_back({p.x, p.y, p.z, p.w, p.x + 0.2, p.y, 0.25});
                starts.push_back({p.x, p.y, p.z, p.w, p.x, std::min(1.0, p.y + 0.2), 0.25});
            }
            for (const std::vector<double>& x0 : starts) {
                const std::vector<double> x = nelderMead(f, x0, {0.1, 0.08, 0.1, 0.08, 0.15, 0.1, 0.15}, 250);
                const double v = f(x);
                if (v < bestValue) bestValue = v, best = clampParams(x);
            }
        } else if (table.taps == 3) {
            // Start from the one-tap table of --init (both reads where it reads) and from the split sum.
            const glm::dvec4 one = initTable.empty() ? glm::dvec4(0.0, roughness, 0.0, 0.0) : initTable.sample(NdotV, roughness);
            const std::vector<double> fromInit = initTable.taps == 3 ? std::vector<double>{one.x, one.y, one.z, one.w}
                                                                     : std::vector<double>{one.x, one.y, one.x, one.y};
            for (const std::vector<double>& x0 : {fromInit, std::vector<double>{0.0, roughness, 0.0, roughness}}) {
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
        table.at(col, row) = best[0];
        if (table.planes() > 1) table.at(col, row, 1) = best[1];
        gain[std::size_t(idx)] = {base, bestValue};
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "n.v %.3f r %.3f: rms %.3f -> %.3f  (%.3f %.3f %.3f %.3f | %.3f %.3f %.3f)\n", NdotV, roughness, std::sqrt(base),
                     std::sqrt(bestValue), best[0].x, best[0].y, best[0].z, best[0].w, best[1].x, best[1].y, best[1].z);
    });

    const std::string outPath = a.out.empty() ? (kSourceDir / "renderer" / "ibl" / "specular_lobe_fit.inc").string() : a.out;
    std::ofstream(outPath) << lobeTableInclude(table, a);
    double sb = 0.0, sf = 0.0;
    for (const auto& g : gain) sb += g[0], sf += g[1];
    std::fprintf(stderr, "wrote %s; mean objective %.4f -> %.4f; fit took %.1f s\n", outPath.c_str(), sb / double(gain.size()), sf / double(gain.size()),
                 secondsSince(t0));
    return 0;
}

} // namespace iblab::accuracy
