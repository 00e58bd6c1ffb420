#pragma once
// Image file reading and writing behind an interface, so that the executable does not link
// OpenImageIO: its implementation, image_codec_oiio.cpp, is the shared module
// libiblab_oiio.so, loaded with dlopen the first time it is needed. OpenEXR and Radiance
// files are read and written directly where they can be (image_codec_direct.hpp).
// OpenImageIO pulls in about 200 shared libraries (OpenEXR, libraw, ffmpeg, TBB, ...) and
// starts thread pools; loading them cost `iblab --help` about 0.3 s, while commands that
// never touch an image file (help, version, a parse error) need none of it.
//
// The module is looked for, in this order, at $IBLAB_IMAGE_MODULE, next to the running
// executable (where CMake builds it beside build/app/iblab), in ../lib/iblab from it (an
// installed iblab, cmake/Install.cmake), and at the path it was built to (for the test
// executables elsewhere in the build tree). Only this interface crosses
// the boundary; both sides are built by the same compiler from the same headers.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace iblab {

// The component types the callers ask for or store; Other is anything else a file holds.
enum class PixelType { UInt8, Int8, UInt16, Int16, Half, Float, Other };

// What a file's header says (OpenImageIO's ImageSpec, reduced to what the callers check).
struct ImageHeader {
    int width = 0, height = 0, depth = 1, channels = 0;
    int x = 0, y = 0, z = 0;          // origin of the data window
    int tileWidth = 0, tileHeight = 0; // 0: scanline file
    bool deep = false;
    PixelType storedType = PixelType::Other;
    std::string colorSpace = {}; // "oiio:ColorSpace", empty when the file names none
};

class ImageReader {
public:
    virtual ~ImageReader() = default;
    virtual const ImageHeader& header() const = 0;
    // Rows [y0, y1) of the data window (file coordinates: header().y is the first row), the
    // first `channels` channels converted to `type` (UInt8 or Float), interleaved. Tiled
    // files are read by whole tiles: y0 must start a tile row. False on failure
    // (takeError() says why).
    virtual bool readRows(int y0, int y1, int channels, PixelType type, void* out) = 0;
    // The whole image at once (OpenImageIO's read_image), as readRows.
    virtual bool readImage(int channels, PixelType type, void* out) = 0;
    // Whether the reader recorded an error, even on a read that returned true (a truncated
    // scanline file can).
    virtual bool hasError() const = 0;
    // The reader's error text, else the library's pending one ("" if none); both are
    // cleared, so that neither surfaces later in an unrelated message.
    virtual std::string takeError() = 0;
};

// One image to store: the rows of `pixels` (of `dataType`, UInt8, Half or Float) from
// `firstRow`, rowStride bytes apart (negative: bottom-up buffer written top-down without a
// copy), each pixel's `channels` values pixelStride bytes after the last pixel's (0: packed;
// more skips values between pixels, such as the A of an RGBA read-back stored as RGB).
struct ImageWrite {
    const char* format = "png"; // OpenImageIO's plugin name: "png", "openexr"
    int width = 0, height = 0, channels = 0;
    PixelType storedType = PixelType::UInt8; // UInt8, Half or Float
    PixelType dataType = PixelType::UInt8;
    const void* firstRow = nullptr;
    std::ptrdiff_t rowStride = 0;
    std::ptrdiff_t pixelStride = 0;
    int tileSize = 0; // "openexr": square tiles of this edge, one level (0: scanlines)
    std::vector<std::string> channelNames = {}; // empty: the format's defaults
    int alphaChannel = -1;
    // Metadata, in the order set (OpenImageIO's spec.attribute: "compression", "Software").
    std::vector<std::pair<std::string, std::variant<std::string, int>>> attributes = {};
};

class ImageCodec {
public:
    virtual ~ImageCodec() = default;
    // nullptr on failure, with the library's reason in `error` ("" if it gave none).
    virtual std::unique_ptr<ImageReader> openFile(const std::string& path, std::string& error) const = 0;
    // Decodes bytes in memory; `nameHint` ("memory.png") only says which reader to try
    // first. Alpha is read as stored (unassociated), never premultiplied.
    virtual std::unique_ptr<ImageReader> openMemory(std::span<const std::uint8_t> bytes, const std::string& nameHint,
                                                    std::string& error) const = 0;
    // Writes `file`; failures throw iblab::Error naming `subject` (the path the user sees,
    // when `file` is a temporary one) and the stage that failed.
    virtual void writeFile(const std::string& subject, const std::string& file, const ImageWrite& image) const = 0;
    // The encoded bytes; failures throw iblab::Error naming `subject`.
    virtual std::vector<std::uint8_t> encode(const std::string& subject, const ImageWrite& image) const = 0;
};

// The codec to use: OpenEXR and Radiance .hdr files without OpenImageIO where
// image_codec_direct.hpp can (the bake's formats: it then never loads the module), the
// module for everything else. Throws as openImageIoCodec() when a call needs the module.
const ImageCodec& imageCodec();

// The module's codec, loaded on first use (thread-safe); throws iblab::Error naming the
// module and dlopen's reason when it cannot be loaded. Tests compare the two with it.
const ImageCodec& openImageIoCodec();

// Starts loading the module on a thread of its own, so that a caller which will soon read
// an image (the GUI, while it opens its window) does not wait for all of it. Joined at exit;
// a failure is reported by the next imageCodec() call instead.
void preloadImageCodec();

// The module's entry point, looked up by this name: returns its codec, which lives as long
// as the process.
using ImageCodecEntry = const ImageCodec*();
inline constexpr const char* kImageCodecEntryName = "iblab_image_codec";

} // namespace iblab
