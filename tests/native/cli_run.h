// How the native tests run the `softshadow` command and check a failure: exit code, one
// "softshadow: error:" line, the fragments it must name.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

struct CliRun {
    int code = -1;
    std::string out;  // stdout
    std::string err;  // stderr
};

// Runs the CLI with a shell command line (arguments already quoted by the caller).
inline CliRun cli(const std::string& args) {
    static int counter = 0;
    fs::path errFile = fs::temp_directory_path() / ("ss_cli_err_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
    std::string command = std::string("'") + SS_CLI_PATH + "' " + args + " 2>'" + errFile.string() + "'";
    CliRun r;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
    int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream e(errFile);
    r.err.assign(std::istreambuf_iterator<char>(e), {});
    fs::remove(errFile);
    return r;
}

// A CLI run stopped by a signal while it writes: started with `args` (argv after the program),
// sent `signal` as soon as `writing()` sees its temporary file, then waited for.
struct SignalledRun {
    pid_t pid = 0;
    bool signalled = false;  // false: the run ended before its temporary file was seen
    int status = 0;
};

inline SignalledRun signalWhileWriting(std::vector<std::string> args, int signal, const std::function<bool()>& writing) {
    args.insert(args.begin(), SS_CLI_PATH);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    SignalledRun run;
    if (posix_spawn(&run.pid, SS_CLI_PATH, nullptr, nullptr, argv.data(), environ) != 0) return run;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline) {
        if (writing()) {
            run.signalled = true;
            kill(run.pid, signal);
            break;
        }
        if (waitpid(run.pid, &run.status, WNOHANG) == run.pid) return run;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    waitpid(run.pid, &run.status, 0);
    return run;
}

inline fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("ss_cli_" + std::to_string(getpid()) + "_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

inline size_t entries(const fs::path& dir) {
    return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

// One failing command: non-zero exit, exactly one "softshadow: error:" line naming the problem.
inline void expectFailure(const CliRun& r, std::initializer_list<std::string> fragments) {
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(r.err.rfind("softshadow: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' not in: " << r.err;
}

}  // namespace
