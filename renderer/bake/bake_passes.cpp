#include "bake/bake_passes.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include <Imath/half.h>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "ibl/prefilter_lod.hpp"
#include "bake/bright_texels_block.hpp"
#include "bake/exact_tiles.hpp"
#include "bake/near_lights.hpp"
#include "bake/source_samples.hpp"
#include "io/error.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/reference.hpp"
#include "gl/seamless_cube_scope.hpp"
#include "gl/uniform.hpp"
#include "bake/bake_pass_uniforms.hpp"

namespace iblab::bake {
namespace {

using namespace detail;

constexpr const char* kEquirectToCube = "bake/equirect_to_cube.comp";
constexpr const char* kSh9Project = "bake/sh9_project.comp";
constexpr const char* kIrradianceRiemann = "bake/irradiance_riemann.comp";
constexpr const char* kIrradianceImportance = "bake/irradiance_importance.comp";
constexpr const char* kIrradianceMoments = "bake/irradiance_moments.comp";
// The size of moment_texel.glsl's MomentTexel: 6 vec4.
constexpr GLsizeiptr kMomentTexelBytes = 6 * 4 * sizeof(float);
constexpr const char* kPrefilter = "bake/prefilter_ggx.comp";
constexpr const char* kBrdfLut = "bake/brdf_lut.comp";
constexpr const char* kDownsample = "bake/downsample.comp";
constexpr const char* kClampLuminance = "bake/clamp_luminance.comp";
constexpr const char* kClampNearLights = "bake/clamp_near_lights.comp";
constexpr const char* kSamplePrefiltered = "bake/sample_prefiltered.comp";

// Clears the units a pass used, so that a later pass cannot read or write through a
// binding it did not make.
void clearPassBindings()
{
    glUseProgram(0);
    glBindTextureUnit(1, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, 0);
}

GLuint groupsFor(int n) { return GLuint((n + 7) / 8); }

} // namespace

float storeMax(GLenum internalFormat) { return internalFormat == GL_RGBA16F ? float(HALF_MAX) : 3.4028234e38f; }

int BakePasses::riemannPhiSteps(float sampleDelta)
{
    return std::max(1, int(std::lround(2.0 * kPi / double(sampleDelta))));
}

int BakePasses::riemannThetaSteps(float sampleDelta)
{
    return std::max(1, int(std::lround(0.5 * kPi / double(sampleDelta))));
}

void BakePasses::compileFor(const BakeSettings& settings, int equirectLevels, bool lut, GLenum cubeFormat)
{
    const GLenum format = cubeFormat != 0 ? cubeFormat : settings.precision == Precision::Half ? GL_RGBA16F : GL_RGBA32F;
    shaders_.program({kEquirectToCube});
    if (equirectLevels > 1)
        shaders_.program({kDownsample}, {{"CUBE", "0"}, {"FORMAT", imageFormatName(GL_RGBA32F)}});
    shaders_.program({kDownsample}, {{"CUBE", "1"}, {"FORMAT", imageFormatName(format)}});
    if (settings.prefilter.brightTexels > 0) {
        shaders_.program({kClampLuminance}, {{"FORMAT", imageFormatName(format)}});
        shaders_.program({kClampNearLights});
    }
    if (settings.sh.device == ShDevice::Gpu)
        shaders_.program({kSh9Project});
    switch (settings.irradiance) {
    case IrradianceMethod::None: break;
    case IrradianceMethod::Riemann: shaders_.program({kIrradianceRiemann}); break;
    case IrradianceMethod::Importance:
        sampleTableProgram(kIrradianceImportance, sampleTableCapacity(settings.importance.samples));
        break;
    case IrradianceMethod::Moments:
        momentsProgram(settings.moments.sourceFaceSize);
        break;
    }
    // The refined mips' tables hold their refined sets too where the split refines them (prefilter()).
    const int refinedSets = settings.prefilter.brightTexels > 0 ? std::max(1, settings.prefilter.refineFactor + 1) : 1;
    for (int level = 1; level < settings.prefilter.levels; ++level) {
        const bool split = prefilterMipRoughness(settings.prefilter, level) > 0.0f && settings.prefilter.brightTexels > 0;
        prefilterProgram(sampleTableCapacity(prefilterSamples(settings.prefilter, level) * (level <= kLastRefinedMip ? refinedSets : 1)),
                         split ? brightBlockCapacity(settings.prefilter) : 0, split ? exactTableCapacity(settings.prefilter) : 0);
    }
    if (lut)
        shaders_.program({kBrdfLut});
}

const gl::ShaderProgram& BakePasses::momentsProgram(int groupsPerEdge)
{
    return shaders_.program({kIrradianceMoments}, {{"GROUPS", std::to_string(6 * groupsPerEdge * groupsPerEdge)}});
}

const gl::ShaderProgram& BakePasses::cubeProgram(const char* file) { return shaders_.program({file}); }

int BakePasses::sampleTableCapacity(int sampleCount) const
{
    // GL_MAX_UNIFORM_BLOCK_SIZE is at least 16 KB (1024 entries); llvmpipe and the desktop
    // drivers allow 64 KB.
    GLint maxBlockBytes = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBlockBytes);
    const int capacity = std::min(maxUniformTableEntries_, int(maxBlockBytes / GLint(sizeof(glm::vec4))));
    return sampleCount <= capacity ? capacity : 0;
}

