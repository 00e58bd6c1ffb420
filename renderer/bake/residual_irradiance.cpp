#include "bake/residual_irradiance.hpp"

namespace iblab::bake {

CubeLevelRgb cubeLevelRgb(const CubeImage& image)
{
    CubeLevelRgb rgb{image.size, {}};
    rgb.texels.reserve(image.texels.size());
    for (const glm::vec4& t : image.texels) rgb.texels.emplace_back(t);
    return rgb;
}

BakedTexture residualIrradianceCube(const BakedTexture& irradiance, const std::vector<ShadingLight>& lights)
{
    CubeLevelRgb cube = cubeLevelRgb(readCubeLevel(irradiance, 0));
    subtractShadingLightsIrradiance(cube, lights);
    CubeImage residual(cube.size);
    for (std::size_t i = 0; i < cube.texels.size(); ++i) residual.texels[i] = glm::vec4(cube.texels[i], 1.0f);
    BakedTexture out = createCubeTexture(irradiance.internalFormat, irradiance.size, 1);
    uploadCubeLevel(out, 0, residual);
    return out;
}

} // namespace iblab::bake
