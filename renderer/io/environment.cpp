#include "io/environment.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <numeric>
#include <mutex>
#include <optional>
#include <sstream>
#include <string_view>

#include <unistd.h>
#include <xxhash.h>

#include "ibl/equirect.hpp"

#include "io/atomic_file.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "io/image_codec.hpp"
#include "ibl/conventions.hpp"
#include "ibl/luminance.hpp"

namespace iblab {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s)
{
    for (char& c : s)
        if (c >= 'A' && c <= 'Z')
            c = char(c - 'A' + 'a');
    return s;
}

std::string formatShort(double v, int precision = 3)
{
    std::ostringstream out;
    out.precision(precision);
    out << v;
    return out.str();
}

// Streams rows through the repair, accumulating the report. Row y of an H-row map.
class TexelRepairer {
public:
    TexelRepairer(int width, int height) : width_(width), height_(height) {}

    // Repairs row y in place and returns its largest component (after the repair).
    float row(float* rgb, int y)
    {
        const double omega = equirectTexelSolidAngle(y, width_, height_);
        if (const std::optional<CleanRow> clean = cleanRow(rgb)) {
            report.positiveEnergy += omega * clean->luminance;
            return clean->max;
        }
        double positive = 0.0;
        double negative = 0.0;
        float max = 0.0f;
        for (int x = 0; x < width_; ++x) {
            bool repaired = false;
            for (int c = 0; c < 3; ++c) {
                float& v = rgb[std::size_t(x) * 3 + std::size_t(c)];
                if (std::isnan(v)) {
                    ++report.nanComponents;
                } else if (std::isinf(v)) {
                    ++(v > 0 ? report.positiveInfComponents : report.negativeInfComponents);
                } else if (v < 0.0f) {
                    ++report.negativeComponents;
                    report.mostNegative = std::min(report.mostNegative, double(v));
                    negative += kLuminanceWeights[c] * -double(v);
                } else {
                    positive += kLuminanceWeights[c] * double(v);
                    if (v == 0.0f)
                        v = 0.0f; // -0.0 -> +0.0
                    max = std::max(max, v);
                    continue;
                }
                v = 0.0f;
                repaired = true;
            }
            report.repairedTexels += repaired ? 1 : 0;
        }
        report.positiveEnergy += omega * positive;
        report.negativeEnergy += omega * negative;
        return max;
    }

    TexelRepairReport report;

private:
    struct CleanRow {
        double luminance = 0.0; // sum over the row
        float max = 0.0f;
    };

    // Nearly every row of a map has nothing to repair. This pass, branch-free so that it
    // vectorises, proves that (NaN and negatives fail v >= 0, +Inf fails v <= FLT_MAX),
    // turns -0.0 into +0.0 and sums the luminance in independent lanes; a row with anything
    // to repair is left untouched for the counting loop. (The counting loop alone was most
    // of a 1024x512 map's ~12 ms of conversion after the decode.)
    std::optional<CleanRow> cleanRow(float* rgb) const
    {
        constexpr int kLanes = 8;
        double luminance[kLanes] = {};
        float max[kLanes] = {};
        bool clean = true;
        const int whole = width_ - width_ % kLanes;
        for (int x0 = 0; x0 < width_; x0 += kLanes) {
            const int lanes = x0 < whole ? kLanes : width_ - x0;
            for (int lane = 0; lane < lanes; ++lane) {
                float* t = rgb + std::size_t(x0 + lane) * 3;
                for (int c = 0; c < 3; ++c) {
                    clean &= (t[c] >= 0.0f) & (t[c] <= std::numeric_limits<float>::max());
                    max[lane] = std::max(max[lane], t[c]);
                }
                luminance[lane] += kLuminanceWeights[0] * double(t[0]) + kLuminanceWeights[1] * double(t[1]) + kLuminanceWeights[2] * double(t[2]);
            }
        }
        if (!clean)
            return std::nullopt;
        for (float* v = rgb; v != rgb + std::size_t(width_) * 3; ++v)
            *v += 0.0f; // -0.0 + +0.0 is +0.0; every other value is unchanged
        CleanRow row;
        for (int lane = 0; lane < kLanes; ++lane) {
            row.luminance += luminance[lane];
            row.max = std::max(row.max, max[lane]);
        }
        return row;
    }