const gl::ShaderProgram& BakePasses::sampleTableProgram(const char* file, int capacity)
{
    return shaders_.program({file}, {{"SAMPLE_TABLE_CAPACITY", std::to_string(capacity)}});
}

const gl::ShaderProgram& BakePasses::prefilterProgram(int capacity, int brightCapacity, int exactCapacity)
{
    return shaders_.program({kPrefilter}, {{"SAMPLE_TABLE_CAPACITY", std::to_string(capacity)},
                                           {"BRIGHT_CAPACITY", std::to_string(brightCapacity)},
                                           {"EXACT_CAPACITY", std::to_string(exactCapacity)}});
}

void BakePasses::downsampleChain(GLuint texture, GLenum target, GLenum internalFormat, int width, int height, int levels)
{
    if (levels <= 1)
        return; // nor compile a program it would not run
    const bool cube = target == GL_TEXTURE_CUBE_MAP;
    const gl::ShaderProgram& program =
        shaders_.program({kDownsample}, {{"CUBE", cube ? "1" : "0"}, {"FORMAT", imageFormatName(internalFormat)}});
    const DownsampleUniforms& uniforms = program.uniforms<DownsampleUniforms>();
    glUseProgram(program.id());
    for (int level = 1; level < levels; ++level) {
        const glm::ivec2 source(std::max(width >> (level - 1), 1), std::max(height >> (level - 1), 1));
        const glm::ivec2 size(std::max(width >> level, 1), std::max(height >> level, 1));
        uniforms.sourceSize.set(source);
        uniforms.targetSize.set(size);
        glBindImageTexture(1, texture, level - 1, GL_TRUE, 0, GL_READ_ONLY, internalFormat);
        glBindImageTexture(0, texture, level, GL_TRUE, 0, GL_WRITE_ONLY, internalFormat);
        glDispatchCompute(groupsFor(size.x), groupsFor(size.y), cube ? 6 : 1);
        // The next level reads this one.
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, internalFormat);
    clearPassBindings();
}

void BakePasses::bindCubeOutput(const gl::ShaderProgram& program, const BakedTexture& out, int level) const
{
    const CubeSliceUniforms& uniforms = program.uniforms<CubeSliceUniforms>();
    uniforms.faceSize.set(out.levelSize(level));
    uniforms.columnOffset.set(0);
    uniforms.storeMax.set(storeMax(out.internalFormat));
    uniforms.output.set(0);
    // Layered: the shader addresses the face as the image's layer.
    glBindImageTexture(0, out.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, out.internalFormat);
    glUseProgram(program.id());
}

void BakePasses::finishCubePass() const
{
    // Later passes sample what this one wrote, or read it back, or build mips from it.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    clearPassBindings();
}

