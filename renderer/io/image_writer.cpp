#include "io/image_writer.hpp"

#include <memory>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/error.hpp"

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

void checkLayout(const std::string& path, int width, int height, int channels, std::size_t size, bool exr)
{
    if (width <= 0 || height <= 0)
        throw Error(path, "cannot write an image of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    const bool channelsOk = exr ? (channels == 1 || channels == 3 || channels == 4) : (channels >= 1 && channels <= 4);
    if (!channelsOk)
        throw Error(path, "cannot write " + std::to_string(channels) + " channels to " + (exr ? "EXR" : "PNG"));
    const std::size_t expected = std::size_t(width) * std::size_t(height) * std::size_t(channels);
    if (size != expected)
        throw Error(path, "pixel buffer holds " + std::to_string(size) + " values, expected " + std::to_string(expected) +
                              " (" + std::to_string(width) + "x" + std::to_string(height) + "x" +
                              std::to_string(channels) + ")");
}

// formatName: OpenImageIO's plugin name ("png", "openexr"); the temporary file's name does
// not end in the right extension, so the writer is chosen explicitly.
void writeImage(const std::string& path, const char* formatName, OIIO::ImageSpec spec, OIIO::TypeDesc dataType,
                const void* data, const ImageWriteOptions& options)
{
    const Settings settings = parseSettings(path, options.settingsJson);
    if (!settings.compact.empty()) {
        spec.attribute("ImageDescription", settings.compact);
        spec.attribute("iblab:settings", settings.compact);
    }
    spec.attribute("Software", "iblab");
    if (spec.nchannels == 2 || spec.nchannels == 4)
        spec.alpha_channel = spec.nchannels - 1;

    // A negative y stride walks the rows from the last one up: the flip costs no copy.
    const OIIO::stride_t rowBytes = OIIO::stride_t(spec.width) * spec.nchannels * OIIO::stride_t(dataType.size());
    const char* first = static_cast<const char*>(data);
    OIIO::stride_t yStride = rowBytes;
    if (options.bottomUp) {
        first += rowBytes * (spec.height - 1);
        yStride = -rowBytes;
    }

    writeFileAtomic(path, [&](const std::string& temp) {
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(formatName);
        if (!out)
            throw Error(path, std::string("no ") + formatName + " writer: " + OIIO::geterror());
        if (!out->open(temp, spec))
            throw Error(path, "cannot write: " + out->geterror());
        if (!out->write_image(dataType, first, OIIO::AutoStride, yStride)) {
            const std::string why = out->geterror();
            out->close();
            throw Error(path, "cannot write pixels: " + why);
        }
        if (!out->close())
            throw Error(path, "cannot finish writing: " + out->geterror());
    });
    if (!settings.pretty.empty())
        writeTextFileAtomic(settingsSidecarPath(path), settings.pretty);
}

} // namespace

std::string settingsSidecarPath(const std::string& path) { return path + ".json"; }

void writePng8(const std::string& path, int width, int height, int channels, std::span<const std::uint8_t> pixels,
               const ImageWriteOptions& options)
{
    checkLayout(path, width, height, channels, pixels.size(), false);
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // PNG stores unassociated alpha; without this hint OpenImageIO would treat our bytes
    // as premultiplied and divide colour by alpha. The bytes given are the bytes stored.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    writeImage(path, "png", spec, OIIO::TypeDesc::UINT8, pixels.data(), options);
}

void writeExr(const std::string& path, int width, int height, int channels, std::span<const float> pixels,
              const ImageWriteOptions& options)
{
    checkLayout(path, width, height, channels, pixels.size(), true);
    OIIO::ImageSpec spec(width, height, channels,
                         options.exrPixelType == ExrPixelType::Half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    if (channels == 1)
        spec.channelnames = {"Y"};
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("compression", "zip");
    writeImage(path, "openexr", spec, OIIO::TypeDesc::FLOAT, pixels.data(), options);
}

void writeExr(const std::string& path, const ImageRGB32F& image, const ImageWriteOptions& options)
{
    writeExr(path, image.width, image.height, 3, image.texels, options);
}

} // namespace iblab
