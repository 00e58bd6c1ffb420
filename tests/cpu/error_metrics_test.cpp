// The error view's numbers on hand-made images whose answers are known in closed form.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/error_metrics.hpp"

namespace iblab {
namespace {

struct Images {
    std::vector<float> value;
    std::vector<float> reference;
    std::vector<std::uint8_t> include;
    void add(glm::vec3 v, glm::vec3 r, bool included = true)
    {
        value.insert(value.end(), {v.r, v.g, v.b, 1.0f});
        reference.insert(reference.end(), {r.r, r.g, r.b, 1.0f});
        include.push_back(included ? 1 : 0);
    }
    ErrorMetrics metrics() const { return computeErrorMetrics(value, reference, include); }
};

TEST(ErrorMetrics, IdenticalImagesHaveNoError)
{
    Images images;
    for (int i = 0; i < 10; ++i) images.add(glm::vec3(0.1f * float(i + 1), 0.3f, 2.0f), glm::vec3(0.1f * float(i + 1), 0.3f, 2.0f));
    const ErrorMetrics m = images.metrics();
    EXPECT_EQ(m.pixels, 10u);
    EXPECT_EQ(m.relativeRmse, 0.0);
    EXPECT_EQ(m.maxRelative, 0.0);
    EXPECT_EQ(m.fireflies, 0u);
}

// Pixel i of 100 is (1 + i/100) grey over a reference of 1: relative error e_i = i/100, so
// mean = 0.495, max = 0.99, the 99th percentile (nearest rank 99 of 100) = 0.98 and
// RMSE = sqrt(sum i^2 / 100) / 100 = sqrt(99 * 100 * 199 / 6 / 100) / 100.
TEST(ErrorMetrics, KnownRampOfErrors)
{
    Images images;
    for (int i = 0; i < 100; ++i) images.add(glm::vec3(1.0f + float(i) / 100.0f), glm::vec3(1.0f));
    const ErrorMetrics m = images.metrics();
    EXPECT_EQ(m.pixels, 100u);
    EXPECT_NEAR(m.meanRelative, 0.495, 1e-6);
    EXPECT_NEAR(m.maxRelative, 0.99, 1e-6);
    EXPECT_NEAR(m.p99Relative, 0.98, 1e-6);
    EXPECT_NEAR(m.relativeRmse, std::sqrt(99.0 * 100.0 * 199.0 / 6.0 / 100.0) / 100.0, 1e-6);
    EXPECT_EQ(m.fireflies, 0u);
}

// The measure is the L1 colour difference over the reference's channel sum: a hue shift at
// equal brightness counts, and a dark channel does not blow the ratio up.
TEST(ErrorMetrics, RelativeErrorIsL1OverTheReferenceSum)
{
    EXPECT_FLOAT_EQ(relativeError(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)), 2.0f);
    EXPECT_FLOAT_EQ(relativeError(glm::vec3(0.5f, 0.1f, 0.0f), glm::vec3(0.4f, 0.1f, 0.0f)), 0.2f);
    EXPECT_TRUE(std::isfinite(relativeError(glm::vec3(1.0f), glm::vec3(0.0f))));
}

TEST(ErrorMetrics, ExcludedPixelsDoNotCount)
{
    Images images;
    images.add(glm::vec3(1.1f), glm::vec3(1.0f));
    images.add(glm::vec3(100.0f), glm::vec3(1.0f), /*included=*/false); // a background pixel
    const ErrorMetrics m = images.metrics();
    EXPECT_EQ(m.pixels, 1u);
    EXPECT_NEAR(m.maxRelative, 0.1, 1e-6);
    EXPECT_EQ(m.fireflies, 0u);
}

TEST(ErrorMetrics, FirefliesExceedThreeTimesTheReference)
{
    Images images;
    images.add(glm::vec3(3.0f), glm::vec3(1.0f));   // exactly 3x: not above
    images.add(glm::vec3(3.1f), glm::vec3(1.0f));   // above
    images.add(glm::vec3(9.0f, 0.0f, 0.0f), glm::vec3(1.0f)); // 9 > 3 * 3 is false: sum 9 = 3 * 3
    images.add(glm::vec3(0.0f, 0.0f, 10.0f), glm::vec3(1.0f)); // sum 10 > 9
    EXPECT_EQ(images.metrics().fireflies, 2u);
}

TEST(ErrorMetrics, NoPixelsGiveZeros)
{
    Images images;
    images.add(glm::vec3(5.0f), glm::vec3(1.0f), false);
    const ErrorMetrics m = images.metrics();
    EXPECT_EQ(m.pixels, 0u);
    EXPECT_EQ(m.relativeRmse, 0.0);
}

TEST(ErrorMetrics, MismatchedSizesThrow)
{
    std::vector<float> four(4, 1.0f), eight(8, 1.0f);
    std::vector<std::uint8_t> one(1, 1);
    EXPECT_THROW(computeErrorMetrics(four, eight, one), std::invalid_argument);
}

// Turbo runs from near black through blue and green to dark red, and clamps outside [0, 1].
TEST(ErrorMetrics, FalseColourRunsBlueToRed)
{
    const glm::vec3 low = falseColour(0.0f), blue = falseColour(0.15f), middle = falseColour(0.5f), high = falseColour(1.0f);
    EXPECT_LT(low.r + low.g + low.b, 0.5f);
    EXPECT_GT(blue.b, blue.r);
    EXPECT_GT(blue.b, blue.g);
    EXPECT_GT(middle.g, middle.b);
    EXPECT_GT(high.r, high.g);
    EXPECT_GT(high.r, high.b);
    EXPECT_EQ(falseColour(-1.0f), low);
    EXPECT_EQ(falseColour(7.0f), high);
    for (float t = 0.0f; t <= 1.0f; t += 0.05f) {
        const glm::vec3 c = falseColour(t);
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(c, glm::vec3(1.0f)))) << t;
    }
}

} // namespace
} // namespace iblab
