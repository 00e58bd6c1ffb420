// The prefiltered cube the GPU actually reads, on the CPU: the mips a bake wrote
// (`iblab bake --env MAP --out DIR`, bake_files.hpp: prefiltered_mip<k>.exr, one strip of 6
// faces per mip) read as textureLod reads them: seamless bilinear within a mip, linear
// between the two mips around the layout's lod (prefilterMipFromRoughness). So the study's
// reads carry everything the bake does to the lobe that an exact prefilter would not: the
// face sizes (256 down to 8 for the default bake), the sampling noise, the PDF source-mip
// filtering that widens each lobe, and half-float storage.
#include "accuracy_study.hpp"

#include <cmath>
#include <stdexcept>

#include "ibl/conventions.hpp"
#include "ibl/shading_lights.hpp"
#include "io/image_codec.hpp"

namespace iblab::accuracy {
namespace {

std::vector<glm::vec3> readStrip(const std::filesystem::path& path, int& faceSize)
{
    std::string error;
    const std::unique_ptr<ImageReader> in = imageCodec().openFile(path.string(), error);
    if (!in) throw std::runtime_error(path.string() + ": cannot open: " + error);
    const ImageHeader& h = in->header();
    if (h.channels < 3 || h.height != 6 * h.width) throw std::runtime_error(path.string() + ": not a cube strip of 6 RGB faces");
    std::vector<float> rgb(std::size_t(h.width) * std::size_t(h.height) * 3);
    if (!in->readImage(3, PixelType::Float, rgb.data())) throw std::runtime_error(path.string() + ": " + in->takeError());
    faceSize = h.width;
    std::vector<glm::vec3> texels(rgb.size() / 3);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = glm::vec3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
    return texels;
}

} // namespace

CubeChain CubeChain::fromBake(const std::filesystem::path& directory, int layout)
{
    CubeChain chain;
    chain.layout_ = layout;
    for (int level = 0; std::filesystem::exists(directory / ("prefiltered_mip" + std::to_string(level) + ".exr")); ++level) {
        Mip mip;
        mip.texels = readStrip(directory / ("prefiltered_mip" + std::to_string(level) + ".exr"), mip.size);
        chain.mips_.push_back(std::move(mip));
    }
    if (chain.mips_.empty()) throw std::runtime_error(directory.string() + ": no prefiltered_mip0.exr (write it with iblab bake --env MAP --out DIR)");
    return chain;
}

// GL's seamless filtering takes a texel beyond a face's edge from the face the texel's
// centre direction lands on; here each of the four bilinear texels outside the face is
// found that way (at a corner GL averages three texels, this takes one: a difference
// confined to the 4 texels around each of the 8 corners).
glm::dvec3 CubeChain::Mip::bilinear(glm::dvec3 direction) const
{
    const glm::vec3 fst = directionToCubeFaceUv(glm::vec3(direction));
    const int face = int(fst.x + 0.5f);
    const double x = double(fst.y) * size - 0.5, y = double(fst.z) * size - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    auto texel = [&](int i, int j) {
        if (i >= 0 && i < size && j >= 0 && j < size) return glm::dvec3(at(face, i, j));
        const glm::vec3 d = cubeFaceUvToDirection(face, glm::vec2((float(i) + 0.5f) / float(size), (float(j) + 0.5f) / float(size)));
        const glm::vec3 g = directionToCubeFaceUv(d);
        const int f = int(g.x + 0.5f);
        return glm::dvec3(at(f, std::clamp(int(g.y * float(size)), 0, size - 1), std::clamp(int(g.z * float(size)), 0, size - 1)));
    };
    return (1.0 - fy) * ((1.0 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) + fy * ((1.0 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

CubeChain CubeChain::withoutShadingLights(const ShadingLights& lights) const
{
    std::vector<CubeLevelRgb> levels;
    std::vector<double> roughness;
    for (const Mip& mip : mips_) {
        roughness.push_back(double(shared::prefilterRoughnessFromMip(float(levels.size()), float(mips_.size()), layout_)));
        levels.push_back({mip.size, mip.texels});
    }
    CubeChain residual;
    residual.layout_ = layout_;
    for (CubeLevelRgb& level : shadingLightResidual(std::move(levels), roughness, lights)) residual.mips_.push_back({level.size, std::move(level.texels)});
    return residual;
}

glm::dvec3 CubeChain::lookup(glm::dvec3 direction, double roughness) const
{
    const double lod = std::clamp(double(shared::prefilterMipFromRoughness(float(roughness), float(mips_.size()), layout_)), 0.0,
                                  double(mips_.size() - 1));
    const int m0 = int(std::floor(lod));
    const int m1 = std::min(m0 + 1, int(mips_.size()) - 1);
    const double t = lod - m0;
    const glm::dvec3 a = mips_[std::size_t(m0)].bilinear(direction);
    if (t <= 0.0 || m1 == m0) return a;
    return a * (1.0 - t) + mips_[std::size_t(m1)].bilinear(direction) * t;
}

} // namespace iblab::accuracy
