#pragma once
// What the frame renderer says about its reference integral, and how the integral is cut
// into slices: plain data shared by the Renderer's interface and the reference renderer's
// internals, so that neither needs the other's header.

namespace iblab {

// The reference renderer's G-buffer layers (what the mesh pass leaves for the integral),
// for read-back: N and V are in the environment's frame (its yaw undone).
enum class ReferenceLayer {
    Normal,    // N, coverage (1 on surfaces, 0 on the background)
    View,      // V, perceptual roughness
    Specular,  // F0, metallic
    BaseColor, // base colour, occlusion
    Emissive,
    Count
};

// How the reference integral is cut into slices: one slice sums the rows of one band of
// the environment for one tileSize x tileSize tile of pixels. rowsPerSlice 0 sizes the band
// so that a slice is about 2^21 texel evaluations. The result does not depend on either.
struct ReferenceSlicing {
    int tileSize = 32;
    int rowsPerSlice = 0;
    bool operator==(const ReferenceSlicing&) const = default;
};

struct ReferenceStatus {
    bool current = false;  // a reference of these settings and size is under way or done
    // Which reference: a new number each time one starts (other settings, size or scene), so
    // that whoever kept a read-back of it knows when that copy went stale.
    unsigned long long run = 0;
    bool complete = false;
    float progress = 0.0f; // fraction of the slices done
    int environmentWidth = 0; // of the environment it sums over (after downsampling)
    int environmentHeight = 0;
    double texelDegrees = 0.0;         // angular width of one of its texels at the equator
    double minResolvedRoughness = 0.0; // referenceMinResolvedRoughness: below it, it is not converged
};

} // namespace iblab
