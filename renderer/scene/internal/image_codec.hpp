#pragma once
// PRIVATE to iblab_scene: texture image decoding and encoding through OpenImageIO (the
// image module, io/image_codec.hpp), in memory (no temporary files).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/material.hpp"

namespace iblab::scene_detail {

// Decodes PNG, JPEG or anything else OpenImageIO reads into RGBA8 (grey is replicated,
// missing alpha is 255, 16-bit values are rounded, no colour conversion). The header is
// read first: an image claiming more than 8 x maxDimension texels in either direction
// is refused; one larger than maxDimension is box-filtered down by the smallest power
// of two that fits, scanline by scanline, so only the output is ever held in memory,
// and `note` says so. On failure returns nullopt with the reason in `problem`.
// Box-filtering averages the encoded values (sRGB, or normal-map xyz), which is what a
// preview needs; shading renormalises normals anyway.
std::optional<TextureImage> decodeImage(const std::vector<std::uint8_t>& encoded, int maxDimension, std::string& problem,
                                        std::string& note);

// PNG bytes of a width x height RGBA8 image. Throws iblab::Error on failure.
std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgba8);

} // namespace iblab::scene_detail
