#pragma once
// The GPU passes of a bake, each a compute dispatch over a slice of its output (a band of
// rows of one face of one mip) so that a job can cut the work into short steps. Each pass
// sets the GL state it needs (program, texture and image units, seamless cube filtering)
// and leaves those bindings as it found them (seamless filtering) or cleared (units).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "bake/bake_settings.hpp"
#include "bake/baked_texture.hpp"
#include "gl/shader_library.hpp"
#include "ibl/image.hpp"
#include "ibl/sh.hpp"

namespace iblab::bake {

// A band of rows of one face of one mip.
struct CubeSlice {
    int level = 0;
    int face = 0;
    int firstRow = 0;
    int rowCount = 0;
};

// Largest finite value the texture's format stores (half: 65504).
float storeMax(GLenum internalFormat);

class BakePasses {
public:
    explicit BakePasses(gl::ShaderLibrary& shaders) : shaders_(shaders) {}

    // Compiles every program the passes use (Mesa caches compiled shaders on disk: the
    // first run on a machine is cold, later ones warm).
    void compileAll();

    // The equirect as a mip-mapped RGBA32F 2D texture (REPEAT in s, CLAMP_TO_EDGE in t).
    gl::Texture uploadEquirect(const ImageRGB32F& image);
    void equirectToCube(GLuint equirect, const BakedTexture& cube, const CubeSlice& slice);
    // Levels 1.. from level 0 by 2x2 box averages (downsample.comp), per face for cubes.
    void generateMips(const BakedTexture& texture);

    // Radiance L_lm on the GPU: float sums over groups of rows, each row weighted by its
    // exact solid angle, the groups added in double on the host (see sh9_project.comp).
    SH9Color projectSh9(GLuint equirect, int width, int height);

    // exactTexelSolidAngle: see BakeSettings.
    void irradianceRiemann(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                           const RiemannIrradianceSettings& settings, bool exactTexelSolidAngle);
    void irradianceImportance(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                              const ImportanceIrradianceSettings& settings, bool exactTexelSolidAngle);
    void prefilter(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice, const PrefilterSettings& settings,
                   bool exactTexelSolidAngle);
    // What shading reads for each query (xyz = direction, w = roughness): textureLod at the
    // layout's lod, seamless trilinear (sample_prefiltered.comp). For accuracy checks.
    std::vector<glm::vec3> samplePrefiltered(const BakedTexture& prefiltered, RoughnessLayout layout, const std::vector<glm::vec4>& queries);
    // Rows [firstRow, firstRow + rowCount) of the LUT.
    void brdfLut(const BakedTexture& out, int firstRow, int rowCount, int samples, GeometryTerm term);

    // Riemann grid steps for a sample delta (LearnOpenGL's loops, rounded to whole cells).
    static int riemannPhiSteps(float sampleDelta);
    static int riemannThetaSteps(float sampleDelta);

private:
    const gl::ShaderProgram& cubeProgram(const char* file);
    void downsampleChain(GLuint texture, GLenum target, GLenum internalFormat, int width, int height, int levels);
    void dispatchCube(const gl::ShaderProgram& program, const BakedTexture& out, const CubeSlice& slice) const;

    gl::ShaderLibrary& shaders_;
};

} // namespace iblab::bake
