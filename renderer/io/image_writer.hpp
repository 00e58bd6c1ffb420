#pragma once
// Writing screenshots, bakes and reference images through OpenImageIO, atomically (see
// atomic_file.hpp), with the settings that produced them attached: the settings JSON is
// stored in the image as "ImageDescription" and as the string attribute "iblab:settings",
// and also written next to it as "<path>.json" (pretty-printed), so it survives formats
// and tools that drop metadata. Failures throw iblab::Error naming the path.
#include <cstdint>
#include <span>
#include <string>

#include "ibl/image.hpp"
#include "io/atomic_file.hpp"

namespace iblab {

enum class ExrPixelType { Half, Float };

struct ImageWriteOptions {
    // The pixel rows are given bottom row first, as glReadPixels returns them; they are
    // flipped so that the file's first scanline is the top of the picture.
    bool bottomUp = false;
    // A JSON document (usually an object) describing how the image was made. Empty: no
    // metadata and no sidecar. Anything else must parse as JSON, or the write throws
    // before touching the disk.
    std::string settingsJson = {};
    ExrPixelType exrPixelType = ExrPixelType::Float; // EXR only
    // EXR only: OpenEXR's compression by OpenImageIO's name ("zip", "none", "piz", "dwaa", ...).
    std::string exrCompression = "zip";
    // EXR only: square tiles of this edge (0: scanlines). OpenEXR encodes and decodes each
    // block as a task on its thread pool, and an uncompressed or RLE scanline file has a
    // block per scanline: the hand-overs cost more than the copies (docs/bake.md).
    int exrTileSize = 0;
    Durability durability = Durability::Flush; // the image's and the sidecar's
};

// 8-bit PNG (sRGB-encoded values, as a display shows them). channels: 1 (grey), 2 (grey +
// alpha), 3 (RGB) or 4 (RGBA); pixels.size() must be width * height * channels,
// interleaved, row-major.
void writePng8(const std::string& path, int width, int height, int channels, std::span<const std::uint8_t> pixels,
               const ImageWriteOptions& options = {});

// Linear-light OpenEXR. channels: 1, 3 (RGB) or 4 (RGBA); layout as for writePng8.
void writeExr(const std::string& path, int width, int height, int channels, std::span<const float> pixels,
              const ImageWriteOptions& options = {});
// An ImageRGB32F is top-down by definition (row 0 = zenith); options.bottomUp flips anyway.
void writeExr(const std::string& path, const ImageRGB32F& image, const ImageWriteOptions& options = {});

// Values stored as they are, half or float, with no conversion (a GL read-back of a half
// texture: converting it to float and back cost more than the rest of the write): the
// first `channels` of each pixel's `pixelValues` (RGBA read back, RGB stored: 3 of 4).
struct ExrPixels {
    int width = 0, height = 0;
    int channels = 3;
    int pixelValues = 4;
    ExrPixelType type = ExrPixelType::Half; // replaces options.exrPixelType
    const void* data = nullptr;              // width * height * pixelValues values, row-major
};
void writeExr(const std::string& path, const ExrPixels& pixels, const ImageWriteOptions& options = {});

// "<path>.json": where the settings sidecar of `path` goes.
std::string settingsSidecarPath(const std::string& path);

} // namespace iblab