void BakePasses::dispatchCube(const gl::ShaderProgram& program, const BakedTexture& out, const CubeSlice& slice) const
{
    bindCubeOutput(program, out, slice.level);
    const CubeSliceUniforms& uniforms = program.uniforms<CubeSliceUniforms>();
    uniforms.firstFace.set(slice.firstFace);
    uniforms.rowOffset.set(slice.firstRow);
    uniforms.rowCount.set(slice.rowCount);
    glDispatchCompute(groupsFor(out.levelSize(slice.level)), groupsFor(slice.rowCount), GLuint(slice.faceCount));
    finishCubePass();
}

void BakePasses::equirectToCube(GLuint equirect, const BakedTexture& cube, const CubeSlice& slice)
{
    const gl::ShaderProgram& program = cubeProgram(kEquirectToCube);
    program.uniforms<EquirectToCubeUniforms>().equirect.set(1);
    glBindTextureUnit(1, equirect);
    dispatchCube(program, cube, slice);
}

void BakePasses::generateMips(const BakedTexture& texture)
{
    downsampleChain(texture.id(), texture.target, texture.internalFormat, texture.size, texture.size, texture.levels);
}

void BakePasses::clampPass(const BakedTexture& environment, const BakedTexture& first, const BakedTexture& second, glm::vec2 thresholds,
                           int targets)
{
    const gl::ShaderProgram& program = shaders_.program({kClampLuminance}, {{"FORMAT", imageFormatName(environment.internalFormat)}});
    const ClampLuminanceUniforms& uniforms = program.uniforms<ClampLuminanceUniforms>();
    glUseProgram(program.id());
    uniforms.size.set(first.size);
    uniforms.step.set(environment.size / first.size);
    uniforms.thresholds.set(thresholds);
    uniforms.targets.set(targets);
    glBindImageTexture(1, environment.id(), 0, GL_TRUE, 0, GL_READ_ONLY, environment.internalFormat);
    // Level 1 only serves a step of 2 or more, which needs the environment to have it.
    glBindImageTexture(3, environment.id(), environment.levels > 1 ? 1 : 0, GL_TRUE, 0, GL_READ_ONLY, environment.internalFormat);
    glBindImageTexture(0, first.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, first.internalFormat);
    glBindImageTexture(2, second.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, first.internalFormat);
    glDispatchCompute(groupsFor(first.size), groupsFor(first.size), 6);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, environment.internalFormat);
    glBindImageTexture(3, 0, 0, GL_FALSE, 0, GL_READ_ONLY, environment.internalFormat);
    glBindImageTexture(2, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, first.internalFormat);
    clearPassBindings();
}

