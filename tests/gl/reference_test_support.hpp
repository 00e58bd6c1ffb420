#pragma once
// What the reference renderer's tests share: a sphere filling a small square frame, the
// reference of it run to completion, and the value a pixel must have by the CPU's exact
// integrals (renderer/ibl/reference.hpp).
#include <chrono>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bake_test_support.hpp"
#include "frame/camera.hpp"
#include "ibl/brdf.hpp"
#include "ibl/reference.hpp"
#include "renderer_fixture.hpp"

namespace iblab::testing {

constexpr int kReferenceFrameSize = 48; // frame width and height: a sphere of ~1000 surface pixels

// Sample pixels spread over the sphere: centre (n.v = 1), halfway out, and near the rim.
inline constexpr glm::ivec2 kSamplePixels[] = {{24, 24}, {14, 30}, {33, 17}, {24, 9}, {38, 24}};

inline glm::vec4 pixelOf(const FrameReadback& f, int x, int y) { return glm::make_vec4(&f.rgba[(std::size_t(y) * std::size_t(f.width) + std::size_t(x)) * 4]); }

class ReferenceTest : public RendererTest {
protected:
    // The loaded map, at its own size: the reference downsamples it itself.
    ImageRGB32F load(const std::string& spec) { return bakeEnvironment(spec, smallBakeSettings()); }
    static FrameSettings sphere(glm::vec3 baseColor, float metallic, float roughness)
    {
        FrameSettings s;
        s.scene.kind = SceneKind::Sphere;
        s.material = {true, baseColor, metallic, roughness, 1.0f, 0.5f};
        s.view.referenceWidth = 64;
        frameBox(s.camera, glm::vec3(0.0f), glm::vec3(1.0f), 1.0f);
        return s;
    }
    FrameReadback reference(const FrameSettings& s, const ReferenceSlicing& slicing = {})
    {
        const ReferenceStatus status = renderer().advanceReference(s, kReferenceFrameSize, kReferenceFrameSize, std::chrono::hours(1), slicing);
        EXPECT_TRUE(status.complete);
        return renderer().readReferenceFrame();
    }
};

// The surface at a pixel of the reference's G-buffer (in the environment's frame).
struct SurfaceSample {
    glm::dvec3 n, v;
};
inline SurfaceSample surfaceAt(const FrameReadback& normals, const FrameReadback& views, glm::ivec2 p)
{
    return {glm::normalize(glm::dvec3(glm::vec3(pixelOf(normals, p.x, p.y)))), glm::normalize(glm::dvec3(glm::vec3(pixelOf(views, p.x, p.y))))};
}

// Every term of the shading model (pbr.frag's combineLobes) from the CPU references, for a
// surface of settings' material seen from v: env is the map the reference sums over (after
// its downsampling), white a uniform map of radiance 1 of the same size (for the
// single-scattering albedo the energy compensation divides by).
inline glm::dvec3 cpuReferencePixel(const ImageRGB32F& env, const ImageRGB32F& white, const FrameSettings& s, const SurfaceSample& surface)
{
    const double intensity = std::exp2(double(s.environment.intensityEv));
    const double roughness = s.material.roughness, metallic = s.material.metallic;
    const glm::dvec3 base(s.material.baseColor);
    const double specularLevel = s.material.specular;
    const glm::dvec3 F0 = glm::mix(glm::dvec3(0.16 * specularLevel * specularLevel), base, metallic);
    const glm::dvec3 n = surface.n, v = surface.v;
    const double NdotV = std::max(glm::dot(n, v), 1e-4);
    glm::dvec3 specular = referenceSpecular(env, n, v, roughness, F0, s.sampling.geometry);
    if (s.sampling.multiscatter) {
        const double singleScatter = referenceSpecular(white, n, v, roughness, glm::dvec3(1.0), s.sampling.geometry).x;
        const glm::dvec3 averageFresnel = F0 + (glm::dvec3(1.0) - F0) / 21.0;
        specular *= s.sampling.multiscatterModel == MultiscatterModel::FdezAguera
                        ? glm::dvec3(1.0) / (glm::dvec3(1.0) - averageFresnel * (1.0 - singleScatter))
                        : glm::dvec3(1.0) + F0 * (1.0 / singleScatter - 1.0);
    }
    const glm::dvec3 kD = (glm::dvec3(1.0) - fresnelSchlickRoughness(NdotV, F0, roughness)) * (1.0 - metallic);
    return (kD * base / kPi * referenceIrradiance(env, n) + specular) * intensity;
}

} // namespace iblab::testing
