#pragma once
// Frames read back from the GPU, as plain pixels: what the analysis functions
// (frame_analysis.hpp) and the image writers take.
#include <cstdint>
#include <vector>

namespace iblab {

struct FrameReadback {
    int width = 0;
    int height = 0;
    // Linear HDR before exposure and tone mapping, bottom row first. In the HDR frame, alpha
    // is the fraction of the pixel's MSAA samples covered by surfaces (the sky's are not):
    // 1 inside a surface, 0 on the background, in between on silhouettes.
    std::vector<float> rgba;
};

struct DisplayReadback {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // sRGB-encoded 8-bit, bottom row first
};

} // namespace iblab
