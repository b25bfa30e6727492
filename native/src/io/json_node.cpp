// How JSON values are checked and converted, naming their path when they are wrong.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/json_node.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace ss {

const char* jsonTypeName(const nlohmann::json& v) {
    switch (v.type()) {
        case nlohmann::json::value_t::null: return "null";
        case nlohmann::json::value_t::object: return "an object";
        case nlohmann::json::value_t::array: return "an array";
        case nlohmann::json::value_t::string: return "a string";
        case nlohmann::json::value_t::boolean: return "a boolean";
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned:
        case nlohmann::json::value_t::number_float: return "a number";
        default: return "an unsupported value";
    }
}

std::string JsonNode::message(const std::string& problem) const {
    return where_ + ": " + (path_.empty() ? std::string() : path_ + ": ") + problem;
}

void JsonNode::fail(const std::string& problem, ss_status status) const {
    ss::fail(status, message(problem));
}

bool JsonNode::has(const char* key) const {
    return value_.is_object() && value_.contains(key);
}

JsonNode JsonNode::at(const char* key) const {
    expectObject();
    std::string child = path_.empty() ? std::string(key) : path_ + "." + key;
    auto it = value_.find(key);
    if (it == value_.end()) JsonNode(value_, where_, child).fail("is missing");
    return JsonNode(*it, where_, child);
}

JsonNode JsonNode::at(size_t index) const {
    expectArray();
    return JsonNode(value_[index], where_, path_ + "[" + std::to_string(index) + "]");
}

size_t JsonNode::size() const {
    expectArray();
    return value_.size();
}

void JsonNode::expectObject() const {
    if (!value_.is_object()) fail(std::string("expected an object, got ") + jsonTypeName(value_));
}

void JsonNode::expectArray() const {
    if (!value_.is_array()) fail(std::string("expected an array, got ") + jsonTypeName(value_));
}

void JsonNode::expectKeys(std::initializer_list<const char*> allowed) const {
    expectObject();
    for (auto it = value_.begin(); it != value_.end(); ++it) {
        bool known = false;
        for (const char* a : allowed) known = known || it.key() == a;
        if (!known) {
            std::string list;
            for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
            fail("unknown key '" + it.key() + "' (expected one of: " + list + ")");
        }
    }
}

double JsonNode::number() const {
    if (!value_.is_number())
        fail(std::string("expected a number, got ") + jsonTypeName(value_) +
             (value_.is_string() ? " ('" + value_.get<std::string>() + "')" : std::string()));
    double v = value_.get<double>();
    if (!std::isfinite(v) || std::abs(v) > kJsonNumberLimit) {
        std::ostringstream m;
        m << "number " << v << " is out of range (|v| must be at most " << kJsonNumberLimit << ")";
        fail(m.str());
    }
    return v;
}

float JsonNode::real() const { return float(number()); }

int64_t JsonNode::integer(int64_t lo, int64_t hi) const {
    double v = number();
    if (v != std::floor(v)) fail("expected a whole number, got " + std::to_string(v));
    if (v < double(lo) || v > double(hi))
        fail("value " + std::to_string(int64_t(v)) + " is outside [" + std::to_string(lo) + ", " +
             std::to_string(hi) + "]");
    return int64_t(v);
}

bool JsonNode::boolean() const {
    if (!value_.is_boolean()) fail(std::string("expected true or false, got ") + jsonTypeName(value_));
    return value_.get<bool>();
}

std::string JsonNode::string() const {
    if (!value_.is_string()) fail(std::string("expected a string, got ") + jsonTypeName(value_));
    return value_.get<std::string>();
}

std::vector<float> JsonNode::reals() const {
    size_t n = size();
    std::vector<float> out(n);
    for (size_t i = 0; i < n; ++i) {
        const nlohmann::json& e = value_[i];
        // Fast path for the common case; the slow path builds the element's path for the message.
        if (e.is_number()) {
            double v = e.get<double>();
            if (std::isfinite(v) && std::abs(v) <= kJsonNumberLimit) {
                out[i] = float(v);
                continue;
            }
        }
        out[i] = at(i).real();
    }
    return out;
}

glm::vec3 JsonNode::vec3() const {
    if (size() != 3) fail("expected 3 numbers, got " + std::to_string(size()));
    return {at(size_t(0)).real(), at(1).real(), at(2).real()};
}

glm::mat4 JsonNode::mat4() const {
    if (size() != 16) fail("expected 16 numbers (a column-major 4x4 matrix), got " + std::to_string(size()));
    std::vector<float> v = reals();
    glm::mat4 m;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = v[size_t(c) * 4 + r];
    return m;
}

double JsonNode::number(const char* key, double fallback) const {
    return has(key) ? at(key).number() : fallback;
}

float JsonNode::real(const char* key, float fallback) const {
    return has(key) ? at(key).real() : fallback;
}

int64_t JsonNode::integer(const char* key, int64_t fallback, int64_t lo, int64_t hi) const {
    return has(key) ? at(key).integer(lo, hi) : fallback;
}

bool JsonNode::boolean(const char* key, bool fallback) const {
    return has(key) ? at(key).boolean() : fallback;
}

}  // namespace ss
