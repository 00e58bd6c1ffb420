#include "scene/material.hpp"

namespace iblab {

std::string_view alphaModeName(AlphaMode mode)
{
    switch (mode) {
    case AlphaMode::Mask: return "MASK";
    case AlphaMode::Blend: return "BLEND";
    case AlphaMode::Opaque: break;
    }
    return "OPAQUE";
}

} // namespace iblab
