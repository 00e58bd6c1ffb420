// The shading lights (ibl/shading_lights.hpp): which groups become lights and how much they
// carry, the residual chain (the prefilter of the map without them), and bake.json's form of
// them (io/shading_lights_json.hpp), bad input included.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/luminance.hpp"
#include "ibl/reference.hpp"
#include "ibl/sh.hpp"
#include "ibl/shading_lights.hpp"
#include "io/error.hpp"
#include "io/shading_lights_json.hpp"

namespace iblab {
namespace {

const glm::dvec3 kSun = glm::normalize(glm::dvec3(0.3, 0.8, -0.5));

// A sky of 0.5 with a 3 degree disc of 2000 (wide enough for a 512-wide map to resolve).
ImageRGB32F sunMap()
{
    return paintEquirect(512, 256, [](glm::dvec3 d) { return glm::vec3(glm::dot(d, kSun) > std::cos(1.5 * kPi / 180.0) ? 2000.0f : 0.5f); });
}

double mapFlux(const ImageRGB32F& image)
{
    double flux = 0.0;
    forEachEquirectTexel(image.width, image.height, [&](int x, int y, glm::dvec3, double dOmega) { flux += double(luminance(image.at(x, y))) * dOmega; });
    return flux;
}

TEST(ShadingLights, ASunBecomesLightsAtItsDirectionCarryingItsExcess)
{
    const ImageRGB32F image = sunMap();
    const ShadingLights found = findShadingLights(image);
    ASSERT_FALSE(found.groups.empty());
    ASSERT_LE(found.groups.size(), std::size_t(kMaxShadingLights));
    // The disc (3 degrees: about 5 groups of 1.4 degrees) minus what the 17th group keeps:
    // at most the disc's flux, and most of it.
    const double disc = (2000.0 - 0.5) * 2.0 * kPi * (1.0 - std::cos(1.5 * kPi / 180.0));
    double flux = 0.0;
    glm::dvec3 centroid(0.0);
    for (const ShadingLightGroup& g : found.groups) {
        flux += double(g.light.flux.g);
        centroid += double(g.light.flux.g) * glm::dvec3(g.light.direction);
        EXPECT_GT(glm::dot(glm::dvec3(g.light.direction), kSun), std::cos(3.0 * kPi / 180.0));
        EXPECT_GE(g.keep, 0.0f);
        EXPECT_LT(g.keep, 1.0f);
        glm::dvec3 points(0.0);
        for (const ShadingLight& p : g.points) points += glm::dvec3(p.flux);
        EXPECT_NEAR(points.g, double(g.light.flux.g), 1e-4 * double(g.light.flux.g)) << "a light's points carry its flux";
    }
    EXPECT_LT(flux, disc * 1.1);
    EXPECT_GT(flux, disc * 0.5);
    EXPECT_GT(glm::dot(glm::normalize(centroid), kSun), std::cos(0.5 * kPi / 180.0));
}

TEST(ShadingLights, AMapWithoutABrightSpotHasNone)
{
    const ImageRGB32F sky = paintEquirect(256, 128, [](glm::dvec3 d) { return glm::vec3(0.2f + 0.1f * float(d.y)); });
    EXPECT_TRUE(findShadingLights(sky).groups.empty());
    EXPECT_TRUE(findShadingLights(paintEquirect(64, 32, [](glm::dvec3) { return glm::vec3(1.0f); })).groups.empty());
    EXPECT_TRUE(findShadingLights(sunMap(), 0).groups.empty());
    // A light below a thousandth of the map's flux is not worth a light's cost.
    const ImageRGB32F faint = paintEquirect(512, 256, [](glm::dvec3 d) { return glm::vec3(glm::dot(d, kSun) > std::cos(2.0 * kPi / 180.0) ? 1.5f : 1.0f); });
    EXPECT_TRUE(findShadingLights(faint).groups.empty()) << "map flux " << mapFlux(faint);
}

// The bake's kernel, written out here: D(h) max(0, n.l) / Z(alpha), v = n.
double kernel(glm::dvec3 n, glm::dvec3 l, double roughness)
{
    const double c = glm::dot(n, l);
    if (c <= 0.0) return 0.0;
    const double alpha = roughness * roughness;
    return ggxD(std::sqrt(0.5 * (1.0 + c)), alpha) * c / ggxPrefilterNormalization(roughness);
}

glm::vec3 texelDirection(int size, int face, int x, int row)
{
    return cubeFaceUvToDirection(face, glm::vec2((float(x) + 0.5f) / float(size), (float(row) + 0.5f) / float(size)));
}

// A chain whose mip m is exactly a constant sky of 0.5 plus the prefilter of two point
// lights: the residual is the sky alone at every mip, and mip 0's texels in the lights'
// groups keep their fraction.
TEST(ShadingLights, TheResidualIsTheChainWithoutTheLights)
{
    ShadingLights lights;
    lights.grid = 8;
    ShadingLightGroup g;
    g.face = 2;
    g.x = 3;
    g.row = 4;
    g.keep = 0.25f;
    const glm::vec3 a = glm::normalize(glm::vec3(0.1f, 1.0f, 0.05f)), b = glm::normalize(glm::vec3(0.12f, 1.0f, 0.02f));
    g.points = {{a, glm::vec3(3.0f, 2.0f, 1.0f)}, {b, glm::vec3(1.0f, 1.0f, 1.0f)}};
    g.light = {glm::normalize(a + b), glm::vec3(4.0f, 3.0f, 2.0f)};
    lights.groups.push_back(g);
    const std::vector<double> roughness{0.0, 0.11, 0.23, 0.55, 1.0};
    std::vector<CubeLevelRgb> chain;
    for (std::size_t m = 0; m < roughness.size(); ++m) {
        const int size = 32 >> m;
        CubeLevelRgb level{size, std::vector<glm::vec3>(std::size_t(6 * size * size), glm::vec3(0.5f))};
        for (int face = 0; face < 6; ++face)
            for (int row = 0; row < size; ++row)
                for (int x = 0; x < size; ++x) {
                    const glm::dvec3 n(texelDirection(size, face, x, row));
                    glm::dvec3 light(0.0);
                    if (m > 0)
                        for (const ShadingLight& p : g.points) light += glm::dvec3(p.flux) * kernel(n, glm::dvec3(p.direction), roughness[m]);
                    level.texels[std::size_t((face * size + row) * size + x)] += glm::vec3(light);
                }
        chain.push_back(level);
    }
    const std::vector<CubeLevelRgb> residual = shadingLightResidual(chain, roughness, lights);
    ASSERT_EQ(residual.size(), chain.size());
    int kept = 0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < 32; ++row)
            for (int x = 0; x < 32; ++x) {
                const bool inGroup = face == 2 && x / 4 == 3 && row / 4 == 4;
                kept += inGroup ? 1 : 0;
                EXPECT_FLOAT_EQ(residual[0].texels[std::size_t((face * 32 + row) * 32 + x)].g, inGroup ? 0.125f : 0.5f);
            }
    EXPECT_EQ(kept, 16);
    for (std::size_t m = 1; m < residual.size(); ++m)
        for (const glm::vec3& t : residual[m].texels)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(t[c], 0.5f, 2e-3f) << "mip " << m;
    // Without lights the chain comes back as it was.
    EXPECT_EQ(shadingLightResidual(chain, roughness, ShadingLights{}).front().texels, chain.front().texels);
    EXPECT_THROW(shadingLightResidual(chain, {0.0, 0.1}, lights), std::invalid_argument);
}

// The diffuse sources less the lights: a cube of a constant sky's irradiance plus the lights'
// exact irradiance comes back as the sky's alone, and the lights' SH9 is what projecting a map
// of them gives (one bright texel each, its radiance x solid angle the light's flux).
TEST(ShadingLights, TheIrradianceLessTheLightsIsTheSkysAlone)
{
    // At texel centres of a 256 x 128 map, so that the map below holds them exactly.
    auto centre = [](int x, int y) { return glm::vec3(equirectUvToDirection(glm::dvec2((x + 0.5) / 256.0, (y + 0.5) / 128.0))); };
    const std::vector<std::pair<int, int>> texels{{40, 30}, {201, 77}};
    const std::vector<ShadingLight> lights{{centre(40, 30), glm::vec3(40.0f, 30.0f, 20.0f)}, {centre(201, 77), glm::vec3(5.0f, 5.0f, 8.0f)}};
    const glm::dvec3 sky(0.5 * kPi); // E of a sky of radiance 0.5 everywhere
    const int size = 16;
    CubeLevelRgb cube{size, std::vector<glm::vec3>(std::size_t(6 * size * size))};
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 n(texelDirection(size, face, x, row));
                glm::dvec3 lit(0.0);
                for (const ShadingLight& l : lights) lit += glm::dvec3(l.flux) * std::max(0.0, glm::dot(n, glm::dvec3(l.direction)));
                EXPECT_NEAR(shadingLightsIrradiance(lights, n).r, lit.r, 1e-9);
                cube.texels[std::size_t((face * size + row) * size + x)] = glm::vec3(sky + lit);
            }
    subtractShadingLightsIrradiance(cube, lights);
    for (const glm::vec3& t : cube.texels)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(t[c], sky[c], 2e-5 * (1.0 + 40.0)) << c;

