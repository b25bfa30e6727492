// Which subcommand of the `softshadow` command runs, and how its failures become one line.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstdio>

int main(int argc, char** argv) {
    (void)argc, (void)argv;
    std::fprintf(stderr, "softshadow: error: not implemented yet\n");
    return 2;
}
