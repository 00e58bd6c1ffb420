#pragma once
// Real-time approximations of the specular IBL integral, evaluated on the CPU with exactly
// the inputs a shader has (n, v, perceptual roughness, F0, the split-sum LUT's (A, B, A + B)
// and a prefiltered-radiance lookup), so that their error against the full integral
// (reference.hpp) can be measured without GL. The research behind them, the tables and the
// recommendation: docs/accuracy-study.md; the measuring tool: renderer/lab/accuracy_study/.
//
// Every method here is prefiltered radiance times the split-sum LUT's terms: the LUT stays
// as it is, and what changes is WHERE the prefiltered cube is read (the lookup direction),
// HOW WIDE a lobe is read (the lookup roughness, i.e. the lod) and, for the two-read
// methods, how the reads combine: mixed with weights that sum to 1 and multiplied by
// (F0 A + B), or (the recommended Fresnel split) one read multiplying F0 A and the other B.
// A uniform environment reads the same radiance everywhere, so every method returns exactly
// the split sum's value there: none adds or removes energy in the white furnace.
//
// The per-pixel formulas are written once in assets/shaders/common/specular_lobe.glsl (the
// common subset of GLSL and C++, included below), so a shader can include them unchanged.
#include <array>
#include <functional>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/prefilter_lod.hpp"
#include "ibl/brdf.hpp"
#include "ibl/glsl_shared.hpp"
#include "ibl/image.hpp"
#include "ibl/shading_lights.hpp"

namespace iblab::shared {
#include "common/specular_lobe.glsl"
}

