#include "ibl/equirect.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace iblab {

double equirectTexelSolidAngle(int y, int width, int height)
{
    const double dPhi = 2.0 * kPi / double(width);
    const double theta0 = kPi * double(y) / double(height);
    const double theta1 = kPi * double(y + 1) / double(height);
    return dPhi * (std::cos(theta0) - std::cos(theta1));
}

glm::dvec3 equirectTexelDirection(int x, int y, int width, int height)
{
    const glm::vec2 uv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
    return glm::normalize(glm::dvec3(equirectUvToDirection(uv)));
}

glm::vec3 equirectBilinearAt(const ImageRGB32F& image, double fx, double fy)
{
    const double x0f = std::floor(fx);
    const double y0f = std::floor(fy);
    const double tx = fx - x0f;
    const double ty = fy - y0f;

    auto wrapX = [&](long x) { return int(((x % image.width) + image.width) % image.width); };
    auto clampY = [&](long y) { return int(std::clamp<long>(y, 0, image.height - 1)); };
    const int xa = wrapX(long(x0f));
    const int xb = wrapX(long(x0f) + 1);
    const int ya = clampY(long(y0f));
    const int yb = clampY(long(y0f) + 1);

    const glm::dvec3 top = glm::dvec3(image.at(xa, ya)) * (1.0 - tx) + glm::dvec3(image.at(xb, ya)) * tx;
    const glm::dvec3 bottom = glm::dvec3(image.at(xa, yb)) * (1.0 - tx) + glm::dvec3(image.at(xb, yb)) * tx;
    return glm::vec3(top * (1.0 - ty) + bottom * ty);
}

glm::vec3 sampleEquirectBilinear(const ImageRGB32F& image, glm::dvec3 dir)
{
    const glm::vec2 uv = directionToEquirectUv(glm::vec3(glm::normalize(dir)));
    // Continuous texel coordinates whose integer values land on texel centres.
    return equirectBilinearAt(image, double(uv.x) * image.width - 0.5, double(uv.y) * image.height - 0.5);
}

ImageRGB32F paintEquirect(int width, int height, const std::function<glm::vec3(glm::dvec3)>& radiance)
{
    ImageRGB32F image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.set(x, y, radiance(equirectTexelDirection(x, y, width, height)));
    return image;
}

} // namespace iblab
