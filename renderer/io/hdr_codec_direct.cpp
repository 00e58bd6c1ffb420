#include "io/image_codec_direct.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/direct_reader.hpp"
#include "io/error.hpp"

namespace iblab {
namespace {

using direct_codec::DirectReader;

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

} // namespace

std::unique_ptr<ImageReader> openHdrDirect(const std::string& path)
{
    const std::optional<HdrHeader> header = parseHdrHeader(path);
    if (!header)
        return nullptr;
    return std::make_unique<HdrReader>(path, *header);
}

} // namespace iblab
