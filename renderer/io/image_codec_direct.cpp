#include "io/image_codec_direct.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <OpenEXR/ImfVersion.h>

#include "io/atomic_file.hpp"
#include "io/error.hpp"

namespace iblab {
namespace {

// OpenImageIO's float -> uint8 conversion: clamp to [0, 1], scale, round to nearest.
void toUInt8(const std::vector<float>& values, void* out)
{
    auto* bytes = static_cast<std::uint8_t*>(out);
    for (std::size_t i = 0; i < values.size(); ++i)
        bytes[i] = std::uint8_t(std::clamp(values[i], 0.0f, 1.0f) * 255.0f + 0.5f);
}

// The part shared by both readers: header, the error they recorded, and the requested
// type, which is decoded as float and converted for UInt8.
class DirectReader : public ImageReader {
public:
    const ImageHeader& header() const override { return header_; }
    bool hasError() const override { return !error_.empty(); }
    std::string takeError() override { return std::exchange(error_, {}); }

    bool readRows(int y0, int y1, int channels, PixelType type, void* out) override
    {
        const ImageHeader& h = header_;
        if (y0 < h.y || y1 > h.y + h.height || y0 >= y1 || channels < 1 || channels > 3 || out == nullptr)
            return fail("rows " + std::to_string(y0) + ".." + std::to_string(y1) + " or " + std::to_string(channels) +
                        " channels are outside the image");
        if (type != PixelType::Float && type != PixelType::UInt8)
            return fail("only float and 8-bit reads are supported");
        try {
            if (type == PixelType::Float)
                return readFloatRows(y0, y1, channels, static_cast<float*>(out));
            std::vector<float> values(std::size_t(y1 - y0) * std::size_t(h.width) * std::size_t(channels));
            if (!readFloatRows(y0, y1, channels, values.data()))
                return false;
            toUInt8(values, out);
            return true;
        } catch (const std::bad_alloc&) {
            return fail("out of memory");
        } catch (const std::exception& e) {
            return fail(e.what());
        }
    }

    bool readImage(int channels, PixelType type, void* out) override
    {
        return readRows(header_.y, header_.y + header_.height, channels, type, out);
    }

protected:
    virtual bool readFloatRows(int y0, int y1, int channels, float* out) = 0;
    bool fail(std::string why)
    {
        error_ = oneLine(why);
        return false;
    }
    ImageHeader header_;

private:
    std::string error_;
};

// ---- OpenEXR ----

struct ExrLayout {
    std::vector<std::string> channels; // read in this order: R, G, B, or the lone Y
    PixelType storedType = PixelType::Float;
};

// R, G and B (any other channels are skipped, as OpenImageIO's first three are R, G, B),
// or a file whose only colour channel is Y; half or float only (OpenImageIO scales uint
// channels to [0, 1], OpenEXR does not).
std::optional<ExrLayout> exrLayout(const Imf::Header& header, int& channelCount)
{
    const Imf::ChannelList& list = header.channels();
    std::map<std::string, Imf::PixelType> types;
    for (auto it = list.begin(); it != list.end(); ++it) {
        if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
            return std::nullopt;
        types[it.name()] = it.channel().type;
    }
    channelCount = int(types.size());
    ExrLayout layout;
    if (types.count("R") && types.count("G") && types.count("B"))
        layout.channels = {"R", "G", "B"};
    else if (types.count("Y") && (types.size() == 1 || (types.size() == 2 && types.count("A"))))
        layout.channels = {"Y"};
    else
        return std::nullopt;
    for (const std::string& name : layout.channels)
        if (types[name] != Imf::HALF && types[name] != Imf::FLOAT)
            return std::nullopt;
    layout.storedType = types[layout.channels.front()] == Imf::HALF ? PixelType::Half : PixelType::Float;
    return layout;
}

class ExrReader final : public DirectReader {
public:
    ExrReader(std::unique_ptr<Imf::InputFile> scanlines, std::unique_ptr<Imf::TiledInputFile> tiles, ExrLayout layout,
              ImageHeader header)
        : scanlines_(std::move(scanlines)), tiles_(std::move(tiles)), layout_(std::move(layout))
    {
        header_ = std::move(header);
    }

