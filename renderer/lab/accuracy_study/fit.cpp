// accuracy_study fit refits the lobe table on the 8 bundled maps only (--leave-out: 7) and writes it as a C++
// include (report.cpp). Per (n.v, roughness) cell, random (n, v) pairs on every map give the
// full integral for copper and for a dielectric; Nelder-Mead then moves the cell's reads
// (direction towards the normal, roughness; two of each for the Fresnel split) to minimise
// the mean squared per-pixel relative error of both, starting from the split sum and, for
// the Fresnel split, from --init's table. With --smooth, passes over the table then re-fit
// every cell with a penalty on its difference from its neighbours (Smoother). Seeded per
// cell and read from snapshots, so the result does not depend on the threads. The commands
// that reproduce the committed table (renderer/ibl/specular_lobe_fit.inc) are in
// docs/accuracy-study.md; its header names the last one.
#include "accuracy_study.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <random>
#include <stdexcept>

#include "ibl/brdf_lut.hpp"
#include "read_floor.hpp"

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
    FullIntegral lights; // --lights: the lights' exact sums, added to every estimate
};

// FNV-1a of a map's name, 32 bits: one of the seeds of its frames.
unsigned nameHash(const std::string& name)
{
    std::uint32_t h = 2166136261u;
    for (const char c : name) h = (h ^ std::uint32_t(static_cast<unsigned char>(c))) * 16777619u;
    return h;
}

// A cell's texels: the first plane's, and layout 4's second (ignored by the others).
using Cell = std::array<glm::vec4, 2>;

// The free parameters of a layout's cell, clamped into the fit's box (t in [-0.5, 1], r and
// w in [0, 1]; layout 2's t in [-1, 1]), and back.
Cell cellFromParameters(int taps, const std::vector<double>& x)
{
    auto towards = [](double t) { return float(std::clamp(t, -0.5, 1.0)); };
    auto unit = [](double v) { return float(std::clamp(v, 0.0, 1.0)); };
    if (taps == 1) return Cell{glm::vec4(towards(x[0]), unit(x[1]), 0.0f, 0.0f), glm::vec4(0.0f)};
    if (taps == 3) return Cell{glm::vec4(towards(x[0]), unit(x[1]), towards(x[2]), unit(x[3])), glm::vec4(0.0f)};
    if (taps == 4) return Cell{glm::vec4(towards(x[0]), unit(x[1]), towards(x[2]), unit(x[3])), glm::vec4(towards(x[4]), unit(x[5]), unit(x[6]), 0.0f)};
    return Cell{glm::vec4(float(std::clamp(x[0], -1.0, 1.0)), float(std::clamp(x[1], -1.0, 1.0)), unit(x[2]), unit(x[3])), glm::vec4(0.0f)};
}

std::vector<double> parametersOf(int taps, const Cell& cell)
{
    const glm::dvec4 p(cell[0]), q(cell[1]);
    if (taps == 1) return {p.x, p.y};
    if (taps == 4) return {p.x, p.y, p.z, p.w, q.x, q.y, q.z};
    return {p.x, p.y, p.z, p.w};
}

Cell cellAt(const LobeFitTable& table, int col, int row)
{
    return {table.at(col, row), table.planes() > 1 ? table.at(col, row, 1) : glm::vec4(0.0f)};
}

void setCell(LobeFitTable& table, int col, int row, const Cell& cell)
{
    table.at(col, row) = cell[0];
    if (table.planes() > 1) table.at(col, row, 1) = cell[1];
}

