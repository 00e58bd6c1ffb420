#pragma once
// Shaders are files under assets/shaders, named purpose.stage (sky.frag, prefilter.comp).
// They are composed with `#include "common/x.glsl"` (each file at most once per program,
// cycles reported), specialised with #defines, and cached per (files, defines).
// A failed compile names the file and line, with the driver's log; on hot reload the last
// good program stays in use and the error is kept for the UI to show.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/fwd.hpp>

#include "gl/handles.hpp"

namespace iblab::gl {

struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

using ShaderDefines = std::vector<std::pair<std::string, std::string>>;

struct PreprocessedSource {
    std::string text;
    std::vector<std::string> files; // index = the source-string number used in #line
};

// Resolves includes and writes #line directives so that the driver's "S:L(C)" positions map
// back to files[S], line L. Throws ShaderError for a missing file or an include cycle.
// Files are looked up in each search root in turn (tests add their own shaders this way).
using ShaderSearchPath = std::vector<std::filesystem::path>;
PreprocessedSource preprocessShader(const ShaderSearchPath& roots, const std::string& file, const ShaderDefines& defines);

// Rewrites a driver log's "S:L(C): " prefixes as "file:L:C: " (Mesa and NVIDIA styles).
std::string mapDriverLog(const std::string& log, const std::vector<std::string>& files);

class ShaderProgram {
public:
    ShaderProgram(Program program, std::vector<std::string> files);
    GLuint id() const { return program_.id(); }
    // -1 (silently ignored by GL) when the uniform was optimised away.
    GLint uniformLocation(const std::string& name) const;
    void set(const std::string& name, int value) const;
    void set(const std::string& name, float value) const;
    void set(const std::string& name, const glm::ivec2& value) const;
    void set(const std::string& name, const glm::vec2& value) const;
    void set(const std::string& name, const glm::vec3& value) const;
    void set(const std::string& name, const glm::vec4& value) const;
    void set(const std::string& name, const glm::mat3& value) const;
    void set(const std::string& name, const glm::mat4& value) const;
    const std::vector<std::string>& files() const { return files_; }

private:
    Program program_;
    std::vector<std::string> files_;
    std::map<std::string, GLint, std::less<>> uniforms_;
};

class ShaderLibrary {
public:
    explicit ShaderLibrary(ShaderSearchPath roots);
    explicit ShaderLibrary(std::filesystem::path root) : ShaderLibrary(ShaderSearchPath{std::move(root)}) {}

    // stages: e.g. {"fullscreen.vert", "sky.frag"} or {"prefilter.comp"}. Compiles on first
    // use, then returns the cached program. Throws ShaderError with the mapped driver log.
    const ShaderProgram& program(const std::vector<std::string>& stages, const ShaderDefines& defines = {});

    // Runs once on every program right after it links (also after a hot reload), for
    // state that belongs to the program rather than to a draw, like sampler units.
    void setProgramInitializer(std::function<void(const ShaderProgram&)> initializer) { initializer_ = std::move(initializer); }

    // Recompiles programs whose files changed on disk. Returns the errors of programs
    // that failed (those keep their last good version).
    std::vector<std::string> reloadChanged();


private:
    struct Entry {
        std::vector<std::string> stages;
        ShaderDefines defines;
        std::unique_ptr<ShaderProgram> program;
        std::filesystem::file_time_type newestInput;
    };
    std::unique_ptr<ShaderProgram> build(const std::vector<std::string>& stages, const ShaderDefines& defines) const;
    std::filesystem::file_time_type newestInput(const ShaderProgram& program) const;

    ShaderSearchPath roots_;
    std::function<void(const ShaderProgram&)> initializer_;
    std::map<std::string, Entry> cache_;
};

} // namespace iblab::gl
