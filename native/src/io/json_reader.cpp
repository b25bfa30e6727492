// How a JSON text is parsed while the path of the value being read is tracked for messages.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/json_reader.h"

#include <set>
#include <vector>

#include "core/error.h"
#include "core/names.h"

namespace ss {

namespace {

using Json = nlohmann::json;
using DomParser = nlohmann::detail::json_sax_dom_parser<Json>;

// The DOM builder, plus a stack of where it is; refuses what the plain parser lets through.
class StrictParser : public DomParser {
public:
    StrictParser(Json& root, const std::string& where) : DomParser(root, true), where_(where) {}

    bool null() { return scalar() && DomParser::null(); }
    bool boolean(bool v) { return scalar() && DomParser::boolean(v); }
    bool number_integer(Json::number_integer_t v) { return scalar() && DomParser::number_integer(v); }
    bool number_unsigned(Json::number_unsigned_t v) { return scalar() && DomParser::number_unsigned(v); }
    bool number_float(Json::number_float_t v, const Json::string_t& s) {
        return scalar() && DomParser::number_float(v, s);
    }
    bool string(Json::string_t& v) {
        checkText(v, "a string");
        return scalar() && DomParser::string(v);
    }
    bool binary(Json::binary_t& v) { return scalar() && DomParser::binary(v); }

    bool start_object(std::size_t n) {
        open(false);
        return DomParser::start_object(n);
    }
    bool key(Json::string_t& k) {
        checkText(k, "a key");
        Frame& f = stack_.back();
        f.key = k;
        f.hasKey = true;
        if (!f.keys.insert(k).second) fail("key " + ss::quoted(k) + " appears twice in the same object");
        return DomParser::key(k);
    }
    bool end_object() {
        close();
        return DomParser::end_object();
    }
    bool start_array(std::size_t n) {
        open(true);
        return DomParser::start_array(n);
    }
    bool end_array() {
        close();
        return DomParser::end_array();
    }
    template <class Exception>
    bool parse_error(std::size_t, const std::string&, const Exception& e) {
        std::string what = e.what();
        size_t cut = what.find("] ");
        fail("malformed JSON: " + (cut == std::string::npos ? what : what.substr(cut + 2)));
    }

private:
    struct Frame {
        bool isArray = false;
        size_t index = 0;
        std::string key;
        bool hasKey = false;
        std::set<std::string> keys;
    };

    std::string path() const {
        std::string p;
        for (const Frame& f : stack_) {
            if (f.isArray) p += "[" + std::to_string(f.index) + "]";
            else if (f.hasKey) p += (p.empty() ? "" : ".") + f.key;
        }
        return p;
    }

    [[noreturn]] void fail(const std::string& problem) const {
        std::string p = path();
        ss::fail(SS_ERROR_IO, where_ + ": " + (p.empty() ? std::string() : p + ": ") + problem);
    }

    void checkText(const std::string& text, const char* what) const {
        if (text.find('\0') != std::string::npos)
            fail(std::string(what) + " holds a NUL character (\\u0000), which would cut it short");
    }

    // A value was read at the current position: the next array element follows.
    bool scalar() {
        advance();
        return true;
    }
    void advance() {
        if (!stack_.empty() && stack_.back().isArray) ++stack_.back().index;
    }
    void open(bool isArray) {
        if (stack_.size() >= kMaxJsonDepth)
            fail("nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        Frame f;
        f.isArray = isArray;
        stack_.push_back(std::move(f));
    }
    void close() {
        stack_.pop_back();
        advance();
    }

    std::string where_;
    std::vector<Frame> stack_;
};

}  // namespace

nlohmann::json parseJsonStrict(const std::string& text, const std::string& where) {
    Json root;
    StrictParser parser(root, where);
    Json::sax_parse(text, &parser);
    return root;
}

}  // namespace ss
