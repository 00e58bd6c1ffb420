#include "frame/frame_analysis.hpp"

#include <algorithm>
#include <cstdio>

#include <glm/glm.hpp>

#include "frame/camera.hpp"
#include "frame/split_view.hpp"
#include "ibl/tonemap.hpp"

namespace iblab {
namespace {

// Cube-cross cell -> GL face, as debug_views.frag lays them out (row 0 at the bottom).
int crossFace(int column, int row)
{
    if (row == 1) return column == 0 ? 1 : column == 1 ? 4 : column == 2 ? 0 : 5;
    if (column != 1) return -1;
    return row == 2 ? 2 : row == 0 ? 3 : -1;
}

constexpr const char* kFaceNames[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

void encodeForDisplay(FrameReadback& image, const ToneMapSettings& toneMap)
{
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        const glm::vec3 shown = displayEncode(glm::vec3(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]), toneMap.exposureEv, toneMap.op);
        for (int c = 0; c < 3; ++c) image.rgba[i + std::size_t(c)] = shown[c];
    }
}

} // namespace

ErrorReport frameErrorReport(FrameReadback frame, FrameReadback reference, const FrameReadback& referenceNormals, const FrameSettings& settings)
{
    if (settings.view.errorSpace == ErrorSpace::Display) {
        encodeForDisplay(frame, settings.toneMap);
        encodeForDisplay(reference, settings.toneMap);
    }
    const int x0 = settings.view.split ? splitColumn(settings.view, frame.width) : frame.width;
    auto side = [&](bool right) {
        std::vector<std::uint8_t> include(frame.rgba.size() / 4);
        for (std::size_t i = 0; i < include.size(); ++i)
            include[i] = isMeasuredPixel(frame.rgba[i * 4 + 3], referenceNormals.rgba[i * 4 + 3]) &&
                         ((int(i % std::size_t(frame.width)) >= x0) == right);
        return computeErrorMetrics(frame.rgba, reference.rgba, include);
    };
    ErrorReport report;
    report.valid = true;
    report.left = side(false);
    if (settings.view.split) report.right = side(true);
    return report;
}

std::vector<SphereReading> sphereReadings(const FrameReadback& frame, const CameraSettings& camera, std::span<const SphereInstance> spheres)
{
    std::vector<SphereReading> readings;
    const glm::mat4 view = cameraView(camera);
    const glm::mat4 projection = cameraProjection(camera, float(frame.width) / float(frame.height));
    for (const SphereInstance& sphere : spheres) {
        // The unit sphere's centre and apparent radius in pixels.
        const glm::vec3 centreView = glm::vec3(view * sphere.model[3]);
        const glm::vec2 pixel = clipToPixel(projection * glm::vec4(centreView, 1.0f), frame.width, frame.height);
        const float radiusPixels = projection[1][1] / -centreView.z * 0.5f * float(frame.height);
        const float reach = 0.5f * radiusPixels;
        glm::dvec3 sum(0.0);
        int count = 0;
        for (int y = int(pixel.y - reach); y <= int(pixel.y + reach); ++y)
            for (int x = int(pixel.x - reach); x <= int(pixel.x + reach); ++x) {
                if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) continue;
                if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - pixel) > reach) continue;
                const float* p = &frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4];
                sum += glm::dvec3(p[0], p[1], p[2]);
                ++count;
            }
        if (count == 0) continue;
        readings.push_back({pixel, glm::vec3(sum / double(count)), sphere.metallic, sphere.roughness});
    }
    return readings;
}

glm::vec2 tileLocal(const DebugTile& tile, float x, float y)
{
    return (glm::vec2(x, y) - glm::vec2(tile.rect)) / (glm::vec2(tile.rect.z, tile.rect.w) - glm::vec2(tile.rect));
}

std::optional<CubeTexel> cubeCrossTexel(glm::vec2 local, int faceSize)
{
    const glm::vec2 cell = local * glm::vec2(4.0f, 3.0f);
    const int face = crossFace(int(cell.x), int(cell.y));
    if (face < 0) return std::nullopt;
    const int column = std::min(int(glm::fract(cell.x) * float(faceSize)), faceSize - 1);
    const int row = std::min(int((1.0f - glm::fract(cell.y)) * float(faceSize)), faceSize - 1);
    return CubeTexel{face, column, row};
}

glm::ivec2 lutTexel(glm::vec2 local, int size)
{
    return {std::min(int(local.x * float(size)), size - 1), std::min(int(local.y * float(size)), size - 1)};
}

std::string prefilterTexelText(const std::string& tileLabel, const CubeTexel& texel, int faceSize, glm::vec4 value)
{
    char text[256];
    std::snprintf(text, sizeof text, "%s, face %s, texel (%d, %d) of %d: %.4g %.4g %.4g", tileLabel.c_str(), kFaceNames[texel.face], texel.column,
                  texel.row, faceSize, value.r, value.g, value.b);
    return text;
}

std::string lutTexelText(glm::ivec2 texel, int size, glm::vec4 value)
{
    char text[256];
    std::snprintf(text, sizeof text, "n.v %.3f, roughness %.3f: A %.4f, B %.4f, A+B %.4f", (texel.x + 0.5f) / float(size), (texel.y + 0.5f) / float(size),
                  value.r, value.g, value.b);
    return text;
}

} // namespace iblab
