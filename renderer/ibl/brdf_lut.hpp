#pragma once
// CPU reference of the split-sum BRDF integration (Karis 2013; LearnOpenGL's IntegrateBRDF,
// generalised to either geometry term), and the energy-compensation terms built on it.
//
// With Fresnel-Schlick, F = F0 + (1 - F0) Fc, Fc = (1 - v.h)^5, the directional albedo of the
// specular lobe splits into a scale and a bias on F0:
//   integral f_spec(v, l) (n.l) dOmega_l = F0 * A + B,
//   A = integral D Vis (1 - Fc) (n.l) dOmega_l,   B = integral D Vis Fc (n.l) dOmega_l.
// Estimated by GGX importance sampling of h over a Hammersley set: with l = reflect(-v, h) the
// density of l is D (n.h) / (4 v.h), so each sample contributes
//   D Vis (n.l) / pdf = Vis * 4 (n.l) (v.h) / (n.h)
// (LearnOpenGL writes the same thing as G (v.h) / ((n.h)(n.v)) using G = 4 Vis (n.l)(n.v)).
// Samples with n.l <= 0 contribute 0 but still count in the denominator (they are part of
// the estimator's sample space).
//
// Table layout (DESIGN.md): x = n.v, y = perceptual roughness, texel centres (i + 0.5) / N,
// alpha = roughness^2, element [row * N + col]; row 0 = the smallest roughness, which is the
// first row a glTexImage2D upload takes (texture coordinate t near 0).
// Channels: (A, B, A + B). The third channel is the single-scattering directional albedo with
// F0 = 1 (Filament's "DFG1", E_ss = A + B); it is what multiple-scattering energy compensation
// needs (Kulla & Conty 2017; Fdez-Agueera 2019; Filament's energyCompensation
// = 1 + F0 (1 / E_ss - 1)). It is redundant with A and B, but keeping it lets a shader read it
// without a second tap or an add, and it is the quantity a white-furnace check looks at.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/brdf.hpp"

namespace iblab {

// (A, B, A + B) for one (n.v, perceptual roughness). roughness > 0, n.v in (0, 1].
glm::dvec3 integrateSplitSumBrdf(double NdotV, double roughness, std::uint32_t sampleCount, GeometryTerm term);

// The whole size x size table, element [row * size + col] = integrateSplitSumBrdf(
// (col + 0.5) / size, (row + 0.5) / size, ...). Rows are spread over threads.
std::vector<glm::vec3> computeBrdfLut(int size, std::uint32_t sampleCount, GeometryTerm term);

// Filament's multiple-scattering compensation (Filament documentation, "Energy loss in
// specular reflectance"): scale the single-scattering specular by 1 + F0 (1 / E_ss - 1), so a
// white (F0 = 1) furnace returns exactly 1.
glm::dvec3 specularEnergyCompensation(glm::dvec3 F0, double Ess);

// Fdez-Agueera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-based
// Lighting" (specular part): the single-scattering F0 A + B plus the multi-
// scattering lobe Fms Ems with Ems = 1 - E_ss, F_avg = F0 + (1 - F0) / 21 and
// Fms = (F0 A + B) F_avg / (1 - Ems F_avg). Returns the total directional albedo to multiply
// the prefiltered radiance by.
glm::dvec3 fdezAgueraSpecularAlbedo(glm::dvec3 F0, double A, double B);

} // namespace iblab
