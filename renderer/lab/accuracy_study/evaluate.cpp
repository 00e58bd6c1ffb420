// accuracy_study eval renders, per environment, the bench's scenes as the GPU shades them --
// a unit sphere from the default camera (fov 45, distance 3.5) in copper (metallic 1) and a
// dielectric (metallic 0, F0 0.04, copper base colour) at roughness 0.2 0.3 0.5 0.7 0.9, and
// the 7 x 7 metallic x roughness grid framed as `iblab bench` frames it -- and measures each
// method's relative RMSE against the full integral with the bench's per-pixel measure
// (common/error_metrics.glsl: L1 difference over the reference's channel sum; RMSE over the
// surface pixels whose roughness the reference resolves). Specular + Lambert diffuse with
// kD = (1 - F_roughness(n.v))(1 - metallic) and exact irradiance, as combineLobes. The
// prefiltered cube is emulated (PrefilteredChain: exact prefilter per mip, 6 mips in the
// quadratic layout, trilinear) and the LUT is the bake's 128^2 x 2048, read bilinearly. A CSV
// row per scene and material is written as it goes, the tables (report.cpp) at the end.
#include "accuracy_study.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "ibl/brdf_lut.hpp"
#include "ibl/reference.hpp"

namespace iblab::accuracy {
namespace {

// ---- Methods ---------------------------------------------------------------------------------
struct Method {
    std::string name;
    std::function<glm::dvec3(const SpecularShadingInputs&, const PrefilteredLookup&, const EnvCase&)> specular;
};

// With --lights, a method's "+lights" twin: the method on the residual's mips plus the lights'
// exact specular (the full integral's sums over the lights alone), as the renderer shades
// the fitted lobe by default.
Method withLights(const Method& m)
{
    return {m.name + "+lights", [f = m.specular](const SpecularShadingInputs& in, const PrefilteredLookup&, const EnvCase& env) {
                const PrefilteredLookup residual = [&](glm::dvec3 d, double r) { return env.residualBake->lookup(d, r); };
                return f(in, residual, env) + env.lights->evaluate(in.n, in.v, env.lightsRoughness(in.roughness), kTerm, false).specular(in.F0);
            }};
}

std::vector<Method> methods(const std::vector<std::pair<std::string, LobeFitTable>>& tables, bool lights)
{
    std::vector<Method> m;
    for (SpecularMethod s : {SpecularMethod::SplitSum, SpecularMethod::FrostbiteDominant, SpecularMethod::FrostbitePerceptual,
                             SpecularMethod::FilamentDominant, SpecularMethod::FittedLobe})
        m.push_back({std::string(specularMethodName(s)), [s](const SpecularShadingInputs& in, const PrefilteredLookup& p, const EnvCase&) {
                         return shadeSpecularApproximation(s, in, p);
                     }});
    for (const auto& [name, table] : tables) {
        const LobeFitTable* t = &table;
        m.push_back({name, [t](const SpecularShadingInputs& in, const PrefilteredLookup& p, const EnvCase&) {
                         return shadeSpecularApproximation(SpecularMethod::FittedLobe, in, p, t);
                     }});
    }
    if (lights) {
        // The split sum, the fitted lobe and the tables (the dominant directions have none).
        const std::size_t plain = m.size();
        for (std::size_t i = 0; i < plain; ++i)
            if (m[i].name == specularMethodName(SpecularMethod::SplitSum) || m[i].name == specularMethodName(SpecularMethod::FittedLobe) ||
                i >= plain - tables.size())
                m.push_back(withLights(m[i]));
    }
    return m;
}

// ---- Evaluation ------------------------------------------------------------------------------
// One measured image: per method, the per-pixel relative errors of total and specular-only.
struct Errors {
    std::vector<double> total, specular;
    std::vector<double> NdotV; // per pixel, for --bins
};

std::string formatRoughness(double r)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", r);
    return text;
}

double rmse(const std::vector<double>& e)
{
    double s = 0.0;
    for (double x : e) s += x * x;
    return e.empty() ? 0.0 : std::sqrt(s / double(e.size()));
}

// Evaluates `pixels` (roughness and metallic set) for every method; appends errors per method.
void evaluatePixels(const EnvCase& env, const std::vector<Pixel>& pixels, const std::vector<Method>& ms, const StudyOptions& a, std::vector<Errors>& out)
{
    const PrefilteredLookup lookup = [&](glm::dvec3 d, double r) {
        return a.exactPrefilter ? referencePrefilteredRadiance(env.image, glm::normalize(d), r) : env.prefiltered(d, r);
    };
    std::vector<Query> queries;
    for (const Pixel& p : pixels) queries.push_back({p.n, p.v, p.roughness});
    const std::vector<FullIntegral> refs = fullIntegrals(env, queries, true);
    std::vector<std::vector<std::pair<double, double>>> perPixel(pixels.size());
    parallelFor(int(pixels.size()), [&](int i) {
        const Pixel& p = pixels[std::size_t(i)];
        const glm::dvec3 F0 = glm::mix(glm::dvec3(kDielectricF0), kCopper, p.metallic);
        const FullIntegral& ref = refs[std::size_t(i)];
        SpecularShadingInputs in;
        in.n = p.n;
        in.v = p.v;
        in.roughness = p.roughness;
        in.F0 = F0;
        in.lut = lut().sample(std::max(glm::dot(p.n, p.v), 1e-4), p.roughness);
        const glm::dvec3 compensation = a.multiscatter ? specularEnergyCompensation(F0, in.lut.z) : glm::dvec3(1.0);
        const Shaded r = combine(p, ref.specular(F0) * compensation, ref.irradiance, F0);
        auto& row = perPixel[std::size_t(i)];
        for (const Method& m : ms) {
            const Shaded s = combine(p, m.specular(in, lookup, env) * compensation, ref.irradiance, F0);
            row.emplace_back(pixelError(s.total, r.total), pixelError(s.specular, r.specular));
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

// --bins: adds one image's total errors to method m's n.v bands, to see where an error lives.
void addBins(std::vector<Bins>& perMethod, std::size_t methods, std::size_t m, const Errors& e)
{
    if (perMethod.size() < methods) perMethod.resize(methods, Bins{});
    for (std::size_t i = 0; i < e.total.size(); ++i) {
        const int b = std::clamp(int(e.NdotV[i] * kBins), 0, kBins - 1);
        perMethod[m][std::size_t(b)][0] += e.total[i] * e.total[i];
        perMethod[m][std::size_t(b)][1] += 1.0;
    }
}

} // namespace

int evalCommand(const StudyOptions& a)
{
    const auto t0 = Clock::now();
    std::vector<std::pair<std::string, LobeFitTable>> tables;
    for (const auto& path : a.tables) tables.emplace_back(std::filesystem::path(path).stem().string(), readLobeTable(path));
    const std::vector<Method> ms = methods(tables, a.lights);
    const double minResolved = referenceMinResolvedRoughness(a.width);
    const std::vector<Pixel> sphere = spherePixels(a.sphere, a.benchScenes ? kBenchSphereDistance : kDefaultCameraDistance, a.benchScenes);
    std::vector<Pixel> grid;
    for (const Pixel& p : gridPixels(a.grid, a.benchScenes))
        if (p.roughness >= minResolved) grid.push_back(p);
    std::fprintf(stderr, "reference %d wide, resolved roughness >= %.3f; sphere %zu pixels, grid %zu pixels; prefiltered cube: %s\n", a.width,
                 minResolved, sphere.size(), grid.size(), a.bakes.empty() ? "exact-prefilter emulation" : ("the bakes in " + a.bakes).c_str());

    std::ofstream csv;
    if (!a.csv.empty()) {
        csv.open(a.csv);
        csv << "environment,set,scene,material,roughness,method,relative_rmse,specular_relative_rmse,pixels\n";
    }
    const std::vector<double> roughnesses = a.roughnesses;
    // The measures, each one table: pooled spheres (copper and the dielectric) and the grid,
    // total and specular alone; or (--bench-scenes) the GPU measure's: one copper sphere per
    // roughness, and the grid.
    std::vector<std::string> measures;
    if (a.benchScenes) {
        for (double r : roughnesses) measures.push_back("copper sphere, roughness " + formatRoughness(r));
        measures.push_back("grid (roughness >= resolved), specular + diffuse");
    } else {
        measures = {"spheres, specular + diffuse", "spheres, specular only", "grid (roughness >= resolved), specular + diffuse", "grid, specular only"};
    }
    const std::vector<double> metals = a.benchScenes ? std::vector<double>{1.0} : std::vector<double>{1.0, 0.0};
    std::vector<EnvironmentRow> rows;
    BinsByEnvironment bins;
    for (const auto& [spec, set] : environmentList(a.sets, a.envs)) {
        const auto te = Clock::now();
        EnvCase env = loadCase(spec, set, a.width, true, a.bakes);
        if (a.lights) splitShadingLightsOf(env, a.bakes);
        EnvironmentRow row{env.name, set, std::vector<std::vector<double>>(ms.size())};
        std::vector<Errors> spheres(ms.size()), gridErr;
        for (double metallic : metals)
            for (double r : roughnesses) {
                std::vector<Pixel> px = sphere;
                for (Pixel& p : px) p.roughness = r, p.metallic = metallic;
                std::vector<Errors> one;
                evaluatePixels(env, px, ms, a, one);
                for (std::size_t m = 0; m < ms.size(); ++m) {
                    spheres[m].total.insert(spheres[m].total.end(), one[m].total.begin(), one[m].total.end());
                    spheres[m].specular.insert(spheres[m].specular.end(), one[m].specular.begin(), one[m].specular.end());
                    if (metallic > 0.5) addBins(bins[env.name], ms.size(), m, one[m]);
                    if (a.benchScenes) row.values[m].push_back(rmse(one[m].total));
                    if (csv)
                        csv << env.name << ',' << set << ",sphere," << (metallic > 0.5 ? "copper" : "dielectric") << ',' << r << ',' << ms[m].name
                            << ',' << rmse(one[m].total) << ',' << rmse(one[m].specular) << ',' << one[m].total.size() << '\n';
                }
            }
        evaluatePixels(env, grid, ms, a, gridErr);
        for (std::size_t m = 0; m < ms.size(); ++m) {
            if (a.benchScenes) row.values[m].push_back(rmse(gridErr[m].total));
            else row.values[m] = {rmse(spheres[m].total), rmse(spheres[m].specular), rmse(gridErr[m].total), rmse(gridErr[m].specular)};
            if (csv)
                csv << env.name << ',' << set << ",grid,all,all," << ms[m].name << ',' << rmse(gridErr[m].total) << ',' << rmse(gridErr[m].specular)
                    << ',' << gridErr[m].total.size() << '\n';
        }
        rows.push_back(row);
        std::fprintf(stderr, "%-20s %6.1f s\n", env.name.c_str(), secondsSince(te));
    }

    std::vector<std::string> names;
    for (const Method& m : ms) names.push_back(m.name);
    printEvaluation(names, measures, rows, a.bins ? &bins : nullptr);
    std::fprintf(stderr, "eval took %.1f s\n", secondsSince(t0));
    return 0;
}

} // namespace iblab::accuracy
