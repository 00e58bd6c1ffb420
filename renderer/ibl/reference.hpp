#pragma once
// Exact references over a discretised environment: the integrals the GPU bakes and the
// split-sum approximate, evaluated by summing over EVERY texel of an equirect image with the
// texel's exact solid angle (equirect.hpp) and double accumulation. They are exact for the
// environment "one constant radiance per texel, seen in the texel-centre direction", so the
// only error against the continuous integral is the midpoint rule inside each texel; that
// error is small when the integrand's lobe spans many texels (roughness well above the
// texel's angular size) and is the caller's to budget for.
//
// Cost is O(texels) per query direction. Large images are summed by several threads over
// bands of rows (partial sums combined in a fixed order, so results do not depend on
// scheduling); for many queries on a big environment, downsample it first.
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/brdf.hpp"
#include "ibl/image.hpp"

namespace iblab {

// Diffuse irradiance E(n) = integral L(w) max(0, n.w) dOmega. n must be unit length.
glm::dvec3 referenceIrradiance(const ImageRGB32F& env, glm::dvec3 n);

// Z(alpha) = integral of D(h) max(0, n.l) dOmega_l over the sphere, with v = n and h the
// half vector of n and l (GGX, alpha = roughness^2): what the exact sum divides its weights
// D(h) max(0, n.l) dOmega by, as the reference divides by the same integral summed over its
// texels. (The sampled part divides by its own sum of n.l, which estimates the same lobe.)
double ggxPrefilterNormalization(double roughness);

// What LearnOpenGL's GGX prefilter converges to with N = V = R, as the sample count -> inf:
//   sum_w L(w) D(h) max(0, n.w) dOmega / sum_w D(h) max(0, n.w) dOmega,  h = normalize(n + w),
// alpha = roughness^2. At roughness 0 the lobe is a delta: returns the bilinear lookup at n.
// (Derivation in reference.cpp.)
glm::dvec3 referencePrefilteredRadiance(const ImageRGB32F& env, glm::dvec3 n, double roughness);

// The prefiltered-radiance and irradiance references above for many directions against one
// environment (the ~1500 directions `iblab bake --json` measures a bake at). Both integrands
// depend on the texel direction w only through c = n.w: the prefilter's weight D(h) (n.w)
// with h = normalize(n + w) has (n.h)^2 = (1 + c) / 2, and irradiance's is max(0, c). So the
// texel directions are computed once per environment instead of once per query, and each
// (query, texel) pair is a dot product and a few flops, in lanes the compiler vectorises.
// The single-query functions above are this class with one query, so there is one
// definition of each sum; a row's sum is formed the same way whatever the batch and the
// threads, and rows are added in order, so results do not depend on either.
class ZonalReference {
public:
    // Throws std::invalid_argument on an empty environment or non-finite radiance.
    explicit ZonalReference(const ImageRGB32F& env);

    struct PrefilterQuery {
        glm::dvec3 direction{0.0, 1.0, 0.0}; // unit length
        double roughness = 0.0;
    };
    std::vector<glm::dvec3> prefilteredRadiance(std::span<const PrefilterQuery> queries) const;
    std::vector<glm::dvec3> irradiance(std::span<const glm::dvec3> normals) const;
    int width() const { return env_.width; }

    static constexpr int kLanes = 4; // texels summed at once, in vector lanes

    struct RowSums {
        double r = 0.0, g = 0.0, b = 0.0, weight = 0.0; // per row, before the row's solid angle
    };

private:
    enum class Kernel { Prefilter, Irradiance };
    struct Query {
        glm::dvec3 direction;
        double alphaSquared = 0.0; // Prefilter only
    };
    std::vector<RowSums> sum(Kernel kernel, std::span<const Query> queries) const;
    RowSums sumRow(Kernel kernel, const Query& query, int row) const;

