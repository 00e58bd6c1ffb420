#pragma once
// The image formats the bake needs, read and written without OpenImageIO: OpenEXR through
// its own library, and Radiance .hdr decoded here (image_codec_direct.cpp says why not by
// stb_image). Loading the OpenImageIO module
// (about 250 shared libraries and its thread pools) took ~250 ms of a ~0.5 s `iblab bake`,
// while decoding a 1024x512 map takes a few ms; these readers and the writer are linked
// into the io layer, which costs ~7 ms of start-up (the OpenEXR libraries), measured by
// scripts/measure-startup.sh.
//
// They take only what they are sure to decode exactly as OpenImageIO does: a file is
// chosen by its magic bytes, and every other case returns nullptr (or false), so that the
// caller (image_codec.cpp) hands it to OpenImageIO with its behaviour and messages as
// before: multi-part, deep or non-image EXRs, channels other than R, G, B (+ any) or a lone
// Y, a header OpenEXR refuses, and Radiance headers with a GAMMA line or an orientation
// other than -Y +X.
#include <memory>
#include <string>

#include "io/image_codec.hpp"
#include "io/image_writer.hpp"

namespace iblab {

// The first four bytes of every OpenEXR file.
inline constexpr char kExrMagic[4] = {'\x76', '\x2f', '\x31', '\x01'};

enum class ImageFileKind { OpenExr, RadianceHdr, Other };

// By the first bytes: OpenEXR's magic number, or Radiance's "#?RADIANCE\n" / "#?RGBE\n".
ImageFileKind sniffImageFile(const std::string& path);

// A reader for the file, or nullptr when OpenImageIO should read it (see above). Rows are
// read as Float or UInt8 (clamped to [0, 1] and rounded, as OpenImageIO converts).
std::unique_ptr<ImageReader> openExrDirect(const std::string& path);
std::unique_ptr<ImageReader> openHdrDirect(const std::string& path);

// writeExr(ExrPixels)'s mirror, for files this program wrote: an OpenEXR file's R, G and B
// read as `type` (OpenEXR converts from what is stored) into the first `channels` of each
// pixel's `pixelValues`, row-major, the values past them left as they are (the caller's
// alpha), with no conversion in between. Throws iblab::Error naming the file for anything
// else: not such an OpenEXR file, another size, a truncated one.
struct ExrPixelTarget {
    int width = 0, height = 0;
    int channels = 3;
    int pixelValues = 4;
    ExrPixelType type = ExrPixelType::Half;
    void* data = nullptr; // width * height * pixelValues values
};
void readExrDirect(const std::string& path, const ExrPixelTarget& target);

// Writes an "openexr" image: 1 (Y), 3 (RGB) or 4 (RGBA) float channels stored as Half or
// Float, or half channels stored as Half (written from where they are), with a compression OpenEXR names and string attributes ("ImageDescription" is
// stored as OpenEXR's "comments", as OpenImageIO does). False, with nothing written, for
// anything else; failures throw iblab::Error naming `subject`.
bool writeExrDirect(const std::string& subject, const std::string& file, const ImageWrite& image);

} // namespace iblab
