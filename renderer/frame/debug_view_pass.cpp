#include "frame/debug_view_pass.hpp"

#include <vector>

#include "bake/bake_result.hpp"
#include "frame/debug_layout.hpp"
#include "frame/texture_units.hpp"

namespace iblab {
namespace {

struct DebugViewUniforms {
    explicit DebugViewUniforms(const gl::ShaderProgram& p) : ibl(p), tileCount(p, "uTileCount"), tiles(p, "uTiles") {}
    IblUniforms ibl;
    gl::Uniform<int> tileCount;
    gl::UniformArray<glm::vec4> tiles;
};

} // namespace

void DebugViewPass::draw(const FrameSettings& settings, const Lighting& lighting, int width, int height)
{
    const bake::BakeResult& bake = *lighting.bake;
    const bool lutView = settings.view.mode == ViewMode::Lut;
    const std::vector<DebugTile> tiles = debugTiles(settings.view.mode, prefilterMipRoughnessOf(bake), width, height);
    const gl::ShaderProgram& program = shaders_.program({"fullscreen.vert", "debug_views.frag"}, {{"VIEW", lutView ? "2" : "1"}});
    const DebugViewUniforms& u = program.uniforms<DebugViewUniforms>();
    glUseProgram(program.id());
    u.ibl.bind(lighting, settings);
    glBindTextureUnit(kUnitLutSchlick, bake.lut(GeometryTerm::SchlickGGX).id());
    glBindTextureUnit(kUnitLutCorrelated, bake.lut(GeometryTerm::HeightCorrelatedSmith).id());
    std::vector<glm::vec4> rects;
    for (const DebugTile& tile : tiles) rects.push_back(tile.rect);
    u.tileCount.set(int(rects.size()));
    u.tiles.set(rects);
    triangle_.draw();
}

TexelProbe probeDebugView(const FrameSettings& settings, const bake::BakeResult& bake, int width, int height, float x, float y)
{
    const std::vector<DebugTile> tiles = debugTiles(settings.view.mode, prefilterMipRoughnessOf(bake), width, height);
    const int t = debugTileAt(tiles, x, y);
    if (t < 0) return {};
    const DebugTile& tile = tiles[std::size_t(t)];
    const glm::vec2 local = tileLocal(tile, x, y);
    glm::vec4 value(0.0f);
    if (settings.view.mode == ViewMode::PrefilterMips) {
        const int size = bake.prefiltered.levelSize(tile.index);
        const std::optional<CubeTexel> texel = cubeCrossTexel(local, size);
        if (!texel) return {};
        glGetTextureSubImage(bake.prefiltered.id(), tile.index, texel->column, texel->row, texel->face, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof value,
                             &value.x);
        return {true, prefilterTexelText(tile.label, *texel, size, value)};
    }
    const bake::BakedTexture& lut = bake.lut(GeometryTerm(tile.index));
    if (!lut) return {};
    const glm::ivec2 texel = lutTexel(local, lut.size);
    glGetTextureSubImage(lut.id(), 0, texel.x, texel.y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof value, &value.x);
    return {true, lutTexelText(texel, lut.size, value)};
}

} // namespace iblab