    int width_;
    int height_;
};

// Energy-preserving equirect downsampling. Destination texel (i, j) is the solid-angle
// weighted mean of the source texels it overlaps: horizontally by overlap length (solid
// angle is uniform in u), vertically by the overlap in cos(theta). The sum of L * Omega
// over the map is therefore unchanged, and unlike Lanczos there are no negative lobes
// to ring around a sun. Rows are fed one at a time, so a huge file never sits in memory.
class EquirectDownsampler {
public:
    EquirectDownsampler(int srcWidth, int srcHeight, ImageRGB32F& dst)
        : srcHeight_(srcHeight), dst_(dst), rowTmp_(std::size_t(dst.width) * 3)
    {
        const double scale = double(srcWidth) / dst.width;
        for (int i = 0; i < dst.width; ++i) {
            const double a = i * scale;
            const double b = std::min(double(srcWidth), (i + 1) * scale);
            Span span;
            span.first = int(std::floor(a));
            const int last = std::min(srcWidth - 1, int(std::ceil(b)) - 1);
            for (int c = span.first; c <= last; ++c)
                span.weights.push_back(float((std::min(b, c + 1.0) - std::max(a, double(c))) / scale));
            columns_.push_back(std::move(span));
        }
    }

    void addRow(const float* src, int y)
    {
        std::fill(rowTmp_.begin(), rowTmp_.end(), 0.0f);
        for (int i = 0; i < dst_.width; ++i) {
            const Span& span = columns_[std::size_t(i)];
            float* out = &rowTmp_[std::size_t(i) * 3];
            for (std::size_t k = 0; k < span.weights.size(); ++k) {
                const float* p = src + (std::size_t(span.first) + k) * 3;
                for (int c = 0; c < 3; ++c)
                    out[c] += span.weights[k] * p[c];
            }
        }
        const double s0 = kPi * y / srcHeight_;
        const double s1 = kPi * (y + 1) / srcHeight_;
        const int h = dst_.height;
        const int j0 = std::max(0, int(std::floor(s0 / kPi * h)));
        const int j1 = std::min(h - 1, int(std::ceil(s1 / kPi * h)));
        for (int j = j0; j <= j1; ++j) {
            const double d0 = kPi * j / h;
            const double d1 = kPi * (j + 1) / h;
            const double t0 = std::max(s0, d0);
            const double t1 = std::min(s1, d1);
            if (t1 <= t0)
                continue;
            const float w = float((std::cos(t0) - std::cos(t1)) / (std::cos(d0) - std::cos(d1)));
            float* out = &dst_.texels[dst_.offset(0, j)];
            for (std::size_t k = 0; k < rowTmp_.size(); ++k)
                out[k] += w * rowTmp_[k];
        }
    }

private:
    struct Span {
        int first = 0;
        std::vector<float> weights;
    };
    int srcHeight_;
    ImageRGB32F& dst_;
    std::vector<Span> columns_;
    std::vector<float> rowTmp_;
};

enum class Encoding { Linear, Srgb, Gamma, Rec709 };

// "1536x512 is 3:1", or "1000x431 is 2.32:1" when the reduced ratio is not small.
std::string aspectText(int w, int h)
{
    const int g = std::gcd(w, h);
    std::string text = std::to_string(w) + "x" + std::to_string(h) + " is ";
    if (w / g <= 32 && h / g <= 32)
        return text + std::to_string(w / g) + ":" + std::to_string(h / g);
    return text + formatShort(double(w) / h) + ":1";
}

// " (2^k)" for a power of two, which is how the limits are written in the docs.
std::string powerOfTwoText(std::uint64_t n)
{
    return std::has_single_bit(n) ? " (2^" + std::to_string(std::countr_zero(n)) + ")" : "";
}

std::string orFallback(std::string error, const char* fallback) { return error.empty() ? std::string(fallback) : error; }