    // Rows [y0, y1) of the first `channels` channels, as `type` (OpenEXR converts from what
    // is stored), each pixel xStride bytes after the last; the bytes between are left alone.
    bool readSlices(int y0, int y1, int channels, Imf::PixelType type, char* out, std::size_t xStride)
    {
        const ImageHeader& h = header_;
        // Frame buffer for rows [y0, y1) only: Slice::Make places the base pointer, which
        // lies outside the buffer for rows before y0, inside OpenEXR.
        if (std::size_t(channels) > layout_.channels.size())
            return fail("cannot read " + std::to_string(channels) + " channels of a grey (Y) image");
        Imf::FrameBuffer frame;
        const std::size_t valueBytes = type == Imf::HALF ? sizeof(half) : sizeof(float);
        const std::size_t yStride = xStride * std::size_t(h.width);
        for (int c = 0; c < channels; ++c) {
            frame.insert(layout_.channels[std::size_t(c)],
                         Imf::Slice::Make(type, out + std::size_t(c) * valueBytes, IMATH_NAMESPACE::V2i(h.x, y0), h.width, y1 - y0, xStride, yStride));
        }
        if (tiles_) {
            // Whole tile rows, as OpenImageIO's read_tiles: the band must start one and end
            // one (or at the image's end), or tiles would be written past the buffer.
            const int first = y0 - h.y, end = y1 - h.y;
            if (first % h.tileHeight != 0 || (end % h.tileHeight != 0 && y1 != h.y + h.height))
                return fail("rows " + std::to_string(y0) + ".." + std::to_string(y1) + " are not whole tile rows");
            tiles_->setFrameBuffer(frame);
            tiles_->readTiles(0, tiles_->numXTiles(0) - 1, first / h.tileHeight, (end - 1) / h.tileHeight, 0, 0);
        } else {
            scanlines_->setFrameBuffer(frame);
            scanlines_->readPixels(y0, y1 - 1);
        }
        return true;
    }

protected:
    bool readFloatRows(int y0, int y1, int channels, float* out) override
    {
        return readSlices(y0, y1, channels, Imf::FLOAT, reinterpret_cast<char*>(out), sizeof(float) * std::size_t(channels));
    }

private:
    std::unique_ptr<Imf::InputFile> scanlines_;
    std::unique_ptr<Imf::TiledInputFile> tiles_;
    ExrLayout layout_;
};

// The int32 version field after the magic number: format 2, and its flags.
std::optional<int> exrVersion(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    char head[8] = {};
    if (!in.read(head, 8) || std::memcmp(head, kExrMagic, 4) != 0)
        return std::nullopt;
    std::int32_t version = 0;
    std::memcpy(&version, head + 4, 4);
    return version;
}

std::unique_ptr<ImageReader> openExr(const std::string& path)
{
    // OpenEXR decodes a file's blocks (32 to 256 rows for the lossy codecs) in parallel on
    // its global pool, which has no threads until told: OpenImageIO sizes it to the cores,
    // and so do we (DWAB's courtyard.exr decodes in about half the time on 2 cores).
    static std::once_flag threads;
    std::call_once(threads, [] { Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency()))); });
    const std::optional<int> version = exrVersion(path);
    if (!version || Imf::getVersion(*version) != 2 || Imf::isMultiPart(*version) || Imf::isNonImage(*version))
        return nullptr;
    std::unique_ptr<Imf::InputFile> scanlines;
    std::unique_ptr<Imf::TiledInputFile> tiles;
    if (Imf::isTiled(*version))
        tiles = std::make_unique<Imf::TiledInputFile>(path.c_str());
    else
        scanlines = std::make_unique<Imf::InputFile>(path.c_str());
    const Imf::Header& header = tiles ? tiles->header() : scanlines->header();
    int channelCount = 0;
    std::optional<ExrLayout> layout = exrLayout(header, channelCount);
    if (!layout)
        return nullptr;
    const IMATH_NAMESPACE::Box2i& window = header.dataWindow();
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width < 0 || width > INT_MAX || height < 0 || height > INT_MAX)
        return nullptr;
    ImageHeader h{.width = int(width),
                  .height = int(height),
                  .channels = channelCount,
                  .x = window.min.x,
                  .y = window.min.y,
                  .storedType = layout->storedType};
    if (tiles) {
        if (tiles->tileXSize() > unsigned(INT_MAX) || tiles->tileYSize() > unsigned(INT_MAX))
            return nullptr;
        h.tileWidth = int(tiles->tileXSize());
        h.tileHeight = int(tiles->tileYSize());
    }
    if (const auto* colorSpace = header.findTypedAttribute<Imf::StringAttribute>("oiio:ColorSpace"))
        h.colorSpace = colorSpace->value();
    return std::make_unique<ExrReader>(std::move(scanlines), std::move(tiles), std::move(*layout), std::move(h));
}