// One cell's fitting problem: `--frames` random frames (n uniform on the sphere, v at the
// cell's n.v with a random azimuth) on every map with their full integrals, seeded by the
// cell and the map's name, so that a map's frames (and their cached integrals) are the same
// whichever maps are fitted with it (--leave-out), and the objective of a candidate cell.
class CellProblem {
public:
    CellProblem(const StudyOptions& a, const std::vector<EnvCase>& envs, int cellCol, int cellRow, const Cell& splitSum)
        : col(cellCol), row(cellRow), NdotV((cellCol + 0.5) / a.size), roughness((cellRow + 0.5) / a.size), options_(&a), maps_(envs.size())
    {
        lut_ = lut().sample(NdotV, roughness);
        if (a.readFloor) floor_ = readRoughnessFloor(NdotV, roughness, kTerm);
        // The compensation (--no-multiscatter: none) is a constant of the cell for each F0.
        compensationCopper_ = a.multiscatter ? specularEnergyCompensation(kCopper, lut_.z) : glm::dvec3(1.0);
        compensationDielectric_ = a.multiscatter ? specularEnergyCompensation(glm::dvec3(kDielectricF0), lut_.z) : glm::dvec3(1.0);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (std::size_t envIndex = 0; envIndex < envs.size(); ++envIndex) {
            const EnvCase& env = envs[envIndex];
            std::seed_seq seeds{a.seed, unsigned(cellRow * a.size + cellCol), nameHash(env.name)};
            std::mt19937 rng(seeds);
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
                const FullIntegral lights = env.lights ? env.lights->evaluate(queries[k].n, queries[k].v, env.lightsRoughness(roughness), kTerm, false) : FullIntegral{};
                // The dielectric as combineLobes shades it (metallic 0, copper base colour).
                const Pixel p{queries[k].n, queries[k].v, roughness, 0.0};
                const glm::dvec3 diffuse = combine(p, glm::dvec3(0.0), refs[k].irradiance, glm::dvec3(kDielectricF0)).total;
                samples_.push_back({&env, envIndex, queries[k].n, queries[k].v, refs[k].specular(kCopper) * compensationCopper_,
                                    refs[k].specular(glm::dvec3(kDielectricF0)) * compensationDielectric_ + diffuse, diffuse, lights});
            }
        }
        splitSumPerMap_ = perMapErrors(splitSum);
    }

    // The squared errors summed over the samples, or (--per-map-ratio) the mean over the maps
    // of each map's sum relative to the split sum's in this cell: the bar is a ratio per map,
    // so a map where the split sum is already close (city, night) weighs as much as one where
    // it is far off (sunrise).
    double objective(const Cell& cell) const
    {
        const std::vector<double> perMap = perMapErrors(cell);
        double e = 0.0;
        if (!options_->perMapRatio) {
            for (double x : perMap) e += x;
            return e / double(samples_.size());
        }
        for (std::size_t m = 0; m < perMap.size(); ++m) e += perMap[m] / std::max(splitSumPerMap_[m], 1e-12);
        return e / double(perMap.size());
    }

    // A candidate's parameters as a cell, its reads no sharper than --read-floor allows.
    Cell cellFrom(int taps, const std::vector<double>& x) const
    {
        Cell c = cellFromParameters(taps, x);
        if (taps < 3) return c; // the floors are per term of the Fresnel split
        c[0].y = std::max(c[0].y, float(floor_.a));
        c[0].w = std::max(c[0].w, float(floor_.b));
        if (taps == 4) c[1].y = std::max(c[1].y, float(floor_.a));
        return c;
    }

    int col, row;
    double NdotV, roughness;