// libpng prints "libpng error: ..." to stderr itself although OpenImageIO installs an error
// handler: the handler returns, so libpng falls back to its default one, which prints before
// it unwinds. OpenImageIO reports the same text through geterror(), which our one-line error
// already carries, so the print only breaks the one-line contract. While a file is read,
// stderr goes to a temporary file; afterwards every line except libpng's is written back, so
// no one else's output is lost (only delayed). fd 2 is process-wide: one reader at a time.
class LibpngStderrFilter {
public:
    LibpngStderrFilter() : lock_(processMutex())
    {
        std::fflush(stderr);
        capture_ = std::tmpfile();
        if (!capture_) return;
        savedStderr_ = ::dup(STDERR_FILENO);
        if (savedStderr_ < 0 || ::dup2(::fileno(capture_), STDERR_FILENO) < 0) {
            if (savedStderr_ >= 0) ::close(savedStderr_);
            std::fclose(capture_);
            capture_ = nullptr;
        }
    }
    ~LibpngStderrFilter()
    {
        if (!capture_) return;
        std::fflush(stderr);
        ::dup2(savedStderr_, STDERR_FILENO);
        ::close(savedStderr_);
        std::rewind(capture_);
        char line[1024];
        while (std::fgets(line, sizeof line, capture_))
            if (std::strncmp(line, "libpng ", 7) != 0) std::fputs(line, stderr);
        std::fclose(capture_);
    }
    LibpngStderrFilter(const LibpngStderrFilter&) = delete;
    LibpngStderrFilter& operator=(const LibpngStderrFilter&) = delete;

private:
    static std::mutex& processMutex()
    {
        static std::mutex mutex;
        return mutex;
    }
    std::lock_guard<std::mutex> lock_;
    std::FILE* capture_ = nullptr;
    int savedStderr_ = -1;
};

// Refuses what no environment is (deep, volume, no pixels or channels, not 2:1, too small)
// and what would cost too much to read, all from the header, before anything is allocated.
void checkHeader(const std::string& path, const ImageHeader& spec, const EnvironmentLoadOptions& options)
{
    if (spec.deep)
        throw Error(path, "deep images are not supported");
    if (spec.width <= 0 || spec.height <= 0)
        throw Error(path, "image has no pixels (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ")");
    if (spec.depth > 1)
        throw Error(path, "volume images are not supported (depth " + std::to_string(spec.depth) + ")");
    if (spec.channels < 1)
        throw Error(path, "image has no channels");
    const std::uint64_t texels = std::uint64_t(spec.width) * std::uint64_t(spec.height);
    if (texels > options.maxSourceTexels)
        throw Error(path, std::to_string(spec.width) + "x" + std::to_string(spec.height) + " is " +
                              std::to_string(texels) + " texels, more than the limit of " +
                              std::to_string(options.maxSourceTexels) + powerOfTwoText(options.maxSourceTexels));
    // Below this an "environment" is a handful of colours, and 1x1 passes the aspect check
    // by rounding: refuse it rather than bake a cube of 1-texel faces.
    if (spec.width < kMinEnvironmentWidth || spec.height < kMinEnvironmentWidth / 2)
        throw Error(path, "too small for an environment: " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                              " (at least " + std::to_string(kMinEnvironmentWidth) + "x" + std::to_string(kMinEnvironmentWidth / 2) + ")");
    // Equirect maps are 2:1; allow one texel of rounding either way.
    if (std::abs(std::int64_t(spec.width) - 2 * std::int64_t(spec.height)) > 1)
        throw Error(path, "not equirectangular: " + aspectText(spec.width, spec.height) + ", expected 2:1");
    // Tiles larger than the image are legal (a 64x64 tile on a 16x8 map), but a header can
    // declare any size, and the reader decodes a whole tile row at once: refuse absurd ones
    // before anything is allocated for them.
    const std::uint64_t tileTexels = std::uint64_t(std::max(spec.tileWidth, 0)) * std::uint64_t(std::max(spec.tileHeight, 0));
    if (tileTexels > kMaxTileTexels)
        throw Error(path, "tiles of " + std::to_string(spec.tileWidth) + "x" + std::to_string(spec.tileHeight) + " are " +
                              std::to_string(tileTexels) + " texels each, more than the limit of " +
                              std::to_string(kMaxTileTexels) + powerOfTwoText(kMaxTileTexels));
    if (options.maxWidth < 2 || options.maxWidth % 2 != 0)
        throw Error(path, "invalid size cap maxWidth=" + std::to_string(options.maxWidth) + " (must be even and >= 2)");
}

