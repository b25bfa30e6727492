// How a JSON value is read with its path (e.g. meshes[2].positions[7]) in every error message.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "softshadow/softshadow.h"

namespace ss {

// Numbers whose magnitude exceeds this are rejected: they are typos or overflow, and single
// precision geometry cannot use them.
inline constexpr double kJsonNumberLimit = 1e15;

class JsonNode {
public:
    // `where` prefixes every message (e.g. "scene 'a.json'"); `path` is this node's JSON path.
    JsonNode(const nlohmann::json& value, std::string where, std::string path)
        : value_(value), where_(std::move(where)), path_(std::move(path)) {}

    const nlohmann::json& value() const { return value_; }
    const std::string& path() const { return path_; }
    // "<where>: <path>: <problem>"
    std::string message(const std::string& problem) const;
    [[noreturn]] void fail(const std::string& problem, ss_status status = SS_ERROR_IO) const;

    bool has(const char* key) const;
    JsonNode at(const char* key) const;  // required member of an object
    JsonNode at(size_t index) const;
    size_t size() const;  // of an array (checks it is one)

    void expectObject() const;
    void expectArray() const;
    // Every member key must be one of `allowed` (catches typos such as "postions").
    void expectKeys(std::initializer_list<const char*> allowed) const;

    double number() const;  // finite, |v| <= kJsonNumberLimit
    float real() const;      // number() as float
    int64_t integer(int64_t lo, int64_t hi) const;
    bool boolean() const;
    std::string string() const;
    std::vector<float> reals() const;  // an array of numbers
    glm::vec3 vec3() const;
    glm::mat4 mat4() const;  // 16 numbers, column-major

    // Optional members with a fallback.
    double number(const char* key, double fallback) const;
    float real(const char* key, float fallback) const;
    int64_t integer(const char* key, int64_t fallback, int64_t lo, int64_t hi) const;
    bool boolean(const char* key, bool fallback) const;

private:
    const nlohmann::json& value_;
    std::string where_;
    std::string path_;
};

const char* jsonTypeName(const nlohmann::json& value);

}  // namespace ss
