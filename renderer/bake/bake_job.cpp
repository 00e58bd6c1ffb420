#include "bake/bake_job.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <stdexcept>
#include <utility>

#include "bake/equirect_moments.hpp"
#include "bake/near_lights.hpp"
#include "ibl/reference.hpp"
#include "gl/pass_timer.hpp"
#include "io/error.hpp"

namespace iblab::bake {
namespace {

std::atomic<HostWorkPlacement> hostWorkPlacement{HostWorkPlacement::Auto};

bool splitsBrightTexels(const PrefilterSettings& p) { return p.brightTexels > 0 && p.levels > 1; }

using Clock = std::chrono::steady_clock;

// Work estimates in texture samples, the unit of BakeSettings::samplesPerStep. Steps that
// are not sampling passes get a rough equivalent so that the progress bar does not stall
// on them: shader compilation costs about as much as a few million samples on llvmpipe.
constexpr double kCompileCost = 4.0e6;

// Rows of `size` per step so that a step costs about `budget` samples: at least one row, a
// multiple of 8 (whole 8x8 work groups) where there are that many.
int rowsPerStep(double budget, double rowCost, int size)
{
    int rows = int(std::clamp(budget / rowCost, 1.0, double(size)));
    if (rows >= 8)
        rows -= rows % 8;
    return rows;
}

// The settings that describe an imported bake: its sizes, levels, layout and diffuse, so
// that shading, the accuracy report and the files read it as they read iblab's own. The
// sizes come from the files (checked by the KTX readers), not from the settings' ranges.
BakeSettings importedSettings(BakeSettings settings, const ImportedBake& imported)
{
    settings.cube.faceSize = imported.sky.width;
    settings.cube.maxFaceSize = std::max(settings.cube.maxFaceSize, imported.sky.width);
    settings.prefilter.faceSize = imported.prefiltered.front().width;
    settings.prefilter.levels = int(imported.prefiltered.size());
    settings.prefilter.layout = RoughnessLayout(imported.roughnessLayout);
    // The glTF-IBL-Sampler's Lambertian cube is cosine-weighted importance sampling
    // (filter.frag), the method iblab calls importance.
    settings.irradiance = imported.irradiance ? IrradianceMethod::Importance : IrradianceMethod::None;
    if (imported.irradiance) settings.importance.faceSize = imported.irradiance->width;
    // The tool's SH as it is: no window of iblab's on top (iblab's own carries its window).
    if (imported.shIrradiance) settings.sh.window = imported.shWindowed ? imported.shWindowed->window : ShWindow::None;
    return settings;
}

CubeImage cubeImageFromStrip(const ImageRGB32F& strip)
{
    CubeImage image(strip.width);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < strip.width; ++row)
            for (int x = 0; x < strip.width; ++x)
                image.at(face, x, row) = glm::vec4(strip.at(x, face * strip.width + row), 1.0f);
    return image;
}

} // namespace

void setHostWorkPlacement(HostWorkPlacement placement)
{
    hostWorkPlacement = placement;
}

BakeJob::BakeJob(gl::ShaderLibrary& shaders, Environment environment, const BakeSettings& settings, BakeCache* cache)
    : passes_(shaders), cache_(cache)
{
    validate(settings);
    if (environment.image.empty())
        throw Error(environment.source, "cannot bake an empty environment");
    image_ = std::move(environment.image);
    imported_ = std::move(environment.imported);
    result_.settings = imported_ ? importedSettings(settings, *imported_) : settings;
    result_.source = environment.source;
    result_.contentHash = environment.contentHash;
    if (cache_)
        result_.shaderFingerprint = bakeShaderFingerprint(shaders.roots());
    result_.sourceWidth = image_.width;
    result_.sourceHeight = image_.height;
    // The job reads a map too coarse for mip 1's lobe as its bilinear upsample; the result
    // still names the map's own size, from which the cache's record plans the same job.
    result_.sourceUpsample = imported_ ? 1 : bakeSourceUpsampleFactor(result_.settings.prefilter, image_.width);
    if (result_.sourceUpsample > 1)
        image_ = upsampleEquirectBilinear(image_, result_.sourceUpsample);
    plan();
}