// The inverse of BT.709's opto-electronic transfer function (ITU-R BT.709-6, item 1.2:
// V = 4.5 L below L = 0.018, else 1.099 L^0.45 - 0.099).
float rec709ToLinear(float v)
{
    return v < 0.081f ? v / 4.5f : std::pow((v + 0.099f) / 1.099f, 1.0f / 0.45f);
}

// How the stored values are encoded: what the header's colour space says, else sRGB for
// integer images (display-referred); an unknown colour space is read as linear, with a warning.
struct StoredEncoding {
    Encoding encoding = Encoding::Linear;
    float gamma = 1.0f;
    bool eightBit = false;
};

StoredEncoding storedEncoding(const ImageHeader& spec, std::vector<std::string>& warnings)
{
    const PixelType base = spec.storedType;
    const bool eightBit = base == PixelType::UInt8 || base == PixelType::Int8;
    const bool integer = eightBit || base == PixelType::UInt16 || base == PixelType::Int16;
    const std::string& colorSpace = spec.colorSpace;
    const std::string cs = lower(colorSpace);
    StoredEncoding stored;
    Encoding& encoding = stored.encoding;
    float& gamma = stored.gamma;
    if (cs.starts_with("srgb") && cs != "srgb_linear" && cs != "srgb-linear") {
        encoding = Encoding::Srgb;
    } else if (cs.starts_with("gamma")) {
        // OpenImageIO spells it "Gamma2.2" or "GammaCorrected2.2".
        const std::size_t digit = cs.find_first_of("0123456789");
        gamma = digit == std::string::npos ? 2.2f : std::strtof(cs.c_str() + digit, nullptr);
        encoding = gamma > 0.0f && gamma != 1.0f ? Encoding::Gamma : Encoding::Linear;
    } else if (cs == "rec709") {
        // OpenImageIO names every PNM file "Rec709": netpbm's PPM and PGM samples carry
        // BT.709's transfer function, while a PFM's floats are linear by that format's own
        // convention.
        encoding = integer ? Encoding::Rec709 : Encoding::Linear;
    } else if (cs.empty() && integer) {
        encoding = Encoding::Srgb; // integer images that name no colour space are display-referred
    } else if (!cs.empty() && cs.find("lin") == std::string::npos && cs != "raw" && cs.find("aces") == std::string::npos &&
               cs != "scene_linear") {
        warnings.push_back("unknown colour space '" + colorSpace + "', treated as linear");
    }
    stored.eightBit = eightBit;
    return stored;
}

