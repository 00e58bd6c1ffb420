#include "gl/uniform.hpp"

#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace iblab::gl::detail {

void setUniform(GLuint program, GLint location, bool value) { glProgramUniform1i(program, location, value ? 1 : 0); }
void setUniform(GLuint program, GLint location, int value) { glProgramUniform1i(program, location, value); }
void setUniform(GLuint program, GLint location, float value) { glProgramUniform1f(program, location, value); }
void setUniform(GLuint program, GLint location, const glm::ivec2& v) { glProgramUniform2iv(program, location, 1, glm::value_ptr(v)); }
void setUniform(GLuint program, GLint location, const glm::ivec4& v) { glProgramUniform4iv(program, location, 1, glm::value_ptr(v)); }
void setUniform(GLuint program, GLint location, const glm::vec2& v) { glProgramUniform2fv(program, location, 1, glm::value_ptr(v)); }
void setUniform(GLuint program, GLint location, const glm::vec3& v) { glProgramUniform3fv(program, location, 1, glm::value_ptr(v)); }
void setUniform(GLuint program, GLint location, const glm::vec4& v) { glProgramUniform4fv(program, location, 1, glm::value_ptr(v)); }
void setUniform(GLuint program, GLint location, const glm::mat3& m)
{
    glProgramUniformMatrix3fv(program, location, 1, GL_FALSE, glm::value_ptr(m));
}
void setUniform(GLuint program, GLint location, const glm::mat4& m)
{
    glProgramUniformMatrix4fv(program, location, 1, GL_FALSE, glm::value_ptr(m));
}

void setUniformArray(GLuint program, GLint location, std::span<const glm::vec3> values)
{
    if (!values.empty()) glProgramUniform3fv(program, location, GLsizei(values.size()), glm::value_ptr(values[0]));
}
void setUniformArray(GLuint program, GLint location, std::span<const glm::vec4> values)
{
    if (!values.empty()) glProgramUniform4fv(program, location, GLsizei(values.size()), glm::value_ptr(values[0]));
}

} // namespace iblab::gl::detail
