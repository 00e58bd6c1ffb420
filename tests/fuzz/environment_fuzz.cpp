// libFuzzer target: any bytes, as an .exr, .hdr or .png environment file. The loader must
// either return a finite, non-negative 2:1 (+-1 texel) image or throw iblab::Error;
// anything else (a crash, a sanitizer report, another exception, a hang) is a bug.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

#include "io/environment.hpp"
#include "io/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0) return 0;
    // The first byte picks the extension (OpenImageIO also sniffs the content).
    static const char* const kExtensions[] = {".exr", ".hdr", ".png"};
    const std::string path = "/tmp/iblab-fuzz-env-" + std::to_string(::getpid()) + kExtensions[data[0] % 3];
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    try {
        iblab::EnvironmentLoadOptions options;
        options.maxWidth = 512; // keep each run fast; the cap's downsampling is exercised too
        // libFuzzer counts any single allocation over -rss_limit_mb (2 GB) as a failure, and
        // an interlaced 16-bit RGBA PNG header at the default 2^28 texels makes OpenImageIO
        // allocate exactly that for the whole image. The limit itself is tested elsewhere;
        // here it keeps every decoder's full-image buffer well under the fuzzer's budget.
        options.maxSourceTexels = std::uint64_t(1) << 24;
        const iblab::Environment environment = iblab::loadEnvironment(path, options);
        // 2:1 within the one texel of rounding the loader allows (a 17x8 file loads as is).
        if (std::abs(environment.image.width - 2 * environment.image.height) > 1) __builtin_trap();
        for (float v : environment.image.texels)
            if (!std::isfinite(v) || v < 0.0f) __builtin_trap();
    } catch (const iblab::Error&) {
    }
    std::remove(path.c_str());
    return 0;
}