Environment loadFile(const std::string& path, const EnvironmentLoadOptions& options)
{
    const LibpngStderrFilter quietLibpng;
    std::error_code ec;
    requireFile(path);
    const fs::file_status status = fs::status(path, ec);
    if (fs::is_regular_file(status) && fs::file_size(path, ec) == 0 && !ec)
        throw Error(path, "empty file (0 bytes)");

    std::string openError;
    const std::unique_ptr<ImageReader> in = imageCodec().openFile(path, openError);
    if (!in)
        throw Error(path, "cannot read as an image: " + orFallback(openError, "unknown format"));
    const ImageHeader& spec = in->header();

    checkHeader(path, spec, options);

    const int srcW = spec.width;
    const int srcH = spec.height;
    const bool downsample = srcW > options.maxWidth || srcH > options.maxWidth / 2;
    Environment env;
    env.source = path;
    env.image = downsample ? ImageRGB32F(options.maxWidth, options.maxWidth / 2) : ImageRGB32F(srcW, srcH);

    const StoredEncoding stored = storedEncoding(spec, env.warnings);
    const Encoding encoding = stored.encoding;
    const float gamma = stored.gamma;
    const bool eightBit = stored.eightBit;

    // Read in bands of rows (whole tile rows for tiled files), decode, repair, store.
    const int channelsRead = spec.channels >= 3 ? 3 : 1; // grey (+alpha) -> replicate
    const int band = std::min(srcH, spec.tileWidth > 0 ? spec.tileHeight * std::max(1, 64 / std::max(1, spec.tileHeight)) : 64);
    // Linear RGB at its own size, the bundled maps' case: rows are decoded straight into the
    // image and repaired there, without the staging buffer and the copy.
    const bool direct = channelsRead == 3 && encoding == Encoding::Linear && !downsample;
    std::vector<float> buffer(direct ? 0 : std::size_t(band) * std::size_t(srcW) * std::size_t(channelsRead));
    std::vector<float> row(direct ? 0 : std::size_t(srcW) * 3);
    TexelRepairer repairer(srcW, srcH);
    std::optional<EquirectDownsampler> downsampler;
    if (downsample)
        downsampler.emplace(srcW, srcH, env.image);
    float maxValue = 0.0f;
    for (int y0 = 0; y0 < srcH; y0 += band) {
        const int y1 = std::min(srcH, y0 + band);
        float* rows = direct ? &env.image.texels[env.image.offset(0, y0)] : buffer.data();
        const bool ok = in->readRows(spec.y + y0, spec.y + y1, channelsRead, PixelType::Float, rows);
        if (!ok || in->hasError())
            throw Error(path, "cannot read pixels (truncated or corrupt file?): " + orFallback(in->takeError(), "no reason given"));
        if (direct) {
            for (int y = y0; y < y1; ++y)
                maxValue = std::max(maxValue, repairer.row(&env.image.texels[env.image.offset(0, y)], y));
            continue;
        }
        for (int y = y0; y < y1; ++y) {
            const float* src = &buffer[std::size_t(y - y0) * std::size_t(srcW) * std::size_t(channelsRead)];
            for (int x = 0; x < srcW; ++x)
                for (int c = 0; c < 3; ++c) {
                    float v = src[std::size_t(x) * std::size_t(channelsRead) + std::size_t(channelsRead == 3 ? c : 0)];
                    if (encoding == Encoding::Srgb)
                        v = srgbToLinear(v);
                    else if (encoding == Encoding::Gamma && v > 0.0f)
                        v = std::pow(v, gamma);
                    else if (encoding == Encoding::Rec709)
                        v = rec709ToLinear(v);
                    row[std::size_t(x) * 3 + std::size_t(c)] = v;
                }
            maxValue = std::max(maxValue, repairer.row(row.data(), y));
            if (downsampler)
                downsampler->addRow(row.data(), y);
            else
                std::memcpy(&env.image.texels[env.image.offset(0, y)], row.data(), row.size() * sizeof(float));
        }
    }
    env.repair = repairer.report;
    if (eightBit || maxValue <= 1.0f) {
        std::string w = eightBit ? "8-bit input" : "no value above 1 (max " + formatShort(maxValue) + ")";
        w += ": limited dynamic range, not an HDR environment; lighting will look flat";
        if (encoding == Encoding::Srgb)
            w += " (decoded from sRGB to linear)";
        else if (encoding == Encoding::Gamma)
            w += " (decoded from gamma " + formatShort(gamma) + " to linear)";
        else if (encoding == Encoding::Rec709)
            w += " (decoded from BT.709's transfer function to linear)";
        env.warnings.push_back(w);
    }
    if (downsample)
        env.warnings.push_back("downsampled from " + std::to_string(srcW) + "x" + std::to_string(srcH) + " to " +
                               std::to_string(env.image.width) + "x" + std::to_string(env.image.height) +
                               " (size cap " + std::to_string(options.maxWidth) + " wide)");
    if (!env.repair.clean())
        env.warnings.push_back(env.repair.summary());
    env.contentHash = contentHash(env.image);
    return env;
}

Environment loadBuiltin(const std::string& specText, const EnvironmentLoadOptions& options)
{
    const BuiltinSpec spec = parseBuiltinSpec(specText);
    const int width = int(spec.get("width"));
    if (width > options.maxWidth)
        throw Error(specText, "width " + std::to_string(width) + " exceeds the size cap of " +
                                  std::to_string(options.maxWidth));
    Environment env;
    env.source = spec.canonical();
    env.image = makeBuiltinEnvironment(spec);
    env.repair = repairTexels(env.image);
    if (!env.repair.clean())
        env.warnings.push_back(env.repair.summary());
    env.contentHash = contentHash(env.image);
    return env;
}

} // namespace

