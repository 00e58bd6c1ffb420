#include "io/builtin_environments.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>

#include <glm/geometric.hpp>

#include "io/error.hpp"
#include "ibl/conventions.hpp"

namespace iblab {
namespace {

constexpr double kDegrees = kPi / 180.0;
constexpr double kHuge = 1e9;

BuiltinParameter widthParameter()
{
    return {"width", 512, 8, 16384, true, "equirect width in texels (even); height = width / 2"};
}

std::vector<BuiltinEnvironmentInfo> makeRegistry()
{
    std::vector<BuiltinEnvironmentInfo> r;
    r.push_back({"white",
                 "uniform radiance `value` in every direction (white furnace test)",
                 {widthParameter(), {"value", 1.0, 0, kHuge, false, "radiance of every texel"}}});
    r.push_back({"black", "zero radiance everywhere (no light at all)", {widthParameter()}});
    r.push_back({"sky",
                 "radiance `top` above the horizon, `ground` below; solid-angle mean (top + ground) / 2",
                 {widthParameter(),
                  {"top", 1.0, 0, kHuge, false, "radiance of the upper hemisphere (y > 0)"},
                  {"ground", 0.1, 0, kHuge, false, "radiance of the lower hemisphere (y < 0)"}}});
    r.push_back({"axes",
                 "radiance (1 + d) / 2 per channel of direction d: +X (1, .5, .5), -X (0, .5, .5), and so on for Y (green) and Z "
                 "(blue): a distinct colour in each axis direction, to check a cube map's orientation",
                 {widthParameter()}});
    r.push_back({"sun",
                 "a sun disc of radiance sky + `intensity` on a uniform sky of radiance `sky`",
                 {widthParameter(),
                  {"elevation", 45, -90, 90, false, "degrees above the horizon"},
                  {"azimuth", 0, -360, 360, false, "degrees from -Z towards +X"},
                  {"size", 0.53, 0.01, 90, false, "angular diameter of the disc in degrees (the real sun: 0.53)"},
                  {"intensity", 1e4, 0, kHuge, false, "radiance added inside the disc"},
                  {"sky", 0.05, 0, kHuge, false, "radiance of the uniform sky"}}});
    r.push_back({"lights",
                 "`count` small bright discs evenly spaced in azimuth on a ring at `elevation`, on black",
                 {widthParameter(),
                  {"count", 1, 1, 32, true, "number of discs"},
                  {"size", 5, 0.01, 45, false, "angular diameter of each disc in degrees"},
                  {"intensity", 100, 0, kHuge, false, "radiance of each disc"},
                  {"elevation", 30, -90, 90, false, "elevation of the ring in degrees"},
                  {"azimuth", 0, -360, 360, false, "azimuth of the first disc; disc i sits at azimuth + 360 i / count"}}});
    r.push_back({"studio",
                 "dark studio lit by saturated red, green, blue and warm softboxes and a cool overhead disc",
                 {widthParameter(),
                  {"intensity", 1, 0, 1e6, false, "scale applied to every light"},
                  {"background", 0.02, 0, kHuge, false, "radiance of the background"}}});
    r.push_back({"texel",
                 "one texel of radiance sky + `intensity` (the texel holding the direction), on a uniform sky",
                 {widthParameter(),
                  {"elevation", 10, -90, 90, false, "degrees above the horizon of a direction inside the lit texel"},
                  {"azimuth", 44, -360, 360, false, "degrees from -Z towards +X (44: next to the -Z/+X cube edge)"},
                  {"intensity", 1e4, 0, kHuge, false, "radiance added to the one texel"},
                  {"sky", 0, 0, kHuge, false, "radiance of every texel"}}});
    r.push_back({"slits",
                 "`count` thin vertical slits of radiance `intensity`, evenly spaced in azimuth across the horizon, on black "
                 "(narrower than a texel at the default width: aliasing and moire)",
                 {widthParameter(),
                  {"count", 48, 1, 1024, true, "number of slits"},
                  {"size", 0.3, 0.001, 90, false, "width of each slit in degrees of azimuth"},
                  {"height", 60, 0.01, 180, false, "extent in elevation in degrees, centred on the horizon"},
                  {"intensity", 100, 0, kHuge, false, "radiance of each slit"}}});
    r.push_back({"nan",
                 "builtin:sky with `count` texels each of NaN, +Inf, -Inf and `negative` spread over the map (all three "
                 "components); the loader repairs them to 0 and reports them",
                 {widthParameter(),
                  {"count", 16, 1, 4096, true, "texels of each invalid kind"},
                  {"negative", -4, -kHuge, -1e-30, false, "value of the negative texels"}}});
    return r;
}

std::string formatNumber(double v)
{
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

std::string_view trim(std::string_view s)
{
    const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (!s.empty() && isSpace(s.front()))
        s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back()))
        s.remove_suffix(1);
    return s;
}

std::string lower(std::string_view s)
{
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z')
            c = char(c - 'A' + 'a');
    return out;
}

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

std::string parameterNames(const BuiltinEnvironmentInfo& info)
{
    std::vector<std::string> names;
    for (const BuiltinParameter& p : info.parameters)
        names.push_back(p.name);
    return joinNames(names);
}

// ---- Rasterisation ---------------------------------------------------------------------
// Texel (x, y) of a W x H equirect covers u in [x/W, (x+1)/W] and polar angle
// theta in [y pi/H, (y+1) pi/H]. Solid angle is uniform in (u, cos theta), so coverage
// fractions below are measured in those coordinates and are fractions of solid angle.

void fill(ImageRGB32F& img, glm::dvec3 radiance)
{
    for (std::size_t i = 0; i < img.texelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            img.texels[i * 3 + std::size_t(c)] = float(radiance[c]);
}

void addToTexel(ImageRGB32F& img, int x, int y, glm::dvec3 radiance, double fraction)
{
    float* p = &img.texels[img.offset(x, y)];
    for (int c = 0; c < 3; ++c)
        p[c] += float(radiance[c] * fraction);
}

// A rectangle in (azimuth, elevation): exact coverage (product of the u overlap and the
// cos(theta) overlap). Azimuth ranges may cross the seam at +-180 degrees.
void addLatLongRect(ImageRGB32F& img, double azMin, double azMax, double elMin, double elMax, glm::dvec3 radiance)
{
    const int w = img.width;
    const int h = img.height;
    const double uA = 0.5 + azMin / 360.0;
    const double uB = 0.5 + azMax / 360.0;
    const double yA = std::sin(elMin * kDegrees);
    const double yB = std::sin(elMax * kDegrees);
    for (int y = 0; y < h; ++y) {
        const double c0 = std::cos(y * kPi / h);       // cos(theta) at the top edge (larger)
        const double c1 = std::cos((y + 1) * kPi / h); // at the bottom edge
        const double vOverlap = std::min(c0, yB) - std::max(c1, yA);
        if (vOverlap <= 0.0)
            continue;
        const double vFraction = vOverlap / (c0 - c1);
        for (int x = 0; x < w; ++x) {
            const double t0 = double(x) / w;
            const double t1 = double(x + 1) / w;
            double uOverlap = 0.0;
            for (int k = -1; k <= 1; ++k)
                uOverlap += std::max(0.0, std::min(t1, uB + k) - std::max(t0, uA + k));
            if (uOverlap > 0.0)
                addToTexel(img, x, y, radiance, std::min(1.0, uOverlap * w) * vFraction);
        }
    }
}

// A disc of angular radius r around unit direction `centre`. Texels entirely inside get
// fraction 1, entirely outside 0. For a texel on the rim, the part of it that overlaps the
// disc's bounding box in (phi, cos theta) is supersampled with n x n strata of equal solid
// angle: the strata shrink with the disc, so a disc smaller than a texel (the real sun at
// width 512 is 3/4 of a texel) is resolved as well as a large one. The covered solid angle
// then matches 2 pi (1 - cos r) to about 0.1% (the only error: strata cut by the rim, which
// largely cancel around it).
void addDisc(ImageRGB32F& img, glm::dvec3 centre, double r, glm::dvec3 radiance)
{
    constexpr int n = 32;
    const int w = img.width;
    const int h = img.height;
    const double dTheta = kPi / h;
    const double dPhi = 2.0 * kPi / w;
    // Any point of a texel is within dTheta/2 + dPhi/2 (great-circle) of its centre: walk
    // along the meridian, then along the parallel, whose arc is at most dPhi/2.
    const double margin = 0.5 * (dTheta + dPhi);
    const double cosR = std::cos(r);
    const double thetaC = std::acos(std::clamp(centre.y, -1.0, 1.0));
    const double phiC = std::atan2(centre.x, -centre.z); // phi = 2 pi (u - 0.5)
    // Bounding box of the cap: cos theta within [cosLo, cosHi]; longitude within
    // phiC +- asin(sin r / sin thetaC), or everything if the cap holds a pole.
    const double cosHi = std::cos(std::max(0.0, thetaC - r));
    const double cosLo = std::cos(std::min(kPi, thetaC + r));
    const bool holdsPole = thetaC - r <= 0.0 || thetaC + r >= kPi;
    const double halfPhi = holdsPole ? kPi : std::asin(std::min(1.0, std::sin(r) / std::sin(thetaC)));
    for (int y = 0; y < h; ++y) {
        const double th0 = y * dTheta;
        const double th1 = (y + 1) * dTheta;
        if (th1 < thetaC - r || th0 > thetaC + r)
            continue;
        const double c0 = std::cos(th0);
        const double c1 = std::cos(th1);
        const double lo = std::max(c1, cosLo);
        const double hi = std::min(c0, cosHi);
        if (hi <= lo)
            continue;
        const double thetaMid = (y + 0.5) * dTheta;
        for (int x = 0; x < w; ++x) {
            const double phiMid = ((x + 0.5) / w - 0.5) * 2.0 * kPi;
            const glm::dvec3 d(std::sin(thetaMid) * std::sin(phiMid), std::cos(thetaMid),
                               -std::sin(thetaMid) * std::cos(phiMid));
            const double angle = std::acos(std::clamp(glm::dot(d, centre), -1.0, 1.0));
            if (angle - margin >= r)
                continue;
            if (angle + margin <= r) {
                addToTexel(img, x, y, radiance, 1.0);
                continue;
            }
            // The texel's longitudes relative to phiC, wrapped to the side nearest the disc.
            const double offset = std::remainder(phiMid - phiC, 2.0 * kPi);
            const double a = holdsPole ? offset - 0.5 * dPhi : std::max(offset - 0.5 * dPhi, -halfPhi);
            const double b = holdsPole ? offset + 0.5 * dPhi : std::min(offset + 0.5 * dPhi, halfPhi);
            if (b <= a)
                continue;
            int hits = 0;
            for (int j = 0; j < n; ++j) {
                const double cosT = lo + (hi - lo) * (j + 0.5) / n;
                const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
                for (int i = 0; i < n; ++i) {
                    const double phi = phiC + a + (b - a) * (i + 0.5) / n;
                    const glm::dvec3 s(sinT * std::sin(phi), cosT, -sinT * std::cos(phi));
                    hits += glm::dot(s, centre) >= cosR ? 1 : 0;
                }
            }
            const double boxFraction = ((b - a) / dPhi) * ((hi - lo) / (c0 - c1));
            if (hits > 0)
                addToTexel(img, x, y, radiance, boxFraction * hits / (double(n) * n));
        }
    }
}

ImageRGB32F makeSky(int w, double top, double ground)
{
    ImageRGB32F img(w, w / 2);
    const int h = img.height;
    for (int y = 0; y < h; ++y) {
        // Share of the row's solid angle above the horizon (cos theta > 0): exact, so a
        // row straddling the horizon (odd heights) holds the area-weighted average.
        const double c0 = std::cos(y * kPi / h);
        const double c1 = std::cos((y + 1) * kPi / h);
        const double above = std::clamp((c0 - std::max(c1, 0.0)) / (c0 - c1), 0.0, 1.0);
        const float value = float(ground + (top - ground) * above);
        for (int x = 0; x < w; ++x)
            img.set(x, y, glm::vec3(value));
    }
    return img;
}

// One texel: the one whose footprint holds `direction` (texel (x, y) covers
// [x/W, (x+1)/W) x [y/H, (y+1)/H) of the conventions' uv).
ImageRGB32F makeTexel(int w, glm::dvec3 direction, double intensity, double sky)
{
    ImageRGB32F img(w, w / 2);
    fill(img, glm::dvec3(sky));
    const glm::vec2 uv = directionToEquirectUv(glm::vec3(direction));
    const int x = std::clamp(int(std::floor(uv.x * float(img.width))), 0, img.width - 1);
    const int y = std::clamp(int(std::floor(uv.y * float(img.height))), 0, img.height - 1);
    addToTexel(img, x, y, glm::dvec3(intensity), 1.0);
    return img;
}

ImageRGB32F makeSlits(int w, int count, double sizeDegrees, double heightDegrees, double intensity)
{
    ImageRGB32F img(w, w / 2);
    for (int i = 0; i < count; ++i) {
        // Half a spacing in from the seam, so the pattern is symmetric about the panorama's centre.
        const double centre = -180.0 + 360.0 * (i + 0.5) / count;
        addLatLongRect(img, centre - 0.5 * sizeDegrees, centre + 0.5 * sizeDegrees, -0.5 * heightDegrees, 0.5 * heightDegrees,
                       glm::dvec3(intensity));
    }
    return img;
}

// builtin:sky with invalid texels. Kind k of texel i takes linear texel index
// (4 i + k + 0.5) * texels / (4 count): spread evenly over the map, never two on one texel.
ImageRGB32F makeInvalid(const std::string& canonicalSpec, int w, int count, double negative)
{
    ImageRGB32F img = makeSky(w, 1.0, 0.1);
    const std::size_t texels = img.texelCount();
    const std::size_t needed = std::size_t(4) * std::size_t(count);
    if (needed > texels)
        throw Error(canonicalSpec, "count=" + std::to_string(count) + " needs " + std::to_string(needed) + " texels, width=" +
                                       std::to_string(w) + " has " + std::to_string(texels));
    const float values[4] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity(), float(negative)};
    for (std::size_t k = 0; k < needed; ++k) {
        const std::size_t texel = std::size_t((double(k) + 0.5) * double(texels) / double(needed));
        for (int c = 0; c < 3; ++c)
            img.texels[texel * 3 + std::size_t(c)] = values[k % 4];
    }
    return img;
}

ImageRGB32F makeStudio(int w, double intensity, double background)
{
    ImageRGB32F img(w, w / 2);
    fill(img, glm::dvec3(background));
    const double k = intensity;
    // Softboxes as (azimuth range, elevation range, radiance). Deliberately saturated, and
    // the green one straddles the +-180 degree seam to exercise wrap-around.
    addLatLongRect(img, -100, -70, 0, 40, k * glm::dvec3(10.0, 0.2, 0.1)); // red, left
    addLatLongRect(img, 70, 100, 0, 40, k * glm::dvec3(0.1, 0.3, 10.0));   // blue, right
    addLatLongRect(img, 160, 200, 10, 30, k * glm::dvec3(0.2, 8.0, 0.3));  // green, behind
    addLatLongRect(img, -30, 10, 35, 60, k * glm::dvec3(12.0, 8.0, 4.0));  // warm key, front
    addDisc(img, glm::dvec3(0, 1, 0), 15.0 * kDegrees, k * glm::dvec3(2.0, 3.0, 4.0)); // cool overhead
    return img;
}

} // namespace

