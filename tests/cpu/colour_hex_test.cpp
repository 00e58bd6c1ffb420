// The colour swatch's hex (ui/widgets) is sRGB, as --base-color #rrggbb reads it: a hex copied
// from the GUI gives the same colour on the command line. The picker showed the linear
// values' hex (#F2A38A for the default copper) and the command line read it as sRGB.
#include <gtest/gtest.h>

#include "io/environment.hpp"
#include "frame/settings.hpp"
#include "ui/widgets.hpp"

namespace iblab {
namespace {

TEST(ColourHex, IsTheSrgbEncodingTheCommandLineDecodes)
{
    const glm::vec3 copper = MaterialSettings{}.baseColor;
    const std::string hex = ui::srgbHex(&copper.x);
    EXPECT_EQ(hex, "#F9D1C2");
    for (int c = 0; c < 3; ++c) {
        const float encoded = float(std::stoi(hex.substr(1 + std::size_t(c) * 2, 2), nullptr, 16)) / 255.0f;
        EXPECT_NEAR(srgbToLinear(encoded), copper[c], 0.005f) << "channel " << c;
    }
}

} // namespace
} // namespace iblab
