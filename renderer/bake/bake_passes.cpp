#include "bake/bake_passes.hpp"

#include <cmath>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "bake/prefilter_lod.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"

namespace iblab::bake {
namespace {

constexpr const char* kEquirectToCube = "bake/equirect_to_cube.comp";
constexpr const char* kSh9Project = "bake/sh9_project.comp";
constexpr const char* kIrradianceRiemann = "bake/irradiance_riemann.comp";
constexpr const char* kIrradianceImportance = "bake/irradiance_importance.comp";
constexpr const char* kPrefilter = "bake/prefilter_ggx.comp";
constexpr const char* kBrdfLut = "bake/brdf_lut.comp";
constexpr const char* kDownsample = "bake/downsample.comp";
constexpr const char* kSamplePrefiltered = "bake/sample_prefiltered.comp";

const char* imageFormatName(GLenum internalFormat) { return internalFormat == GL_RGBA16F ? "rgba16f" : "rgba32f"; }

// Seamless filtering across cube faces (GL 4.5 core, global state): without it a texel
// near a face edge is clamped to its own face, and the blurred mips show their seams.
// Turned on for the pass and restored after it.
class SeamlessCubeScope {
public:
    SeamlessCubeScope() : wasEnabled_(glIsEnabled(GL_TEXTURE_CUBE_MAP_SEAMLESS) == GL_TRUE)
    {
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    }
    ~SeamlessCubeScope()
    {
        if (!wasEnabled_)
            glDisable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    }
    SeamlessCubeScope(const SeamlessCubeScope&) = delete;
    SeamlessCubeScope& operator=(const SeamlessCubeScope&) = delete;

private:
    bool wasEnabled_;
};

// Clears the units a pass used, so that a later pass cannot read or write through a
// binding it did not make.
void clearPassBindings()
{
    glUseProgram(0);
    glBindTextureUnit(1, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
}

GLuint groupsFor(int n) { return GLuint((n + 7) / 8); }

} // namespace

float storeMax(GLenum internalFormat)
{
    return internalFormat == GL_RGBA16F ? 65504.0f : 3.4028234e38f;
}

int BakePasses::riemannPhiSteps(float sampleDelta)
{
    return std::max(1, int(std::lround(2.0 * kPi / double(sampleDelta))));
}

int BakePasses::riemannThetaSteps(float sampleDelta)
{
    return std::max(1, int(std::lround(0.5 * kPi / double(sampleDelta))));
}

void BakePasses::compileAll()
{
    for (const char* file : {kEquirectToCube, kSh9Project, kIrradianceRiemann, kIrradianceImportance, kPrefilter, kBrdfLut})
        shaders_.program({file});
    for (const char* cube : {"0", "1"})
        for (const char* format : {"rgba16f", "rgba32f"})
            shaders_.program({kDownsample}, {{"CUBE", cube}, {"FORMAT", format}});
}

const gl::ShaderProgram& BakePasses::cubeProgram(const char* file) { return shaders_.program({file}); }

gl::Texture BakePasses::uploadEquirect(const ImageRGB32F& image)
{
    // RGBA32F, not RGB32F: the mips are built by image load/store, which RGB formats lack.
    const int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
    gl::Texture texture = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), levels, GL_RGBA32F, image.width, image.height);
    // Padded to RGBA here: the upload is then a copy, where Mesa's RGB -> RGBA conversion
    // path costs about as much as the rest of the upload and mip chain together.
    std::vector<glm::vec4> rgba(image.texelCount());
    for (std::size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = glm::vec4(image.texels[3 * i], image.texels[3 * i + 1], image.texels[3 * i + 2], 1.0f);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    downsampleChain(texture.id(), GL_TEXTURE_2D, GL_RGBA32F, image.width, image.height, levels);
    return texture;
}

void BakePasses::downsampleChain(GLuint texture, GLenum target, GLenum internalFormat, int width, int height, int levels)
{
    const bool cube = target == GL_TEXTURE_CUBE_MAP;
    const gl::ShaderProgram& program =
        shaders_.program({kDownsample}, {{"CUBE", cube ? "1" : "0"}, {"FORMAT", imageFormatName(internalFormat)}});
    glUseProgram(program.id());
    for (int level = 1; level < levels; ++level) {
        const glm::ivec2 source(std::max(width >> (level - 1), 1), std::max(height >> (level - 1), 1));
        const glm::ivec2 size(std::max(width >> level, 1), std::max(height >> level, 1));
        glProgramUniform2i(program.id(), program.uniformLocation("uSourceSize"), source.x, source.y);
        glProgramUniform2i(program.id(), program.uniformLocation("uTargetSize"), size.x, size.y);
        glBindImageTexture(1, texture, level - 1, GL_TRUE, 0, GL_READ_ONLY, internalFormat);
        glBindImageTexture(0, texture, level, GL_TRUE, 0, GL_WRITE_ONLY, internalFormat);
        glDispatchCompute(groupsFor(size.x), groupsFor(size.y), cube ? 6 : 1);
        // The next level reads this one.
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, internalFormat);
    clearPassBindings();
}

void BakePasses::dispatchCube(const gl::ShaderProgram& program, const BakedTexture& out, const CubeSlice& slice) const
{
    program.set("uFace", slice.face);
    program.set("uFaceSize", out.levelSize(slice.level));
    program.set("uRowOffset", slice.firstRow);
    program.set("uRowCount", slice.rowCount);
    program.set("uStoreMax", storeMax(out.internalFormat));
    program.set("uOutput", 0);
    // Layered: the shader addresses the face as the image's layer.
    glBindImageTexture(0, out.id(), slice.level, GL_TRUE, 0, GL_WRITE_ONLY, out.internalFormat);
    glUseProgram(program.id());
    glDispatchCompute(groupsFor(out.levelSize(slice.level)), groupsFor(slice.rowCount), 1);
    // Later passes sample what this one wrote, or read it back, or build mips from it.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    clearPassBindings();
}

void BakePasses::equirectToCube(GLuint equirect, const BakedTexture& cube, const CubeSlice& slice)
{
    const gl::ShaderProgram& program = cubeProgram(kEquirectToCube);
    program.set("uEquirect", 1);
    glBindTextureUnit(1, equirect);
    dispatchCube(program, cube, slice);
}

void BakePasses::generateMips(const BakedTexture& texture)
{
    downsampleChain(texture.id(), texture.target, texture.internalFormat, texture.size, texture.size, texture.levels);
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
    gl::Buffer rowSolidAngles = gl::createBuffer();
    glNamedBufferStorage(rowSolidAngles.id(), GLsizeiptr(solidAngles.size() * sizeof(float)), solidAngles.data(), 0);
    gl::Buffer groupSums = gl::createBuffer();
    const auto bytes = GLsizeiptr(std::size_t(groups) * kSh9Count * sizeof(glm::vec4));
    glNamedBufferStorage(groupSums.id(), bytes, nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, groupSums.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, rowSolidAngles.id());
    glBindTextureUnit(1, equirect);
    program.set("uEquirect", 1);
    program.set("uRowsPerGroup", kRowsPerGroup);
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
// the cube on unit 1 and the numbers sourceLodFromPdf[At] takes (prefilter_lod.glsl).
void bindSource(const gl::ShaderProgram& program, const BakedTexture& environment, bool mipFiltering, float mipBias, bool exactTexelSolidAngle)
{
    program.set("uEnvironment", 1);
    program.set("uMipFiltering", mipFiltering ? 1 : 0);
    program.set("uMipBias", mipBias);
    program.set("uSourceFaceSize", float(environment.size));
    program.set("uExactTexelSolidAngle", exactTexelSolidAngle ? 1 : 0);
    program.set("uMaxSourceLod", float(environment.levels - 1));
    glBindTextureUnit(1, environment.id());
}

} // namespace

void BakePasses::irradianceRiemann(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                                   const RiemannIrradianceSettings& settings, bool exactTexelSolidAngle)
{
    SeamlessCubeScope seamless;
    const gl::ShaderProgram& program = cubeProgram(kIrradianceRiemann);
    program.set("uPhiSteps", riemannPhiSteps(settings.sampleDelta));
    program.set("uThetaSteps", riemannThetaSteps(settings.sampleDelta));
    bindSource(program, environment, settings.mipFiltering, settings.mipBias, exactTexelSolidAngle);
    dispatchCube(program, out, slice);
}

void BakePasses::irradianceImportance(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                                      const ImportanceIrradianceSettings& settings, bool exactTexelSolidAngle)
{
    SeamlessCubeScope seamless;
    const gl::ShaderProgram& program = cubeProgram(kIrradianceImportance);
    program.set("uSampleCount", settings.samples);
    bindSource(program, environment, settings.mipFiltering, settings.mipBias, exactTexelSolidAngle);
    dispatchCube(program, out, slice);
}

void BakePasses::prefilter(const BakedTexture& environment, const BakedTexture& out, const CubeSlice& slice,
                           const PrefilterSettings& settings, bool exactTexelSolidAngle)
{
    SeamlessCubeScope seamless;
    const gl::ShaderProgram& program = cubeProgram(kPrefilter);
    program.set("uRoughness", prefilterMipRoughness(settings, slice.level));
    program.set("uMirrorCopy", settings.mirrorCopy ? 1 : 0);
    program.set("uSampleCount", prefilterSamples(settings, slice.level));
    bindSource(program, environment, settings.mipFiltering, settings.mipBias, exactTexelSolidAngle);
    // The mirror level copies the source mip whose texels are this level's size.
    const float copyLod = std::log2(float(environment.size) / float(out.levelSize(slice.level)));
    program.set("uCopyLod", std::clamp(copyLod, 0.0f, float(environment.levels - 1)));
    dispatchCube(program, out, slice);
}

std::vector<glm::vec3> BakePasses::samplePrefiltered(const BakedTexture& prefiltered, RoughnessLayout layout,
                                                     const std::vector<glm::vec4>& queries)
{
    if (queries.empty()) return {};
    SeamlessCubeScope seamless;
    const gl::ShaderProgram& program = shaders_.program({kSamplePrefiltered});
    gl::Buffer in = gl::createBuffer();
    gl::Buffer out = gl::createBuffer();
    const auto bytes = GLsizeiptr(queries.size() * sizeof(glm::vec4));
    glNamedBufferStorage(in.id(), bytes, queries.data(), 0);
    glNamedBufferStorage(out.id(), bytes, nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    program.set("uCount", int(queries.size()));
    program.set("uPrefiltered", 1);
    program.set("uLevels", float(prefiltered.levels));
    program.set("uLayout", int(layout));
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
    program.set("uSize", out.size);
    program.set("uSampleCount", samples);
    program.set("uGeometry", term == GeometryTerm::SchlickGGX ? 0 : 1);
    program.set("uRowOffset", firstRow);
    program.set("uRowCount", rowCount);
    program.set("uLut", 0);
    glBindImageTexture(0, out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, out.internalFormat);
    glUseProgram(program.id());
    glDispatchCompute(groupsFor(out.size), groupsFor(rowCount), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    clearPassBindings();
}

} // namespace iblab::bake
