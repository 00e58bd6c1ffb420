#pragma once
// 64-bit FNV-1a (offset basis 14695981039346656037, prime 1099511628211): the cache keys'
// hash. Not cryptographic: keys only need to tell honest inputs apart.
#include <cstdint>
#include <string_view>

namespace iblab {

inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 14695981039346656037ull)
{
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

} // namespace iblab