double BuiltinSpec::get(std::string_view parameter) const
{
    for (const auto& [key, value] : values)
        if (key == parameter)
            return value;
    throw Error(canonical(), "no parameter '" + std::string(parameter) + "'");
}

std::string BuiltinSpec::canonical() const
{
    std::string out = std::string(kBuiltinPrefix) + name;
    const BuiltinEnvironmentInfo* info = nullptr;
    for (const BuiltinEnvironmentInfo& i : builtinEnvironments())
        if (i.name == name)
            info = &i;
    char sep = '?';
    for (const auto& [key, value] : values) {
        bool isDefault = false;
        if (info)
            for (const BuiltinParameter& p : info->parameters)
                isDefault = isDefault || (p.name == key && p.defaultValue == value);
        if (isDefault)
            continue;
        out += sep + key + "=" + formatNumber(value);
        sep = '&';
    }
    return out;
}

const std::vector<BuiltinEnvironmentInfo>& builtinEnvironments()
{
    static const std::vector<BuiltinEnvironmentInfo> registry = makeRegistry();
    return registry;
}

std::vector<std::string> builtinEnvironmentNames()
{
    std::vector<std::string> names;
    for (const BuiltinEnvironmentInfo& info : builtinEnvironments())
        names.push_back(info.name);
    return names;
}

