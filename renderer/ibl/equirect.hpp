#pragma once
// Texel geometry of an equirectangular environment: where each texel looks, and how much
// of the sphere it covers. Every CPU reference (SH projection, exact integrals) sums over
// texels with these weights, so they are exact for the piecewise-constant image rather
// than "approximately sin(theta) dtheta dphi".
//
// Texel (x, y) of a W x H image covers u in [x/W, (x+1)/W] and v in [y/H, (y+1)/H]; its
// centre is uv = ((x + 0.5)/W, (y + 0.5)/H) and equirectUvToDirection (conventions.glsl)
// turns that into a direction. Row 0 is the zenith +Y.
#include <functional>

#include <glm/vec3.hpp>

#include "ibl/conventions.hpp"
#include "ibl/image.hpp"

namespace iblab {

// Exact solid angle of any texel in row y of a width x height equirect.
// With theta = pi v the polar angle from +Y and phi = 2 pi u, dOmega = sin(theta) dtheta dphi,
// so a texel spanning [theta0, theta1] x [phi0, phi0 + dphi] covers
//   integral sin(theta) dtheta * dphi = dphi * (cos(theta0) - cos(theta1)),
// which sums to exactly 4 pi over the image (the cosines telescope from 1 to -1).
double equirectTexelSolidAngle(int y, int width, int height);

// Unit direction through the centre of texel (x, y), via conventions.hpp (float math,
// promoted and renormalised in double).
glm::dvec3 equirectTexelDirection(int x, int y, int width, int height);

// Calls fn(x, y, direction, solidAngle) for every texel, row by row. The row's solid angle
// is computed once per row (it does not depend on x).
template <typename Fn>
void forEachEquirectTexel(int width, int height, Fn&& fn)
{
    for (int y = 0; y < height; ++y) {
        const double dOmega = equirectTexelSolidAngle(y, width, height);
        for (int x = 0; x < width; ++x)
            fn(x, y, equirectTexelDirection(x, y, width, height), dOmega);
    }
}

// Bilinear lookup of an equirect image in direction dir (need not be normalised; must be
// non-zero), with the texel-centre convention above: u wraps around (the seam at u = 0/1 is
// continuous), v clamps at the poles (no filtering across the pole). Matches a GL sampler
// with GL_REPEAT in s and GL_CLAMP_TO_EDGE in t at mip 0.
glm::vec3 sampleEquirectBilinear(const ImageRGB32F& image, glm::dvec3 dir);
// The same read at continuous texel coordinates (texel centres at integers): wrapping in x,
// clamped in y, as the GPU's sampler reads the map (GL_REPEAT / GL_CLAMP_TO_EDGE).
glm::vec3 equirectBilinearAt(const ImageRGB32F& image, double fx, double fy);

// An equirect image whose every texel holds radiance(direction of its centre): analytic
// test environments and the procedural builtins are made this way.
ImageRGB32F paintEquirect(int width, int height, const std::function<glm::vec3(glm::dvec3)>& radiance);

} // namespace iblab
