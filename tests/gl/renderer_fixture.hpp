#pragma once
// GL tests of whole frames: one Renderer per test, lit by the bake of an environment.
#include <memory>
#include <string>

#include "bake/bake_job.hpp"
#include "io/environment.hpp"
#include "gl_test_fixture.hpp"
#include "frame/renderer.hpp"

namespace iblab::testing {

class RendererTest : public GlTest {
protected:
    Renderer& renderer()
    {
        if (!renderer_) renderer_ = std::make_unique<Renderer>(shaderDirectory());
        return *renderer_;
    }
    // Loads spec as the background and lights with its bake; returns the loaded map.
    ImageRGB32F bakeEnvironment(const std::string& spec, const bake::BakeSettings& settings)
    {
        const Environment environment = loadEnvironment(spec);
        renderer().setEnvironment(environment.image);
        bake::BakeJob job(renderer().shaders(), environment, settings);
        renderer().setBake(std::make_shared<bake::BakeResult>(job.runToCompletion()));
        return environment.image;
    }

private:
    std::unique_ptr<Renderer> renderer_;
};

} // namespace iblab::testing