BakeJob::BakeJob(gl::ShaderLibrary& shaders, const std::string& source, const BakeCache::SourceRecord& record, const BakeSettings& settings,
                 BakeCache& cache)
    : passes_(shaders), cache_(&cache)
{
    validate(settings);
    if (!cache.enabled())
        throw std::logic_error("BakeJob: a job from the cache needs an enabled cache");
    result_.settings = settings;
    result_.source = source;
    result_.contentHash = record.contentHash;
    result_.shaderFingerprint = bakeShaderFingerprint(shaders.roots());
    result_.sourceWidth = record.width;
    result_.sourceHeight = record.height;
    result_.sourceUpsample = bakeSourceUpsampleFactor(settings.prefilter, record.width);
    plan();
}

BakeJob::~BakeJob() = default;

GLenum BakeJob::cubeFormat() const
{
    if (result_.settings.precision == Precision::Float)
        return GL_RGBA32F;
    // A half float holds at most 65504. A map brighter than that in any channel (an unclipped
    // sun, a sky in absolute units) is baked in floats: in halves the environment cube would
    // clip it, and with it the bases, every prefiltered mip and the irradiance (a 2 degree sun
    // of 1e6 read 0.59 at mip 1; docs/bake.md, "Brighter than a half float").
    // Another tool's bake in floats can be as bright: its cubes are uploaded as they are.
    auto brightest = [](const ImageRGB32F& image) { return image.empty() ? 0.0f : *std::ranges::max_element(image.texels); };
    float peak = brightest(image_);
    if (imported_) {
        peak = std::max(peak, brightest(imported_->sky));
        if (imported_->irradiance) peak = std::max(peak, brightest(*imported_->irradiance));
        for (const ImageRGB32F& level : imported_->prefiltered)
            peak = std::max(peak, brightest(level));
    }
    return peak > storeMax(GL_RGBA16F) ? GL_RGBA32F : GL_RGBA16F;
}

bool BakeJob::compilesLut(const BakeSettings& settings, const BakeCache* cache)
{
    return (cache == nullptr || !cache->enabled()) && (settings.lut.schlickGgx || settings.lut.heightCorrelatedSmith);
}

void BakeJob::compilePrograms(gl::ShaderLibrary& shaders, const BakeSettings& settings, const BakeCache* cache)
{
    BakePasses(shaders).compileFor(settings, 1, compilesLut(settings, cache));
}

BakeJob::StepGroup BakeJob::lutGroup(GeometryTerm term)
{
    return term == GeometryTerm::SchlickGGX ? StepGroup::LutSchlickGgx : StepGroup::LutHeightCorrelatedSmith;
}

void BakeJob::planCubeSlices(BakePhase phase, StepGroup group, int faceSize, int level, double samplesPerTexel,
                             const std::function<void(const CubeSlice&)>& run, const std::string& part)
{
    const int size = std::max(faceSize >> level, 1);
    const double rowCost = double(size) * samplesPerTexel;
    const double budget = double(result_.settings.samplesPerStep);
    const int rows = rowsPerStep(budget, rowCost, size);
    // Whole faces fit a step: as many of them per step as the budget allows.
    const int facesPerStep = rows < size ? 1 : int(std::clamp(budget / (rowCost * size), 1.0, 6.0));
    for (int face = 0; face < 6; face += facesPerStep)
        for (int row = 0; row < size; row += rows) {
            const CubeSlice slice{.level = level,
                                  .firstFace = face,
                                  .faceCount = std::min(facesPerStep, 6 - face),
                                  .firstRow = row,
                                  .rowCount = std::min(rows, size - row)};
            steps_.push_back({phase, group, rowCost * slice.rowCount * slice.faceCount, [run, slice] { run(slice); }, part});
        }
}

