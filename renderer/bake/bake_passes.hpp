#pragma once
// The GPU passes of a bake, each a compute dispatch over a slice of its output (a band of
// rows of one or more faces of one mip) so that a job can cut the work into short steps. Each pass
// sets the GL state it needs (program, texture and image units, seamless cube filtering)
// and leaves those bindings as it found them (seamless filtering) or cleared (units).
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "bake/bake_settings.hpp"
#include "bake/baked_texture.hpp"
#include "bake/bright_texels.hpp"
#include "gl/shader_library.hpp"
#include "ibl/image.hpp"
#include "ibl/sh.hpp"

namespace iblab::bake {

// A band of rows of faces [firstFace, firstFace + faceCount) of one mip.
struct CubeSlice {
    int level = 0;
    int firstFace = 0;
    int faceCount = 1;
    int firstRow = 0;
    int rowCount = 0;
};

// The groups of environment texels the moment irradiance sums over, in a uniform buffer
// of moment_texel.glsl's MomentTexel.
struct MomentTexels {
    gl::Buffer buffer;
    int groupsPerEdge = 0; // 6 groupsPerEdge^2 groups
};

// Largest finite value the texture's format stores (half: 65504).
float storeMax(GLenum internalFormat);

// Where a split's bases are resampled from the map clamped (BakePasses::clampedBases,
// near_lights.hpp).
struct NearLights {
    GLuint equirect = 0;                        // the map the environment was resampled from
    const std::vector<std::uint8_t>* marks = nullptr; // per level-0 texel of the environment: 1 near a bright map texel
};

class BakePasses {
public:
    // Sample tables of up to this many entries are read from a uniform block, larger ones
    // from a storage buffer (source_samples.glsl says why); 4096 entries fill the 64 KB block
    // that llvmpipe and the desktop drivers allow.
    static constexpr int kUniformTableEntries = 4096;

    // maxUniformTableEntries: kUniformTableEntries, or fewer where the driver's uniform
    // blocks are smaller; 0 keeps every table in a storage buffer (tests compare the two).
    explicit BakePasses(gl::ShaderLibrary& shaders, int maxUniformTableEntries = kUniformTableEntries)
        : shaders_(shaders), maxUniformTableEntries_(maxUniformTableEntries)
    {
    }

    // Compiles the programs a bake with these settings runs (Mesa caches compiled shaders on
    // disk: the first run on a machine is cold, later ones warm), the BRDF LUT's only with
    // `lut` (a bake compiles it when it misses the LUT cache), the 2D downsample only for an
    // equirect of more than one level. Each program compiled costs a few milliseconds even
    // when cached, so a bake compiles no program it does not run. cubeFormat: the cubes' format
    // where it is not the settings' precision (BakeJob::cubeFormat); 0: the settings'.
    void compileFor(const BakeSettings& settings, int equirectLevels, bool lut, GLenum cubeFormat = 0);

    // The entries of the uniform block that holds a level's exact-sum table
    // (prefilter_ggx.comp's EXACT_CAPACITY; the table is padded to it), or 0 when the table
    // needs a storage buffer.
    int exactTableCapacity(const PrefilterSettings& settings) const { return sampleTableCapacity(2 * settings.exactSumTexels); }

    // The equirect levels equirectToCube reads for a cube of faceSize texels per edge: its
    // footprint's minor axis is at most a face-centre texel, 2/f rad, against an equirect
    // row's pi/H, so its lod is at most log2(2H / (pi f)); levels are built up to that lod
    // rounded to the nearest (a footprint of under 1.5 texels is read bilinearly at lod 0).
    static int equirectLevelsForCube(int width, int height, int faceSize);
    // The equirect as an RGBA32F 2D texture (RGB32F when it has one level; REPEAT in s,
    // CLAMP_TO_EDGE in t) with `levels` mips (0: the full chain).
    gl::Texture uploadEquirect(const ImageRGB32F& image, int levels = 0);
    // The same in parts, for a job that spreads a large map's upload over several steps: the
    // texture, then bands of level 0's rows, then the mips from level 0.
    gl::Texture createEquirect(const ImageRGB32F& image, int levels = 0);
    void uploadEquirectRows(const gl::Texture& texture, const ImageRGB32F& image, int levels, int firstRow, int rowCount);
    void finishEquirect(const gl::Texture& texture, const ImageRGB32F& image, int levels = 0);
    void equirectToCube(GLuint equirect, const BakedTexture& cube, const CubeSlice& slice);
    // Levels 1.. from level 0 by 2x2 box averages (downsample.comp), per face for cubes.
    void generateMips(const BakedTexture& texture);
    // The bright-texel split's bases (bright_texels.hpp), one per threshold (at most 2): level
    // 0 of `environment` with each texel's luminance clamped to the threshold, box-averaged
    // into level 0 of the base (the same format, a face a power of two smaller or equal;
    // clamp_luminance.comp, which reads each texel once for both, and a 2 x 2 block too dim
    // to hold a texel above either threshold as its average from the environment's level 1,
    // which must be built), then each base's mips. Bases of two sizes (mip 1's from a finer
    // level than the rougher mips') take one pass each. With nearLights, the texels within
    // reach of a map texel above a threshold are the environment pass's filter applied to the
    // map clamped instead (clamp_near_lights.comp, after the clamp pass).
    void clampedBases(const BakedTexture& environment, const std::vector<BakedTexture>& bases, const std::vector<float>& thresholds,
                      const NearLights& nearLights = {});

