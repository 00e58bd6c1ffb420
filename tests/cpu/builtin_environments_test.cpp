// Procedural environments against their closed-form integrals. Solid angles, luminance
// and directions are recomputed here from the conventions' formulas, not taken from the
// code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "ibl/conventions.hpp"

using namespace iblab;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kDeg = kPiD / 180.0;

double rowOmega(int y, int w, int h) { return 2.0 * kPiD / w * (std::cos(kPiD * y / h) - std::cos(kPiD * (y + 1) / h)); }

// Sum over texels of L_c * dOmega for one channel.
double integral(const ImageRGB32F& img, int channel, double minus = 0.0)
{
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y) {
        double row = 0.0;
        for (int x = 0; x < img.width; ++x)
            row += double(img.texels[img.offset(x, y) + std::size_t(channel)]) - minus;
        sum += row * rowOmega(y, img.width, img.height);
    }
    return sum;
}

double discSolidAngle(double diameterDegrees) { return 2.0 * kPiD * (1.0 - std::cos(0.5 * diameterDegrees * kDeg)); }

// Connected components of texels with any channel > threshold, 8-connected, with the
// equirect's horizontal wrap-around (column W-1 touches column 0).
int countBlobs(const ImageRGB32F& img, float threshold)
{
    const int w = img.width, h = img.height;
    std::vector<int> label(std::size_t(w) * h, 0);
    const auto lit = [&](int x, int y) {
        const glm::vec3 c = img.at(x, y);
        return std::max({c.r, c.g, c.b}) > threshold;
    };
    int blobs = 0;
    std::vector<std::pair<int, int>> stack;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!lit(x, y) || label[std::size_t(y) * w + x])
                continue;
            ++blobs;
            stack.push_back({x, y});
            label[std::size_t(y) * w + x] = blobs;
            while (!stack.empty()) {
                const auto [cx, cy] = stack.back();
                stack.pop_back();
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = (cx + dx + w) % w;
                        const int ny = cy + dy;
                        if (ny < 0 || ny >= h || !lit(nx, ny) || label[std::size_t(ny) * w + nx])
                            continue;
                        label[std::size_t(ny) * w + nx] = blobs;
                        stack.push_back({nx, ny});
                    }
            }
        }
    return blobs;
}

std::string errorMessage(const std::string& spec)
{
    try {
        makeBuiltinEnvironment(spec);
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos);
        EXPECT_NE(what.find(spec), std::string::npos) << "message must name the spec: " << what;
        return what;
    }
    ADD_FAILURE() << spec << ": no iblab::Error";
    return {};
}

} // namespace

TEST(Builtin, WhiteIsExactlyOneEverywhere)
{
    const ImageRGB32F img = makeBuiltinEnvironment("builtin:white");
    EXPECT_EQ(img.width, 512);
    EXPECT_EQ(img.height, 256);
    ASSERT_EQ(img.texels.size(), 512u * 256u * 3u);
    for (float v : img.texels)
        ASSERT_EQ(v, 1.0f);
    // Furnace identity: the integral of 1 over the sphere is 4 pi (to rounding of the
    // per-row solid angles).
    EXPECT_NEAR(integral(img, 1), 4.0 * kPiD, 1e-9);
    for (float v : makeBuiltinEnvironment("builtin:white?value=2.5&width=64").texels)
        ASSERT_EQ(v, 2.5f);
}

TEST(Builtin, BlackIsZero)
{
    const ImageRGB32F img = makeBuiltinEnvironment("builtin:black?width=32");
    EXPECT_EQ(img.width, 32);
    for (float v : img.texels)
        ASSERT_EQ(v, 0.0f);
}

TEST(Builtin, SkyMeanIsHalfTopPlusGround)
{
    // Width 510 gives 255 rows: the middle row straddles the horizon and must hold the
    // solid-angle weighted average for the mean to stay exact.
    for (const char* spec : {"builtin:sky", "builtin:sky?top=3&ground=0.5&width=510", "sky?width=66&ground=0"}) {
        const BuiltinSpec parsed = parseBuiltinSpec(spec);
        const ImageRGB32F img = makeBuiltinEnvironment(parsed);
        const double expected = 0.5 * (parsed.get("top") + parsed.get("ground"));
        for (int c = 0; c < 3; ++c) {
            const double mean = integral(img, c) / (4.0 * kPiD);
            // Only float storage of the texels limits this: ~6e-8 relative.
            EXPECT_NEAR(mean, expected, 1e-5 * expected) << spec;
        }
        EXPECT_EQ(img.at(7, 0).g, float(parsed.get("top")));
        EXPECT_EQ(img.at(7, img.height - 1).g, float(parsed.get("ground")));
    }
}