    ImageRGB32F env_;
    std::size_t rowStride_ = 0; // width rounded up to whole vector lanes
    // Per texel, row-major, one array per component so that rows stream into vector lanes.
    std::vector<double> dirX_, dirY_, dirZ_;
    std::vector<float> red_, green_, blue_;
    // Per row: its texels' solid angle, and bounds on their directions that let a query
    // skip a row where every texel has n.w <= 0 (both kernels are 0 there).
    std::vector<double> rowSolidAngle_, rowMinY_, rowMaxY_, rowMaxHorizontal_;
};

// The full specular integral without the split-sum factorisation:
//   integral L(w) D(h) Vis(n.v, n.w) F(v.h) max(0, n.w) dOmega,  h = normalize(v + w),
// with Fresnel-Schlick of F0 (per channel) and the chosen geometry term. Returns outgoing
// radiance towards v (unit, pointing away from the surface). 0 if n.v <= 0.
glm::dvec3 referenceSpecular(const ImageRGB32F& env, glm::dvec3 n, glm::dvec3 v, double roughness,
                             glm::dvec3 F0, GeometryTerm term);

// Halves both dimensions (which must be even; throws std::invalid_argument otherwise). Each
// output texel is the solid-angle-weighted mean of its 2 x 2 parents: the two parent rows
// cover different solid angles, and weighting by them makes the output texel's radiance times
// its solid angle (which is exactly the sum of its parents') equal to the parents' total
// power. So integrals of L against slowly varying weights are preserved.
ImageRGB32F downsampleEquirect2x(const ImageRGB32F& env);

// Halves env with downsampleEquirect2x until it is at most maxWidth wide (or its
// dimensions stop being even): the environment a reference over many pixels sums over.
ImageRGB32F downsampleEquirectToWidth(const ImageRGB32F& env, int maxWidth);

// The smallest perceptual roughness whose specular lobe a sum over a width-texel-wide
// equirect resolves. The midpoint rule's error inside a texel grows with the integrand's
// curvature across it; the reflected GGX lobe's full width at half maximum is about 2.6
// alpha radians (from D's half-maximum at tan^2(theta_h) = (sqrt 2 - 1) alpha^2, doubled by
// the reflection), so with at least four texels of 2 pi / width across it,
//   alpha >= 1.5 * 2 pi / width,  roughness = sqrt(alpha).
// Below it the reference itself is not converged, and differences it reports there are
// partly its own. At it, a 64-wide map is within 2% of a 512-wide one even for lights one
// texel wide and 100x their surroundings (tests/cpu/reference_test.cpp).
double referenceMinResolvedRoughness(int width);

// env with every texel split into factor x factor, each the bilinear interpolation of env at
// its centre, wrapping in longitude as the GPU's sampler reads it (GL_REPEAT), with the rows'
// weights made to keep each source texel's flux (fluxConservingRowBlends). A reference over a
// map too coarse for a lobe (referenceMinResolvedRoughness) sums this instead: the continuous
// map that the sky and the bake's environment cube show, resolved finely enough for the
// midpoint rule, with the light of the map's own texels.
ImageRGB32F upsampleEquirectBilinear(const ImageRGB32F& env, int factor);

// Row k of an upsample by `factor` of a map `height` rows high: (1 - weight) row `first` +
// weight row `second`. The bilinear read's rows (clamped at the poles, as GL_CLAMP_TO_EDGE
// reads them), whose weights give the polar rows more light than they hold: a ring's solid
// angle grows as sin(theta) from the pole, and the clamped read of the first row spreads it
// over finer rings that hold more, 12.5% more by 2 (9.4% by 4), and the rough mips of a 0.5
// degree sun at the zenith of a 512-wide map read 0.12 against the map's own texels. So from
// each pole towards the equator the weight of each source row on the finer rows that blend it
// with the next is scaled until its ring's flux is its own; the weights still sum to 1, so a
// uniform map stays uniform, and they move by about 0.1 / (r + 1) of a row at row r.
struct EquirectRowBlend {
    int first = 0;
    int second = 0;
    double weight = 0.0; // of `second`
};
std::vector<EquirectRowBlend> fluxConservingRowBlends(int height, int factor);

// The smallest power-of-two factor that upsampleEquirectBilinear needs for a reference over
// env to resolve roughness (referenceMinResolvedRoughness), at most maxFactor.
int referenceUpsampleFactor(int width, double roughness, int maxFactor);

} // namespace iblab
