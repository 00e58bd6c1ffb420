#pragma once
// A bake on disk: the layout the cache and `iblab bake --out DIR` share.
//
//   environment.exr            the environment cube, level 0 (lower mips are rebuilt)
//   irradiance_riemann.exr     when baked
//   irradiance_importance.exr  when baked
//   irradiance_moments.exr     when baked
//   prefiltered_mip<k>.exr     one file per mip, k = 0 .. levels - 1; in the cache, not the
//                              mirror mip when it is a copy of an environment level
//                              (bake.json: prefiltered.mirror_of_environment_level)
//   sh.json                    kSh9Convention, radiance / irradiance / windowed irradiance
//   bake.json                  written last: format, source, content hash, settings, sizes,
//                              formats, the list of files, the timings of the bake
//
// A cube level is one EXR "strip": width = face size, height = 6 x face size, face k (GL
// order +X, -X, +Y, -Y, +Z, -Z) in rows [k size, (k + 1) size), each face's row 0 (t = 0)
// first; RGB, half floats for half textures (lossless) or floats. A LUT is an EXR of
// size x size RGB whose first scanline is roughness near 0 (row 0 of the texture).
// Every file is written atomically (writeFileAtomic).
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/bake_result.hpp"
#include "bake/baked_texture.hpp"
#include "io/atomic_file.hpp"

namespace iblab::bake {

// 2: the mirror mip is not stored twice in the cache. Older entries have other keys
// (BakeCache::bakeKey hashes this) and a bake.json that readBakeDirectory refuses.
// 3: contentHash is XXH3 (was FNV-1a): the source records that map a file to its hash
// are versioned by this too, so none of the older hashes is looked up again.
inline constexpr int kBakeFormatVersion = 3;
// The LUT files' own, unchanged since version 1 of the bakes.
inline constexpr int kLutFormatVersion = 1;

// Whether a prefiltered level that is a texel copy of an environment level (the mirror,
// BakePasses::mirrorSourceLevel) gets a file of its own (`--out`: every mip a file, for
// other tools) or is copied from the environment's when read (the cache: stored once).
enum class MirrorFile { Written, FromEnvironment };

// A file of a stored bake that cannot be used: missing where listed, unreadable,
// truncated, the wrong size, or bad JSON. what() is one line naming the file.
struct BakeFileError : std::runtime_error {
    BakeFileError(const std::filesystem::path& file, const std::string& problem)
        : std::runtime_error(file.string() + ": " + problem), path(file)
    {
    }
    std::filesystem::path path;
};

// A bake's files in CPU memory: what the GL read-back gives, so that writing them (encoding,
// and fsyncs unless durability says not) can happen off the GL thread.
struct BakeSnapshot {
    struct CubeFile {
        std::string name; // "prefiltered_mip2.exr"
        StoredCubeLevel image; // written as stored: half textures as half EXRs, lossless
    };
    std::vector<CubeFile> cubes;
    std::string exrCompression = "zip"; // ImageWriteOptions::exrCompression
    Durability durability = Durability::Flush; // the cache's need no fsync (atomic_file.hpp)
    std::string shJson;
    std::string metaJson; // bake.json
};

// Reads the textures back (GL). extraJson: an object whose members are added to bake.json
// (e.g. the CLI's error report); may be empty.
BakeSnapshot snapshotBake(const BakeResult& result, const std::string& extraJson = {}, MirrorFile mirror = MirrorFile::Written);
// Writes the snapshot's files, bake.json last. No GL: may run on any thread.
void writeBakeSnapshot(const std::filesystem::path& directory, const BakeSnapshot& snapshot);
// Both, in turn.
void writeBakeDirectory(const std::filesystem::path& directory, const BakeResult& result, const std::string& extraJson = {});

// Whether directory/bake.json exists (a half-written entry has none: a plain miss).
bool hasBakeDirectory(const std::filesystem::path& directory);

// Reads what writeBakeDirectory wrote back into textures, given a result whose settings and
// source size say what to expect; throws BakeFileError for anything that does not match.
// buildMips fills the environment cube's mips from its level 0 (BakePasses::generateMips).
using MipBuilder = std::function<void(const BakedTexture&)>;
void readBakeDirectory(const std::filesystem::path& directory, BakeResult& result, const MipBuilder& buildMips);

// LUT files. multiscatterChannel false writes 0 in B (the `iblab lut` default).
void writeLutExr(const std::filesystem::path& path, const Image2D& lut, int samples, GeometryTerm term, bool multiscatterChannel,
                 bool halfPixels, const std::string& exrCompression = "zip", Durability durability = Durability::Flush);
// Throws BakeFileError unless the file is an RGB EXR of expectedSize^2.
Image2D readLutExr(const std::filesystem::path& path, int expectedSize);

// {"basis": kSh9Convention, "radiance": [[r,g,b] x 9], "irradiance": [...], "irradiance_windowed": [...],
//  "window": "...", "window_width": w}
std::string shJsonText(const ShResult& sh, int indent = 2);

} // namespace iblab::bake
