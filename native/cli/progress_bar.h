// How a long render shows its progress on a terminal (stderr), and stays silent otherwise.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <chrono>
#include <mutex>
#include <string>

namespace ss::cli {

class ProgressBar {
public:
    explicit ProgressBar(std::string label);
    ~ProgressBar();
    // Thread-safe; draws only on a terminal, only after a moment has passed, at most ~10 times a second.
    void update(float fraction, const char* stage);
    void finish();  // clears the line

    // An ss_progress_fn: user is a ProgressBar*. Never cancels.
    static int callback(void* user, float fraction, const char* stage);

private:
    std::string label_;
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_, lastDraw_;
    std::mutex mutex_;
};

}  // namespace ss::cli
