#include "io/image_writer.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_codec.hpp"

namespace iblab {
namespace {

// Validates and normalises the settings: compact for the metadata, indented for the file.
struct Settings {
    std::string compact;
    std::string pretty;
};

Settings parseSettings(const std::string& path, const std::string& json)
{
    if (json.empty())
        return {};
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(json);
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(path, std::string("settings are not valid JSON: ") + e.what());
    }
    return {doc.dump(), doc.dump(2) + "\n"};
}

// pixelValues: the values per pixel in the buffer, of which `channels` are written.
void checkLayout(const std::string& path, int width, int height, int channels, std::size_t size, bool exr, int pixelValues)
{
    if (width <= 0 || height <= 0)
        throw Error(path, "cannot write an image of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    const bool channelsOk = exr ? (channels == 1 || channels == 3 || channels == 4) : (channels >= 1 && channels <= 4);
    if (!channelsOk)
        throw Error(path, "cannot write " + std::to_string(channels) + " channels to " + (exr ? "EXR" : "PNG"));
    if (pixelValues < channels)
        throw Error(path, "cannot write " + std::to_string(channels) + " channels of pixels of " + std::to_string(pixelValues) + " values");
    const std::size_t expected = std::size_t(width) * std::size_t(height) * std::size_t(pixelValues);
    if (size != expected)
        throw Error(path, "pixel buffer holds " + std::to_string(size) + " values, expected " + std::to_string(expected) +
                              " (" + std::to_string(width) + "x" + std::to_string(height) + "x" +
                              std::to_string(channels) + ")");
}

// image: all but the metadata and the rows, which come from `data` (pixels pixelBytes
// apart) and the options.
void writeImage(const std::string& path, ImageWrite image, std::size_t pixelBytes, const void* data, const ImageWriteOptions& options)
{
    const Settings settings = parseSettings(path, options.settingsJson);
    if (!settings.compact.empty()) {
        image.attributes.emplace_back("ImageDescription", settings.compact);
        image.attributes.emplace_back("iblab:settings", settings.compact);
    }
    image.attributes.emplace_back("Software", "iblab");
    if (image.channels == 2 || image.channels == 4)
        image.alphaChannel = image.channels - 1;

    // A negative row stride walks the rows from the last one up: the flip costs no copy.
    const std::ptrdiff_t rowBytes = std::ptrdiff_t(image.width) * std::ptrdiff_t(pixelBytes);
    image.pixelStride = std::ptrdiff_t(pixelBytes);
    image.firstRow = data;
    image.rowStride = rowBytes;
    if (options.bottomUp) {
        image.firstRow = static_cast<const char*>(data) + rowBytes * (image.height - 1);
        image.rowStride = -rowBytes;
    }

    const ImageCodec& codec = imageCodec();
    writeFileAtomic(path, [&](const std::string& temp) { codec.writeFile(path, temp, image); }, options.durability);
    if (!settings.pretty.empty())
        writeTextFileAtomic(settingsSidecarPath(path), settings.pretty, options.durability);
}

void writeExrImage(const std::string& path, int width, int height, int channels, ExrPixelType stored, PixelType data,
                   std::size_t pixelBytes, const void* pixels, const ImageWriteOptions& options)
{
    ImageWrite image{.format = "openexr",
                     .width = width,
                     .height = height,
                     .channels = channels,
                     .storedType = stored == ExrPixelType::Half ? PixelType::Half : PixelType::Float,
                     .dataType = data};
    if (channels == 1)
        image.channelNames = {"Y"};
    image.attributes.emplace_back("oiio:ColorSpace", "Linear");
    image.attributes.emplace_back("compression", options.exrCompression);
    image.tileSize = options.exrTileSize;
    writeImage(path, std::move(image), pixelBytes, pixels, options);
}

} // namespace

std::string settingsSidecarPath(const std::string& path) { return path + ".json"; }

void writePng8(const std::string& path, int width, int height, int channels, std::span<const std::uint8_t> pixels,
               const ImageWriteOptions& options)
{
    checkLayout(path, width, height, channels, pixels.size(), false, channels);
    ImageWrite image{.format = "png", .width = width, .height = height, .channels = channels};
    image.attributes.emplace_back("oiio:ColorSpace", "sRGB");
    // PNG stores unassociated alpha; without this hint OpenImageIO would treat our bytes
    // as premultiplied and divide colour by alpha. The bytes given are the bytes stored.
    image.attributes.emplace_back("oiio:UnassociatedAlpha", 1);
    writeImage(path, std::move(image), std::size_t(channels) * sizeof(std::uint8_t), pixels.data(), options);
}

void writeExr(const std::string& path, int width, int height, int channels, std::span<const float> pixels,
              const ImageWriteOptions& options)
{
    checkLayout(path, width, height, channels, pixels.size(), true, channels);
    writeExrImage(path, width, height, channels, options.exrPixelType, PixelType::Float, std::size_t(channels) * sizeof(float),
                  pixels.data(), options);
}

void writeExr(const std::string& path, const ExrPixels& pixels, const ImageWriteOptions& options)
{
    const bool half = pixels.type == ExrPixelType::Half;
    checkLayout(path, pixels.width, pixels.height, pixels.channels,
                std::size_t(std::max(pixels.width, 0)) * std::size_t(std::max(pixels.height, 0)) * std::size_t(pixels.pixelValues),
                true, pixels.pixelValues);
    writeExrImage(path, pixels.width, pixels.height, pixels.channels, pixels.type, half ? PixelType::Half : PixelType::Float,
                  std::size_t(pixels.pixelValues) * (half ? 2 : sizeof(float)), pixels.data, options);
}

void writeExr(const std::string& path, const ImageRGB32F& image, const ImageWriteOptions& options)
{
    writeExr(path, image.width, image.height, 3, image.texels, options);
}

} // namespace iblab
