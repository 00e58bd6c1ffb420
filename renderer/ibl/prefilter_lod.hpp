#pragma once
// C++ view of assets/shaders/common/prefilter_lod.glsl: the roughness-per-mip mapping of
// the prefiltered cube and the PDF-based source-mip formula, the very same source the bake
// shaders compile (tests/gl/bake_shared_glsl_gltest.cpp pins the two compilers together).
#include "ibl/glsl_shared.hpp"

namespace iblab::shared {
#include "common/prefilter_lod.glsl"
}

// In ibl's namespace, as the rest of the math (docs/architecture.md, Namespaces).
namespace iblab {
using shared::cubeAverageTexelSolidAngle;
using shared::cubeTexelSolidAngle;
using shared::prefilterMipFromRoughness;
using shared::prefilterRoughnessFromMip;
using shared::sourceLodFromPdf;
using shared::sourceLodFromPdfAt;
using shared::sourceLodFromSampleTerm;
using shared::sourceLodFromSolidAngle;
using shared::sourceLodSampleTerm;
}