private:
    std::vector<double> perMapErrors(const Cell& cell) const
    {
        const int taps = options_->taps;
        const glm::vec4& p = cell[0];
        const glm::vec4& q = cell[1];
        const glm::dvec3 albedoCopper = (kCopper * lut_.x + lut_.y) * compensationCopper_;
        const glm::dvec3 albedoDielectric = glm::dvec3(kDielectricF0 * lut_.x + lut_.y) * compensationDielectric_;
        std::vector<double> perMap(maps_, 0.0);
        for (const FitSample& s : samples_) {
            double& e = perMap[s.envIndex];
            const glm::dvec3 R = 2.0 * glm::dot(s.n, s.v) * s.n - s.v;
            // With --lights the reads are the residual's, and the lights add their exact sums.
            auto read = [&](glm::dvec3 d, double r) { return s.env->residualBake ? s.env->residualBake->lookup(d, r) : s.env->prefiltered(d, r); };
            const glm::dvec3 lightsCopper = s.lights.specular(kCopper), lightsDielectric = s.lights.specular(glm::dvec3(kDielectricF0));
            if (taps >= 3) {
                // Fresnel split: F0 A read_A + B read_B; layout 4 mixes a second read into read_A.
                glm::dvec3 preA = read(glm::mix(R, s.n, double(p.x)), p.y);
                if (taps == 4)
                    preA = glm::mix(preA, read(glm::mix(R, s.n, double(shared::lobeSecondATowardsNormal(q))), shared::lobeSecondARoughness(q)),
                                    double(shared::lobeSecondAWeight(q)));
                const glm::dvec3 preB = read(glm::mix(R, s.n, double(p.z)), p.w);
                const double ec = pixelError((kCopper * lut_.x * preA + lut_.y * preB + lightsCopper) * compensationCopper_, s.refCopper);
                const glm::dvec3 specD = (kDielectricF0 * lut_.x * preA + lut_.y * preB + lightsDielectric) * compensationDielectric_;
                const double ed = pixelError(specD + s.diffuseDielectric, s.refDielectric);
                const double es = options_->mixedObjective ? pixelError(specD, s.refDielectric - s.diffuseDielectric) : 0.0;
                e += ec * ec + ed * ed + es * es;
                continue;
            }
            glm::dvec3 pre(0.0);
            for (int k = 0; k < taps; ++k) {
                const glm::dvec3 d = glm::mix(R, s.n, double(shared::lobeTapTowardsNormal(p, taps, k)));
                pre += double(shared::lobeTapWeight(p, taps, k)) * read(d, shared::lobeTapRoughness(p, taps, k));
            }
            const glm::dvec3 specC = pre * albedoCopper + lightsCopper * compensationCopper_;
            const glm::dvec3 specD = pre * albedoDielectric + lightsDielectric * compensationDielectric_;
            const double ec = pixelError(specC, s.refCopper);
            const double ed = pixelError(specD + s.diffuseDielectric, s.refDielectric);
            const double es = options_->mixedObjective ? pixelError(specD, s.refDielectric - s.diffuseDielectric) : 0.0;
            e += ec * ec + ed * ed + es * es;
        }
        return perMap;
    }

    const StudyOptions* options_;
    std::size_t maps_;
    std::vector<FitSample> samples_;
    glm::dvec3 lut_;                     // the split-sum LUT's (A, B, A + B) at the cell
    glm::dvec3 compensationCopper_{1.0}, compensationDielectric_{1.0};
    std::vector<double> splitSumPerMap_; // --per-map-ratio's denominators
    ReadRoughnessFloor floor_;           // --read-floor's; zero without it
};

// The cell fitted alone, from where --init (or, without one, the split sum) puts it; `value`
// is its objective.
Cell fitAlone(const CellProblem& cell, const LobeFitTable& initTable, int taps, const Cell& splitSum, double& value)
{
    auto f = [&](const std::vector<double>& x) { return cell.objective(cell.cellFrom(taps, x)); };
    const double roughness = cell.roughness;
    Cell best = splitSum;
    value = cell.objective(splitSum);
    auto tryFrom = [&](const std::vector<double>& x0, const std::vector<double>& step, int iterations) {
        const std::vector<double> x = nelderMead(f, x0, step, iterations);
        const double v = f(x);
        if (v < value) value = v, best = cell.cellFrom(taps, x);
    };
    if (taps == 4) {
        // From --init's Fresnel split (its A read kept, the second A read at weight 1/4):
        // once beside it along the plane of N and V at the same width (a stretched lobe),
        // once at its direction and wider (a peak with tails). A layout 4 --init is
        // refined from where it is.
        const glm::dvec4 p = initTable.empty() ? glm::dvec4(0.0, roughness, 0.0, roughness) : initTable.sample(cell.NdotV, roughness);
        const std::vector<double> step{0.1, 0.08, 0.1, 0.08, 0.15, 0.1, 0.15};
        if (initTable.taps == 4) {
            const glm::dvec4 q = initTable.sample(cell.NdotV, roughness, 1);
            tryFrom({p.x, p.y, p.z, p.w, q.x, q.y, q.z}, step, 250);
        } else {
            tryFrom({p.x, p.y, p.z, p.w, p.x + 0.2, p.y, 0.25}, step, 250);
            tryFrom({p.x, p.y, p.z, p.w, p.x, std::min(1.0, p.y + 0.2), 0.25}, step, 250);
        }
    } else if (taps == 3) {
        // Start from the one-tap table of --init (both reads where it reads) and from the split sum.
        const glm::dvec4 one = initTable.empty() ? glm::dvec4(0.0, roughness, 0.0, 0.0) : initTable.sample(cell.NdotV, roughness);
        const std::vector<double> fromInit =
            initTable.taps == 3 ? std::vector<double>{one.x, one.y, one.z, one.w} : std::vector<double>{one.x, one.y, one.x, one.y};
        for (const std::vector<double>& x0 : {fromInit, std::vector<double>{0.0, roughness, 0.0, roughness}}) tryFrom(x0, {0.15, 0.1, 0.15, 0.1}, 200);
    } else if (taps == 1) {
        for (double t0s : {0.0, 0.3, 0.6}) tryFrom({t0s, roughness}, {0.15, 0.1}, 80);
    } else {
        for (double spread : {0.2, 0.5})
            for (double t0s : {0.0, 0.4}) tryFrom({t0s - spread, t0s + spread, roughness * 0.8, 0.5}, {0.15, 0.15, 0.1, 0.2}, 160);
    }
    return best;
}