namespace iblab {

// What a fragment shader has for one surface point.
struct SpecularShadingInputs {
    glm::dvec3 n{0.0, 0.0, 1.0}; // unit normal
    glm::dvec3 v{0.0, 0.0, 1.0}; // unit, towards the viewer
    double roughness = 0.5;      // perceptual; alpha = roughness^2
    glm::dvec3 F0{0.04};
    glm::dvec3 lut{1.0, 0.0, 1.0}; // (A, B, A + B) of the split-sum LUT at (n.v, roughness)
};

// The prefiltered cube as a shader reads it: radiance around `direction` (need not be
// unit length) for perceptual `roughness` (the caller maps it to a lod, as
// prefilterMipFromRoughness does on the GPU).
using PrefilteredLookup = std::function<glm::dvec3(glm::dvec3 direction, double roughness)>;

// A fitted lobe: per (n.v, roughness) cell, one or two reads of the prefiltered cube, tap k at
// direction normalize(mix(R, N, t_k)) and roughness r_k. Stored as one RGBA texel per cell,
// as a GPU texture would hold it (specular_lobe.glsl decodes it); `taps` is the layout:
//   1: (t, r_eff, -, -)                 one read
//   2: (t_0, t_1, r_eff, w_1)           sum_k w_k read_k, w_0 = 1 - w_1
//   3: (t_A, r_A, t_B, r_B)             Fresnel split: F0 A read_A + B read_B
//   4: layout 3's texel, and in a second plane (t_A2, r_A2, w_A2, -): F0 A ((1 - w_A2) read_A
//      + w_A2 read_A2) + B read_B (specular_lobe.glsl)
// Axes as the split-sum LUT's (brdf_lut.hpp): x = n.v, y = perceptual roughness, texel
// centres at (i + 0.5) / size, bilinear with clamp to edge; the planes stacked along y, each
// clamped to its own edge (lobeFitPlaneY).
struct LobeFitTable {
    int taps = 1; // the layout
    int nvSize = 0;
    int roughnessSize = 0;
    // Rows below it were not fitted and keep the split sum's read at R (accuracy_study fit
    // --min-roughness), so the step up to the first fitted row is by design.
    double minFittedRoughness = 0.0;
    std::vector<glm::vec4> cells; // [(plane * roughnessSize + row) * nvSize + col], row = roughness
    int planes() const { return shared::lobeFitPlanes(taps); }
    bool empty() const { return cells.empty(); }
    glm::dvec4 sample(double NdotV, double roughness, int plane = 0) const; // bilinear, clamp to edge
    std::size_t index(int col, int row, int plane) const
    {
        return (std::size_t(plane) * std::size_t(roughnessSize) + std::size_t(row)) * std::size_t(nvSize) + std::size_t(col);
    }
    glm::vec4& at(int col, int row, int plane = 0) { return cells[index(col, row, plane)]; }
    const glm::vec4& at(int col, int row, int plane = 0) const { return cells[index(col, row, plane)]; }
};

// The table refitted by `accuracy_study fit` on the 8 bundled maps (specular_lobe_fit.inc).
const LobeFitTable& fittedLobeTable();

enum class SpecularMethod {
    SplitSum,          // prefiltered(R, r) (F0 A + B): today's default (ibl_lighting.glsl)
    FrostbiteDominant, // read at Frostbite's dominant direction, alpha convention
    FrostbitePerceptual, // the same formula fed perceptual roughness (as e.g. Blender's EEVEE does)
    FilamentDominant,  // read at mix(R, N, alpha^2) (Filament's getReflectedVector)
    FittedLobe,        // read per the fitted table (fittedLobeTable(): the Fresnel split, layout 3)
};
std::string_view specularMethodName(SpecularMethod method);

// The specular radiance of one method: sum_k w_k prefiltered(d_k, r_k) (F0 A + B), or for
// the Fresnel-split layout F0 A prefiltered(d_A, r_A) + B prefiltered(d_B, r_B). `fit` is
// used by FittedLobe only (fittedLobeTable() when null).
glm::dvec3 shadeSpecularApproximation(SpecularMethod method, const SpecularShadingInputs& in, const PrefilteredLookup& prefiltered,
                                      const LobeFitTable* fit = nullptr);

// The fitted lobe's taps for one pixel (directions unit length), from a table texel. For the
// Fresnel split, tap 0 multiplies F0 A and tap 1 multiplies B, both with weight 1; layout 4
// adds tap 2, a second F0 A read, the two A weights summing to 1.
struct LobeTap {
    glm::dvec3 direction{0.0};
    double roughness = 0.0;
    double weight = 0.0;
    bool multipliesB = false; // Fresnel split: this read is B's, not F0 A's
};
std::vector<LobeTap> fittedLobeTaps(const LobeFitTable& fit, glm::dvec3 n, glm::dvec3 v, double roughness);

// ---- CPU emulation of the GPU's prefiltered cube ---------------------------------------
// The bake's chain (bake_settings.hpp defaultPreset): `levels` mips, mip m holding the
// N = V = R prefilter at prefilterRoughnessFromMip(m) (Filament's quadratic layout by
// default), read with trilinear filtering at lod prefilterMipFromRoughness(roughness).
// Each mip here is an equirect holding the EXACT prefilter (referencePrefilteredRadiance's
// sum over every texel of `env`) at its texel centres, read bilinearly; mip 0 is `env`
// itself (the mirror). So the only differences from a converged GPU bake are the storage
// (equirect instead of cube faces) and its resolution; the discrete roughness levels, and
// the blend between two of them that an in-between roughness gets, are the GPU's.
class PrefilteredChain {
public:
    PrefilteredChain() = default;
    // mipWidths[m - 1]: width of the equirect that holds mip m (m >= 1); defaults to
    // min(env.width, 256 >> (m - 1)) with a floor of 32.
    explicit PrefilteredChain(const ImageRGB32F& env, int levels = 6, int layout = PREFILTER_LAYOUT_QUADRATIC);
    // A chain from mips computed earlier (mips[0] = the environment), e.g. read from a cache.
    static PrefilteredChain fromMips(std::vector<ImageRGB32F> mips, int layout);
    glm::dvec3 lookupLod(glm::dvec3 direction, double lod) const;
    glm::dvec3 lookup(glm::dvec3 direction, double roughness) const;
    int levels() const { return int(mips_.size()); }
    int layout() const { return layout_; }
    const ImageRGB32F& mip(int m) const { return mips_[std::size_t(m)]; }

private:
    std::vector<ImageRGB32F> mips_;
    int layout_ = PREFILTER_LAYOUT_QUADRATIC;
};

// The exact N = V = R prefilter of `env` at `roughness`, evaluated at the texel centres of
// a width x width/2 equirect (threads over rows). Texel for texel the same sum as
// referencePrefilteredRadiance.
ImageRGB32F prefilterEquirect(const ImageRGB32F& env, double roughness, int width);

// ---- The full integral, fast -----------------------------------------------------------
// referenceSpecular and referenceIrradiance's sums for many pixels: the texel directions,
// solid angles and radiances are tabulated once, and one pass returns the two Fresnel parts
//   Ia = integral L D Vis (1 - Fc) (n.l) dOmega,  Ib = integral L D Vis Fc (n.l) dOmega,
// so the specular radiance for any F0 is F0 Ia + Ib (referenceSpecular is linear in F0),
// and the irradiance E. As the reference renderer (reference_integral.comp): n.v clamped
// to 1e-4 and alpha to 1e-3. Single-threaded; callers parallelise over pixels.
struct FullIntegral {
    glm::dvec3 Ia{0.0};
    glm::dvec3 Ib{0.0};
    glm::dvec3 irradiance{0.0};
    glm::dvec3 specular(glm::dvec3 F0) const { return F0 * Ia + Ib; }
};

class ReferenceSums {
public:
    explicit ReferenceSums(const ImageRGB32F& env);
    // The same sums over point lights (shading_lights.hpp), each its flux at its direction.
    explicit ReferenceSums(const std::vector<ShadingLight>& lights);
    FullIntegral evaluate(glm::dvec3 n, glm::dvec3 v, double roughness, GeometryTerm term, bool withIrradiance = true) const;
    int width() const { return width_; }

private:
    struct Texel {
        glm::dvec3 direction;
        glm::dvec3 radianceTimesSolidAngle;
    };
    std::vector<Texel> texels_;
    int width_ = 0;
};

} // namespace iblab
