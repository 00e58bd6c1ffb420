#pragma once
// What an image was made from, compared by value: its settings (reduced to those it
// depends on), its size, and the revision of what the renderer's setters gave it. The
// running mean and the reference each keep the key of what they hold.
#include <cstdint>

#include "frame/settings.hpp"

namespace iblab {

struct FrameKey {
    FrameSettings settings;
    int width = 0;
    int height = 0;
    std::uint64_t revision = 0;
    bool operator==(const FrameKey&) const = default;
};

} // namespace iblab
