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
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfTileDescriptionAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <OpenEXR/ImfVersion.h>

#include "io/atomic_file.hpp"
#include "io/direct_reader.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"

namespace iblab {
namespace {

using direct_codec::DirectReader;
using direct_codec::toUInt8;

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

// Opens the file's decoder at the first read, not with the header: OpenEXR's InputFile and
// TiledInputFile allocate their block buffers as they open (a few scanlines or a tile per
// decoding thread), so a header declaring a 2^24-texel-wide data window or 8x2^24-texel
// tiles costs gigabytes of memory (19 GB mapped for the first; under AddressSanitizer, tens
// of seconds) before a caller could refuse it from header(). The loader checks the header
// first (environment.cpp), and reads only what it accepts.
class ExrReader final : public DirectReader {
public:
    ExrReader(std::string path, bool tiled, ExrLayout layout, ImageHeader header)
        : path_(std::move(path)), tiled_(tiled), layout_(std::move(layout))
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
        if (!openDecoder())
            return false;
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
    // Throws what OpenEXR throws for a file it cannot open (callers catch it).
    bool openDecoder()
    {
        if (scanlines_ || tiles_)
            return true;
        const ImageHeader& h = header_;
        // Guards every caller, the loader's own check of the tile size aside.
        if (tiled_ && std::uint64_t(h.tileWidth) * std::uint64_t(h.tileHeight) > kMaxTileTexels)
            return fail("tiles of " + std::to_string(h.tileWidth) + "x" + std::to_string(h.tileHeight) + " texels are too large to decode");
        if (tiled_)
            tiles_ = std::make_unique<Imf::TiledInputFile>(path_.c_str());
        else
            scanlines_ = std::make_unique<Imf::InputFile>(path_.c_str());
        // The file is opened a second time here, so it may have been replaced since its header
        // was read (a bake rewritten under a reader): the frame buffer is laid out for that
        // header, and a larger window would be decoded past it.
        const Imf::Header& opened = tiles_ ? tiles_->header() : scanlines_->header();
        const IMATH_NAMESPACE::Box2i& window = opened.dataWindow();
        int channelCount = 0;
        const std::optional<ExrLayout> layout = exrLayout(opened, channelCount);
        const bool sameTiles = !tiled_ || (opened.hasTileDescription() && int(opened.tileDescription().xSize) == h.tileWidth &&
                                           int(opened.tileDescription().ySize) == h.tileHeight);
        if (window.min.x != h.x || window.min.y != h.y || std::int64_t(window.max.x) - window.min.x + 1 != h.width ||
            std::int64_t(window.max.y) - window.min.y + 1 != h.height || !sameTiles || !layout ||
            layout->channels != layout_.channels || layout->storedType != layout_.storedType) {
            scanlines_.reset();
            tiles_.reset();
            return fail("the file changed between reading its header and its pixels");
        }
        return true;
    }

    std::string path_;
    bool tiled_ = false;
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
    // The header alone, checked as InputFile checks it; the decoder opens at the first read.
    Imf::Header header;
    {
        Imf::StdIFStream stream(path.c_str());
        stream.seekg(8); // past the magic number and the version field
        int versionField = *version;
        header.readFrom(stream, versionField);
        header.sanityCheck(Imf::isTiled(*version));
    }
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
    if (header.hasTileDescription()) {
        const Imf::TileDescription& tile = header.tileDescription();
        if (tile.xSize > unsigned(INT_MAX) || tile.ySize > unsigned(INT_MAX))
            return nullptr;
        h.tileWidth = int(tile.xSize);
        h.tileHeight = int(tile.ySize);
    }
    if (const auto* colorSpace = header.findTypedAttribute<Imf::StringAttribute>("oiio:ColorSpace"))
        h.colorSpace = colorSpace->value();
    return std::make_unique<ExrReader>(path, Imf::isTiled(*version), std::move(*layout), std::move(h));
}

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