void BakeJob::planImported()
{
    const BakeSettings& s = result_.settings;
    const GLenum format = cubeFormat();
    steps_.push_back({BakePhase::Shaders, StepGroup::None, kCompileCost,
                      [this, format] { passes_.compileFor(result_.settings, 1, compilesLut(result_.settings, cache_), format); }});
    const double texels = 6.0 * s.prefilter.faceSize * s.prefilter.faceSize;
    steps_.push_back({BakePhase::Upload, StepGroup::Environment, texels, [this, format] {
                          const ImportedBake& in = *imported_;
                          const int skyLevels = std::bit_width(unsigned(in.sky.width));
                          result_.environmentCube = createCubeTexture(format, in.sky.width, skyLevels);
                          uploadCubeLevel(result_.environmentCube, 0, cubeImageFromStrip(in.sky));
                          passes_.generateMips(result_.environmentCube);
                          if (in.irradiance) {
                              result_.irradianceCube = createCubeTexture(format, in.irradiance->width, 1);
                              uploadCubeLevel(result_.irradianceCube, 0, cubeImageFromStrip(*in.irradiance));
                          }
                          result_.prefiltered = createCubeTexture(format, in.prefiltered.front().width, int(in.prefiltered.size()));
                          for (std::size_t level = 0; level < in.prefiltered.size(); ++level)
                              uploadCubeLevel(result_.prefiltered, int(level), cubeImageFromStrip(in.prefiltered[level]));
                      }});
    steps_.push_back({BakePhase::Sh9, StepGroup::Environment, texels, [this] {
                          ShResult& out = result_.sh;
                          if (imported_->shIrradiance) {
                              out.irradiance = *imported_->shIrradiance;
                              for (int i = 0; i < kSh9Count; ++i)
                                  out.radiance.c[std::size_t(i)] = out.irradiance.c[std::size_t(i)] / cosineLobeBandFactor(sh9Band(i));
                          } else {
                              out.radiance = projectEquirect(image_);
                              out.irradiance = convolveWithCosineLobe(out.radiance);
                          }
                          if (imported_->shWindowed) {
                              out.window = imported_->shWindowed->window;
                              out.windowWidth = imported_->shWindowed->width;
                              out.irradianceWindowed = imported_->shWindowed->irradiance;
                          } else {
                              out.window = ShWindow::None;
                              out.windowWidth = 0.0;
                              out.irradianceWindowed = out.irradiance;
                          }
                      }});
    planLuts();
    for (const Step& step : steps_)
        totalCost_ += step.cost;
}

// The irradiance cube's steps, by method; they read the environment cube of face envFace.
void BakeJob::planIrradiance(int envFace)
{
    const BakeSettings& s = result_.settings;
    switch (s.irradiance) {
    case IrradianceMethod::None: break;
    case IrradianceMethod::Riemann: {
        const double perTexel = double(BakePasses::riemannPhiSteps(s.riemann.sampleDelta)) *
                                double(BakePasses::riemannThetaSteps(s.riemann.sampleDelta));
        planCubeSlices(irradiancePhase(s.irradiance), StepGroup::Environment, s.riemann.faceSize, 0, perTexel, [this](const CubeSlice& slice) {
            passes_.irradianceRiemann(result_.environmentCube, result_.irradianceCube, slice, result_.settings.riemann,
                                      result_.settings.exactTexelSolidAngle);
        });
        break;
    }
    case IrradianceMethod::Importance:
        planCubeSlices(irradiancePhase(s.irradiance), StepGroup::Environment, s.importance.faceSize, 0, s.importance.samples, [this](const CubeSlice& slice) {
            passes_.irradianceImportance(result_.environmentCube, result_.irradianceCube, slice, result_.settings.importance,
                                         result_.settings.exactTexelSolidAngle);
        });
        break;
    case IrradianceMethod::Moments: {
        steps_.push_back({irradiancePhase(s.irradiance), StepGroup::Environment, double(envFace) * envFace * 6.0, [this, envFace] {
                              const int groups = momentGroupsPerEdge(envFace);
                              momentTexels_ = passes_.uploadIrradianceMoments(
                                  momentGroups_.valid() ? momentGroups_.get() : equirectMomentTexels(image_, groups), groups);
                          }});
        const double groups = 6.0 * s.moments.sourceFaceSize * s.moments.sourceFaceSize;
        // A group costs a few multiply-adds, about a tenth of a filtered texture read.
        planCubeSlices(irradiancePhase(s.irradiance), StepGroup::Environment, s.moments.faceSize, 0, groups / 10.0, [this](const CubeSlice& slice) {
            passes_.irradianceMoments(momentTexels_, result_.irradianceCube, slice);
        });
        break;
    }
    }
}

