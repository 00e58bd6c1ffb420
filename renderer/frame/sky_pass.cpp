#include "frame/sky_pass.hpp"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "bake/bake_result.hpp"
#include "frame/camera.hpp"

namespace iblab {
namespace {

struct SkyUniforms {
    explicit SkyUniforms(const gl::ShaderProgram& p)
        : ibl(p), inverseViewProjection(p, "uInverseViewProjection"), backgroundMip(p, "uBackgroundMip"),
          solidColour(p, "uSolidColour")
    {
    }
    IblUniforms ibl;
    gl::Uniform<glm::mat4> inverseViewProjection;
    gl::Uniform<float> backgroundMip;
    gl::Uniform<glm::vec3> solidColour;
};

// What the background shows: the view's choice, except that views of baked data fall back
// to the environment until a bake exists, the irradiance view shows the bake's irradiance,
// and the furnace view shows its uniform radiance 1 (times the intensity).
struct Background {
    BackgroundMode mode = BackgroundMode::Environment;
    glm::vec3 solidColour{0.0f};
};

Background backgroundOf(const FrameSettings& settings, bool haveBake)
{
    Background b{settings.view.background, settings.view.solidColour};
    if (!haveBake && (b.mode == BackgroundMode::Irradiance || b.mode == BackgroundMode::PrefilterMip)) b.mode = BackgroundMode::Environment;
    if (settings.view.mode == ViewMode::Irradiance && haveBake) b.mode = BackgroundMode::Irradiance;
    if (settings.view.mode == ViewMode::Furnace) {
        b.mode = BackgroundMode::SolidColour;
        b.solidColour = glm::vec3(std::exp2(settings.environment.intensityEv));
    }
    return b;
}

} // namespace

void SkyPass::draw(const FrameSettings& settings, const Lighting& lighting, float aspect)
{
    // The rotation alone: the sky is at infinity.
    const glm::mat4 viewRotation = glm::mat4(glm::mat3(cameraView(settings.camera)));
    const glm::mat4 inverseViewProjection = glm::inverse(cameraProjection(settings.camera, aspect) * viewRotation);
    const Background background = backgroundOf(settings, lighting.bake != nullptr);
    // The background's mode is compiled in (sky.frag): one program per mode shown.
    const gl::ShaderProgram& program = shaders_.program(
        {"fullscreen.vert", "sky.frag"},
        {{"AT_FAR_PLANE", "1"},
         {"BACKGROUND", std::to_string(int(background.mode))},
         {"SKY_FROM_CUBE", lighting.bake ? "1" : "0"},
         diffuseSourceDefine(lighting, settings)});
    const SkyUniforms& u = program.uniforms<SkyUniforms>();
    glUseProgram(program.id());
    u.ibl.bind(lighting, settings);
    u.inverseViewProjection.set(inverseViewProjection);
    const int lastMip = lighting.bake ? lighting.bake->prefiltered.levels - 1 : 0;
    u.backgroundMip.set(float(std::clamp(settings.view.backgroundMip, 0, lastMip)));
    u.solidColour.set(background.solidColour);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS); // the cube's faces filtered across their edges
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    triangle_.draw();
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
}

} // namespace iblab
