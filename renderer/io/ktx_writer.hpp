#pragma once
// KTX 1.1 and KTX 2.0 writers for uncompressed RGBA float textures (2D or cube, with mips).
// docs/engine-export.md lists the specification sections each part follows.
#include <string>

#include "io/atomic_file.hpp"
#include "io/ktx_texture.hpp"

namespace iblab::ktx {

// The whole file in memory. KTX 1.1: little-endian header, key/value data as given (each
// value NUL-terminated), per level imageSize (one face's bytes for a cube map, section 2.16)
// then the faces. KTX 2.0: header, level index, a basic DFD, key/value data (KTXwriter added),
// levels stored smallest first (section 3.9), no supercompression.
std::string encodeKtx1(const KtxTexture& texture);
std::string encodeKtx2(const KtxTexture& texture);

// Written atomically; throws iblab::Error naming the file on failure.
void writeKtx1(const std::string& path, const KtxTexture& texture, Durability durability = Durability::Flush);
void writeKtx2(const std::string& path, const KtxTexture& texture, Durability durability = Durability::Flush);

} // namespace iblab::ktx