// --smooth. Fitted alone, neighbouring cells can land in different minima of nearly the same
// error (the two A reads trading places or widths between mip 4 and the widest mip, a B read
// where B is negligible), and the bilinear lookup between them reads neither: the rings of
// rough spheres. A pass re-fits every cell against its objective plus
//   smooth * sum over the axes n.v and roughness of |x - line|^2,
// x the cell's parameters and `line` where the straight line through its two neighbours
// along that axis puts it (their mean; at the table's edge, the line through the two cells
// inside, extrapolated). That is a penalty on the table's second differences: a ramp costs
// nothing, a step or an alternation does. Only fitted cells (roughness >= --min-roughness)
// count as neighbours. Each pass updates the cells of one parity of col + row, then the
// other, each half from a snapshot of the table, so a half's cells are independent (threads
// cannot change the result) and see the other half's new values (Gauss-Seidel's pace).
class Smoother {
public:
    explicit Smoother(const StudyOptions& a) : a_(a), taps_(a.taps) {}

    bool fitted(int col, int row) const
    {
        return col >= 0 && row >= 0 && col < a_.size && row < a_.size && (row + 0.5) / a_.size >= a_.minRoughness;
    }

    // Where the lines through the neighbours of (col, row) put it, one per axis that has any.
    std::vector<std::vector<double>> lines(const LobeFitTable& snapshot, int col, int row) const
    {
        std::vector<std::vector<double>> out;
        for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{0, 1}}) {
            auto at = [&](int k) { return parametersOf(taps_, cellAt(snapshot, col + k * dc, row + k * dr)); };
            auto has = [&](int k) { return fitted(col + k * dc, row + k * dr); };
            std::optional<std::vector<double>> line;
            if (has(-1) && has(1)) line = combination(at(-1), 0.5, at(1), 0.5);
            else if (has(1)) line = has(2) ? combination(at(1), 2.0, at(2), -1.0) : at(1);
            else if (has(-1)) line = has(-2) ? combination(at(-1), 2.0, at(-2), -1.0) : at(-1);
            if (line) out.push_back(*line);
        }
        return out;
    }

    double penalty(const Cell& cell, const std::vector<std::vector<double>>& lines) const
    {
        const std::vector<double> x = parametersOf(taps_, cell);
        double e = 0.0;
        for (const std::vector<double>& line : lines)
            for (std::size_t j = 0; j < x.size(); ++j) e += (x[j] - line[j]) * (x[j] - line[j]);
        return a_.smooth * e;
    }

    // The cell re-fitted with the penalty, from where it is and from the mean of its lines
    // (which can leave a minimum its neighbours are not in).
    Cell refit(const CellProblem& cell, const Cell& current, const std::vector<std::vector<double>>& lines) const
    {
        auto f = [&](const std::vector<double>& x) {
            const Cell c = cell.cellFrom(taps_, x);
            return cell.objective(c) + penalty(c, lines);
        };
        std::vector<std::vector<double>> starts{parametersOf(taps_, current)};
        if (!lines.empty()) {
            std::vector<double> mean(starts[0].size(), 0.0);
            for (const std::vector<double>& line : lines) mean = combination(mean, 1.0, line, 1.0 / double(lines.size()));
            starts.push_back(parametersOf(taps_, cell.cellFrom(taps_, mean)));
        }
        Cell best = current;
        double bestValue = f(starts[0]);
        for (const std::vector<double>& x0 : starts) {
            const std::vector<double> x = nelderMead(f, x0, std::vector<double>(x0.size(), 0.08), 150);
            const double v = f(x);
            if (v < bestValue) bestValue = v, best = cell.cellFrom(taps_, x);
        }
        return best;
    }

    // The largest difference of any parameter between two fitted cells next to each other.
    double largestStep(const LobeFitTable& table) const
    {
        double step = 0.0;
        for (int row = 0; row < a_.size; ++row)
            for (int col = 0; col < a_.size; ++col)
                for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{0, 1}}) {
                    if (!fitted(col, row) || !fitted(col + dc, row + dr)) continue;
                    const std::vector<double> x = parametersOf(taps_, cellAt(table, col, row)), y = parametersOf(taps_, cellAt(table, col + dc, row + dr));
                    for (std::size_t j = 0; j < x.size(); ++j) step = std::max(step, std::abs(x[j] - y[j]));
                }
        return step;
    }