void BakeJob::plan()
{
    if (imported_) {
        planImported();
        return;
    }
    const BakeSettings& s = result_.settings;
    const GLenum format = cubeFormat();
    const int sourceWidth = result_.sourceWidth * result_.sourceUpsample, sourceHeight = result_.sourceHeight * result_.sourceUpsample;
    const double sourceTexels = double(sourceWidth) * double(sourceHeight);
    const int envFace = environmentFaceSize(s.cube, sourceWidth, sourceHeight); // bakeEnvironmentFaceSize's
    const int envLevels = std::bit_width(unsigned(envFace)); // full chain down to 1x1
    // No pixels: a job from the cache's record of the file (the constructor's second form).
    const bool cacheOnly = image_.empty();

    const int equirectLevels = BakePasses::equirectLevelsForCube(sourceWidth, sourceHeight, envFace);
    steps_.push_back({BakePhase::Shaders, StepGroup::None, kCompileCost, [this, equirectLevels, format] {
                          passes_.compileFor(result_.settings, equirectLevels, compilesLut(result_.settings, cache_), format);
                      }});
    if (diskCache())
        steps_.push_back({BakePhase::CacheLookup, StepGroup::None, sourceTexels, [this] {
                              const MipBuilder buildMips = [this](const BakedTexture& t) { passes_.generateMips(t); };
                              if (cache_->loadBake(result_, buildMips, result_.notes)) {
                                  result_.fromCache = true;
                                  skipGroup(StepGroup::Environment);
                              }
                          }});

    if (cacheOnly) {
        // Reached only when the lookup missed (a hit skips the group).
        steps_.push_back({BakePhase::CacheLookup, StepGroup::Environment, 1.0, [this] { missedCache_ = true; }});
        planLuts();
        for (const Step& step : steps_)
            totalCost_ += step.cost;
        return;
    }

    const bool hostWorkBeside = planHostWork(sourceTexels, envFace);
    planUpload(format, envFace, envLevels, equirectLevels);

    // Footprint filtering takes 1..4 taps, about 2 on average.
    planCubeSlices(BakePhase::EnvironmentCube, StepGroup::Environment, envFace, 0, 2.0,
                   [this](const CubeSlice& slice) { passes_.equirectToCube(equirect_.id(), result_.environmentCube, slice); });
    steps_.push_back({BakePhase::EnvironmentCube, StepGroup::Environment, 6.0 * envFace * envFace / 3.0,
                      [this] { passes_.generateMips(result_.environmentCube); }});

    steps_.push_back({BakePhase::Sh9, StepGroup::Environment, sourceTexels, [this] {
                          const ShSettings& sh = result_.settings.sh;
                          ShResult& out = result_.sh;
                          out.radiance = sh.device == ShDevice::Cpu ? projectEquirect(image_)
                                                                    : passes_.projectSh9(equirect_.id(), image_.width, image_.height);
                          out.irradiance = convolveWithCosineLobe(out.radiance);
                          out.window = sh.window;
                          if (sh.window == ShWindow::None)
                              out.windowWidth = 0.0;
                          else
                              out.windowWidth = sh.windowWidth > 0.0 ? sh.windowWidth
                                                                     : findNonNegativeWindowWidth(out.irradiance, sh.window);
                          out.irradianceWindowed = applyWindow(out.irradiance, sh.window, out.windowWidth);
                      }});

    planIrradiance(envFace);

    planPrefilter(envFace, hostWorkBeside);

    planLuts();

    if (diskCache())
        steps_.push_back({BakePhase::CacheStore, StepGroup::Environment, sourceTexels, [this] { cache_->storeBake(result_); }});

    for (const Step& step : steps_)
        totalCost_ += step.cost;
}

