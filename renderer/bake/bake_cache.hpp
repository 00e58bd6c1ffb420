#pragma once
// The on-disk cache of bakes, so that an environment baked once with given settings is
// loaded instead of recomputed.
//
//   <root>/bake/<key>/...       a bake directory (bake_files.hpp), key = hash of the input
//                               pixels (Environment::contentHash), every setting that
//                               changes the output and the shaders (bakeShaderFingerprint)
//   <root>/lut/<key>.exr        one BRDF LUT, key = its own (size, samples, geometry) and the
//                               shaders only: it depends on no environment
//   <root>/source/<key>.json    what a file decoded to when it was last loaded (its content
//                               hash and size), key = its absolute path, size and
//                               modification time: a bake can then be read from the cache
//                               while the file decodes, not after (the GUI's environment
//                               switch). The decoded pixels' hash is still checked; a
//                               record that no longer matches only costs that overlap.
//
// root: $IBLAB_CACHE_DIR if set (tests), else $XDG_CACHE_HOME/iblab, else $HOME/.cache/iblab.
// A cache without a root (enabled() false: `--no-cache`, or none of the variables set) reads
// and writes no files but still keeps the LUTs in memory: they depend on no environment, and
// baking them again for every map of a batch or every environment of a GUI session would cost
// more than the map's own bake (~140 ms of the default LUTs on llvmpipe).
// Files are written atomically (a reader never sees half a file) and bake.json last (an
// entry without it is incomplete: a miss). A corrupt file (truncated EXR, bad JSON, wrong
// size) is reported as one line naming it, the entry is removed and the bake is redone.
// Failing to write the cache (read-only disk) is reported the same way and is not an error.
// The EXRs use kCacheExrCompression ($IBLAB_CACHE_EXR_COMPRESSION overrides it, for
// scripts/measure-bake.sh writes, which measured the choice: docs/bake.md).
//
// Stores read the textures back on the calling (GL) thread and write the files on a
// background thread, which would otherwise stall the frame (GUI) or the bake's timing. The
// files are renamed into place atomically but not fsync'd (Durability::NoFlush): about
// 10 ms a file here, more than the rest of the write, and an entry a power cut leaves
// short is caught when it is read (a corrupt entry: reported, removed and baked again). A lookup waits
// for the writes in flight to its own entry, so a store followed by a load always hits, and
// for no other: a batch's next map bakes while the previous one's files are written.
#include <future>
#include <map>
#include <mutex>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bake/bake_files.hpp"
#include "bake/bake_result.hpp"
#include "gl/shader_library.hpp"

namespace iblab::bake {

// Empty when none of the variables is set.
std::filesystem::path defaultCacheDirectory();

// FNV-1a 64 of every file under the roots' bake/ and common/ folders (the bake's shaders and
// what they include), each with its path relative to its root, in path order: part of every
// cache key, so that an edited or updated shader is never answered with a bake made by the
// one before. Reads them each time (about 30 files, 160 KB), so a GUI session's hot-reloaded
// shaders count from its next bake on.
std::uint64_t bakeShaderFingerprint(const gl::ShaderSearchPath& roots);

inline constexpr const char* kCacheExrCompression = "none";

class BakeCache {
public:
    explicit BakeCache(std::filesystem::path root = defaultCacheDirectory());
    ~BakeCache(); // waits for the writes in flight
    BakeCache(const BakeCache&) = delete;
    BakeCache& operator=(const BakeCache&) = delete;

    const std::filesystem::path& root() const { return root_; }
    bool enabled() const { return !root_.empty(); }

    // 16 hex digits: FNV-1a 64 of the format version, the content hash, the settings that
    // affect the output (not the preset's name nor the step size) and the bake's shader sources
    // (bakeShaderFingerprint).
    static std::string bakeKey(std::uint64_t contentHash, const BakeSettings& settings, std::uint64_t shaderFingerprint);
    static std::string lutKey(int size, int samples, GeometryTerm term, std::uint64_t shaderFingerprint);
    std::filesystem::path bakeDirectory(const std::string& key) const;
    std::filesystem::path lutPath(const std::string& key) const;

    // Fills the environment-dependent part of result (environment cube, irradiance cubes,
    // prefiltered cube, SH) from the entry for result.contentHash and result.settings. Returns
    // false on a miss; a corrupt entry adds a line to notes, is removed, and is a miss.
    bool loadBake(BakeResult& result, const MipBuilder& buildMips, std::vector<std::string>& notes);
    void storeBake(const BakeResult& result);

    // Creates `out` (RGBA16F) from the LUT kept in memory or, for an enabled cache, its file;
    // false on a miss (a corrupt file: noted, removed).
    bool loadLut(int size, int samples, GeometryTerm term, std::uint64_t shaderFingerprint, BakedTexture& out, std::vector<std::string>& notes);
    // Keeps the LUT in memory and, for an enabled cache, writes its file.
    void storeLut(const BakedTexture& lut, int samples, GeometryTerm term, std::uint64_t shaderFingerprint);

    // What a file decoded to when it was last loaded, if the cache has a record of it and the
    // file's size and modification time are still those; nullopt for builtins, unknown or
    // changed files, and unreadable records.
    struct SourceRecord {
        std::uint64_t contentHash = 0;
        int width = 0;
        int height = 0;
    };
    std::optional<SourceRecord> findSource(const std::string& spec) const;
    // Records what spec decoded to (written in the background; builtins are not recorded).
    void rememberSource(const std::string& spec, const SourceRecord& record);

    // Waits for the background writes; returns one line for each that failed.
    std::vector<std::string> finishWrites();
    // The time the finished background writes took, summed (they run beside the caller).
    double writeMilliseconds();

private:
    struct PendingWrite {
        std::filesystem::path target; // the entry's directory or the LUT's file
        std::future<void> done;
    };
    void writeInBackground(std::filesystem::path target, std::function<void()> write);
    // The record's path for spec as the file is now; empty for builtins and missing files.
    std::filesystem::path sourceRecordPath(const std::string& spec) const;
    // Waits for the writes to `target` in flight, forgets the finished ones, and returns one
    // line for each write that failed so far.
    std::vector<std::string> settleWrites(const std::filesystem::path& target);

    std::filesystem::path root_;
    // The LUTs read or stored so far, by lutKey: every bake after the first in a process (a
    // batch, the GUI's next environment) uploads them from memory instead of decoding the
    // files again, or, without a root, instead of baking them again.
    std::map<std::string, Image2D> lutImages_;
    std::vector<PendingWrite> pending_;
    std::string exrCompression_;
    std::mutex notesMutex_; // guards the two below, which the writing threads update
    std::vector<std::string> writeNotes_; // failures of background writes, not yet collected
    double writeMilliseconds_ = 0.0;
};

} // namespace iblab::bake
