// The foundation every GL feature stands on: the headless context, KHR_debug, the RAII
// handles, the shader library's error reporting and hot reload, and uniform handles.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <epoxy/gl.h>

#include "gl/context_info.hpp"
#include "gl/handles.hpp"
#include "gl/shader_library.hpp"
#include "gl/uniform.hpp"
#include "gl_test_fixture.hpp"
#include "temp_dir.hpp"

namespace iblab {
namespace {

using testing::GlTest;

const gl::ShaderSearchPath kSearchPath{IBLAB_TEST_SHADER_DIR, IBLAB_SHADER_DIR};

TEST_F(GlTest, ContextIsCoreFourFive)
{
    EXPECT_GE(epoxy_gl_version(), 45);
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_NO_THROW(gl::requireCurrentContextFeatures());
}

TEST_F(GlTest, DebugOutputCountsErrors)
{
    glEnable(GL_TEXTURE_2D); // not a capability in a core profile: GL_INVALID_ENUM
    EXPECT_EQ(debugOutput().errorCount(), 1);
    ASSERT_FALSE(debugOutput().messages().empty());
    EXPECT_NE(debugOutput().messages().back().text.find("error"), std::string::npos);
    debugOutput().clear(); // the error was the point of this test
}

TEST_F(GlTest, HandlesOwnAndReleaseObjects)
{
    const int before = gl::liveObjectCount(gl::ObjectKind::Texture);
    GLuint id = 0;
    {
        gl::Texture a = gl::createTexture(GL_TEXTURE_2D);
        id = a.id();
        EXPECT_TRUE(glIsTexture(id));
        EXPECT_EQ(gl::liveObjectCount(gl::ObjectKind::Texture), before + 1);
        gl::Texture b = std::move(a);
        EXPECT_EQ(a.id(), 0u);
        EXPECT_EQ(b.id(), id);
        EXPECT_EQ(gl::liveObjectCount(gl::ObjectKind::Texture), before + 1);
    }
    EXPECT_FALSE(glIsTexture(id));
    EXPECT_EQ(gl::liveObjectCount(gl::ObjectKind::Texture), before);
}

TEST_F(GlTest, CompileErrorNamesFileAndLine)
{
    gl::ShaderLibrary library(kSearchPath);
    try {
        library.program({"fullscreen.vert", "broken.frag"});
        FAIL() << "a broken shader compiled";
    } catch (const gl::ShaderError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("broken.frag:4"), std::string::npos) << message;
        EXPECT_NE(message.find("undeclaredThing"), std::string::npos) << message;
    }
    debugOutput().clear(); // the driver also reports the deliberate error through KHR_debug
}

TEST_F(GlTest, IncludeCycleIsReported)
{
    gl::ShaderLibrary library(kSearchPath);
    try {
        library.program({"fullscreen.vert", "cycle.frag"});
        FAIL() << "an include cycle went unnoticed";
    } catch (const gl::ShaderError& e) {
        EXPECT_NE(std::string(e.what()).find("cycle_a.glsl -> cycle_b.glsl -> cycle_a.glsl"), std::string::npos) << e.what();
    }
}

TEST(ShaderPreprocessor, IncludesOnceAndMapsLines)
{
    const gl::PreprocessedSource source = gl::preprocessShader(kSearchPath, "sky.frag", {{"EXTRA", "1"}});
    EXPECT_EQ(source.files.front(), "sky.frag");
    EXPECT_EQ(std::count(source.files.begin(), source.files.end(), "common/conventions.glsl"), 1);
    EXPECT_EQ(source.text.rfind("#version 450 core\n", 0), 0u);
    EXPECT_NE(source.text.find("#define EXTRA 1"), std::string::npos);
    const std::string mapped = gl::mapDriverLog("1:7(3): error: boom", source.files);
    EXPECT_EQ(mapped, source.files[1] + ":7:3: error: boom\n");
}

TEST_F(GlTest, ProgramsAreCachedPerDefines)
{
    gl::ShaderLibrary library(kSearchPath);
    const gl::ShaderProgram& a = library.program({"conventions_probe.comp"}, {{"MODE", "0"}});
    const gl::ShaderProgram& b = library.program({"conventions_probe.comp"}, {{"MODE", "0"}});
    const gl::ShaderProgram& c = library.program({"conventions_probe.comp"}, {{"MODE", "1"}});
    EXPECT_EQ(&a, &b);
    EXPECT_NE(a.id(), c.id());
}

// A compute shader that writes scale * uValue to values[0]; the second version declares
// another uniform first, so that uValue need not keep its location.
void writeValueProbe(const std::filesystem::path& file, int scale, bool extraUniform)
{
    std::ofstream out(file);
    out << "layout(local_size_x = 1) in;\n"
        << (extraUniform ? "uniform int uExtra;\n" : "") << "uniform int uValue;\n"
        << "layout(std430, binding = 0) buffer Values { int values[]; };\n"
        << "void main() { values[0] = " << scale << " * uValue" << (extraUniform ? " + uExtra" : "") << "; }\n";
}

struct ValueProbeUniforms {
    explicit ValueProbeUniforms(const gl::ShaderProgram& p) : value(p, "uValue") {}
    gl::Uniform<int> value;
};

int runValueProbe(const gl::ShaderProgram& program, int value)
{
    gl::Buffer values = gl::createBuffer();
    const int zero = 0;
    glNamedBufferStorage(values.id(), sizeof zero, &zero, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, values.id());
    program.uniforms<ValueProbeUniforms>().value.set(value);
    glUseProgram(program.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    int result = 0;
    glGetNamedBufferSubData(values.id(), 0, sizeof result, &result);
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    return result;
}

// Handles are located once per link: the same struct until a hot reload links the program
// again, then handles of the new program (a stale one would set the deleted program's
// uniform, a GL error, and leave the new one's at 0).
TEST_F(GlTest, UniformHandlesFollowAHotReload)
{
    const testing::TempDir directory("iblab-uniform-reload");
    const std::filesystem::path file = directory.file("value_probe.comp");
    writeValueProbe(file, 1, false);
    gl::ShaderLibrary library(gl::ShaderSearchPath{directory.path});
    const gl::ShaderProgram& first = library.program({"value_probe.comp"});
    EXPECT_EQ(&first.uniforms<ValueProbeUniforms>(), &first.uniforms<ValueProbeUniforms>()) << "located once per link";
    EXPECT_EQ(runValueProbe(first, 7), 7);

    writeValueProbe(file, 10, true);
    std::filesystem::last_write_time(file, std::filesystem::last_write_time(file) + std::chrono::seconds(2));
    EXPECT_TRUE(library.reloadChanged().empty());
    const gl::ShaderProgram& reloaded = library.program({"value_probe.comp"});
    EXPECT_EQ(runValueProbe(reloaded, 3), 30);
}

} // namespace
} // namespace iblab
