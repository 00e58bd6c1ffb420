#include "gl/shader_library.hpp"

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include <epoxy/gl.h>

namespace iblab::gl {
namespace {

std::string readFile(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ShaderError(path.string() + ": cannot open shader file");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The first root that has the file; empty when none has it.
std::filesystem::path locate(const ShaderSearchPath& roots, const std::string& file)
{
    for (const auto& root : roots)
        if (std::filesystem::exists(root / file)) return root / file;
    return {};
}

std::string searchPathText(const ShaderSearchPath& roots)
{
    std::string text;
    for (const auto& root : roots) text += (text.empty() ? "" : ":") + root.string();
    return text;
}

struct Preprocessor {
    const ShaderSearchPath& roots;
    PreprocessedSource out;
    std::vector<std::string> stack;

    int fileIndex(const std::string& file)
    {
        auto it = std::find(out.files.begin(), out.files.end(), file);
        if (it != out.files.end()) return int(it - out.files.begin());
        out.files.push_back(file);
        return int(out.files.size()) - 1;
    }

    void expand(const std::string& file)
    {
        if (std::find(stack.begin(), stack.end(), file) != stack.end()) {
            std::string chain;
            for (const auto& f : stack) chain += f + " -> ";
            throw ShaderError(stack.back() + ": include cycle: " + chain + file);
        }
        const bool alreadyIncluded = std::find(out.files.begin(), out.files.end(), file) != out.files.end();
        if (alreadyIncluded) return; // include-once: shared files define functions
        const int index = fileIndex(file);
        const std::filesystem::path path = locate(roots, file);
        if (path.empty()) throw ShaderError(file + ": shader file not found in " + searchPathText(roots));
        const std::string text = readFile(path);
        stack.push_back(file);
        static const std::regex includeLine(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
        std::istringstream lines(text);
        std::string line;
        int lineNumber = 0;
        out.text += "#line 1 " + std::to_string(index) + "\n";
        while (std::getline(lines, line)) {
            ++lineNumber;
            std::smatch match;
            if (std::regex_match(line, match, includeLine)) {
                const std::string included = match[1].str();
                if (locate(roots, included).empty())
                    throw ShaderError(file + ":" + std::to_string(lineNumber) + ": included file \"" + included + "\" not found in " +
                                      searchPathText(roots));
                expand(included);
                out.text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(index) + "\n";
            } else {
                out.text += line;
                out.text += '\n';
            }
        }
        stack.pop_back();
    }
};

GLenum stageOf(const std::string& file)
{
    const std::string ext = std::filesystem::path(file).extension().string();
    if (ext == ".vert") return GL_VERTEX_SHADER;
    if (ext == ".frag") return GL_FRAGMENT_SHADER;
    if (ext == ".comp") return GL_COMPUTE_SHADER;
    if (ext == ".geom") return GL_GEOMETRY_SHADER;
    throw ShaderError(file + ": unknown shader stage (expected .vert, .frag, .comp or .geom)");
}

std::string cacheKey(const std::vector<std::string>& stages, const ShaderDefines& defines)
{
    std::string key;
    for (const auto& s : stages) key += s + "|";
    key += "#";
    ShaderDefines sorted = defines;
    std::sort(sorted.begin(), sorted.end());
    for (const auto& [name, value] : sorted) key += name + "=" + value + ";";
    return key;
}

} // namespace

PreprocessedSource preprocessShader(const ShaderSearchPath& roots, const std::string& file, const ShaderDefines& defines)
{
    Preprocessor p{roots, {}, {}};
    p.out.text = "#version 450 core\n";
    // Shared .glsl files are also compiled as C++, where IBL_FN means inline.
    p.out.text += "#define IBL_FN\n";
    for (const auto& [name, value] : defines) p.out.text += "#define " + name + " " + value + "\n";
    p.expand(file);
    return std::move(p.out);
}

std::string mapDriverLog(const std::string& log, const std::vector<std::string>& files)
{
    // Mesa: "0:12(5): error: ...", NVIDIA: "0(12) : error ...".
    static const std::regex position(R"((\d+):(\d+)\((\d+)\)|(\d+)\((\d+)\))");
    std::string result;
    std::istringstream lines(log);
    std::string line;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_search(line, m, position) && m.position(0) == 0) {
            const bool mesa = m[1].matched;
            const std::size_t index = std::stoul(mesa ? m[1].str() : m[4].str());
            const std::string lineNo = mesa ? m[2].str() : m[5].str();
            const std::string file = index < files.size() ? files[index] : "source " + std::to_string(index);
            result += file + ":" + lineNo + (mesa ? ":" + m[3].str() : "") + m.suffix().str() + "\n";
        } else if (!line.empty()) {
            result += line + "\n";
        }
    }
    return result;
}

ShaderProgram::ShaderProgram(Program program, std::vector<std::string> files) : program_(std::move(program)), files_(std::move(files))
{
    GLint count = 0;
    glGetProgramiv(program_.id(), GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; ++i) {
        char name[256];
        GLsizei length = 0;
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(program_.id(), GLuint(i), sizeof name, &length, &size, &type, name);
        std::string uniformName(name, std::size_t(length));
        // Arrays are reported as "name[0]"; both spellings look up the first element.
        if (uniformName.ends_with("[0]")) locations_[uniformName.substr(0, uniformName.size() - 3)] = glGetUniformLocation(program_.id(), name);
        locations_[uniformName] = glGetUniformLocation(program_.id(), name);
    }
}

GLint ShaderProgram::uniformLocation(std::string_view name) const
{
    auto it = locations_.find(name);
    return it == locations_.end() ? -1 : it->second;
}

ShaderLibrary::ShaderLibrary(ShaderSearchPath roots) : roots_(std::move(roots)) {}

std::unique_ptr<ShaderProgram> ShaderLibrary::build(const std::vector<std::string>& stages, const ShaderDefines& defines) const
{
    Program program(glCreateProgram());
    std::vector<Shader> shaders;
    std::vector<std::string> allFiles;
    for (const std::string& stageFile : stages) {
        const PreprocessedSource source = preprocessShader(roots_, stageFile, defines);
        Shader shader(glCreateShader(stageOf(stageFile)));
        const char* text = source.text.c_str();
        glShaderSource(shader.id(), 1, &text, nullptr);
        glCompileShader(shader.id());
        GLint ok = GL_FALSE;
        glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint logLength = 0;
            glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &logLength);
            std::string log(std::size_t(std::max(logLength, 1)), '\0');
            glGetShaderInfoLog(shader.id(), logLength, nullptr, log.data());
            throw ShaderError("shader compile failed: " + stageFile + "\n" + mapDriverLog(log.c_str(), source.files));
        }
        glAttachShader(program.id(), shader.id());
        shaders.push_back(std::move(shader));
        for (const auto& f : source.files)
            if (std::find(allFiles.begin(), allFiles.end(), f) == allFiles.end()) allFiles.push_back(f);
    }
    glLinkProgram(program.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint logLength = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &logLength);
        std::string log(std::size_t(std::max(logLength, 1)), '\0');
        glGetProgramInfoLog(program.id(), logLength, nullptr, log.data());
        std::string names;
        for (const auto& s : stages) names += (names.empty() ? "" : " + ") + s;
        throw ShaderError("shader link failed: " + names + "\n" + std::string(log.c_str()));
    }
    for (const Shader& shader : shaders) glDetachShader(program.id(), shader.id());
    auto linked = std::make_unique<ShaderProgram>(std::move(program), std::move(allFiles));
    if (initializer_) initializer_(*linked);
    return linked;
}

