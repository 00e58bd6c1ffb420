#pragma once
// Typed uniform handles, located once per linked program. A pass declares a struct of them
// for each program it draws with; ShaderProgram::uniforms builds it from the program's name
// table on first use and keeps it as long as that link lives (a hot reload links a new
// program, whose handles are built anew), so that setting a uniform is one glProgramUniform
// call with no name lookup:
//
//     struct SkyUniforms {
//         explicit SkyUniforms(const gl::ShaderProgram& p) : background(p, "uBackground") {}
//         gl::Uniform<int> background;
//     };
//     program.uniforms<SkyUniforms>().background.set(2);
#include <span>
#include <string_view>

#include <glm/fwd.hpp>

#include "gl/shader_library.hpp"

namespace iblab::gl {

// The value types a uniform handle sets, one glProgramUniform* each. GLSL bools are set as
// ints (GL's rule for bool uniforms).
namespace detail {
void setUniform(GLuint program, GLint location, bool value);
void setUniform(GLuint program, GLint location, int value);
void setUniform(GLuint program, GLint location, float value);
void setUniform(GLuint program, GLint location, const glm::ivec2& value);
void setUniform(GLuint program, GLint location, const glm::ivec4& value);
void setUniform(GLuint program, GLint location, const glm::vec2& value);
void setUniform(GLuint program, GLint location, const glm::vec3& value);
void setUniform(GLuint program, GLint location, const glm::vec4& value);
void setUniform(GLuint program, GLint location, const glm::mat3& value);
void setUniform(GLuint program, GLint location, const glm::mat4& value);
void setUniformArray(GLuint program, GLint location, std::span<const glm::vec3> values);
void setUniformArray(GLuint program, GLint location, std::span<const glm::vec4> values);
} // namespace detail

// One uniform of one linked program. A name the program lacks (declared in a shared file
// but unused by this program, so optimised away) gets location -1, which GL ignores: the
// value could not change the program's output anyway.
template <class T>
class Uniform {
public:
    Uniform() = default;
    Uniform(const ShaderProgram& program, std::string_view name) : program_(program.id()), location_(program.uniformLocation(name)) {}
    void set(const T& value) const { detail::setUniform(program_, location_, value); }

private:
    GLuint program_ = 0;
    GLint location_ = -1;
};

// A uniform array, set from its first element on.
template <class T>
class UniformArray {
public:
    UniformArray() = default;
    UniformArray(const ShaderProgram& program, std::string_view name) : program_(program.id()), location_(program.uniformLocation(name)) {}
    void set(std::span<const T> values) const { detail::setUniformArray(program_, location_, values); }

private:
    GLuint program_ = 0;
    GLint location_ = -1;
};

} // namespace iblab::gl
