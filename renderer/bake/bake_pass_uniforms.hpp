#pragma once
// The uniforms each bake shader declares, located once per program link (gl/uniform.hpp):
// internal to bake_passes.cpp, the programs' C++ side.
#include <glm/vec2.hpp>

#include "gl/shader_library.hpp"
#include "gl/uniform.hpp"

namespace iblab::bake::detail {

struct DownsampleUniforms {
    explicit DownsampleUniforms(const gl::ShaderProgram& p) : sourceSize(p, "uSourceSize"), targetSize(p, "uTargetSize") {}
    gl::Uniform<glm::ivec2> sourceSize;
    gl::Uniform<glm::ivec2> targetSize;
};

// bake/cube_texel.glsl's, for every pass that writes a slice of a cube.
struct CubeSliceUniforms {
    explicit CubeSliceUniforms(const gl::ShaderProgram& p)
        : firstFace(p, "uFirstFace"), faceSize(p, "uFaceSize"), columnOffset(p, "uColumnOffset"), rowOffset(p, "uRowOffset"), rowCount(p, "uRowCount"),
          storeMax(p, "uStoreMax"), output(p, "uOutput")
    {
    }
    gl::Uniform<int> firstFace;
    gl::Uniform<int> faceSize;
    gl::Uniform<int> columnOffset; // 0 but for a dispatch of one tile (BakePasses::dispatchExactTiles)
    gl::Uniform<int> rowOffset;
    gl::Uniform<int> rowCount;
    gl::Uniform<float> storeMax;
    gl::Uniform<int> output;
};

struct EquirectToCubeUniforms {
    explicit EquirectToCubeUniforms(const gl::ShaderProgram& p) : equirect(p, "uEquirect") {}
    gl::Uniform<int> equirect;
};

struct Sh9ProjectUniforms {
    explicit Sh9ProjectUniforms(const gl::ShaderProgram& p) : equirect(p, "uEquirect"), rowsPerGroup(p, "uRowsPerGroup") {}
    gl::Uniform<int> equirect;
    gl::Uniform<int> rowsPerGroup;
};

// bake/source_read.glsl's.
struct SourceReadUniforms {
    explicit SourceReadUniforms(const gl::ShaderProgram& p)
        : environment(p, "uEnvironment"), mipFiltering(p, "uMipFiltering"), sourceFaceSize(p, "uSourceFaceSize"),
          exactTexelSolidAngle(p, "uExactTexelSolidAngle"), maxSourceLod(p, "uMaxSourceLod")
    {
    }
    gl::Uniform<int> environment;
    gl::Uniform<int> mipFiltering;
    gl::Uniform<float> sourceFaceSize;
    gl::Uniform<int> exactTexelSolidAngle;
    gl::Uniform<float> maxSourceLod;
};

struct RiemannUniforms {
    explicit RiemannUniforms(const gl::ShaderProgram& p) : phiSteps(p, "uPhiSteps"), thetaSteps(p, "uThetaSteps"), mipBias(p, "uMipBias") {}
    gl::Uniform<int> phiSteps;
    gl::Uniform<int> thetaSteps;
    gl::Uniform<float> mipBias;
};

struct MomentsUniforms {
    explicit MomentsUniforms(const gl::ShaderProgram& p) : groupCount(p, "uGroupCount") {}
    gl::Uniform<int> groupCount;
};

struct PrefilterUniforms {
    explicit PrefilterUniforms(const gl::ShaderProgram& p)
        : roughness(p, "uRoughness"), weightSum(p, "uWeightSum"), mirrorCopy(p, "uMirrorCopy"), copyLod(p, "uCopyLod"),
          brightCount(p, "uBrightCount"), alpha2(p, "uAlpha2"), brightScale(p, "uBrightScale"), nearCos(p, "uNearCos"), exactCount(p, "uExactCount"),
          refineCount(p, "uRefineCount"), refineSpread(p, "uRefineSpread"), refineWeightSum(p, "uRefineWeightSum"), refineError(p, "uRefineError"),
          tileLightsPerEdge(p, "uTileLightsPerEdge")
    {
    }
    gl::Uniform<float> roughness;
    gl::Uniform<float> weightSum;
    gl::Uniform<int> mirrorCopy;
    gl::Uniform<float> copyLod;
    gl::Uniform<int> brightCount; // the four absent (-1) in a program without bright texels
    gl::Uniform<float> alpha2;
    gl::Uniform<float> brightScale;
    gl::Uniform<float> nearCos;
    gl::Uniform<int> exactCount; // texels of the base's mip summed exactly; 0: the base is sampled
    gl::Uniform<int> refineCount; // the table's second set (after uSampleCount entries); 0: none
    gl::Uniform<float> refineSpread;
    gl::Uniform<float> refineWeightSum;
    gl::Uniform<float> refineError;
    gl::Uniform<int> tileLightsPerEdge; // mips 1 and 2: tiles per face edge of their lights' lists (binding 3); 0: none
};

struct SamplePrefilteredUniforms {
    explicit SamplePrefilteredUniforms(const gl::ShaderProgram& p) : count(p, "uCount"), prefiltered(p, "uPrefiltered"), levels(p, "uLevels"), layout(p, "uLayout") {}
    gl::Uniform<int> count;
    gl::Uniform<int> prefiltered;
    gl::Uniform<float> levels;
    gl::Uniform<int> layout;
};

struct BrdfLutUniforms {
    explicit BrdfLutUniforms(const gl::ShaderProgram& p)
        : size(p, "uSize"), sampleCount(p, "uSampleCount"), geometry(p, "uGeometry"), rowOffset(p, "uRowOffset"), rowCount(p, "uRowCount"), lut(p, "uLut")
    {
    }
    gl::Uniform<int> size;
    gl::Uniform<int> sampleCount;
    gl::Uniform<int> geometry;
    gl::Uniform<int> rowOffset;
    gl::Uniform<int> rowCount;
    gl::Uniform<int> lut;
};

// bake/clamp_luminance.comp's.
struct ClampLuminanceUniforms {
    explicit ClampLuminanceUniforms(const gl::ShaderProgram& p)
        : size(p, "uSize"), step(p, "uStep"), thresholds(p, "uThresholds"), targets(p, "uTargets")
    {
    }
    gl::Uniform<int> size;
    gl::Uniform<int> step;
    gl::Uniform<glm::vec2> thresholds;
    gl::Uniform<int> targets;
};

// bake/clamp_near_lights.comp's.
struct ClampNearLightsUniforms {
    explicit ClampNearLightsUniforms(const gl::ShaderProgram& p)
        : count(p, "uCount"), step(p, "uStep"), sourceSize(p, "uSourceSize"), thresholds(p, "uThresholds"), targets(p, "uTargets"),
          equirect(p, "uEquirect")
    {
    }
    gl::Uniform<int> count;
    gl::Uniform<int> step;
    gl::Uniform<int> sourceSize;
    gl::Uniform<glm::vec2> thresholds;
    gl::Uniform<int> targets;
    gl::Uniform<int> equirect;
};

} // namespace iblab::bake::detail