float srgbToLinear(float v)
{
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::string TexelRepairReport::summary() const
{
    if (clean())
        return "no invalid texels";
    std::ostringstream out;
    // A newcomer's first map should not read as damaged when nothing visible changed.
    if (negligible()) {
        out << "repaired " << negativeComponents << " slightly negative texel components to 0 (" << formatShort(100.0 * negativeEnergyShare(), 2)
            << "% of the light: negligible)";
        return out.str();
    }
    out << "repaired " << repairedComponents() << " texel components in " << repairedTexels << " texels (set to 0): "
        << negativeComponents << " negative";
    if (negativeComponents > 0)
        out << " down to " << formatShort(mostNegative, 4) << ", " << formatShort(100.0 * negativeEnergyShare(), 3)
            << "% of the positive energy";
    out << "; " << nanComponents << " NaN; " << positiveInfComponents << " +Inf; " << negativeInfComponents << " -Inf";
    return out.str();
}

TexelRepairReport repairTexels(ImageRGB32F& image)
{
    TexelRepairer repairer(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        repairer.row(&image.texels[image.offset(0, y)], y);
    return repairer.report;
}

std::uint64_t contentHash(const ImageRGB32F& image)
{
    // XXH3 of the texels' bytes as they lie in memory, seeded with the size. The cache
    // directories this keys may be shared between machines, which are all little-endian
    // where iblab builds (x86-64, arm64).
    static_assert(std::endian::native == std::endian::little, "contentHash keys caches by little-endian bytes");
    const std::uint64_t seed = (std::uint64_t(std::uint32_t(image.width)) << 32) | std::uint32_t(image.height);
    return XXH3_64bits_withSeed(image.texels.data(), image.texels.size() * sizeof(float), seed);
}

Environment loadEnvironment(const std::string& spec, const EnvironmentLoadOptions& options)
{
    if (spec.empty())
        throw Error("(no environment)", "empty file name");
    if (isBuiltinSpec(spec))
        return loadBuiltin(spec, options);
    if (isImportedBakeSpec(spec)) {
        Environment environment;
        environment.source = spec;
        environment.imported = rethrowAsError(spec, "reading the bake", "cannot read", [&] { return loadImportedBake(spec, environment.image); });
        environment.warnings = environment.imported->notes;
        environment.contentHash = contentHash(environment.image);
        return environment;
    }
    // The image libraries below OpenImageIO throw on their own (std::bad_alloc for a header
    // that asks for more than the machine has, std::exception from OpenEXR): every way out
    // of a file load is one Error naming the file.
    return rethrowAsError(spec, "reading (a corrupt header claiming a huge size?)", "cannot read", [&] { return loadFile(spec, options); });
}

bool isEnvironmentImagePath(const std::string& path)
{
    static constexpr std::string_view kExtensions[] = {".exr", ".hdr", ".pfm", ".tif", ".tiff", ".png", ".jpg", ".jpeg"};
    const std::string extension = lower(fs::path(path).extension().string());
    return std::find(std::begin(kExtensions), std::end(kExtensions), extension) != std::end(kExtensions);
}

const char* const kEnvironmentImageKinds = ".exr, .hdr, .pfm, .tif, .png or .jpg";

std::string defaultEnvironmentPath(const std::string& assetDir)
{
    return (fs::path(assetDir) / "environments" / "courtyard.exr").string();
}

std::vector<std::string> galleryEnvironments(const std::string& assetDir)
{
    std::vector<std::string> paths;
    std::error_code ec;
    const fs::path dir = fs::path(assetDir) / "environments";
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& p = it->path();
        const std::string name = p.filename().string();
        if (!name.empty() && name[0] != '.' && lower(p.extension().string()) == ".exr" && it->is_regular_file(ec))
            paths.push_back(p.string());
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

} // namespace iblab
