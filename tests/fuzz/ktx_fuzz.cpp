// libFuzzer target: any bytes as a KTX cube and as another tool's bake. The first byte picks
// the path: the reader on the bytes in memory, cmgen's NAME_ibl.ktx through loadEnvironment
// (key/values, the `sh` parse, the reorientation, the equirect of the sky), or a KTX2
// specular + diffuse pair (the same file twice). Each must return a cube / environment whose
// texels are finite and >= 0, or throw iblab::Error; anything else is a bug.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

#include "io/environment.hpp"
#include "io/error.hpp"
#include "io/ktx_cube.hpp"

namespace {

void checkTexels(const iblab::ImageRGB32F& image)
{
    for (float v : image.texels)
        if (!std::isfinite(v) || v < 0.0f) __builtin_trap();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0) return 0;
    const int mode = data[0] % 3;
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data + 1), size - 1);
    // Faces up to 64^2 keep each run fast; the limit's own check is tested in ktx_reader_test.
    const iblab::KtxReadOptions options{.maxFaceSize = 64};
    try {
        if (mode == 0) {
            const iblab::KtxCube cube = iblab::parseKtxCube(bytes, "fuzz.ktx", options);
            if (int(cube.levels.size()) < 1 || cube.faceSize > 64) __builtin_trap();
            for (const iblab::ImageRGB32F& level : cube.levels)
                checkTexels(level);
            return 0;
        }
        const std::string base = "/tmp/iblab-fuzz-ktx-" + std::to_string(::getpid());
        const std::string path = base + (mode == 1 ? "_ibl.ktx" : ".ktx2");
        std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        try {
            const iblab::Environment environment = iblab::loadEnvironment(mode == 1 ? path : path + "," + path);
            if (!environment.imported) __builtin_trap();
            checkTexels(environment.image);
            for (const iblab::ImageRGB32F& level : environment.imported->prefiltered)
                checkTexels(level);
        } catch (const iblab::Error&) {
        }
        std::remove(path.c_str());
    } catch (const iblab::Error&) {
    }
    return 0;
}
