// How shader files are expanded, compiled, linked, cached and given uniforms.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/program.h"

#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "gl/shader_sources.h"

namespace ss::gl {

namespace {

int sourceIndex(const std::string& path) {
    const auto& table = shaderSources();
    for (size_t i = 0; i < table.size(); ++i)
        if (path == table[i].path) return int(i);
    fail(SS_ERROR_GL, "shader file '" + path + "' is not embedded (is it under shaders/?)");
}

void expandInto(const std::string& path, std::set<std::string>& seen, std::ostringstream& out,
                int depth) {
    if (depth > 16) fail(SS_ERROR_GL, "shader includes nest too deep at '" + path + "'");
    if (!seen.insert(path).second) return;
    int index = sourceIndex(path);
    std::istringstream in(shaderSources()[index].text);
    static const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
    static const std::regex version(R"(^\s*#\s*version\b.*$)");
    std::string line;
    int lineNo = 0;
    out << "#line 1 " << index << "\n";
    while (std::getline(in, line)) {
        ++lineNo;
        std::smatch m;
        if (std::regex_match(line, m, include)) {
            expandInto(m[1].str(), seen, out, depth + 1);
            out << "#line " << lineNo + 1 << " " << index << "\n";
        } else if (std::regex_match(line, version)) {
            out << "\n";  // the version is ours to set, once, on the first line
        } else {
            out << line << "\n";
        }
    }
}

std::string sourceLegend(const std::string& text) {
    // Mesa reports "0:12(3): error": the first number is the #line source index.
    std::string legend;
    std::set<int> listed;
    static const std::regex mark(R"(#line \d+ (\d+))");
    for (std::sregex_iterator it(text.begin(), text.end(), mark), end; it != end; ++it) {
        int i = std::stoi((*it)[1].str());
        if (listed.insert(i).second)
            legend += "\n  source " + std::to_string(i) + " = " + shaderSources()[i].path;
    }
    return legend;
}

// Nothing when the shader's or program's `status` (compile or link) is set; else its info log.
// Shaders and programs have the same pair of getters, passed in.
std::optional<std::string> failureLog(GLuint object, GLenum status, PFNGLGETSHADERIVPROC getParameter,
                                      PFNGLGETSHADERINFOLOGPROC getInfoLog) {
    GLint ok = 0;
    getParameter(object, status, &ok);
    if (ok) return std::nullopt;
    GLint length = 0;
    getParameter(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    getInfoLog(object, length, nullptr, log.data());
    return std::string(log.c_str());
}

GLuint compileStage(const Functions& gl, GLenum stage, const std::string& path,
                    const std::vector<std::string>& defines) {
    std::string text = expandShader(path, defines);
    GLuint shader = gl.CreateShader(stage);
    const char* src = text.c_str();
    gl.ShaderSource(shader, 1, &src, nullptr);
    gl.CompileShader(shader);
    if (std::optional<std::string> log = failureLog(shader, GL_COMPILE_STATUS, gl.GetShaderiv, gl.GetShaderInfoLog)) {
        gl.DeleteShader(shader);
        fail(SS_ERROR_GL, "shader '" + path + "' does not compile:\n" + *log + sourceLegend(text));
    }
    return shader;
}

thread_local std::map<std::string, std::unique_ptr<Program>>* tPrograms = nullptr;

}  // namespace

std::string ProgramDesc::key() const {
    std::string k = vertex + "|" + geometry + "|" + fragment + "|" + compute;
    for (auto& d : defines) k += "|" + d;
    return k;
}

std::string expandShader(const std::string& path, const std::vector<std::string>& defines) {
    std::ostringstream out;
    out << "#version 450 core\n";
    for (const std::string& d : defines) {
        size_t eq = d.find('=');
        if (eq == std::string::npos) out << "#define " << d << "\n";
        else out << "#define " << d.substr(0, eq) << " " << d.substr(eq + 1) << "\n";
    }
    std::set<std::string> seen;
    expandInto(path, seen, out, 0);
    return out.str();
}

Program::Program(const ProgramDesc& desc) {
    const Functions& gl = api();
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders) gl.DeleteShader(s);
    };
    try {
        if (!desc.compute.empty()) shaders.push_back(compileStage(gl, GL_COMPUTE_SHADER, desc.compute, desc.defines));
        if (!desc.vertex.empty()) shaders.push_back(compileStage(gl, GL_VERTEX_SHADER, desc.vertex, desc.defines));
        if (!desc.geometry.empty()) shaders.push_back(compileStage(gl, GL_GEOMETRY_SHADER, desc.geometry, desc.defines));
        if (!desc.fragment.empty()) shaders.push_back(compileStage(gl, GL_FRAGMENT_SHADER, desc.fragment, desc.defines));
    } catch (...) {
        cleanup();
        throw;
    }
    if (shaders.empty()) fail(SS_ERROR_GL, "a program needs at least one shader stage");
    id_ = gl.CreateProgram();
    for (GLuint s : shaders) gl.AttachShader(id_, s);
    gl.LinkProgram(id_);
    cleanup();
    if (std::optional<std::string> log = failureLog(id_, GL_LINK_STATUS, gl.GetProgramiv, gl.GetProgramInfoLog)) {
        gl.DeleteProgram(id_);
        id_ = 0;
        fail(SS_ERROR_GL, "program " + desc.key() + " does not link:\n" + *log);
    }
}

