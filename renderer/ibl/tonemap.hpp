#pragma once
// C++ view of assets/shaders/common/tonemap.glsl: the same source compiled with glm, so a
// CPU-side screenshot, a test and the display shader apply the same curves. Adds the typed
// operator enum (values = the GLSL ids) and the names the UI and command line use.
#include <array>
#include <optional>
#include <string_view>

#include "ibl/enum_names.hpp"
#include "ibl/glsl_shared.hpp"

namespace iblab::shared {
#include "common/tonemap.glsl"
}

namespace iblab {

using shared::applyExposure;
using shared::displayEncode;
using shared::srgbEncode;
using shared::srgbOetf;
using shared::toneMap;

enum class ToneMapOperator : int {
    None = shared::IBL_TONEMAP_NONE,
    Reinhard = shared::IBL_TONEMAP_REINHARD,
    AcesNarkowicz = shared::IBL_TONEMAP_ACES_NARKOWICZ,
    AcesHill = shared::IBL_TONEMAP_ACES_HILL,
    Hable = shared::IBL_TONEMAP_HABLE,
    PbrNeutral = shared::IBL_TONEMAP_PBR_NEUTRAL,
    Agx = shared::IBL_TONEMAP_AGX,
};

inline constexpr int kToneMapOperatorCount = shared::IBL_TONEMAP_COUNT;

template <>
struct EnumNames<ToneMapOperator> {
    static constexpr std::array<EnumName<ToneMapOperator>, kToneMapOperatorCount> entries{{
        {ToneMapOperator::None, "none"},
        {ToneMapOperator::Reinhard, "reinhard"},
        {ToneMapOperator::AcesNarkowicz, "aces-narkowicz"},
        {ToneMapOperator::AcesHill, "aces-hill"},
        {ToneMapOperator::Hable, "hable"},
        {ToneMapOperator::PbrNeutral, "pbr-neutral"},
        {ToneMapOperator::Agx, "agx"},
    }};
};

inline glm::vec3 toneMap(glm::vec3 hdr, ToneMapOperator op)
{
    return shared::toneMap(hdr, int(op));
}

inline glm::vec3 displayEncode(glm::vec3 hdr, float exposureEv, ToneMapOperator op)
{
    return shared::displayEncode(hdr, exposureEv, int(op));
}

// Every operator in id order, for pickers and sweeps.
inline constexpr std::array<ToneMapOperator, kToneMapOperatorCount> allToneMapOperators()
{
    std::array<ToneMapOperator, kToneMapOperatorCount> all{};
    for (int id = 0; id < kToneMapOperatorCount; ++id) all[std::size_t(id)] = ToneMapOperator(id);
    return all;
}

// What the UI shows: the curve and where it comes from.
inline constexpr std::array<const char*, kToneMapOperatorCount> kToneMapOperatorLabels = {
    "None (clamp)", "Reinhard", "ACES (Narkowicz fit)", "ACES (Hill RRT+ODT fit)", "Uncharted 2 / Hable", "Khronos PBR Neutral", "AgX (Filament, three.js)",
};

constexpr const char* toneMapOperatorLabel(ToneMapOperator op)
{
    const int id = int(op);
    return id >= 0 && id < kToneMapOperatorCount ? kToneMapOperatorLabels[std::size_t(id)] : "?";
}

} // namespace iblab