const BuiltinEnvironmentInfo& builtinEnvironmentInfo(std::string_view name)
{
    for (const BuiltinEnvironmentInfo& info : builtinEnvironments())
        if (info.name == name)
            return info;
    throw Error(std::string(kBuiltinPrefix) + std::string(name),
                "unknown builtin environment; valid: " + joinNames(builtinEnvironmentNames()));
}

const std::string& builtinEnvironmentDescription(std::string_view name) { return builtinEnvironmentInfo(name).description; }

bool isBuiltinSpec(std::string_view spec) { return trim(spec).starts_with(kBuiltinPrefix); }

BuiltinSpec parseBuiltinSpec(std::string_view specText)
{
    const std::string subject(trim(specText));
    std::string_view rest = trim(specText);
    if (rest.starts_with(kBuiltinPrefix))
        rest.remove_prefix(kBuiltinPrefix.size());
    const std::size_t question = rest.find('?');
    const std::string name = lower(trim(rest.substr(0, question)));
    std::string_view query = question == std::string_view::npos ? std::string_view() : rest.substr(question + 1);

    const BuiltinEnvironmentInfo* info = nullptr;
    for (const BuiltinEnvironmentInfo& i : builtinEnvironments())
        if (i.name == name)
            info = &i;
    if (!info)
        throw Error(subject, (name.empty() ? std::string("no builtin environment named")
                                           : "unknown builtin environment '" + name + "'") +
                                 "; valid: " + joinNames(builtinEnvironmentNames()));

    BuiltinSpec spec;
    spec.name = info->name;
    for (const BuiltinParameter& p : info->parameters)
        spec.values.emplace_back(p.name, p.defaultValue);
    std::vector<bool> seen(info->parameters.size(), false);

    while (!query.empty()) {
        const std::size_t amp = query.find('&');
        const std::string_view segment = trim(query.substr(0, amp));
        query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
        if (segment.empty())
            continue;
        const std::size_t eq = segment.find('=');
        if (eq == std::string_view::npos)
            throw Error(subject, "parameter '" + std::string(segment) + "' has no value (expected name=value)");
        const std::string key = lower(trim(segment.substr(0, eq)));
        std::string_view valueText = trim(segment.substr(eq + 1));

        std::size_t index = info->parameters.size();
        for (std::size_t i = 0; i < info->parameters.size(); ++i)
            if (info->parameters[i].name == key)
                index = i;
        if (index == info->parameters.size())
            throw Error(subject, "unknown parameter '" + key + "' for builtin:" + info->name +
                                     "; valid: " + parameterNames(*info));
        if (seen[index])
            throw Error(subject, "parameter '" + key + "' given twice");
        seen[index] = true;

        const BuiltinParameter& p = info->parameters[index];
        if (valueText.starts_with('+'))
            valueText.remove_prefix(1);
        double value = 0.0;
        const auto res = std::from_chars(valueText.data(), valueText.data() + valueText.size(), value);
        if (valueText.empty() || res.ec != std::errc() || res.ptr != valueText.data() + valueText.size() ||
            !std::isfinite(value))
            throw Error(subject, key + "='" + std::string(valueText) + "' is not a finite number");
        if (value < p.minValue || value > p.maxValue)
            throw Error(subject, key + "=" + formatNumber(value) + " is out of range [" + formatNumber(p.minValue) +
                                     ", " + formatNumber(p.maxValue) + "]");
        if (p.integer && value != std::floor(value))
            throw Error(subject, key + "=" + formatNumber(value) + " must be a whole number");
        if (key == "width" && std::fmod(value, 2.0) != 0.0)
            throw Error(subject, "width=" + formatNumber(value) + " must be even (height = width / 2)");
        spec.values[index].second = value;
    }
    return spec;
}

