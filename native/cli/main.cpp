// Which subcommand of the `softshadow` command runs, and how its failures become one line.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli_common.h"

namespace {

const char* kUsage =
    "usage: softshadow <command> [options]\n"
    "\n"
    "commands:\n"
    "  info [--backend egl|osmesa|auto] [--json]\n"
    "      the GL backend, renderer, GL version and limits\n"
    "  render SCENE -m METHOD[,METHOD...] -o OUT.exr [-l LIGHT[,LIGHT...]] [--width W] [--height H]\n"
    "         [--samples N] [--seed S] [--set key=value]... [--refine] [--no-extra] [--backend B]\n"
    "         [--png-dir DIR]\n"
    "      renders soft-shadow visibility passes into a multilayer EXR\n"
    "  compare A.exr [B.exr] [--mask PASS|none] [--against METHOD] [--json]\n"
    "      error metrics between the passes of two files (or of each method against\n"
    "      `reference` inside one file)\n"
    "  report SCENE [--json]\n"
    "      the scene's meshes (open/non-manifold/inconsistent edges, degenerate faces), lights (with\n"
    "      the meshes that shadow each and those it lights), camera\n"
    "  version\n";

bool asksForHelp(const std::vector<std::string>& args) {
    for (const std::string& a : args)
        if (a == "-h" || a == "--help") return true;
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    ss_remove_temporary_files_on_signals();  // an interrupted write leaves no temporary file
    std::vector<std::string> args(argv + 1, argv + argc);
    int code = 1;
    try {
        if (args.empty() || args[0] == "help" || asksForHelp(args)) {
            std::fputs(kUsage, args.empty() ? stderr : stdout);
            code = args.empty() ? 2 : 0;
        } else {
            std::string command = args[0];
            std::vector<std::string> rest(args.begin() + 1, args.end());
            if (command == "info") code = ss::cli::runInfo(rest);
            else if (command == "render") code = ss::cli::runRender(rest);
            else if (command == "compare") code = ss::cli::runCompare(rest);
            else if (command == "report") code = ss::cli::runReport(rest);
            else if (command == "version" || command == "--version") {
                std::printf("softshadow %s\n", ss_version());
                code = 0;
            } else {
                throw ss::cli::CliError("unknown command '" + command + "' (try softshadow --help)");
            }
        }
    } catch (const std::exception& e) {
        std::string message = e.what();
        for (char& c : message)
            if (c == '\n') c = ' ';  // one line, so scripts can grep it
        std::fprintf(stderr, "softshadow: error: %s\n", message.c_str());
        code = 1;
    }
    ss_shutdown();
    return code;
}
