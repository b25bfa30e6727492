// How GLSL programs are built from the embedded shaders/ files (includes, #define variants).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_functions.h"

namespace ss::gl {

// Paths are relative to shaders/ (e.g. "shadow_map/resolve.frag.glsl"); empty = no such stage.
// Each define is "NAME" or "NAME=VALUE" and becomes "#define NAME VALUE" after #version.
struct ProgramDesc {
    std::string vertex, geometry, fragment, compute;
    std::vector<std::string> defines;
    std::string key() const;
};

// A linked program. Setters look uniforms up by name (cached) and ignore names the compiler
// optimised away, so one C++ routine can drive several variants.
class Program {
public:
    Program() = default;
    explicit Program(const ProgramDesc& desc);  // throws ss::Error(SS_ERROR_GL) with the info log
    ~Program();
    Program(Program&& o) noexcept;
    Program& operator=(Program&& o) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    GLuint id() const { return id_; }
    void use() const;
    GLint location(const char* name) const;  // -1 when absent

    void set(const char* name, int v) const;
    void set(const char* name, unsigned v) const;
    void set(const char* name, float v) const;
    void set(const char* name, const glm::vec2& v) const;
    void set(const char* name, const glm::vec3& v) const;
    void set(const char* name, const glm::vec4& v) const;
    void set(const char* name, const glm::ivec2& v) const;
    void set(const char* name, const glm::mat4& v) const;
    // Binds `texture` (a 2D texture unless `target` says otherwise) to `unit` and points the
    // sampler uniform `name` at it.
    void setTexture(const char* name, int unit, GLuint texture, GLenum target = GL_TEXTURE_2D) const;

private:
    GLuint id_ = 0;
    mutable std::unordered_map<std::string, GLint> locations_;
};

// The program for `desc`, compiled once per render thread and kept until the thread stops.
const Program& program(const ProgramDesc& desc);
// Shorthand for the common vertex + fragment case.
const Program& program(const std::string& vertex, const std::string& fragment,
                       const std::vector<std::string>& defines = {});

// The text handed to the compiler for one stage: "#version 450 core", the defines, then the
// file with every `#include "path"` expanded once (later repeats are dropped) and #line marks
// whose source number is the file's index in shaderSources(). Throws for a missing file.
std::string expandShader(const std::string& path, const std::vector<std::string>& defines);

// Deletes this thread's cached programs (the render thread calls it before its context dies).
void releaseThreadPrograms();

}  // namespace ss::gl