glm::dvec3 directionFromElevationAzimuth(double elevationDegrees, double azimuthDegrees)
{
    const double el = elevationDegrees * kDegrees;
    const double az = azimuthDegrees * kDegrees;
    return {std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az)};
}

ImageRGB32F makeBuiltinEnvironment(const BuiltinSpec& spec)
{
    const int w = int(spec.get("width"));
    const std::string& n = spec.name;
    if (n == "white") {
        ImageRGB32F img(w, w / 2);
        fill(img, glm::dvec3(spec.get("value")));
        return img;
    }
    if (n == "black")
        return ImageRGB32F(w, w / 2);
    if (n == "sky")
        return makeSky(w, spec.get("top"), spec.get("ground"));
    if (n == "axes") {
        ImageRGB32F img(w, w / 2);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec3 d = equirectUvToDirection(glm::vec2((x + 0.5f) / float(w), (y + 0.5f) / float(img.height)));
                img.set(x, y, 0.5f * (glm::vec3(1.0f) + d));
            }
        return img;
    }
    if (n == "sun") {
        ImageRGB32F img(w, w / 2);
        fill(img, glm::dvec3(spec.get("sky")));
        addDisc(img, directionFromElevationAzimuth(spec.get("elevation"), spec.get("azimuth")),
                0.5 * spec.get("size") * kDegrees, glm::dvec3(spec.get("intensity")));
        return img;
    }
    if (n == "lights") {
        ImageRGB32F img(w, w / 2);
        const int count = int(spec.get("count"));
        for (int i = 0; i < count; ++i) {
            const double az = spec.get("azimuth") + 360.0 * i / count;
            addDisc(img, directionFromElevationAzimuth(spec.get("elevation"), az), 0.5 * spec.get("size") * kDegrees,
                    glm::dvec3(spec.get("intensity")));
        }
        return img;
    }
    if (n == "studio")
        return makeStudio(w, spec.get("intensity"), spec.get("background"));
    if (n == "texel")
        return makeTexel(w, directionFromElevationAzimuth(spec.get("elevation"), spec.get("azimuth")), spec.get("intensity"),
                         spec.get("sky"));
    if (n == "slits")
        return makeSlits(w, int(spec.get("count")), spec.get("size"), spec.get("height"), spec.get("intensity"));
    if (n == "nan")
        return makeInvalid(spec.canonical(), w, int(spec.get("count")), spec.get("negative"));
    throw Error(spec.canonical(), "unknown builtin environment; valid: " + joinNames(builtinEnvironmentNames()));
}

ImageRGB32F makeBuiltinEnvironment(std::string_view spec) { return makeBuiltinEnvironment(parseBuiltinSpec(spec)); }

} // namespace iblab