// The upload's steps: the textures, then the map's rows.
void BakeJob::planUpload(GLenum format, int envFace, int envLevels, int equirectLevels)
{
    const BakeSettings& s = result_.settings;
    const int sourceWidth = image_.width, sourceHeight = image_.height;
    // The textures in two steps and the map's rows in bands: on llvmpipe a texture's storage
    // costs its pages' first touch as it is made (a 4096 x 2048 map's equirect 43-89 ms, its
    // cubes 88-129; 270-350 ms as one step with the upload), a band of rows about 1 ms.
    steps_.push_back({BakePhase::Upload, StepGroup::Environment, 1.0,
                      [this, equirectLevels] { equirect_ = passes_.createEquirect(image_, equirectLevels); }});
    steps_.push_back({BakePhase::Upload, StepGroup::Environment, 1.0, [this, format, envFace, envLevels] {
                          const BakeSettings& st = result_.settings;
                          result_.environmentCube = createCubeTexture(format, envFace, envLevels);
                          if (st.irradiance != IrradianceMethod::None)
                              result_.irradianceCube = createCubeTexture(format, irradianceFaceSize(st), 1);
                          result_.prefiltered = createCubeTexture(format, st.prefilter.faceSize, st.prefilter.levels);
                      }});
    // A texel's upload counted as a sample: a 1024 x 512 map is one step, a 4096 x 2048 one
    // eight in the GUI.
    const int uploadRows = rowsPerStep(double(s.samplesPerStep), double(sourceWidth), sourceHeight);
    for (int row = 0; row < sourceHeight; row += uploadRows) {
        const int count = std::min(uploadRows, sourceHeight - row);
        steps_.push_back({BakePhase::Upload, StepGroup::Environment, double(count) * sourceWidth, [this, equirectLevels, row, count] {
                              passes_.uploadEquirectRows(equirect_, image_, equirectLevels, row, count);
                          }});
    }
    if (equirectLevels > 1)
        steps_.push_back({BakePhase::Upload, StepGroup::Environment, double(sourceWidth) * sourceHeight / 3.0,
                          [this, equirectLevels] { passes_.finishEquirect(equirect_, image_, equirectLevels); }});
}

// The moment irradiance's groups per face edge: the settings', at most one per texel of the
// environment cube.
int BakeJob::momentGroupsPerEdge(int envFace) const { return std::min(result_.settings.moments.sourceFaceSize, envFace); }

bool BakeJob::planHostWork(double sourceTexels, int envFace)
{
    // The host work that reads only the float map: the fitted lobe's shading lights and the
    // split's plan. On a hardware GPU it runs on worker threads from here on, beside the
    // environment's passes, while this thread waits on their fences: in steps of its own it
    // left the GPU idle for a third to a half of the bake on an H200 (docs/gpu-timings.md). On llvmpipe the GPU's work
    // is the CPU's too (when the shading lights ran beside the prefilter's last passes, the
    // phase grew by about twice their own time), so there both run in this step, while no GL
    // work is in flight: the shading lights on this thread, the split's plan on a worker that
    // the split's step waits for (courtyard's and sunrise's split 4.6-5.1 ms shorter than with
    // the plan in that step, the lights' step about as long).
    const BakeSettings& s = result_.settings;
    const bool split = splitsBrightTexels(s.prefilter);
    const HostWorkPlacement placement = hostWorkPlacement.load();
    const bool threads = placement == HostWorkPlacement::Auto ? !gl::isSoftwareRenderer() : placement == HostWorkPlacement::WorkerThreads;
    const bool hostWorkBeside = threads && (split || s.prefilter.shadingLights > 0);
    if (s.prefilter.shadingLights > 0 || hostWorkBeside)
        steps_.push_back({BakePhase::Prefilter, StepGroup::Environment, sourceTexels, [this, split, hostWorkBeside, envFace] {
                              // A copy: the worker threads' lambdas keep it.
                              const PrefilterSettings p = result_.settings.prefilter;
                              // Groups no finer than the mirror's texels, so that each covers whole texels of it.
                              const int grid = std::min(kShadingLightGrid, p.faceSize);
                              auto planSplit = [this, p, envFace] {
                                  BrightSplitPlan plan = planBrightSplit(splitCandidates(image_, p), p);
                                  plan.nearLightsMarks = nearLightsMarks(plan, envFace);
                                  plan.nearLightsFaceSize = envFace;
                                  return plan;
                              };
                              if (!hostWorkBeside) {
                                  // No GL work is in flight, so the split's plan has a core of its
                                  // own while this thread finds the lights.
                                  if (split)
                                      splitPlan_ = std::async(std::launch::async, planSplit);
                                  result_.shadingLights = findShadingLights(image_, p.shadingLights, grid);
                                  return;
                              }
                              if (p.shadingLights > 0)
                                  shadingLights_ = std::async(std::launch::async, [this, p, grid] { return findShadingLights(image_, p.shadingLights, grid); });
                              // Where the host work runs in steps of its own (llvmpipe), the irradiance's
                              // step sums them instead, when no GL work holds the cores.
                              if (result_.settings.irradiance == IrradianceMethod::Moments)
                                  momentGroups_ = std::async(std::launch::async, [this, envFace] {
                                      return equirectMomentTexels(image_, momentGroupsPerEdge(envFace));
                                  });
                              if (split)
                                  splitPlan_ = std::async(std::launch::async, planSplit);
                          }, hostWorkBeside ? "host_work_start" : "shading_lights"});
    return hostWorkBeside;
}