void BakePasses::nearLightsPass(const BakedTexture& environment, const BakedTexture& first, const BakedTexture& second,
                                glm::vec2 thresholds, int targets, const NearLights& nearLights)
{
    if (nearLights.equirect == 0 || nearLights.marks == nullptr || nearLights.marks->empty())
        return;
    const int step = environment.size / first.size;
    const std::vector<glm::ivec4> texels = nearLightsBaseTexels(*nearLights.marks, environment.size, step);
    if (texels.empty())
        return;
    const gl::ShaderProgram& program = shaders_.program({kClampNearLights});
    const ClampNearLightsUniforms& uniforms = program.uniforms<ClampNearLightsUniforms>();
    glUseProgram(program.id());
    uniforms.count.set(int(texels.size()));
    uniforms.step.set(step);
    uniforms.sourceSize.set(environment.size);
    uniforms.thresholds.set(thresholds);
    uniforms.targets.set(targets);
    uniforms.equirect.set(1);
    const gl::Buffer list = gl::createBufferWith<glm::ivec4>(texels);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, list.id());
    glBindTextureUnit(1, nearLights.equirect);
    glBindImageTexture(0, first.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, first.internalFormat);
    glBindImageTexture(2, second.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, first.internalFormat);
    glDispatchCompute(GLuint((texels.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glBindImageTexture(2, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, first.internalFormat);
    clearPassBindings();
}

void BakePasses::clampedBases(const BakedTexture& environment, const std::vector<BakedTexture>& bases, const std::vector<float>& thresholds,
                              const NearLights& nearLights)
{
    if (bases.empty() || bases.size() > 2 || thresholds.size() != bases.size())
        throw Error("prefilter", "the bright-texel split builds one or two bases, each with its threshold");
    // Bases of one size from one read of each texel; of two sizes (mip 1's finer), one pass each.
    if (bases.front().size == bases.back().size) {
        const glm::vec2 both(thresholds.front(), thresholds.back());
        clampPass(environment, bases.front(), bases.back(), both, int(bases.size()));
        nearLightsPass(environment, bases.front(), bases.back(), both, int(bases.size()), nearLights);
    } else {
        for (std::size_t i = 0; i < bases.size(); ++i) {
            clampPass(environment, bases[i], bases[i], glm::vec2(thresholds[i]), 1);
            nearLightsPass(environment, bases[i], bases[i], glm::vec2(thresholds[i]), 1, nearLights);
        }
    }
    for (const BakedTexture& base : bases)
        generateMips(base);
}

SH9Color BakePasses::projectSh9(GLuint equirect, int width, int height)
{
    const gl::ShaderProgram& program = shaders_.program({kSh9Project});
    // 8 rows per group: 64 groups for a 1024 x 512 map, enough to keep llvmpipe's threads
    // busy, few enough that the reductions are cheap.
    constexpr int kRowsPerGroup = 8;
    const int groups = (height + kRowsPerGroup - 1) / kRowsPerGroup;
    std::vector<float> solidAngles(static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        solidAngles[std::size_t(y)] = float(equirectTexelSolidAngle(y, width, height));
    const gl::Buffer rowSolidAngles = gl::createBufferWith<float>(solidAngles);
    gl::Buffer groupSums = gl::createBuffer();
    const auto bytes = GLsizeiptr(std::size_t(groups) * kSh9Count * sizeof(glm::vec4));
    glNamedBufferStorage(groupSums.id(), bytes, nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, groupSums.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, rowSolidAngles.id());
    glBindTextureUnit(1, equirect);
    const Sh9ProjectUniforms& uniforms = program.uniforms<Sh9ProjectUniforms>();
    uniforms.equirect.set(1);
    uniforms.rowsPerGroup.set(kRowsPerGroup);
    glUseProgram(program.id());
    glDispatchCompute(GLuint(groups), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> sums(std::size_t(groups) * kSh9Count);
    glGetNamedBufferSubData(groupSums.id(), 0, bytes, sums.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    clearPassBindings();

    SH9Color sh;
    for (int g = 0; g < groups; ++g)
        for (int i = 0; i < kSh9Count; ++i)
            sh.c[std::size_t(i)] += glm::dvec3(glm::vec3(sums[std::size_t(g) * kSh9Count + std::size_t(i)]));
    return sh;
}

namespace {

// What every pass that reads the environment cube with PDF-based mip selection needs:
// the cube on unit 1 and the uniforms of bake/source_read.glsl.
void bindSource(const gl::ShaderProgram& program, const BakedTexture& environment, bool mipFiltering, bool exactTexelSolidAngle)
{
    const SourceReadUniforms& uniforms = program.uniforms<SourceReadUniforms>();
    uniforms.environment.set(1);
    uniforms.mipFiltering.set(mipFiltering ? 1 : 0);
    uniforms.sourceFaceSize.set(float(environment.size));
    uniforms.exactTexelSolidAngle.set(exactTexelSolidAngle ? 1 : 0);
    uniforms.maxSourceLod.set(float(environment.levels - 1));
    glBindTextureUnit(1, environment.id());
}

struct SampleTableUniforms {
    explicit SampleTableUniforms(const gl::ShaderProgram& p) : sampleCount(p, "uSampleCount") {}
    gl::Uniform<int> sampleCount;
};

// A pass's sample table (source_samples.glsl) on binding 0 of the kind `program` was built
// for (sampleTableDefines), for one dispatch. A uniform block is padded to its declared
// size: GL leaves reads undefined where the bound range is shorter than the block.
gl::Buffer bindSampleTable(const gl::ShaderProgram& program, int capacity, const std::vector<glm::vec4>& table)
{
    program.uniforms<SampleTableUniforms>().sampleCount.set(int(table.size()));
    if (capacity == 0) {
        gl::Buffer buffer = gl::createBufferWith<glm::vec4>(table);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
        return buffer;
    }
    std::vector<glm::vec4> padded(std::size_t(capacity), glm::vec4(0.0f));
    std::copy(table.begin(), table.end(), padded.begin());
    gl::Buffer buffer = gl::createBufferWith<glm::vec4>(padded);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffer.id());
    return buffer;
}

} // namespace

void BakePasses::irradianceRiemann(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                                   const RiemannIrradianceSettings& settings, bool exactTexelSolidAngle)
{
    gl::SeamlessCubeScope seamless;
    const gl::ShaderProgram& program = cubeProgram(kIrradianceRiemann);
    const RiemannUniforms& uniforms = program.uniforms<RiemannUniforms>();
    uniforms.phiSteps.set(riemannPhiSteps(settings.sampleDelta));
    uniforms.thetaSteps.set(riemannThetaSteps(settings.sampleDelta));
    uniforms.mipBias.set(settings.mipBias);
    bindSource(program, environment, settings.mipFiltering, exactTexelSolidAngle);
    dispatchCube(program, out, slice);
}

void BakePasses::irradianceImportance(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                                      const ImportanceIrradianceSettings& settings, bool exactTexelSolidAngle)
{
    gl::SeamlessCubeScope seamless;
    const int capacity = sampleTableCapacity(settings.samples);
    const gl::ShaderProgram& program = sampleTableProgram(kIrradianceImportance, capacity);
    const gl::Buffer table = bindSampleTable(program, capacity, cosineSampleTable(settings.samples, settings.mipBias));
    bindSource(program, environment, settings.mipFiltering, exactTexelSolidAngle);
    dispatchCube(program, out, slice);
}

MomentTexels BakePasses::uploadIrradianceMoments(const std::vector<glm::vec4>& texels, int groupsPerEdge)
{
    const GLsizeiptr bytes = GLsizeiptr(texels.size() * sizeof(glm::vec4));
    GLint maxBlockBytes = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBlockBytes);
    if (bytes > maxBlockBytes)
        throw Error("moment irradiance", std::to_string(6 * groupsPerEdge * groupsPerEdge) + " groups need a " + std::to_string(bytes) +
                                             "-byte uniform block; this GL driver allows " + std::to_string(maxBlockBytes) +
                                             " (lower moments.sourceFaceSize)");
    return {gl::createBufferWith<glm::vec4>(texels), groupsPerEdge};
}

void BakePasses::irradianceMoments(const MomentTexels& groups, const BakedTexture& out, const CubeSlice& slice)
{
    const gl::ShaderProgram& program = momentsProgram(groups.groupsPerEdge);
    program.uniforms<MomentsUniforms>().groupCount.set(6 * groups.groupsPerEdge * groups.groupsPerEdge);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, groups.buffer.id());
    dispatchCube(program, out, slice);
}

void BakePasses::prefilter(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                           const PrefilterSettings& settings, bool exactTexelSolidAngle, const PrefilterBrightTexels* bright)
{
    if (copyMirrorLevel(environment, out, slice, settings))
        return;
    gl::SeamlessCubeScope seamless;
    const int sampleCount = prefilterSamples(settings, slice.level);
    const float roughness = prefilterMipRoughness(settings, slice.level);
    // The mirror level has no lobe to weight lights by: it reads the environment itself.
    const bool split = bright && roughness > 0.0f && std::size_t(slice.level) < bright->levels.size() && bright->levels[std::size_t(slice.level)].base >= 0;
    const PrefilterBrightTexels::Level* lights = split ? &bright->levels[std::size_t(slice.level)] : nullptr;
    // A level the split refines (mips 1 and 2, bright_texels.hpp) takes a second, larger set where its first is unsure.
    const int refineCount = lights && lights->refineSpread >= 0.0f ? sampleCount * lights->refineFactor : 0;
    const int capacity = sampleTableCapacity(sampleCount + refineCount);
    const int exactCapacity = lights ? exactTableCapacity(settings) : 0;
    const gl::ShaderProgram& program = prefilterProgram(capacity, lights ? lights->capacity : 0, exactCapacity);
    std::vector<glm::vec4> samples = ggxReflectedSampleTable(roughness, sampleCount, settings.mipBias, settings.sampleRotation);
    auto weightSumOf = [](std::span<const glm::vec4> set) {
        return std::accumulate(set.begin(), set.end(), 0.0f, [](float sum, const glm::vec4& sample) { return sum + sample.z; });
    };
    const float weightSum = weightSumOf(samples);
    float refineWeightSum = 0.0f;
    if (refineCount > 0) {
        const std::vector<glm::vec4> refined = ggxReflectedSampleTable(roughness, refineCount, settings.mipBias, settings.sampleRotation);
        refineWeightSum = weightSumOf(refined);
        samples.insert(samples.end(), refined.begin(), refined.end());
    }
    const gl::Buffer table = bindSampleTable(program, capacity, samples);
    const PrefilterUniforms& uniforms = program.uniforms<PrefilterUniforms>();
    program.uniforms<SampleTableUniforms>().sampleCount.set(sampleCount);
    uniforms.refineCount.set(refineCount);
    uniforms.refineWeightSum.set(refineWeightSum);
    uniforms.refineSpread.set(lights ? lights->refineSpread : 0.0f);
    uniforms.refineError.set(lights ? lights->refineError : 0.0f);
    uniforms.roughness.set(roughness);
    uniforms.weightSum.set(weightSum);
    uniforms.mirrorCopy.set(settings.mirrorCopy ? 1 : 0);
    if (lights) {
        const double alpha = double(roughness) * double(roughness);
        uniforms.brightCount.set(lights->count);
        uniforms.nearCos.set(brightNearCos(brightCellFaceSize(roughness)));
        uniforms.alpha2.set(float(alpha * alpha));
        uniforms.brightScale.set(float(alpha * alpha / (kPi * ggxPrefilterNormalization(roughness))));
        glBindBufferBase(GL_UNIFORM_BUFFER, 1, lights->texels.id());
        uniforms.exactCount.set(lights->exactCount);
        glBindBufferBase(exactCapacity > 0 ? GL_UNIFORM_BUFFER : GL_SHADER_STORAGE_BUFFER, 2, lights->exactCount > 0 ? lights->exactTexels.id() : 0);
        uniforms.tileLightsPerEdge.set(lights->tileLightsPerEdge);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, lights->tileLightsPerEdge > 0 ? lights->tileLights.id() : 0);
    }
    // Roughness 0 is a delta: no footprint to filter, every sample reads mip 0 (as the loop of a bake without the mirror copy does).
    bindSource(program, lights ? bright->bases[std::size_t(lights->base)] : environment, settings.mipFiltering && roughness > 0.0f, exactTexelSolidAngle);
    // The mirror level copies the source mip whose texels are this level's size.
    uniforms.copyLod.set(std::clamp(std::log2(float(environment.size) / float(out.levelSize(slice.level))), 0.0f, float(environment.levels - 1)));
    if (lights && lights->exactTilesPerEdge > 0)
        dispatchExactTiles(program, out, slice, *lights, exactCapacity);
    else
        dispatchCube(program, out, slice);
}

void BakePasses::dispatchExactTiles(const gl::ShaderProgram& program, const BakedTexture& out, const CubeSlice& slice,
                                    const PrefilterBrightTexels::Level& level, int capacity) const
{
    // One dispatch per tile, each with its own list bound as the exact table: a uniform
    // block, whose entries every lane reads at once (exact_tiles.hpp).
    bindCubeOutput(program, out, slice.level);
    const CubeSliceUniforms& uniforms = program.uniforms<CubeSliceUniforms>();
    const gl::Uniform<int>& exactCount = program.uniforms<PrefilterUniforms>().exactCount;
    const int faceSize = out.levelSize(slice.level);
    const int edge = level.exactTilesPerEdge;
    const int endRow = slice.firstRow + slice.rowCount;
    for (int face = slice.firstFace; face < slice.firstFace + slice.faceCount; ++face)
        for (int ty = 0; ty < edge; ++ty) {
            const int firstRow = std::max(ty * kExactTileTexels, slice.firstRow);
            const int rows = std::min((ty + 1) * kExactTileTexels, std::min(endRow, faceSize)) - firstRow;
            if (rows <= 0)
                continue;
            uniforms.firstFace.set(face);
            uniforms.rowOffset.set(firstRow);
            uniforms.rowCount.set(rows);
            for (int tx = 0; tx < edge; ++tx) {
                const std::size_t tile = (std::size_t(face) * std::size_t(edge) + std::size_t(ty)) * std::size_t(edge) + std::size_t(tx);
                uniforms.columnOffset.set(tx * kExactTileTexels);
                exactCount.set(level.exactTileCount[tile]);
                glBindBufferRange(GL_UNIFORM_BUFFER, 2, level.exactTiles.id(), GLintptr(level.exactTileFirst[tile]) * GLintptr(sizeof(glm::vec4)),
                                  GLsizeiptr(capacity) * GLsizeiptr(sizeof(glm::vec4)));
                glDispatchCompute(GLuint(groupsFor(std::min(kExactTileTexels, faceSize - tx * kExactTileTexels))), GLuint(groupsFor(rows)), 1);
            }
        }
    uniforms.columnOffset.set(0);
    finishCubePass();
}

std::optional<int> BakePasses::mirrorSourceLevel(const BakedTexture& environment, const BakedTexture& prefiltered, int level,
                                                 const PrefilterSettings& settings)
{
    // The mirror level reads the source mip with its own texel size at texel centres, which
    // is that mip's texels themselves: a copy, when the formats and sizes match.
    if (!settings.mirrorCopy || prefilterMipRoughness(settings, level) > 0.0f || environment.internalFormat != prefiltered.internalFormat)
        return std::nullopt;
    int sourceLevel = 0;
    while (sourceLevel + 1 < environment.levels && environment.levelSize(sourceLevel) > prefiltered.levelSize(level))
        ++sourceLevel;
    if (environment.levelSize(sourceLevel) != prefiltered.levelSize(level))
        return std::nullopt;
    return sourceLevel;
}

bool BakePasses::copyMirrorLevel(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                                 const PrefilterSettings& settings)
{
    const std::optional<int> sourceLevel = mirrorSourceLevel(environment, out, slice.level, settings);
    if (!sourceLevel)
        return false;
    copyCubeRows(environment, *sourceLevel, out, slice.level, slice.firstFace, slice.faceCount, slice.firstRow, slice.rowCount);
    return true;
}

std::vector<glm::vec3> BakePasses::samplePrefiltered(const BakedTexture& prefiltered, RoughnessLayout layout,
                                                     const std::vector<glm::vec4>& queries)
{
    if (queries.empty()) return {};
    gl::SeamlessCubeScope seamless;
    const gl::ShaderProgram& program = shaders_.program({kSamplePrefiltered});
    const gl::Buffer in = gl::createBufferWith<glm::vec4>(queries);
    gl::Buffer out = gl::createBuffer();
    const auto bytes = GLsizeiptr(queries.size() * sizeof(glm::vec4));
    glNamedBufferStorage(out.id(), bytes, nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    const SamplePrefilteredUniforms& uniforms = program.uniforms<SamplePrefilteredUniforms>();
    uniforms.count.set(int(queries.size()));
    uniforms.prefiltered.set(1);
    uniforms.levels.set(float(prefiltered.levels));
    uniforms.layout.set(int(layout));
    glBindTextureUnit(1, prefiltered.id());
    glUseProgram(program.id());
    glDispatchCompute(GLuint((queries.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> texels(queries.size());
    glGetNamedBufferSubData(out.id(), 0, bytes, texels.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    clearPassBindings();
    return {texels.begin(), texels.end()};
}

void BakePasses::brdfLut(const BakedTexture& out, int firstRow, int rowCount, int samples, GeometryTerm term)
{
    const gl::ShaderProgram& program = shaders_.program({kBrdfLut});
    const BrdfLutUniforms& uniforms = program.uniforms<BrdfLutUniforms>();
    uniforms.size.set(out.size);
    uniforms.sampleCount.set(samples);
    uniforms.geometry.set(term == GeometryTerm::SchlickGGX ? 0 : 1);
    uniforms.rowOffset.set(firstRow);
    uniforms.rowCount.set(rowCount);
    uniforms.lut.set(0);
    glBindImageTexture(0, out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, out.internalFormat);
    glUseProgram(program.id());
    glDispatchCompute(groupsFor(out.size), groupsFor(rowCount), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    clearPassBindings();
}

} // namespace iblab::bake