    // Radiance L_lm on the GPU: float sums over groups of rows, each row weighted by its
    // exact solid angle, the groups added in double on the host (see sh9_project.comp).
    SH9Color projectSh9(GLuint equirect, int width, int height);

    // exactTexelSolidAngle: see BakeSettings.
    void irradianceRiemann(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                           const RiemannIrradianceSettings& settings, bool exactTexelSolidAngle);
    void irradianceImportance(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                              const ImportanceIrradianceSettings& settings, bool exactTexelSolidAngle);
    // The map's texels in groups (the texels of a groupsPerEdge^2 cube), each with its flux
    // and moments (equirect_moments.hpp), as the uniform block irradianceMoments reads.
    MomentTexels uploadIrradianceMoments(const std::vector<glm::vec4>& texels, int groupsPerEdge);
    // Irradiance from those groups (irradiance_moments.comp).
    void irradianceMoments(const MomentTexels& groups, const BakedTexture& out, const CubeSlice& slice);
    // bright (bright_texels.hpp; null: none): the mips with roughness > 0 sample its base
    // instead of the environment and add its lights exactly.
    void prefilter(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice, const PrefilterSettings& settings,
                   bool exactTexelSolidAngle, const PrefilterBrightTexels* bright = nullptr);
    // What shading reads for each query (xyz = direction, w = roughness): textureLod at the
    // layout's lod, seamless trilinear (sample_prefiltered.comp). For accuracy checks.
    std::vector<glm::vec3> samplePrefiltered(const BakedTexture& prefiltered, RoughnessLayout layout, const std::vector<glm::vec4>& queries);
    // Rows [firstRow, firstRow + rowCount) of the LUT.
    void brdfLut(const BakedTexture& out, int firstRow, int rowCount, int samples, GeometryTerm term);

    // The environment level that the prefilter's `level` is a texel copy of: the mirror
    // level (roughness 0 with mirrorCopy), where the environment has a level of its size and
    // format. nullopt: the level is filtered.
    static std::optional<int> mirrorSourceLevel(const BakedTexture& environment, const BakedTexture& prefiltered, int level,
                                                const PrefilterSettings& settings);

    // Riemann grid steps for a sample delta (LearnOpenGL's loops, rounded to whole cells).
    static int riemannPhiSteps(float sampleDelta);
    static int riemannThetaSteps(float sampleDelta);

private:
    const gl::ShaderProgram& cubeProgram(const char* file);
    const gl::ShaderProgram& momentsProgram(int groupsPerEdge);
    // The uniform block's entries (source_samples.glsl's SAMPLE_TABLE_CAPACITY) for a table of
    // sampleCount entries, or 0 when it needs a storage buffer.
    int sampleTableCapacity(int sampleCount) const;
    const gl::ShaderProgram& sampleTableProgram(const char* file, int capacity);
    const gl::ShaderProgram& prefilterProgram(int capacity, int brightCapacity, int exactCapacity);
    // One clamp_luminance.comp pass into `first` (and `second`, of the same size, where
    // targets is 2).
    void clampPass(const BakedTexture& environment, const BakedTexture& first, const BakedTexture& second, glm::vec2 thresholds,
                   int targets);
    // clamp_near_lights.comp over the base texels under nearLights' marks, after clampPass.
    void nearLightsPass(const BakedTexture& environment, const BakedTexture& first, const BakedTexture& second, glm::vec2 thresholds,
                        int targets, const NearLights& nearLights);
    // The prefilter's mirror level as a texel copy (mirrorSourceLevel); false: nothing done.
    bool copyMirrorLevel(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                         const PrefilterSettings& settings);
    void downsampleChain(GLuint texture, GLenum target, GLenum internalFormat, int width, int height, int levels);
    // A cube pass's output mip bound and its program in use, and the barrier after it.
    void bindCubeOutput(const gl::ShaderProgram& program, const BakedTexture& out, int level) const;
    void finishCubePass() const;
    void dispatchCube(const gl::ShaderProgram& program, const BakedTexture& out, const CubeSlice& slice) const;
    void dispatchExactTiles(const gl::ShaderProgram& program, const BakedTexture& out, const CubeSlice& slice,
                            const PrefilterBrightTexels::Level& level, int capacity) const;

    gl::ShaderLibrary& shaders_;
    int maxUniformTableEntries_;
};

} // namespace iblab::bake
