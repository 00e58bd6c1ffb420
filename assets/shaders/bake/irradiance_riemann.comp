// Diffuse irradiance E(n) = integral L(w) max(0, n.w) dOmega by LearnOpenGL's Riemann sum: a
// regular grid in (theta, phi) over the hemisphere around n, the environment read at mip 0.
// Two corrections to the tutorial's bookkeeping, neither changes its cost:
//  - each cell is weighted by its exact integral of cos(theta) sin(theta) dtheta dphi,
//    (sin^2 theta1 - sin^2 theta0) / 2 * dphi, with the sample at the cell's centre, instead
//    of "pi * sum(L cos sin) / count" over a grid that starts at 0 and overshoots 2 pi and
//    pi/2 by up to one step: a constant environment now integrates to exactly pi L;
//  - the result is E itself (white -> pi), not the tutorial's E / pi.
// uPhiSteps = round(2 pi / sampleDelta), uThetaSteps = round(pi/2 / sampleDelta).
// An option the tutorial does not have, uMipFiltering: each cell reads the source mip whose
// texels are as large as the cell (prefilter_lod.glsl), so that a coarse grid averages the
// environment over its cells instead of point-sampling it (which aliases on a small bright
// source, and needs the tutorial's fine grid on a smooth one).
#include "common/conventions.glsl"
#include "common/sampling.glsl"
#include "bake/cube_texel.glsl"
#include "bake/source_read.glsl"

uniform int uPhiSteps;
uniform int uThetaSteps;
uniform float uMipBias;

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    mat3 frame = tangentFrame(outputTexelDirection(texel));
    float dPhi = 2.0 * IBL_PI / float(uPhiSteps);
    float dTheta = 0.5 * IBL_PI / float(uThetaSteps);
    vec3 irradiance = vec3(0.0);
    for (int t = 0; t < uThetaSteps; ++t) {
        float sin0 = sin(float(t) * dTheta);
        float sin1 = sin(float(t + 1) * dTheta);
        float weight = 0.5 * (sin1 * sin1 - sin0 * sin0) * dPhi;
        float theta = (float(t) + 0.5) * dTheta;
        float sinTheta = sin(theta);
        float cosTheta = cos(theta);
        // The cell's solid angle: integral of sin(theta) dtheta dphi.
        float cellSolidAngle = (cos(float(t) * dTheta) - cos(float(t + 1) * dTheta)) * dPhi;
        float cellLodTerm = sourceLodSampleTerm(cellSolidAngle, uMipBias);
        vec3 ring = vec3(0.0);
        for (int p = 0; p < uPhiSteps; ++p) {
            float phi = (float(p) + 0.5) * dPhi;
            vec3 l = frame * vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
            ring += readSource(cellLodTerm, l);
        }
        irradiance += ring * weight;
    }
    storeOutput(texel, irradiance);
}
