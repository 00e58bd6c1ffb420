#pragma once
// Shaders are files under assets/shaders, named purpose.stage (sky.frag, prefilter.comp).
// They are composed with `#include "common/x.glsl"` (each file at most once per program,
// cycles reported), specialised with #defines, and cached per (files, defines).
// A failed compile names the file and line, with the driver's log; on hot reload the last
// good program stays in use and the error is kept for the UI to show.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

#include "gl/handles.hpp"

namespace iblab::gl {

struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

using ShaderDefine = std::pair<std::string, std::string>;
using ShaderDefines = std::vector<ShaderDefine>;

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
    // -1 (silently ignored by GL) when the uniform was optimised away. What the uniform
    // handles of gl/uniform.hpp are built from; nothing sets a uniform by name.
    GLint uniformLocation(std::string_view name) const;
    // This program's uniform handles of type Locations (a struct constructible from a
    // ShaderProgram, whose members are gl::Uniform handles): built on the first call, then
    // kept as long as this link lives. A hot reload links a new ShaderProgram, so handles
    // are located again exactly when the program changes.
    template <class Locations>
    const Locations& uniforms() const;
    const std::vector<std::string>& files() const { return files_; }

private:
    Program program_;
    std::vector<std::string> files_;
    std::map<std::string, GLint, std::less<>> locations_;
    // The handle structs built so far, one per type (a pass's own, and those of the shared
    // files it includes).
    mutable std::vector<std::pair<std::type_index, std::shared_ptr<const void>>> handles_;
};

template <class Locations>
const Locations& ShaderProgram::uniforms() const
{
    for (const auto& [type, handles] : handles_)
        if (type == std::type_index(typeid(Locations))) return *static_cast<const Locations*>(handles.get());
    auto built = std::make_shared<const Locations>(*this);
    handles_.emplace_back(std::type_index(typeid(Locations)), built);
    return *built;
}

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
    // Programs that reloadChanged linked again: when it moves, what was drawn or computed
    // with the old programs (a running mean, a reference) is stale.
    std::uint64_t reloads() const { return reloads_; }
    // Where the library looks for files, first root first.
    const ShaderSearchPath& roots() const { return roots_; }


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
    std::uint64_t reloads_ = 0;
};

} // namespace iblab::gl
