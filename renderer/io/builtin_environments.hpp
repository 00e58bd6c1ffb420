#pragma once
// Procedural environments with known integrals, addressable as "builtin:NAME" with
// optional query-style overrides: "builtin:sun?elevation=30&size=0.5&intensity=1e4".
// Every one is rasterised analytically (exact area/solid-angle coverage of each texel, or
// stratified supersampling of disc edges), so tests can compare the discretised map with
// closed-form solid-angle integrals.
//
// Angles are in degrees. A direction given as (elevation, azimuth) is
//   (cos(el) sin(az), sin(el), -cos(el) cos(az)):
// elevation is measured up from the horizon (+90 = zenith +Y), azimuth from -Z (the centre
// of the panorama, u = 0.5) towards +X, so u = 0.5 + az / 360 (see conventions.glsl).
//
// Every builtin has the parameter `width` (default 512, even, 8..16384); height = width/2.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/image.hpp"

namespace iblab {

inline constexpr std::string_view kBuiltinPrefix = "builtin:";

struct BuiltinParameter {
    std::string name;
    double defaultValue = 0.0;
    double minValue = 0.0;
    double maxValue = 0.0;
    bool integer = false;     // must be a whole number (width, count)
    std::string description;  // one line, for tooltips and error messages
};

struct BuiltinEnvironmentInfo {
    std::string name;
    std::string description;  // one line, for tooltips
    std::vector<BuiltinParameter> parameters; // `width` first
};

// A parsed spec: the builtin's name and a value for every one of its parameters (defaults
// filled in), in the order of BuiltinEnvironmentInfo::parameters.
struct BuiltinSpec {
    std::string name;
    std::vector<std::pair<std::string, double>> values;

    double get(std::string_view parameter) const; // throws iblab::Error if not a parameter
    // "builtin:NAME" plus "?k=v&..." for the parameters that differ from their defaults, in
    // declaration order: equal environments get equal strings.
    std::string canonical() const;
};

// All builtins, in a stable order (white, black, sky, sun, lights, studio, texel, slits, nan).
const std::vector<BuiltinEnvironmentInfo>& builtinEnvironments();
std::vector<std::string> builtinEnvironmentNames();
// Throws iblab::Error listing the valid names when `name` is not one of them.
const BuiltinEnvironmentInfo& builtinEnvironmentInfo(std::string_view name);
const std::string& builtinEnvironmentDescription(std::string_view name);

// True for "builtin:..." specs.
bool isBuiltinSpec(std::string_view spec);

// Accepts "builtin:NAME?k=v&k=v" or just "NAME?k=v". Whitespace around names, keys and
// values is ignored, empty segments ("a=1&&b=2", a trailing '&') are skipped. Throws
// iblab::Error naming the spec for: an unknown name (lists the valid names), an unknown
// parameter (lists the valid ones), a parameter given twice, a value that is not a finite
// number, out of range, or not whole where it must be.
BuiltinSpec parseBuiltinSpec(std::string_view spec);

ImageRGB32F makeBuiltinEnvironment(const BuiltinSpec& spec);
ImageRGB32F makeBuiltinEnvironment(std::string_view spec);

// The unit direction for (elevation, azimuth) in degrees, per the convention above.
glm::dvec3 directionFromElevationAzimuth(double elevationDegrees, double azimuthDegrees);

} // namespace iblab