private:
    static std::vector<double> combination(const std::vector<double>& x, double a, const std::vector<double>& y, double b)
    {
        std::vector<double> out(x.size());
        for (std::size_t j = 0; j < x.size(); ++j) out[j] = a * x[j] + b * y[j];
        return out;
    }

    const StudyOptions& a_;
    int taps_;
};

void printCell(std::mutex& print, const CellProblem& cell, double base, double value, const Cell& best)
{
    std::lock_guard<std::mutex> lock(print);
    std::fprintf(stderr, "n.v %.3f r %.3f: rms %.3f -> %.3f  (%.3f %.3f %.3f %.3f | %.3f %.3f %.3f)\n", cell.NdotV, cell.roughness, std::sqrt(base),
                 std::sqrt(value), best[0].x, best[0].y, best[0].z, best[0].w, best[1].x, best[1].y, best[1].z);
}

// The maps a fit reads: the bundled ones (but --leave-out's), or --env's, with their bakes
// and (--lights) their shading lights.
std::vector<EnvCase> fitMaps(const StudyOptions& a)
{
    // --env replaces the bundled maps: a diagnostic (the best a table of this layout can do on
    // a map it is fitted on), never how the committed table is made.
    std::vector<std::pair<std::string, std::string>> maps = a.envs.empty() ? environmentList("bundled", {}) : environmentList("none", a.envs);
    if (!a.leaveOut.empty()) {
        // Checked before the maps load, so that a misspelt name costs nothing.
        const auto left = std::remove_if(maps.begin(), maps.end(), [&](const auto& m) { return std::filesystem::path(m.first).stem().string() == a.leaveOut; });
        if (left == maps.end()) throw std::runtime_error("--leave-out " + a.leaveOut + ": no bundled map of that name (assets/environments)");
        maps.erase(left, maps.end());
    }
    std::vector<EnvCase> envs;
    for (const auto& [spec, set] : maps) {
        envs.push_back(loadCase(spec, set, a.width, true, a.bakes));
        if (a.lights) splitShadingLightsOf(envs.back(), a.bakes);
    }
    return envs;
}

} // namespace

