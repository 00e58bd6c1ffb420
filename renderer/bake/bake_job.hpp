#pragma once
// A bake as a job of small steps, so that the GUI can run a time-budgeted slice of it per
// frame and draw a progress bar, and the CLI can run it to the end:
//
//   BakeJob job(shaders, environment, settings, &cache);
//   while (job.runFor(std::chrono::milliseconds(8))) drawProgress(job.progress());   // GUI
//   BakeResult result = job.takeResult();
//   BakeResult result = BakeJob(shaders, environment, settings).runToCompletion();   // CLI
//
// A step is about settings.samplesPerStep texture samples of one pass on one mip (a band of
// rows of a face, or one or more whole faces), one SH projection, one cache read or write. Each
// step ends with a fence, and the next step first waits for the previous one's: the GPU runs a
// slice's last step while the caller draws its frame, at most one step's work is ever queued
// behind that frame, and no step stalls on glFinish. A step's time is the steady clock from
// its issue to its fence (llvmpipe's timer queries are wrong); in the GUI, a step still running
// when its slice ends also counts the frame drawn meanwhile. Needs the context that was current when the
// job was made to be current at every call. Step failures (a shader that does not compile,
// a GL error surfaced as an exception) propagate out of step(); the job is then failed.
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "bake/bake_cache.hpp"
#include "bake/bake_passes.hpp"
#include "bake/bake_result.hpp"
#include "io/environment.hpp"
#include "gl/fence.hpp"
#include "gl/shader_library.hpp"

namespace iblab::bake {

// Where a bake runs the host work that reads only the float map (the fitted lobe's shading
// lights, the bright-texel split's plan): Auto picks worker threads beside the GPU's passes on
// a hardware GPU and steps of their own, with no GL work in flight, on a software renderer
// (BakeJob::planHostWork()). Process-wide, read when a job is made; the other two force one
// way (`iblab bake --host-work`, tests).
enum class HostWorkPlacement { Auto, WorkerThreads, OwnSteps };
void setHostWorkPlacement(HostWorkPlacement placement);

class BakeJob {
public:
    // Keeps the environment's pixels: a copy (the caller may load another one meanwhile), or
    // moved in by a caller that needs them no longer. cache may be null (no cache), or
    // without a root (its LUTs in memory only, bake_cache.hpp); it must outlive the job.
    // Throws iblab::Error for invalid settings.
    BakeJob(gl::ShaderLibrary& shaders, Environment environment, const BakeSettings& settings, BakeCache* cache = nullptr);
    // A job for a map whose pixels are not decoded yet, from what the cache recorded of its
    // file (BakeCache::findSource): it only reads the cache (the bake's entry and the LUTs),
    // so that the bake is shown while the file decodes. If the entry is gone, the job ends
    // with missedCache() and a result without the environment's textures.
    BakeJob(gl::ShaderLibrary& shaders, const std::string& source, const BakeCache::SourceRecord& record, const BakeSettings& settings,
            BakeCache& cache);
    ~BakeJob();
    BakeJob(const BakeJob&) = delete;
    BakeJob& operator=(const BakeJob&) = delete;

    // Compiles the programs a bake with these settings runs, before its environment is
    // known, so that a caller can do it while the map loads (the job's Shaders step then
    // finds them built). The equirect's downsample program, which only some map sizes need,
    // is left to the step. cache as for the constructor.
    static void compilePrograms(gl::ShaderLibrary& shaders, const BakeSettings& settings, const BakeCache* cache);

    // Runs the next step; returns true while steps remain.
    bool step();
    // Runs steps until `budget` has passed (at least one step); returns true while steps remain.
    bool runFor(std::chrono::steady_clock::duration budget);
    // Runs every remaining step and returns the result.
    BakeResult runToCompletion();

    bool done() const { return steps_.empty(); }
    bool failed() const { return failed_; }
    bool missedCache() const { return missedCache_; }
    // Share of the estimated work done, 0..1 (work = texture samples; cache hits skip ahead).
    float progress() const;
    // The phase the next step belongs to (nullopt when done).
    std::optional<BakePhase> currentPhase() const;

    // The result, once done (throws std::logic_error before).
    BakeResult takeResult();

private:
    // A cache hit skips the rest of its group: the environment's results, or one LUT.
    enum class StepGroup { None, Environment, LutSchlickGgx, LutHeightCorrelatedSmith };
    static StepGroup lutGroup(GeometryTerm term);
    // The LUTs' program only when no cache could have them.
    static bool compilesLut(const BakeSettings& settings, const BakeCache* cache);
    // The bake's own entry is looked up and stored only in a cache with files; the LUTs in
    // any cache (bake_cache.hpp).
    bool diskCache() const { return cache_ && cache_->enabled(); }
    struct Step {
        BakePhase phase;
        StepGroup group;
        double cost = 1.0;
        std::function<void()> run;
        std::string part = {}; // BakeResult::partTimings's name after the phase's; empty: none
    };
    // A step whose commands are issued and whose fence has not been seen signalled yet.
    struct StepInFlight {
        BakePhase phase;
        std::chrono::steady_clock::time_point issued;
        gl::Fence fence;
        std::string part;
    };
    void plan();
    // The cubes' format: the settings' precision, or floats where the map is brighter than a
    // half float holds (takeResult adds a note saying so).
    GLenum cubeFormat() const;
    // An imported bake (Environment::imported): its cubes are uploaded, not baked.
    void planImported();
    void planIrradiance(int envFace);
    // The prefilter's first step, which runs or starts the host work that reads only the map;
    // true where it starts it on worker threads.
    void planUpload(GLenum format, int envFace, int envLevels, int equirectLevels);
    int momentGroupsPerEdge(int envFace) const;
    bool planHostWork(double sourceTexels, int envFace);
    // The split (or the wait for the worker threads) and every mip's slices.
    void planPrefilter(int envFace, bool hostWorkBeside);
    void planLuts();
    void planCubeSlices(BakePhase phase, StepGroup group, int faceSize, int level, double samplesPerTexel,
                        const std::function<void(const CubeSlice&)>& run, const std::string& part = {});
    void skipGroup(StepGroup group);
    // Waits for the step in flight, if any, and books its time.
    void retireStepInFlight();
    void addTiming(BakePhase phase, double ms);
    void addPartTiming(BakePhase phase, const std::string& part, double ms);

    BakePasses passes_;
    BakeCache* cache_;
    BakeResult result_;
    ImageRGB32F image_;
    std::shared_ptr<const ImportedBake> imported_;
    gl::Texture equirect_;
    MomentTexels momentTexels_; // irradiance_moments' groups, between its steps
    std::optional<PrefilterBrightTexels> bright_; // the prefilter's split, between its steps
    std::deque<Step> steps_;
    std::optional<StepInFlight> inFlight_;
    double totalCost_ = 0.0;
    double doneCost_ = 0.0;
    bool failed_ = false;
    bool missedCache_ = false;
    // Host work on worker threads (plan()), from image_: declared after it, so that a job
    // destroyed mid-bake waits for them before image_ goes.
    std::future<ShadingLights> shadingLights_;
    std::future<BrightSplitPlan> splitPlan_;
    // The moment irradiance's groups (equirect_moments.hpp), where host work runs beside the GPU.
    std::future<std::vector<glm::vec4>> momentGroups_;
};

} // namespace iblab::bake