TEST(Builtin, SunPowerMatchesDiscSolidAngle)
{
    // Sum of (L - sky) dOmega = intensity * 2 pi (1 - cos(size / 2)). At width 2048 the
    // 0.53 degree disc spans 3 texels (~7 texels of area, ~10 on the rim). Rim texels are
    // supersampled on 32x32 equal-solid-angle strata over the part of the texel inside the
    // disc's bounding box, so the error is only the strata cut by the rim, ~1/32 of a
    // stratum row each and partly cancelling: measured 0.03% at 2048, 0.3% when the disc is
    // smaller than a texel (width 512). 2% leaves room for rounding of the float texels and
    // still fails for the usual mistakes (point-sampling texel centres misses by 10-30%, a
    // radius/diameter mix-up by 300%, a missing sin(theta) in the weights by far more at 80
    // degrees elevation).
    for (const char* spec : {"builtin:sun?width=2048", "builtin:sun?width=2048&elevation=80&azimuth=-130&size=2",
                             "builtin:sun?width=512&elevation=10&size=0.53" /* smaller than a texel */,
                             "builtin:sun?width=256&elevation=89.5&size=3" /* holds the pole */,
                             "builtin:sun?width=512&elevation=-20&azimuth=180&size=1" /* on the seam */}) {
        const BuiltinSpec parsed = parseBuiltinSpec(spec);
        const ImageRGB32F img = makeBuiltinEnvironment(parsed);
        const double expected = parsed.get("intensity") * discSolidAngle(parsed.get("size"));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(integral(img, c, parsed.get("sky")), expected, 0.02 * expected) << spec;
    }
}

TEST(Builtin, SunSitsAtElevationAndAzimuth)
{
    // Azimuth is measured from -Z towards +X: azimuth 90 must put the sun towards +X.
    const ImageRGB32F img = makeBuiltinEnvironment("builtin:sun?width=1024&elevation=30&azimuth=90&size=2");
    int bx = 0, by = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.at(x, y).r > img.at(bx, by).r)
                bx = x, by = y;
    const glm::vec3 d = equirectUvToDirection(glm::vec2((bx + 0.5f) / img.width, (by + 0.5f) / img.height));
    const glm::vec3 expected(float(std::cos(30 * kDeg)), float(std::sin(30 * kDeg)), 0.0f);
    EXPECT_GT(glm::dot(d, expected), std::cos(1.0 * kDeg)) << d.x << " " << d.y << " " << d.z;
    const glm::dvec3 helper = directionFromElevationAzimuth(30, 90);
    EXPECT_NEAR(helper.x, std::cos(30 * kDeg), 1e-12);
    EXPECT_NEAR(helper.y, 0.5, 1e-12);
    EXPECT_NEAR(helper.z, 0.0, 1e-12);
    EXPECT_NEAR(directionFromElevationAzimuth(0, 0).z, -1.0, 1e-12); // azimuth 0 = -Z
}

TEST(Builtin, LightsCountGivesThatManySeparateBlobs)
{
    // azimuth=180 puts the first disc on the u = 0 / 1 seam: without wrap-around it would
    // count twice.
    for (int count : {1, 2, 3, 5, 8}) {
        const std::string spec = "builtin:lights?count=" + std::to_string(count) + "&azimuth=180";
        const BuiltinSpec parsed = parseBuiltinSpec(spec);
        const ImageRGB32F img = makeBuiltinEnvironment(parsed);
        EXPECT_EQ(countBlobs(img, 0.0f), count) << spec;
        const double expected = count * parsed.get("intensity") * discSolidAngle(parsed.get("size"));
        EXPECT_NEAR(integral(img, 0), expected, 0.02 * expected) << spec; // see the sun test
    }
}

