#include "scene/internal/image_codec.hpp"

#include <algorithm>
#include <memory>

#include "io/error.hpp"
#include "io/image_codec.hpp"
#include "scene/internal/gltf_document.hpp"

namespace iblab::scene_detail {
namespace {

// OpenImageIO keeps unretrieved error texts per thread; ImageReader::takeError fetches
// them so that they neither pile up nor surface in a later, unrelated message.
std::string describeError(std::string text)
{
    text = oneLine(text);
    return text.empty() ? "unrecognised or corrupt image data" : text;
}

// Copies one texel of `channels` 8-bit values as RGBA: grey is replicated, grey + alpha
// keeps its alpha, a missing alpha is opaque, channels past the fourth are dropped.
void toRgba(const std::uint8_t* src, int channels, std::uint8_t* dst)
{
    if (channels <= 2) {
        dst[0] = dst[1] = dst[2] = src[0];
        dst[3] = channels == 2 ? src[1] : 255;
    } else {
        dst[0] = src[0];
        dst[1] = src[1];
        dst[2] = src[2];
        dst[3] = channels >= 4 ? src[3] : 255;
    }
}

} // namespace

std::optional<TextureImage> decodeImage(const std::vector<std::uint8_t>& encoded, int maxDimension, std::string& problem,
                                        std::string& note)
{
    if (encoded.empty()) {
        problem = "is empty";
        return std::nullopt;
    }
    // The name only hints the reader to try first (OpenImageIO tries all of them if that
    // one fails); it is never opened as a file, the proxy supplies the bytes.
    const std::string mime = sniffImageMimeType(encoded);
    const std::string hint = mime == "image/jpeg" ? "memory.jpg" : mime == "image/png" ? "memory.png" : "memory.img";
    // glTF colours are straight (unassociated) alpha, as openMemory reads them.
    std::string openError;
    const std::unique_ptr<ImageReader> in = imageCodec().openMemory(encoded, hint, openError);
    if (!in) {
        problem = "cannot be decoded: " + describeError(openError);
        return std::nullopt;
    }
    const ImageHeader& spec = in->header();
    const int width = spec.width, height = spec.height, channels = spec.channels;
    if (width < 1 || height < 1 || spec.depth > 1 || channels < 1) {
        problem = "has an unusable size " + std::to_string(width) + "x" + std::to_string(height) + " (" +
                  std::to_string(channels) + " channels)";
        return std::nullopt;
    }
    const std::int64_t hardLimit = 8 * std::int64_t(std::max(maxDimension, 1));
    if (width > hardLimit || height > hardLimit) {
        problem = "claims " + std::to_string(width) + "x" + std::to_string(height) + " texels, more than 8x the " +
                  std::to_string(maxDimension) + " texture size limit (ModelLoadOptions::maxTextureDimension)";
        return std::nullopt;
    }
    int factor = 1;
    while ((width + factor - 1) / factor > maxDimension || (height + factor - 1) / factor > maxDimension) factor *= 2;

    TextureImage image;
    image.width = (width + factor - 1) / factor;
    image.height = (height + factor - 1) / factor;
    image.rgba8.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
    const auto fail = [&] {
        problem = "cannot be decoded: " + describeError(in->takeError());
        return std::nullopt;
    };

    if (factor == 1) {
        std::vector<std::uint8_t> texels(std::size_t(width) * std::size_t(height) * std::size_t(channels));
        if (!in->readImage(channels, PixelType::UInt8, texels.data()))
            return fail();
        for (std::size_t i = 0, n = std::size_t(width) * std::size_t(height); i < n; ++i)
            toRgba(&texels[i * std::size_t(channels)], channels, &image.rgba8[i * 4]);
        return image;
    }

    // Box filter: each output texel averages the factor x factor input block (clipped at
    // the right and bottom edges), accumulated one input scanline at a time.
    std::vector<std::uint8_t> row(std::size_t(width) * std::size_t(channels));
    std::vector<std::uint32_t> sums(std::size_t(image.width) * 4);
    std::vector<std::uint32_t> counts(std::size_t(image.width));
    for (int y = 0; y < height; ++y) {
        if (!in->readRows(spec.y + y, spec.y + y + 1, channels, PixelType::UInt8, row.data()))
            return fail();
        for (int x = 0; x < width; ++x) {
            std::uint8_t texel[4];
            toRgba(&row[std::size_t(x) * std::size_t(channels)], channels, texel);
            const std::size_t o = std::size_t(x / factor);
            for (int c = 0; c < 4; ++c) sums[o * 4 + std::size_t(c)] += texel[c];
            ++counts[o];
        }
        if ((y + 1) % factor == 0 || y + 1 == height) {
            std::uint8_t* out = &image.rgba8[std::size_t(y / factor) * std::size_t(image.width) * 4];
            for (std::size_t o = 0; o < counts.size(); ++o)
                for (std::size_t c = 0; c < 4; ++c) out[o * 4 + c] = std::uint8_t((sums[o * 4 + c] + counts[o] / 2) / counts[o]);
            std::fill(sums.begin(), sums.end(), 0u);
            std::fill(counts.begin(), counts.end(), 0u);
        }
    }
    note = "is " + std::to_string(width) + "x" + std::to_string(height) + ", downsampled to " + std::to_string(image.width) +
           "x" + std::to_string(image.height) + " to fit the " + std::to_string(maxDimension) +
           " texture size limit (ModelLoadOptions::maxTextureDimension)";
    return image;
}

std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgba8)
{
    const ImageWrite image{.format = "png",
                           .width = width,
                           .height = height,
                           .channels = 4,
                           .firstRow = rgba8.data(),
                           .rowStride = std::ptrdiff_t(width) * 4,
                           .attributes = {{"oiio:UnassociatedAlpha", 1}}};
    return imageCodec().encode("PNG encoder", image);
}

} // namespace iblab::scene_detail