std::filesystem::file_time_type ShaderLibrary::newestInput(const ShaderProgram& program) const
{
    // From the clock's minimum, not its epoch: libstdc++'s file clock counts from 2174, so
    // every real modification time is negative and a zero start would hide them all.
    auto newest = std::filesystem::file_time_type::min();
    for (const auto& f : program.files()) {
        std::error_code ec;
        const auto t = std::filesystem::last_write_time(locate(roots_, f), ec);
        if (!ec) newest = std::max(newest, t);
    }
    return newest;
}

const ShaderProgram& ShaderLibrary::program(const std::vector<std::string>& stages, const ShaderDefines& defines)
{
    const std::string key = cacheKey(stages, defines);
    auto it = cache_.find(key);
    if (it != cache_.end()) return *it->second.program;
    Entry entry{stages, defines, build(stages, defines), {}};
    entry.newestInput = newestInput(*entry.program);
    return *cache_.emplace(key, std::move(entry)).first->second.program;
}

std::vector<std::string> ShaderLibrary::reloadChanged()
{
    std::vector<std::string> errors;
    for (auto& [key, entry] : cache_) {
        const auto newest = newestInput(*entry.program);
        if (newest <= entry.newestInput) continue;
        entry.newestInput = newest; // do not retry a broken file every frame
        try {
            entry.program = build(entry.stages, entry.defines);
            ++reloads_;
        } catch (const ShaderError& e) {
            errors.push_back(e.what());
        }
    }
    return errors;
}

} // namespace iblab::gl