    // One texel of a 256-wide map per light, holding its flux over the texel's solid angle.
    ImageRGB32F map(256, 128);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const auto [x, y] = texels[i];
        map.set(x, y, lights[i].flux / float(equirectTexelSolidAngle(y, 256, 128)));
    }
    const SH9Color projected = convolveWithCosineLobe(projectEquirect(map));
    const SH9Color ours = shadingLightsShIrradiance(lights);
    for (int i = 0; i < kSh9Count; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ours.c[std::size_t(i)][c], projected.c[std::size_t(i)][c], 1e-4 * 40.0) << i << " " << c;
    EXPECT_GT(std::abs(ours.c[0].r), 10.0) << "the lights carry irradiance";
}

TEST(ShadingLightsJson, RoundTripsAndRejectsWhatIsNotLights)
{
    const ShadingLights found = findShadingLights(sunMap());
    const ShadingLights back = shadingLightsFromJson(nlohmann::json::parse(shadingLightsJson(found).dump()), "test");
    ASSERT_EQ(back.groups.size(), found.groups.size());
    EXPECT_EQ(back.grid, found.grid);
    for (std::size_t i = 0; i < found.groups.size(); ++i) {
        EXPECT_EQ(back.groups[i].face, found.groups[i].face);
        EXPECT_EQ(back.groups[i].points.size(), found.groups[i].points.size());
        EXPECT_NEAR(back.groups[i].light.flux.g, found.groups[i].light.flux.g, 1e-4f * found.groups[i].light.flux.g);
    }
    auto rejects = [](const char* text, const char* words) {
        try {
            shadingLightsFromJson(nlohmann::json::parse(text), "bake.json");
            ADD_FAILURE() << "accepted " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bake.json"), std::string::npos) << e.what();
        }
    };
    const std::string group = R"("face": 0, "x": 1, "row": 2, "keep": 0.5, "flux": [1, 1, 1], "points": [])";
    rejects("[]", "grid and groups");
    rejects(R"({"grid": 0, "groups": []})", "grid");
    rejects(R"({"grid": 8, "groups": [{"face": 0}]})", "lacks");
    rejects((R"({"grid": 8, "groups": [{"direction": [0, 2, 0], )" + group + "}]}").c_str(), "unit");
    rejects((R"({"grid": 8, "groups": [{"direction": [0, 1], )" + group + "}]}").c_str(), "3 numbers");
    rejects(R"({"grid": 8, "groups": [{"face": 9, "x": 1, "row": 2, "keep": 0.5, "direction": [0, 1, 0], "flux": [1, 1, 1], "points": []}]})", "face");
    rejects(R"({"grid": 8, "groups": [{"face": 0, "x": 1, "row": 2, "keep": 2, "direction": [0, 1, 0], "flux": [1, 1, 1], "points": []}]})", "keep");
    rejects(R"({"grid": 8, "groups": [{"face": 0, "x": 1, "row": 2, "keep": 0.5, "direction": [0, 1, 0], "flux": [-1, 1, 1], "points": []}]})", "negative");
    rejects(R"({"grid": 8, "groups": [{"face": 0, "x": 1, "row": 2, "keep": 0.5, "direction": [0, 1, 0], "flux": [1, 1, 1], "points": [[0, 1, 0]]}]})",
            "6 numbers");
}

} // namespace
} // namespace iblab
