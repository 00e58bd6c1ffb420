#pragma once
// The narrowest read a lobe-table cell may make (accuracy_study fit --read-floor).
//
// A read of the prefiltered cube at roughness r averages the map over a GGX lobe; a map's
// detail finer than that lobe passes through it in proportion to the lobe's peakedness. For
// detail finer than every lobe (a texel-noise map, `noise` and `sparks` of
// scripts/heldout-maps.py), the error of standing one lobe in for another is the L2 norm of
// their difference, and a read much sharper than the lobe it stands for passes noise the true
// lobe averages away: the committed table (fitted without a floor) reads a roughness-0.28
// cell's F0 A term at 0.45-0.70 of that roughness (n.v 0.1-0.6), and is 1.96 times the split
// sum's error on texel noise (docs/accuracy-study.md, where the floor is measured). The
// measure of peakedness used here is a lobe's effective solid angle,
//   Omega = (integral k)^2 / integral k^2,
// the solid angle of a flat lobe that passes as much white noise. The floor of a read is the
// roughness whose read has the Omega of the term it stands for (the LUT's F0 A term for the A
// reads, its B term for the B read), at most the cell's own roughness: the table may read as
// wide as it likes and never sharper than the true lobe is; where the true lobe is itself
// squeezed (grazing n.v), that is sharper than the cell's roughness. Derived from
// the BRDF and the chain's mips alone: no map decides it. Not modelled: the bilinear read
// within a mip (a texel's blur) and the bake's own error, which is larger at the sharp mips.
#include "ibl/brdf.hpp"
#include "ibl/prefilter_lod.hpp"

namespace iblab::accuracy {

// The prefiltered chain a table reads: the default bake's (256 face, 6 levels, quadratic).
struct ReadChain {
    int levels = 6;
    int layout = PREFILTER_LAYOUT_QUADRATIC;
    int faceSize = 256;
};

// Omega of a read of that chain at this perceptual roughness: the blend of the two mips
// around its lod (linear between mips, as textureLod reads them) of each mip's prefilter
// lobe (N = V = R, weight D(h) (n.l)), the mirror mip a texel of the face.
double prefilterReadSolidAngle(double roughness, const ReadChain& chain = {});

// Omega of the specular lobe's two terms over l at (n.v, roughness): f (n.l) times (1 - s)
// (the term F0 multiplies, A's) and times s (B's), s = (1 - v.h)^5.
struct SpecularLobeSolidAngles {
    double a = 0.0, b = 0.0;
};
SpecularLobeSolidAngles specularLobeSolidAngles(double NdotV, double roughness, GeometryTerm term);

// The smallest perceptual roughness each read may take: the A reads', the B read's.
struct ReadRoughnessFloor {
    double a = 0.0, b = 0.0;
};
ReadRoughnessFloor readRoughnessFloor(double NdotV, double roughness, GeometryTerm term, const ReadChain& chain = {});

} // namespace iblab::accuracy
