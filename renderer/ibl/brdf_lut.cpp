#include "ibl/brdf_lut.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include <glm/geometric.hpp>

#include "ibl/sampling.hpp"

namespace iblab {

glm::dvec3 integrateSplitSumBrdf(double NdotV, double roughness, std::uint32_t sampleCount, GeometryTerm term)
{
    if (sampleCount == 0 || !(roughness > 0.0) || !(NdotV > 0.0) || NdotV > 1.0)
        throw std::invalid_argument("integrateSplitSumBrdf: need sampleCount > 0, roughness > 0, NdotV in (0, 1]; got " +
                                    std::to_string(sampleCount) + ", " + std::to_string(roughness) + ", " +
                                    std::to_string(NdotV));
    const double alpha = roughness * roughness;
    // Isotropic lobe: only the angle between v and n matters, so put v in the xz plane.
    const glm::dvec3 v(std::sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    double A = 0.0;
    double B = 0.0;
    for (std::uint32_t i = 0; i < sampleCount; ++i) {
        const glm::dvec3 h = sampleGgxHalfVector(hammersley(i, sampleCount), alpha);
        const double VdotH = glm::dot(v, h);
        const glm::dvec3 l = 2.0 * VdotH * h - v;
        const double NdotL = l.z;
        if (NdotL <= 0.0 || VdotH <= 0.0)
            continue;
        const double NdotH = h.z;
        const double weight = visibility(term, NdotV, NdotL, alpha) * 4.0 * NdotL * VdotH / NdotH;
        const double Fc = schlickWeight(VdotH);
        A += (1.0 - Fc) * weight;
        B += Fc * weight;
    }
    A /= double(sampleCount);
    B /= double(sampleCount);
    return {A, B, A + B};
}

std::vector<glm::vec3> computeBrdfLut(int size, std::uint32_t sampleCount, GeometryTerm term)
{
    if (size <= 0)
        throw std::invalid_argument("computeBrdfLut: size must be > 0, got " + std::to_string(size));
    std::vector<glm::vec3> table(std::size_t(size) * std::size_t(size));
    auto fillRows = [&](int r0, int r1) {
        for (int row = r0; row < r1; ++row)
            for (int col = 0; col < size; ++col)
                table[std::size_t(row) * std::size_t(size) + std::size_t(col)] = glm::vec3(
                    integrateSplitSumBrdf((col + 0.5) / size, (row + 0.5) / size, sampleCount, term));
    };
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(size)));
    if (threads == 1 || std::size_t(size) * size * sampleCount < (1u << 16)) {
        fillRows(0, size);
        return table;
    }
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back(fillRows, size * t / threads, size * (t + 1) / threads);
    for (auto& th : pool)
        th.join();
    return table;
}

glm::dvec3 specularEnergyCompensation(glm::dvec3 F0, double Ess)
{
    return glm::dvec3(1.0) + F0 * (1.0 / Ess - 1.0);
}

glm::dvec3 fdezAgueraSpecularAlbedo(glm::dvec3 F0, double A, double B)
{
    const glm::dvec3 FssEss = F0 * A + B;
    const double Ess = A + B;
    const double Ems = 1.0 - Ess;
    const glm::dvec3 Favg = F0 + (1.0 - F0) / 21.0;
    const glm::dvec3 Fms = FssEss * Favg / (1.0 - Ems * Favg);
    return FssEss + Fms * Ems;
}

} // namespace iblab