int fitCommand(const StudyOptions& a)
{
    const auto t0 = Clock::now();
    const std::vector<EnvCase> envs = fitMaps(a);
    std::fprintf(stderr, "fit on %zu maps at %d wide (%.1f s to load and prefilter)\n", envs.size(), a.width, secondsSince(t0));

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
    table.cells.assign(std::size_t(a.size) * std::size_t(a.size) * std::size_t(table.planes()), glm::vec4(0.0f));
    for (int row = 0; row < a.size; ++row)
        for (int col = 0; col < a.size; ++col) {
            const float r = (float(row) + 0.5f) / float(a.size);
            table.at(col, row) = a.taps == 1 ? glm::vec4(0.0f, r, 0.0f, 0.0f) : a.taps == 2 ? glm::vec4(0.0f, 0.0f, r, 0.0f) : glm::vec4(0.0f, r, 0.0f, r);
            if (table.planes() > 1) table.at(col, row, 1) = glm::vec4(0.0f, r, 0.0f, 0.0f); // second A read, weight 0
        }
    const LobeFitTable splitSum = table; // every cell reads at R at its own roughness

    const Smoother smoother(a);
    std::vector<std::pair<int, int>> fittedCells; // (col, row)
    for (int row = 0; row < a.size; ++row)
        for (int col = 0; col < a.size; ++col)
            if (smoother.fitted(col, row)) fittedCells.emplace_back(col, row);
    std::vector<std::unique_ptr<CellProblem>> cells(fittedCells.size());
    std::vector<std::array<double, 2>> gain(cells.size(), {0.0, 0.0}); // split-sum objective, fitted objective
    // Where --init's table of the same layout and size stood, to weigh what the fit changed.
    const bool initComparable = initTable.taps == a.taps && initTable.nvSize == a.size && initTable.roughnessSize == a.size;
    std::vector<double> initObjective(cells.size(), 0.0);
    auto meanFitted = [&] {
        double s = 0.0;
        for (const auto& g : gain) s += g[1];
        return s / double(gain.size());
    };
    std::mutex print;
    parallelFor(int(cells.size()), [&](int i) {
        const auto [col, row] = fittedCells[std::size_t(i)];
        const Cell identity = cellAt(splitSum, col, row);
        cells[std::size_t(i)] = std::make_unique<CellProblem>(a, envs, col, row, identity);
        const CellProblem& cell = *cells[std::size_t(i)];
        if (initComparable) initObjective[std::size_t(i)] = cell.objective(cellAt(initTable, col, row));
        double value = 0.0;
        const Cell best = fitAlone(cell, initTable, a.taps, identity, value);
        setCell(table, col, row, best);
        gain[std::size_t(i)] = {cell.objective(identity), value};
        printCell(print, cell, gain[std::size_t(i)][0], value, best);
    });
    if (initComparable) {
        double mean = 0.0;
        for (double v : initObjective) mean += v / double(initObjective.size());
        std::fprintf(stderr, "--init's table: mean objective %.4f, largest step between adjacent cells %.3f\n", mean, smoother.largestStep(initTable));
    }
    std::fprintf(stderr, "fitted alone: mean objective %.4f, largest step between adjacent cells %.3f (%.1f s)\n", meanFitted(),
                 smoother.largestStep(table), secondsSince(t0));

    if (a.smooth > 0.0) {
        for (int pass = 1; pass <= a.smoothPasses; ++pass) {
            double penalties = 0.0;
            for (int parity = 0; parity < 2; ++parity) {
                const LobeFitTable snapshot = table;
                std::vector<double> cellPenalty(cells.size(), 0.0);
                parallelFor(int(cells.size()), [&](int i) {
                    const CellProblem& cell = *cells[std::size_t(i)];
                    if ((cell.col + cell.row) % 2 != parity) return;
                    const std::vector<std::vector<double>> lines = smoother.lines(snapshot, cell.col, cell.row);
                    const Cell best = smoother.refit(cell, cellAt(snapshot, cell.col, cell.row), lines);
                    setCell(table, cell.col, cell.row, best);
                    gain[std::size_t(i)][1] = cell.objective(best);
                    cellPenalty[std::size_t(i)] = smoother.penalty(best, lines);
                });
                for (double p : cellPenalty) penalties += p;
            }
            std::fprintf(stderr, "smoothing pass %d: mean objective %.4f, mean penalty %.4f, largest step between adjacent cells %.3f (%.1f s)\n", pass,
                         meanFitted(), penalties / double(gain.size()), smoother.largestStep(table), secondsSince(t0));
        }
        for (std::size_t i = 0; i < cells.size(); ++i) printCell(print, *cells[i], gain[i][0], gain[i][1], cellAt(table, cells[i]->col, cells[i]->row));
    }

    const std::string outPath = a.out.empty() ? (kSourceDir / "renderer" / "ibl" / "specular_lobe_fit.inc").string() : a.out;
    std::ofstream(outPath) << lobeTableInclude(table, a);
    double sb = 0.0, sf = 0.0;
    for (const auto& g : gain) sb += g[0], sf += g[1];
    std::fprintf(stderr, "wrote %s; mean objective %.4f -> %.4f; fit took %.1f s\n", outPath.c_str(), sb / double(gain.size()), sf / double(gain.size()),
                 secondsSince(t0));
    return 0;
}

} // namespace iblab::accuracy