// ---- Radiance .hdr ----
//
// Decoded here, as Radiance's rgbe.c (and OpenImageIO's copy of it) does, rather than by
// stb_image: stb_image loops forever on a run of length 0 (a corrupt or truncated file, as
// the fuzz corpus's truncated-hdr is), and decodes the whole map at once, where this reads
// one scanline at a time.

// The header: "#?RADIANCE" or "#?RGBE", lines up to an empty one (FORMAT=32-bit_rle_rgbe
// among them), then "-Y <height> +X <width>", the only orientation taken here.
struct HdrHeader {
    int width = 0, height = 0;
    std::size_t bytes = 0; // up to and including the resolution line's newline
};

std::optional<HdrHeader> parseHdrHeader(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string text(64 * 1024, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(std::size_t(in.gcount()));
    std::size_t pos = 0;
    auto nextLine = [&](std::string& line) {
        const std::size_t end = text.find('\n', pos);
        if (end == std::string::npos)
            return false;
        line = text.substr(pos, end - pos);
        pos = end + 1;
        return true;
    };
    std::string line;
    if (!nextLine(line) || (line != "#?RADIANCE" && line != "#?RGBE"))
        return std::nullopt;
    bool rgbe = false;
    for (;;) {
        if (!nextLine(line))
            return std::nullopt;
        if (line.empty())
            break;
        if (line.starts_with("FORMAT=")) {
            if (line != "FORMAT=32-bit_rle_rgbe")
                return std::nullopt;
            rgbe = true;
        }
        if (line.starts_with("GAMMA=")) // OpenImageIO interprets it
            return std::nullopt;
    }
    if (!rgbe || !nextLine(line) || !line.starts_with("-Y "))
        return std::nullopt;
    char* rest = nullptr;
    errno = 0;
    const long height = std::strtol(line.c_str() + 3, &rest, 10);
    while (*rest == ' ')
        ++rest;
    if (std::strncmp(rest, "+X ", 3) != 0)
        return std::nullopt;
    char* end = nullptr;
    const long width = std::strtol(rest + 3, &end, 10);
    if (errno != 0 || *end != '\0' || width < INT_MIN || width > INT_MAX || height < INT_MIN || height > INT_MAX)
        return std::nullopt;
    return HdrHeader{int(width), int(height), pos};
}

// The pixel bytes through a buffer of our own: a scanline is read a byte or two at a time,
// which through std::ifstream cost ~35 ms for a 1024x512 map.
class ByteSource {
public:
    bool open(const std::string& path, std::size_t offset)
    {
        file_.reset(std::fopen(path.c_str(), "rb"));
        next_ = end_ = 0;
        return file_ && std::fseek(file_.get(), long(offset), SEEK_SET) == 0;
    }
    bool isOpen() const { return bool(file_); }
    bool read(std::uint8_t* out, std::size_t count)
    {
        while (count > 0) {
            if (next_ == end_ && !refill())
                return false;
            const std::size_t n = std::min(count, end_ - next_);
            std::memcpy(out, &buffer_[next_], n);
            next_ += n;
            out += n;
            count -= n;
        }
        return true;
    }

private:
    bool refill()
    {
        next_ = 0;
        end_ = std::fread(buffer_.data(), 1, buffer_.size(), file_.get());
        return end_ > 0;
    }
    struct Close {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    std::unique_ptr<std::FILE, Close> file_;
    std::vector<std::uint8_t> buffer_ = std::vector<std::uint8_t>(std::size_t(1) << 16);
    std::size_t next_ = 0, end_ = 0;
};

// rgbe.c's conversion: mantissas scaled by 2^(e - 136); e = 0 is black.
void rgbeToFloat(const std::uint8_t* rgbe, float* rgb)
{
    const float scale = rgbe[3] ? std::ldexp(1.0f, int(rgbe[3]) - (128 + 8)) : 0.0f;
    for (int c = 0; c < 3; ++c)
        rgb[c] = rgbe[3] ? float(rgbe[c]) * scale : 0.0f;
}

class HdrReader final : public DirectReader {
public:
    HdrReader(std::string path, const HdrHeader& parsed) : path_(std::move(path)), headerBytes_(parsed.bytes)
    {
        header_ = {.width = parsed.width, .height = parsed.height, .channels = 3, .storedType = PixelType::Float};
    }

protected:
    bool readFloatRows(int y0, int y1, int channels, float* out) override
    {
        if (y0 < nextRow_ || !in_.isOpen()) {
            // From the top: scanlines can only be decoded in order.
            nextRow_ = 0;
            flat_ = header_.width < 8 || header_.width > 0x7fff; // too narrow or wide to run-length encode
            if (!in_.open(path_, headerBytes_))
                return fail(std::string("cannot open: ") + std::strerror(errno));
        }
        const std::size_t width = std::size_t(header_.width);
        std::vector<float> rgb(width * 3);
        for (; nextRow_ < y1; ++nextRow_) {
            if (!decodeScanline(rgb.data()))
                return false;
            if (nextRow_ < y0)
                continue;
            for (std::size_t x = 0; x < width; ++x)
                for (int c = 0; c < channels; ++c)
                    *out++ = rgb[x * 3 + std::size_t(c)];
        }
        return true;
    }

private:
    bool truncated() { return fail("truncated: the file ends in scanline " + std::to_string(nextRow_)); }

    // One scanline as rgbe.c's RGBE_ReadPixels_RLE reads it: "2 2 hi lo" and four channels
    // of runs (count > 128: count - 128 copies of one byte) and dumps (count literal
    // bytes); anything else starts flat 4-byte texels, which then run to the image's end.
    bool decodeScanline(float* rgb)
    {
        const std::size_t width = std::size_t(header_.width);
        std::uint8_t texel[4];
        std::size_t first = 0;
        if (!flat_) {
            if (!in_.read(texel, 4))
                return truncated();
            if (texel[0] == 2 && texel[1] == 2 && (texel[2] & 0x80) == 0) {
                if ((std::size_t(texel[2]) << 8 | texel[3]) != width)
                    return fail("scanline " + std::to_string(nextRow_) + " has the wrong length");
                return decodeRunLengths(rgb);
            }
            flat_ = true;
            rgbeToFloat(texel, rgb);
            first = 1;
        }
        for (std::size_t x = first; x < width; ++x) {
            if (!in_.read(texel, 4))
                return truncated();
            rgbeToFloat(texel, rgb + x * 3);
        }
        return true;
    }

    bool decodeRunLengths(float* rgb)
    {
        const std::size_t width = std::size_t(header_.width);
        scanline_.resize(width * 4);
        for (std::size_t channel = 0; channel < 4; ++channel) {
            for (std::size_t x = 0; x < width;) {
                std::uint8_t code[2];
                if (!in_.read(code, 2))
                    return truncated();
                const bool run = code[0] > 128;
                const std::size_t count = run ? code[0] - 128u : code[0];
                if (count == 0 || count > width - x)
                    return fail("bad run-length data in scanline " + std::to_string(nextRow_));
                literals_[0] = code[1];
                if (!run && count > 1 && !in_.read(&literals_[1], count - 1))
                    return truncated();
                for (std::size_t k = 0; k < count; ++k)
                    scanline_[(x + k) * 4 + channel] = run ? code[1] : literals_[k];
                x += count;
            }
        }
        for (std::size_t x = 0; x < width; ++x)
            rgbeToFloat(&scanline_[x * 4], rgb + x * 3);
        return true;
    }

    std::string path_;
    std::size_t headerBytes_;
    ByteSource in_;
    int nextRow_ = 0;
    bool flat_ = false;
    std::vector<std::uint8_t> scanline_;
    std::uint8_t literals_[128] = {}; // a dump has at most 128 bytes
};

// ---- OpenEXR writing ----

// An OpenEXR output stream into memory, for one write of the whole file: OpenEXR hands each
// block to its stream as it is done, a scanline for the uncompressed and RLE files, and a
// file stream passes writes of 1 KB or more straight to the system (libstdc++'s filebuf):
// a system call per 1.5 KB scanline, about 3000 for a bake's files and most of their time.
class MemoryOStream final : public Imf::OStream {
public:
    MemoryOStream(const char* name, std::size_t expectedBytes) : Imf::OStream(name) { bytes_.reserve(expectedBytes + 16 * 1024); }
    void write(const char c[], int n) override
    {
        const std::size_t end = position_ + std::size_t(n);
        if (end > bytes_.size())
            bytes_.resize(end);
        std::memcpy(bytes_.data() + position_, c, std::size_t(n));
        position_ = end;
    }
    std::uint64_t tellp() override { return position_; }
    void seekp(std::uint64_t position) override { position_ = std::size_t(position); }
    std::string_view bytes() const { return {bytes_.data(), bytes_.size()}; }

private:
    std::vector<char> bytes_;
    std::size_t position_ = 0;
};

std::optional<Imf::Compression> exrCompression(const std::string& name)
{
    static const std::map<std::string, Imf::Compression> byName = {
        {"none", Imf::NO_COMPRESSION},     {"rle", Imf::RLE_COMPRESSION},   {"zips", Imf::ZIPS_COMPRESSION},
        {"zip", Imf::ZIP_COMPRESSION},     {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
        {"b44", Imf::B44_COMPRESSION},     {"b44a", Imf::B44A_COMPRESSION}, {"dwaa", Imf::DWAA_COMPRESSION},
        {"dwab", Imf::DWAB_COMPRESSION}};
    const auto it = byName.find(name);
    return it == byName.end() ? std::nullopt : std::optional(it->second);
}

} // namespace

ImageFileKind sniffImageFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    char head[11] = {};
    in.read(head, sizeof head);
    const std::string_view bytes(head, std::size_t(in.gcount()));
    if (bytes.starts_with(std::string_view(kExrMagic, 4)))
        return ImageFileKind::OpenExr;
    if (bytes.starts_with("#?RADIANCE\n") || bytes.starts_with("#?RGBE\n"))
        return ImageFileKind::RadianceHdr;
    return ImageFileKind::Other;
}

std::unique_ptr<ImageReader> openExrDirect(const std::string& path)
{
    try {
        return openExr(path);
    } catch (const std::exception&) {
        return nullptr; // OpenImageIO reads it again and reports its own error, as before
    }
}

void readExrDirect(const std::string& path, const ExrPixelTarget& target)
{
    std::unique_ptr<ImageReader> reader;
    try {
        reader = openExr(path);
    } catch (const std::exception& e) {
        throw Error(path, oneLine(e.what()));
    }
    auto* exr = dynamic_cast<ExrReader*>(reader.get());
    if (!exr)
        throw Error(path, "not an OpenEXR image with R, G and B channels");
    const ImageHeader& h = exr->header();
    if (h.width != target.width || h.height != target.height)
        throw Error(path, "is " + std::to_string(h.width) + "x" + std::to_string(h.height) + ", expected " + std::to_string(target.width) +
                              "x" + std::to_string(target.height));
    const Imf::PixelType type = target.type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
    const std::size_t valueBytes = type == Imf::HALF ? sizeof(half) : sizeof(float);
    bool read = false;
    try {
        read = exr->readSlices(h.y, h.y + h.height, target.channels, type, static_cast<char*>(target.data),
                               valueBytes * std::size_t(target.pixelValues));
    } catch (const std::exception& e) {
        throw Error(path, "cannot read pixels: " + oneLine(e.what()));
    }
    if (!read)
        throw Error(path, "cannot read pixels: " + exr->takeError());
}

std::unique_ptr<ImageReader> openHdrDirect(const std::string& path)
{
    const std::optional<HdrHeader> header = parseHdrHeader(path);
    if (!header)
        return nullptr;
    return std::make_unique<HdrReader>(path, *header);
}

bool writeExrDirect(const std::string& subject, const std::string& file, const ImageWrite& image)
{
    std::vector<std::string> names = image.channelNames;
    if (names.empty() && (image.channels == 3 || image.channels == 4))
        names = image.channels == 3 ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"R", "G", "B", "A"};
    std::optional<Imf::Compression> compression = Imf::ZIP_COMPRESSION;
    std::vector<std::pair<std::string, std::string>> strings;
    for (const auto& [name, value] : image.attributes) {
        if (name == "compression")
            compression = std::holds_alternative<std::string>(value) ? exrCompression(std::get<std::string>(value)) : std::nullopt;
        else if (std::holds_alternative<std::string>(value))
            strings.emplace_back(name == "ImageDescription" ? "comments" : name, std::get<std::string>(value));
        else
            return false;
    }
    if (std::string(image.format) != "openexr" || !compression || int(names.size()) != image.channels || image.width <= 0 ||
        image.height <= 0 || (image.storedType != PixelType::Half && image.storedType != PixelType::Float) ||
        (image.dataType != PixelType::Float && image.dataType != image.storedType))
        return false;

    Imf::Header header(image.width, image.height);
    header.compression() = *compression;
    const Imf::PixelType stored = image.storedType == PixelType::Half ? Imf::HALF : Imf::FLOAT;
    for (const std::string& name : names)
        header.channels().insert(name, Imf::Channel(stored));
    for (const auto& [name, value] : strings)
        header.insert(name, Imf::StringAttribute(value));

    const std::size_t valueBytes = stored == Imf::HALF ? sizeof(half) : sizeof(float);
    const std::size_t dataValueBytes = image.dataType == PixelType::Half ? sizeof(half) : sizeof(float);
    const std::ptrdiff_t pixelStride = image.pixelStride > 0 ? image.pixelStride : std::ptrdiff_t(dataValueBytes) * image.channels;
    const auto* first = static_cast<const char*>(image.firstRow);
    // Rows already in the stored type and top-down (a GL read-back written as is) are read
    // by OpenEXR where they are. OpenEXR neither converts on output nor takes negative
    // (bottom-up) strides: other rows are copied top-down in the stored type first, half as
    // Imath rounds it, as OpenImageIO does.
    const char* base = first;
    std::ptrdiff_t xStride = pixelStride;
    std::ptrdiff_t yStride = image.rowStride;
    std::vector<char> pixels;
    if (image.dataType != image.storedType || image.rowStride <= 0) {
        const std::size_t rowValues = std::size_t(image.width) * std::size_t(image.channels);
        pixels.resize(rowValues * std::size_t(image.height) * valueBytes);
        for (int y = 0; y < image.height; ++y) {
            const char* row = first + image.rowStride * y;
            char* out = &pixels[rowValues * valueBytes * std::size_t(y)];
            for (int x = 0; x < image.width; ++x)
                for (int c = 0; c < image.channels; ++c, out += valueBytes) {
                    const char* value = row + pixelStride * x + std::ptrdiff_t(dataValueBytes) * c;
                    if (image.dataType == image.storedType) {
                        std::memcpy(out, value, valueBytes);
                    } else {
                        float f;
                        std::memcpy(&f, value, sizeof f);
                        const half h(f);
                        std::memcpy(out, &h, sizeof h);
                    }
                }
        }
        base = pixels.data();
        xStride = std::ptrdiff_t(valueBytes) * image.channels;
        yStride = std::ptrdiff_t(rowValues * valueBytes);
    }
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < names.size(); ++c)
        frame.insert(names[c], Imf::Slice(stored, const_cast<char*>(base) + c * valueBytes, std::size_t(xStride), std::size_t(yStride)));
    const int threads = Imf::globalThreadCount();
    MemoryOStream encoded(file.c_str(), std::size_t(image.width) * std::size_t(image.height) * names.size() * valueBytes);
    rethrowAsError(subject, "writing", "cannot write", [&] {
        // The block offsets are written as `out` closes.
        if (image.tileSize > 0) {
            header.setTileDescription(Imf::TileDescription(unsigned(image.tileSize), unsigned(image.tileSize), Imf::ONE_LEVEL));
            Imf::TiledOutputFile out(encoded, header, threads);
            out.setFrameBuffer(frame);
            out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
        } else {
            Imf::OutputFile out(encoded, header, threads);
            out.setFrameBuffer(frame);
            out.writePixels(image.height);
        }
    });
    writeWholeFile(file, encoded.bytes());
    return true;
}

} // namespace iblab
