// The image module, libiblab_oiio.so: image_codec.hpp's interface on OpenImageIO. The only
// file of iblab that includes OpenImageIO; it is loaded with dlopen (image_codec.cpp).
#include <memory>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "io/error.hpp"
#include "io/image_codec.hpp"

namespace iblab {
namespace {

OIIO::TypeDesc toTypeDesc(PixelType type)
{
    switch (type) {
    case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelType::Int8: return OIIO::TypeDesc::INT8;
    case PixelType::UInt16: return OIIO::TypeDesc::UINT16;
    case PixelType::Int16: return OIIO::TypeDesc::INT16;
    case PixelType::Half: return OIIO::TypeDesc::HALF;
    case PixelType::Float: return OIIO::TypeDesc::FLOAT;
    case PixelType::Other: break;
    }
    throw Error("image module", "no OpenImageIO type for PixelType::Other");
}

PixelType fromTypeDesc(OIIO::TypeDesc type)
{
    switch (OIIO::TypeDesc::BASETYPE(type.basetype)) {
    case OIIO::TypeDesc::UINT8: return PixelType::UInt8;
    case OIIO::TypeDesc::INT8: return PixelType::Int8;
    case OIIO::TypeDesc::UINT16: return PixelType::UInt16;
    case OIIO::TypeDesc::INT16: return PixelType::Int16;
    case OIIO::TypeDesc::HALF: return PixelType::Half;
    case OIIO::TypeDesc::FLOAT: return PixelType::Float;
    default: return PixelType::Other;
    }
}

class OiioReader final : public ImageReader {
public:
    // memory: the in-memory source the reader was opened on, kept alive with it (or null).
    OiioReader(std::unique_ptr<OIIO::ImageInput> in, std::unique_ptr<OIIO::Filesystem::IOMemReader> memory)
        : memory_(std::move(memory)), in_(std::move(in))
    {
        const OIIO::ImageSpec& spec = in_->spec();
        header_ = {.width = spec.width,
                   .height = spec.height,
                   .depth = spec.depth,
                   .channels = spec.nchannels,
                   .x = spec.x,
                   .y = spec.y,
                   .z = spec.z,
                   .tileWidth = spec.tile_width,
                   .tileHeight = spec.tile_height,
                   .deep = spec.deep,
                   .storedType = fromTypeDesc(spec.format),
                   .colorSpace = spec.get_string_attribute("oiio:ColorSpace")};
    }
    ~OiioReader() override { in_->close(); }

    const ImageHeader& header() const override { return header_; }

    bool readRows(int y0, int y1, int channels, PixelType type, void* out) override
    {
        const ImageHeader& h = header_;
        const bool ok = h.tileWidth > 0 ? in_->read_tiles(0, 0, h.x, h.x + h.width, y0, y1, h.z, h.z + 1, 0, channels, toTypeDesc(type), out)
                                        : in_->read_scanlines(0, 0, y0, y1, h.z, 0, channels, toTypeDesc(type), out);
        return ok;
    }

    bool readImage(int channels, PixelType type, void* out) override
    {
        return in_->read_image(0, 0, 0, channels, toTypeDesc(type), out);
    }

    bool hasError() const override { return in_->has_error(); }

    std::string takeError() override
    {
        std::string text = in_->geterror();
        const std::string global = OIIO::geterror();
        return text.empty() ? global : text;
    }

private:
    std::unique_ptr<OIIO::Filesystem::IOMemReader> memory_; // outlives in_, which reads from it
    std::unique_ptr<OIIO::ImageInput> in_;
    ImageHeader header_;
};

OIIO::ImageSpec specFor(const ImageWrite& image)
{
    OIIO::ImageSpec spec(image.width, image.height, image.channels, toTypeDesc(image.storedType));
    if (!image.channelNames.empty())
        spec.channelnames = image.channelNames;
    spec.alpha_channel = image.alphaChannel;
    spec.tile_width = spec.tile_height = image.tileSize;
    // A named pair, not a structured binding: clang 14 (the fuzz build) cannot capture those.
    for (const auto& attribute : image.attributes) {
        const std::string& name = attribute.first;
        std::visit([&spec, &name](const auto& v) { spec.attribute(name, v); }, attribute.second);
    }
    return spec;
}

OIIO::stride_t pixelStride(const ImageWrite& image) { return image.pixelStride > 0 ? image.pixelStride : OIIO::AutoStride; }

void writeWith(OIIO::ImageOutput& out, const std::string& subject, const std::string& file, const ImageWrite& image)
{
    if (!out.open(file, specFor(image)))
        throw Error(subject, "cannot write: " + out.geterror());
    if (!out.write_image(toTypeDesc(image.dataType), image.firstRow, pixelStride(image), image.rowStride)) {
        const std::string why = out.geterror();
        out.close();
        throw Error(subject, "cannot write pixels: " + why);
    }
    if (!out.close())
        throw Error(subject, "cannot finish writing: " + out.geterror());
}

class OiioCodec final : public ImageCodec {
public:
    std::unique_ptr<ImageReader> openFile(const std::string& path, std::string& error) const override
    {
        auto in = OIIO::ImageInput::open(path);
        if (!in) {
            error = OIIO::geterror();
            return nullptr;
        }
        return std::make_unique<OiioReader>(std::move(in), nullptr);
    }

    std::unique_ptr<ImageReader> openMemory(std::span<const std::uint8_t> bytes, const std::string& nameHint,
                                            std::string& error) const override
    {
        auto memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes.data(), bytes.size());
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        // With a config spec, OpenImageIO 2.4 takes the proxy from this hint, not only from
        // the argument: without it the reader tries to open nameHint from disk.
        void* proxy = memory.get();
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        auto in = OIIO::ImageInput::open(nameHint, &config, memory.get());
        if (!in) {
            error = OIIO::geterror();
            return nullptr;
        }
        return std::make_unique<OiioReader>(std::move(in), std::move(memory));
    }

    void writeFile(const std::string& subject, const std::string& file, const ImageWrite& image) const override
    {
        // Chosen by name: a temporary file's name does not end in the right extension.
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(image.format);
        if (!out)
            throw Error(subject, std::string("no ") + image.format + " writer: " + OIIO::geterror());
        writeWith(*out, subject, file, image);
    }

    std::vector<std::uint8_t> encode(const std::string& subject, const ImageWrite& image) const override
    {
        std::vector<std::uint8_t> bytes;
        OIIO::Filesystem::IOVecOutput memory(bytes);
        const std::string name = std::string("memory.") + (std::string(image.format) == "openexr" ? "exr" : image.format);
        auto out = OIIO::ImageOutput::create(name, &memory);
        if (!out) {
            const std::string why = OIIO::geterror();
            throw Error(subject, why.empty() ? "unrecognised or corrupt image data" : why);
        }
        if (!out->open(name, specFor(image)) || !out->write_image(toTypeDesc(image.dataType), image.firstRow, pixelStride(image), image.rowStride) ||
            !out->close())
            throw Error(subject, out->geterror());
        return bytes;
    }
};

} // namespace
} // namespace iblab

extern "C" __attribute__((visibility("default"))) const iblab::ImageCodec* iblab_image_codec()
{
    static const iblab::OiioCodec codec;
    return &codec;
}
