// What the `softshadow` subcommands share: argument parsing, failure reporting, C API checks.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "softshadow/softshadow.h"

namespace ss::cli {

// A failure the command reports as one "softshadow: error: ..." line.
struct CliError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Throws CliError with ss_last_error() when status is not SS_OK.
void check(ss_status status);

// Options are "--name value", "--name=value" or "-x value"; flags take no value.
class Args {
public:
    Args(const std::vector<std::string>& argv, const std::set<std::string>& valueOptions,
         const std::set<std::string>& flagOptions);
    const std::vector<std::string>& positional() const { return positional_; }
    bool flag(const std::string& name) const { return flags_.count(name) != 0; }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    // The option's one value; throws CliError when it was given more than once.
    std::string value(const std::string& name, const std::string& fallback = "") const;
    const std::vector<std::string>& values(const std::string& name) const;  // every occurrence
    int integer(const std::string& name, int fallback, int lo, int hi) const;

private:
    std::vector<std::string> positional_;
    std::set<std::string> flags_;
    std::map<std::string, std::vector<std::string>> values_;
};

std::vector<std::string> splitList(const std::string& text, char separator = ',');
// The pass name of a result's layer (ss_pass_name).
std::string passName(const char* light, const char* method, const char* layer);
ss_backend parseBackend(const std::string& name);

int runInfo(const std::vector<std::string>& args);
int runRender(const std::vector<std::string>& args);
int runCompare(const std::vector<std::string>& args);
int runReport(const std::vector<std::string>& args);

}  // namespace ss::cli
