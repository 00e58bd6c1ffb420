#pragma once
// Runs a probe compute shader over a list of vec4 inputs and returns its vec4 outputs, so
// that tests can evaluate shared GLSL functions on the GPU and compare them with C++.
// Probe shaders live in tests/gl/shaders and use the layout of probe_layout.glsl.
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "gl/handles.hpp"
#include "gl/shader_library.hpp"
#include "gl/uniform.hpp"

namespace iblab::testing {

inline std::vector<glm::vec4> runComputeProbe(gl::ShaderLibrary& library, const std::string& shader, const std::vector<glm::vec4>& inputs,
                                              const gl::ShaderDefines& defines = {})
{
    const gl::ShaderProgram& program = library.program({shader}, defines);
    gl::Buffer in = gl::createBuffer();
    gl::Buffer out = gl::createBuffer();
    const auto bytes = GLsizeiptr(inputs.size() * sizeof(glm::vec4));
    glNamedBufferStorage(in.id(), bytes, inputs.data(), 0);
    glNamedBufferStorage(out.id(), bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    glUseProgram(program.id());
    gl::Uniform<int>(program, "uCount").set(int(inputs.size()));
    glDispatchCompute(GLuint((inputs.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> outputs(inputs.size());
    glGetNamedBufferSubData(out.id(), 0, bytes, outputs.data());
    glUseProgram(0);
    return outputs;
}

} // namespace iblab::testing