TEST(Builtin, StudioHasSaturatedColouredLightsOnDarkBackground)
{
    const ImageRGB32F img = makeBuiltinEnvironment("builtin:studio?width=256");
    int red = 0, green = 0, blue = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec3 c = img.at(x, y);
            red += (c.r > 5.0f && c.r > 10.0f * std::max(c.g, c.b)) ? 1 : 0;
            green += (c.g > 5.0f && c.g > 10.0f * std::max(c.r, c.b)) ? 1 : 0;
            blue += (c.b > 5.0f && c.b > 10.0f * std::max(c.r, c.g)) ? 1 : 0;
        }
    EXPECT_GT(red, 20);
    EXPECT_GT(green, 20);
    EXPECT_GT(blue, 20);
    EXPECT_EQ(img.at(0, img.height - 1), glm::vec3(0.02f)); // nadir: background only
    EXPECT_EQ(makeBuiltinEnvironment("builtin:studio?width=256").texels, img.texels); // deterministic
    // intensity scales the lights, not the background.
    const ImageRGB32F brighter = makeBuiltinEnvironment("builtin:studio?width=256&intensity=2");
    EXPECT_NEAR(integral(brighter, 0, 0.02), 2.0 * integral(img, 0, 0.02), 1e-4 * integral(img, 0, 0.02));
}

TEST(Builtin, UnknownNameListsTheValidOnes)
{
    const std::string msg = errorMessage("builtin:moon");
    for (const std::string& name : builtinEnvironmentNames())
        EXPECT_NE(msg.find(name), std::string::npos) << msg;
    EXPECT_NE(msg.find("moon"), std::string::npos);
}

TEST(Builtin, UnknownParameterListsTheValidOnes)
{
    const std::string msg = errorMessage("builtin:sun?colour=red");
    EXPECT_NE(msg.find("colour"), std::string::npos) << msg;
    for (const char* p : {"width", "elevation", "azimuth", "size", "intensity", "sky"})
        EXPECT_NE(msg.find(p), std::string::npos) << msg;
}

TEST(Builtin, BadValuesAreRejected)
{
    errorMessage("builtin:sun?size=abc");
    errorMessage("builtin:sun?size=");
    errorMessage("builtin:sun?size=-1");
    errorMessage("builtin:sun?size=1x");
    errorMessage("builtin:sun?size=nan");
    errorMessage("builtin:sun?elevation=91");
    errorMessage("builtin:sun?width=511");
    errorMessage("builtin:lights?count=2.5");
    errorMessage("builtin:lights?count=0");
    errorMessage("builtin:sun?size=1&size=2");
    errorMessage("builtin:sun?size");
    errorMessage("builtin:");
}

TEST(Builtin, ParsingIsTolerantAndCanonical)
{
    const BuiltinSpec spec = parseBuiltinSpec(" builtin:Sun ? elevation = 30 && SIZE=+0.5& ");
    EXPECT_EQ(spec.name, "sun");
    EXPECT_EQ(spec.get("elevation"), 30.0);
    EXPECT_EQ(spec.get("size"), 0.5);
    EXPECT_EQ(spec.get("intensity"), 1e4); // default
    EXPECT_EQ(spec.canonical(), "builtin:sun?elevation=30&size=0.5");
    EXPECT_EQ(parseBuiltinSpec("builtin:sun?intensity=1e4").canonical(), "builtin:sun");
    EXPECT_EQ(parseBuiltinSpec(spec.canonical()).values, spec.values); // round trip
    EXPECT_TRUE(isBuiltinSpec("builtin:white"));
    EXPECT_FALSE(isBuiltinSpec("white.exr"));
}

TEST(Builtin, NamesAndDescriptions)
{
    const std::vector<std::string> names = builtinEnvironmentNames();
    for (const char* n : {"white", "black", "sky", "sun", "lights", "studio", "texel", "slits", "nan"})
        EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
    for (const std::string& n : names) {
        EXPECT_FALSE(builtinEnvironmentDescription(n).empty());
        EXPECT_EQ(builtinEnvironmentInfo(n).parameters.front().name, "width");
    }
    EXPECT_THROW(builtinEnvironmentDescription("nope"), Error);
}

