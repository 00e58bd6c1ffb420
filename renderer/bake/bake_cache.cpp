#include "bake/bake_cache.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <utility>

#include <nlohmann/json.hpp>

#include "bake/bake_files.hpp"
#include "io/error.hpp"
#include "io/atomic_file.hpp"
#include "io/builtin_environments.hpp"
#include "io/hash.hpp"

namespace iblab::bake {
namespace {

namespace fs = std::filesystem;

const char* envOrNull(const char* name)
{
    const char* v = std::getenv(name);
    return v && *v ? v : nullptr;
}

// Removing a corrupt entry must not throw over the report it follows.
void removeQuietly(const fs::path& path)
{
    std::error_code ec;
    fs::remove_all(path, ec);
}

} // namespace

std::uint64_t bakeShaderFingerprint(const gl::ShaderSearchPath& roots)
{
    std::uint64_t h = fnv1a("iblab-bake-shaders");
    for (const fs::path& root : roots)
        for (const char* folder : {"bake", "common"}) {
            std::error_code ec;
            std::vector<fs::path> files;
            for (fs::recursive_directory_iterator it(root / folder, ec), end; !ec && it != end; it.increment(ec))
                if (it->is_regular_file(ec))
                    files.push_back(it->path());
            std::sort(files.begin(), files.end());
            for (const fs::path& file : files) {
                std::ifstream in(file, std::ios::binary);
                const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
                h = fnv1a(file.lexically_relative(root).generic_string(), h);
                h = fnv1a(std::string_view("\0", 1), h);
                h = fnv1a(text, h);
            }
        }
    return h;
}

fs::path defaultCacheDirectory()
{
    if (const char* dir = envOrNull("IBLAB_CACHE_DIR"))
        return dir;
    if (const char* xdg = envOrNull("XDG_CACHE_HOME"))
        return fs::path(xdg) / "iblab";
    if (const char* home = envOrNull("HOME"))
        return fs::path(home) / ".cache" / "iblab";
    return {};
}

BakeCache::BakeCache(fs::path root) : root_(std::move(root))
{
    const char* compression = envOrNull("IBLAB_CACHE_EXR_COMPRESSION");
    exrCompression_ = compression ? compression : kCacheExrCompression;
}

BakeCache::~BakeCache() { finishWrites(); }

void BakeCache::writeInBackground(fs::path target, std::function<void()> write)
{
    pending_.push_back({std::move(target), std::async(std::launch::async, [this, write = std::move(write)] {
                            const auto start = std::chrono::steady_clock::now();
                            std::string failure;
                            try {
                                write();
                            } catch (const std::exception& e) {
                                failure = std::string("bake cache: not stored: ") + oneLine(e.what());
                            }
                            const std::lock_guard<std::mutex> lock(notesMutex_);
                            writeMilliseconds_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                            if (!failure.empty())
                                writeNotes_.push_back(std::move(failure));
                        })});
}

std::vector<std::string> BakeCache::settleWrites(const fs::path& target)
{
    std::erase_if(pending_, [&target](PendingWrite& write) {
        if (write.target == target)
            write.done.wait();
        return write.done.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    });
    const std::lock_guard<std::mutex> lock(notesMutex_);
    return std::exchange(writeNotes_, {});
}

std::vector<std::string> BakeCache::finishWrites()
{
    for (PendingWrite& write : pending_)
        write.done.wait();
    pending_.clear();
    const std::lock_guard<std::mutex> lock(notesMutex_);
    return std::exchange(writeNotes_, {});
}

double BakeCache::writeMilliseconds()
{
    const std::lock_guard<std::mutex> lock(notesMutex_);
    return writeMilliseconds_;
}

namespace {
// What this build's bake makes of given settings. The key holds every setting and the
// shaders' fingerprint (bakeShaderFingerprint), but a change to the host code that plans or
// feeds the passes changes the output of the same settings and shaders, and a cache written
// by an older build would then be read as this build's bake. Raise it with every such change.
// 2: bright lights merged at alpha / 2 and the rough mips' far cells capped at 8N. 3: mip 1
// refined where its samples disagree, its bases from the finest level its refined samples read. 4: mip 2 refined too. 5: the
// refinement's spread against the base's RMS in blocks as wide as the samples' footprint.
// 6: the bases near the bright texels resampled from the map clamped (near_lights.hpp).
// 7: mip 1's band of lights per tile. 8: mip 2's lights per tile, the rougher mips' caps
// four times the mip before's (tile_lights.hpp). 9: a map too coarse for mip 1's lobe baked
// from its bilinear upsample (bakeSourceUpsampleFactor). 10: mips 1 and 2 refined where
// their samples' standard error is large too (PrefilterSettings::refineError). 11: mip 2's
// lists four times as long where the base they leave is spiky (spikyBase). 12: mip 1's too.
// 13: the rough blocks' caps four times as large where their base is spiky at mip 2. 14: every
// cube in floats where the map is brighter than a half float holds (BakeJob::cubeFormat).
// 15: mip 2's refined set four times as large where its base is spiky. 16: a spiky base's
// lists merged coarser where a tile cannot hold them, and one-texel lines spiky at mip 1
// (spikyBaseRatio). 17: mip 1's refined set four times as large where its base is spiky too.
// 18: the refined sets' spikiness at w^(1/8) (kRefineSpikyExponent). 19: mip 1's over blocks
// twice as wide too. 20: the candidates' larger cap 16 times the cap (kSpikyCandidatesFactor),
// taken where the base is spiky over blocks twice as wide too. 21: a coarse map's upsample
// keeps each texel's flux at the poles (fluxConservingRowBlends). 22: the moment irradiance's
// groups summed over the map's texels (equirect_moments.hpp), not the environment cube's.
constexpr int kBakeOutputRevision = 22;
} // namespace

std::string BakeCache::bakeKey(std::uint64_t contentHash, const BakeSettings& settings, std::uint64_t shaderFingerprint)
{
    nlohmann::json j = nlohmann::json::parse(toJsonText(settings));
    j.erase("preset");
    j.erase("samples_per_step");
    // The factors as the text they were before they became a list, so that a cache written
    // then is still found.
    j["prefilter"]["mip_sample_scale"] = numberListText(settings.prefilter.mipSampleScale);
    return hex16(fnv1a("iblab-bake-" + std::to_string(kBakeFormatVersion) + "-r" + std::to_string(kBakeOutputRevision) + "|" + hex16(contentHash) +
                       "|" + hex16(shaderFingerprint) + "|" + j.dump()));
}

std::string BakeCache::lutKey(int size, int samples, GeometryTerm term, std::uint64_t shaderFingerprint)
{
    return "brdf_lut_" + std::string(enumName(term)) + "_" + std::to_string(size) + "_" + std::to_string(samples) + "_v" +
           std::to_string(kLutFormatVersion) + "_" + hex16(shaderFingerprint);
}

fs::path BakeCache::bakeDirectory(const std::string& key) const { return root_ / "bake" / key; }
fs::path BakeCache::lutPath(const std::string& key) const { return root_ / "lut" / (key + ".exr"); }

bool BakeCache::loadBake(BakeResult& result, const MipBuilder& buildMips, std::vector<std::string>& notes)
{
    if (!enabled())
        return false;
    const fs::path dir = bakeDirectory(bakeKey(result.contentHash, result.settings, result.shaderFingerprint));
    for (std::string& note : settleWrites(dir))
        notes.push_back(std::move(note));
    if (!hasBakeDirectory(dir))
        return false;
    try {
        readBakeDirectory(dir, result, buildMips);
        return true;
    } catch (const BakeFileError& e) {
        notes.push_back(std::string("bake cache: ") + e.what() + "; removed the entry and baked again");
        result.environmentCube = {};
        result.irradianceCube = {};
        result.prefiltered = {};
        removeQuietly(dir);
        return false;
    }
}

void BakeCache::storeBake(const BakeResult& result)
{
    if (!enabled())
        return;
    auto snapshot = std::make_shared<BakeSnapshot>(snapshotBake(result, {}, MirrorFile::FromEnvironment));
    snapshot->exrCompression = exrCompression_;
    snapshot->durability = Durability::NoFlush;
    const fs::path dir = bakeDirectory(bakeKey(result.contentHash, result.settings, result.shaderFingerprint));
    writeInBackground(dir, [dir, snapshot] { writeBakeSnapshot(dir, *snapshot); });
}

fs::path BakeCache::sourceRecordPath(const std::string& spec) const
{
    if (!enabled() || isBuiltinSpec(spec))
        return {};
    std::error_code ec;
    const fs::path file = fs::absolute(spec, ec);
    if (ec)
        return {};
    const auto size = fs::file_size(file, ec);
    if (ec)
        return {};
    const auto modified = fs::last_write_time(file, ec);
    if (ec)
        return {};
    // The loader's version too: a loader that repairs or converts pixels differently makes
    // other pixels of the same file.
    const std::string identity = "iblab-source-" + std::to_string(kBakeFormatVersion) + "|" + file.lexically_normal().string() + "|" +
                                 std::to_string(size) + "|" + std::to_string(modified.time_since_epoch().count());
    return root_ / "source" / (hex16(fnv1a(identity)) + ".json");
}

std::optional<BakeCache::SourceRecord> BakeCache::findSource(const std::string& spec) const
{
    const fs::path path = sourceRecordPath(spec);
    std::error_code ec;
    if (path.empty() || !fs::exists(path, ec))
        return std::nullopt;
    try {
        const nlohmann::json j = nlohmann::json::parse(readTextFile(path.string()));
        SourceRecord record{std::stoull(j.at("content_hash").get<std::string>(), nullptr, 16), j.at("width").get<int>(),
                            j.at("height").get<int>()};
        if (record.width <= 0 || record.height <= 0)
            return std::nullopt;
        return record;
    } catch (const std::exception&) {
        return std::nullopt; // a torn or foreign record is only a miss: the decode decides
    }
}

void BakeCache::rememberSource(const std::string& spec, const SourceRecord& record)
{
    const fs::path path = sourceRecordPath(spec);
    if (path.empty())
        return;
    const std::string text =
        nlohmann::json{{"source", spec}, {"content_hash", hex16(record.contentHash)}, {"width", record.width}, {"height", record.height}}.dump();
    writeInBackground(path, [path, text] {
        std::error_code ec;
        fs::create_directories(path.parent_path(), ec);
        if (ec)
            throw Error(path.parent_path().string(), "cannot create the directory: " + ec.message());
        writeTextFileAtomic(path.string(), text, Durability::NoFlush);
    });
}

bool BakeCache::loadLut(int size, int samples, GeometryTerm term, std::uint64_t shaderFingerprint, BakedTexture& out,
                        std::vector<std::string>& notes)
{
    const std::string key = lutKey(size, samples, term, shaderFingerprint);
    if (const auto kept = lutImages_.find(key); kept != lutImages_.end()) {
        out = create2DTexture(GL_RGBA16F, size);
        upload2D(out, kept->second);
        return true;
    }
    if (!enabled())
        return false;
    const fs::path path = lutPath(key);
    for (std::string& note : settleWrites(path))
        notes.push_back(std::move(note));
    if (!fs::exists(path))
        return false;
    try {
        const Image2D& image = lutImages_[key] = readLutExr(path, size);
        out = create2DTexture(GL_RGBA16F, size);
        upload2D(out, image);
        return true;
    } catch (const BakeFileError& e) {
        notes.push_back(std::string("bake cache: ") + e.what() + "; removed it and baked the LUT again");
        removeQuietly(path);
        removeQuietly(path.string() + ".json");
        return false;
    }
}

void BakeCache::storeLut(const BakedTexture& lut, int samples, GeometryTerm term, std::uint64_t shaderFingerprint)
{
    const std::string key = lutKey(lut.size, samples, term, shaderFingerprint);
    const Image2D& kept = lutImages_[key] = read2D(lut);
    if (!enabled())
        return;
    auto image = std::make_shared<Image2D>(kept);
    const fs::path path = lutPath(key);
    writeInBackground(path, [path, image, samples, term, compression = exrCompression_] {
        std::error_code ec;
        fs::create_directories(path.parent_path(), ec);
        if (ec)
            throw Error(path.parent_path().string(), "cannot create the directory: " + ec.message());
        writeLutExr(path, *image, samples, term, true, true, compression, Durability::NoFlush);
    });
}

} // namespace iblab::bake