Program::~Program() {
    if (id_ && current()) current()->DeleteProgram(id_);
}

Program::Program(Program&& o) noexcept : id_(o.id_), locations_(std::move(o.locations_)) { o.id_ = 0; }

Program& Program::operator=(Program&& o) noexcept {
    if (this != &o) {
        if (id_ && current()) current()->DeleteProgram(id_);
        id_ = o.id_;
        locations_ = std::move(o.locations_);
        o.id_ = 0;
    }
    return *this;
}

void Program::use() const { api().UseProgram(id_); }

GLint Program::location(const char* name) const {
    auto it = locations_.find(name);
    if (it != locations_.end()) return it->second;
    GLint loc = api().GetUniformLocation(id_, name);
    locations_.emplace(name, loc);
    return loc;
}

void Program::set(const char* name, int v) const { api().ProgramUniform1i(id_, location(name), v); }
void Program::set(const char* name, unsigned v) const { api().ProgramUniform1ui(id_, location(name), v); }
void Program::set(const char* name, float v) const { api().ProgramUniform1f(id_, location(name), v); }
void Program::set(const char* name, const glm::vec2& v) const {
    api().ProgramUniform2fv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec3& v) const {
    api().ProgramUniform3fv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec4& v) const {
    api().ProgramUniform4fv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::ivec2& v) const {
    api().ProgramUniform2iv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat4& v) const {
    api().ProgramUniformMatrix4fv(id_, location(name), 1, GL_FALSE, glm::value_ptr(v));
}

void Program::setTexture(const char* name, int unit, GLuint texture, GLenum target) const {
    const Functions& gl = api();
    gl.ActiveTexture(GL_TEXTURE0 + unit);
    gl.BindTexture(target, texture);
    gl.ProgramUniform1i(id_, location(name), unit);
}

const Program& program(const ProgramDesc& desc) {
    api();  // only the render thread holds programs
    if (!tPrograms) tPrograms = new std::map<std::string, std::unique_ptr<Program>>();
    std::string key = desc.key();
    auto it = tPrograms->find(key);
    if (it != tPrograms->end()) return *it->second;
    auto p = std::make_unique<Program>(desc);
    return *tPrograms->emplace(key, std::move(p)).first->second;
}

const Program& program(const std::string& vertex, const std::string& fragment,
                       const std::vector<std::string>& defines) {
    ProgramDesc d;
    d.vertex = vertex;
    d.fragment = fragment;
    d.defines = defines;
    return program(d);
}

void releaseThreadPrograms() {
    delete tPrograms;
    tPrograms = nullptr;
}

}  // namespace ss::gl