void BakeJob::planPrefilter(int envFace, bool hostWorkBeside)
{
    const BakeSettings& s = result_.settings;
    const bool split = splitsBrightTexels(s.prefilter);
    if (split || hostWorkBeside)
        steps_.push_back({BakePhase::Prefilter, StepGroup::Environment, double(envFace) * envFace * 6.0, [this, split] {
                              // The worker threads' results: the wait, if any, is this step's.
                              if (shadingLights_.valid()) result_.shadingLights = shadingLights_.get();
                              if (!split) return;
                              const PrefilterSettings& p = result_.settings.prefilter;
                              bright_ = splitPlan_.valid() ? splitBrightTexels(passes_, result_.environmentCube, splitPlan_.get(), p, equirect_.id())
                                                           : splitBrightTexels(passes_, result_.environmentCube, image_, p, equirect_.id());
                          }, split ? "split" : "host_work_wait"});
    for (int level = 0; level < s.prefilter.levels; ++level)
        planCubeSlices(BakePhase::Prefilter, StepGroup::Environment, s.prefilter.faceSize, level,
                       double(prefilterSamples(s.prefilter, level)) + (level > 0 ? brightTexelCap(s.prefilter, level) / 8.0 : 0.0), [this](const CubeSlice& slice) {
                           passes_.prefilter(result_.environmentCube, result_.prefiltered, slice, result_.settings.prefilter,
                                             result_.settings.exactTexelSolidAngle, bright_ ? &*bright_ : nullptr);
                       }, "mip" + std::to_string(level));
}

void BakeJob::planLuts()
{
    const BakeSettings& s = result_.settings;
    for (GeometryTerm term : kGeometryTerms) {
        if (!s.lut.wants(term))
            continue;
        const StepGroup group = lutGroup(term);
        const std::size_t index = std::size_t(term);
        if (cache_)
            steps_.push_back({BakePhase::BrdfLut, StepGroup::None, 1.0e5, [this, term, index, group] {
                                  const LutSettings& lut = result_.settings.lut;
                                  if (cache_->loadLut(lut.size, lut.samples, term, result_.shaderFingerprint, result_.brdfLut[index], result_.notes)) {
                                      result_.lutFromCache[index] = true;
                                      skipGroup(group);
                                  }
                              }});
        steps_.push_back({BakePhase::BrdfLut, group, 1.0, [this, index] {
                              result_.brdfLut[index] = create2DTexture(GL_RGBA16F, result_.settings.lut.size);
                          }});
        const double rowCost = double(s.lut.size) * s.lut.samples;
        const int rows = rowsPerStep(double(s.samplesPerStep), rowCost, s.lut.size);
        for (int row = 0; row < s.lut.size; row += rows) {
            const int count = std::min(rows, s.lut.size - row);
            steps_.push_back({BakePhase::BrdfLut, group, rowCost * count, [this, index, term, row, count] {
                                  passes_.brdfLut(result_.brdfLut[index], row, count, result_.settings.lut.samples, term);
                              }});
        }
        if (cache_)
            steps_.push_back({BakePhase::BrdfLut, group, 1.0e5, [this, term, index] {
                                  cache_->storeLut(result_.brdfLut[index], result_.settings.lut.samples, term, result_.shaderFingerprint);
                              }});
    }
}