// The texel that holds (elevation, azimuth), recomputed from the convention (u = 0.5 + az /
// 360, v = polar angle / 180), not taken from the code under test.
std::pair<int, int> texelHolding(double elevationDegrees, double azimuthDegrees, int w)
{
    const double u = 0.5 + azimuthDegrees / 360.0;
    const double v = (90.0 - elevationDegrees) / 180.0;
    return {int(std::floor((u - std::floor(u)) * w)), int(std::floor(v * (w / 2)))};
}

TEST(Builtin, TexelLightsExactlyOneTexelWithKnownPower)
{
    for (const char* spec : {"builtin:texel", "builtin:texel?width=64&elevation=-60&azimuth=170&intensity=5e5",
                             "builtin:texel?width=128&elevation=33.3&azimuth=-100.7&sky=0.25&intensity=7"}) {
        const BuiltinSpec parsed = parseBuiltinSpec(spec);
        const ImageRGB32F img = makeBuiltinEnvironment(parsed);
        const auto [ex, ey] = texelHolding(parsed.get("elevation"), parsed.get("azimuth"), img.width);
        const float sky = float(parsed.get("sky"));
        int lit = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                if (img.at(x, y) != glm::vec3(sky)) {
                    ++lit;
                    EXPECT_EQ(x, ex) << spec;
                    EXPECT_EQ(y, ey) << spec;
                    EXPECT_EQ(img.at(x, y), glm::vec3(sky + float(parsed.get("intensity")))) << spec;
                }
        EXPECT_EQ(lit, 1) << spec;
        // Its power is the intensity times that one texel's solid angle (float rounding only).
        const double expected = parsed.get("intensity") * rowOmega(ey, img.width, img.height);
        EXPECT_NEAR(integral(img, 0, sky), expected, 1e-5 * expected + 1e-6) << spec;
    }
}

TEST(Builtin, SlitsHaveKnownPowerAndCount)
{
    // Each slit is a lat-long rectangle: solid angle (size / 360) 2 pi (2 sin(height / 2)),
    // rasterised by exact coverage, so the power holds to float rounding whether or not a
    // slit is narrower than a texel.
    for (const char* spec : {"builtin:slits", "builtin:slits?width=256&count=7&size=4&height=90&intensity=3",
                             "builtin:slits?width=64&count=100&size=0.05"}) {
        const BuiltinSpec parsed = parseBuiltinSpec(spec);
        const ImageRGB32F img = makeBuiltinEnvironment(parsed);
        const double slit = parsed.get("size") / 360.0 * 2.0 * kPiD * 2.0 * std::sin(0.5 * parsed.get("height") * kDeg);
        const double expected = parsed.get("count") * parsed.get("intensity") * slit;
        EXPECT_NEAR(integral(img, 1), expected, 1e-4 * expected) << spec;
        for (int y = 0; y < img.height; ++y) {
            const double elevation = 90.0 - 180.0 * (y + 0.5) / img.height;
            if (std::abs(elevation) > 0.5 * parsed.get("height") + 180.0 / img.height) {
                for (int x = 0; x < img.width; ++x)
                    ASSERT_EQ(img.at(x, y), glm::vec3(0.0f)) << spec << ": light outside the slits' elevation range at row " << y;
            }
        }
    }
    // Separate slits where they are wider apart than a texel: one blob each.
    EXPECT_EQ(countBlobs(makeBuiltinEnvironment("builtin:slits?width=512&count=12&size=1"), 0.0f), 12);
}

TEST(Builtin, NanHoldsEachInvalidKindCountTimes)
{
    const BuiltinSpec parsed = parseBuiltinSpec("builtin:nan?width=64&count=10&negative=-2.5");
    const ImageRGB32F img = makeBuiltinEnvironment(parsed);
    int nan = 0, positiveInf = 0, negativeInf = 0, negative = 0;
    for (float v : img.texels) {
        nan += std::isnan(v);
        positiveInf += std::isinf(v) && v > 0;
        negativeInf += std::isinf(v) && v < 0;
        negative += v == -2.5f;
    }
    // All three components of each invalid texel.
    EXPECT_EQ(nan, 30);
    EXPECT_EQ(positiveInf, 30);
    EXPECT_EQ(negativeInf, 30);
    EXPECT_EQ(negative, 30);
    EXPECT_THROW(makeBuiltinEnvironment("builtin:nan?width=8&count=9"), Error) << "36 invalid texels cannot fit in 8x4";
}