void BakeJob::skipGroup(StepGroup group)
{
    for (auto it = steps_.begin(); it != steps_.end();) {
        if (it->group == group) {
            doneCost_ += it->cost;
            it = steps_.erase(it);
        } else {
            ++it;
        }
    }
}

void BakeJob::addTiming(BakePhase phase, double ms)
{
    auto it = std::find_if(result_.timings.begin(), result_.timings.end(), [&](const PhaseTiming& t) { return t.phase == phase; });
    if (it == result_.timings.end())
        result_.timings.push_back({phase, ms});
    else
        it->milliseconds += ms;
    result_.totalMilliseconds += ms;
}

void BakeJob::addPartTiming(BakePhase phase, const std::string& part, double ms)
{
    const std::string name = std::string(enumName(phase)) + "." + part;
    auto it = std::find_if(result_.partTimings.begin(), result_.partTimings.end(), [&](const PartTiming& t) { return t.name == name; });
    if (it == result_.partTimings.end())
        result_.partTimings.push_back({name, ms});
    else
        it->milliseconds += ms;
}

void BakeJob::retireStepInFlight()
{
    if (!inFlight_) return;
    inFlight_->fence.wait();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - inFlight_->issued).count();
    addTiming(inFlight_->phase, ms);
    if (!inFlight_->part.empty()) addPartTiming(inFlight_->phase, inFlight_->part, ms);
    if (ms > result_.longestStep.milliseconds)
        result_.longestStep = {std::string(enumName(inFlight_->phase)) + (inFlight_->part.empty() ? "" : "." + inFlight_->part), ms};
    inFlight_.reset();
}

bool BakeJob::step()
{
    if (steps_.empty() || failed_)
        return false;
    Step current = std::move(steps_.front());
    steps_.pop_front();
    try {
        // The previous step's fence first, so that its time is its own (issue to fence), and
        // then this step's commands: the GPU runs them while the caller draws its frame.
        retireStepInFlight();
        const auto issued = Clock::now();
        current.run();
        inFlight_ = StepInFlight{current.phase, issued, gl::Fence::afterIssuedCommands(), current.part};
        if (steps_.empty())
            retireStepInFlight();
    } catch (...) {
        failed_ = true;
        steps_.clear();
        inFlight_.reset();
        throw;
    }
    doneCost_ += current.cost;
    if (steps_.empty()) {
        // The intermediates are not part of the result.
        equirect_.reset();
        momentTexels_ = {};
        bright_.reset();
        image_ = {};
    }
    return !steps_.empty();
}

bool BakeJob::runFor(Clock::duration budget)
{
    const auto start = Clock::now();
    do {
        if (!step())
            return false;
    } while (Clock::now() - start < budget);
    // Done already (a cheap step, or a fast GPU): book it now rather than after the caller's
    // frame, which would count that frame into the step's time.
    if (inFlight_ && inFlight_->fence.signalled())
        retireStepInFlight();
    return true;
}

BakeResult BakeJob::runToCompletion()
{
    while (step()) {
    }
    return takeResult();
}

float BakeJob::progress() const
{
    if (steps_.empty())
        return 1.0f;
    return totalCost_ > 0.0 ? float(std::clamp(doneCost_ / totalCost_, 0.0, 1.0)) : 0.0f;
}

std::optional<BakePhase> BakeJob::currentPhase() const
{
    if (steps_.empty()) return std::nullopt;
    return steps_.front().phase;
}

BakeResult BakeJob::takeResult()
{
    if (failed_)
        throw std::logic_error("BakeJob::takeResult: the bake failed");
    if (!steps_.empty())
        throw std::logic_error("BakeJob::takeResult: the bake has " + std::to_string(steps_.size()) + " steps left");
    // Said here, whether the cubes were baked (cubeFormat) or read from the cache's record.
    if (result_.settings.precision == Precision::Half && result_.environmentCube.internalFormat == GL_RGBA32F)
        result_.notes.push_back("baked in 32-bit floats: the map is brighter than a half float holds (65504)");
    return std::move(result_);
}

} // namespace iblab::bake
