// How the progress bar is drawn on stderr.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace ss::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), lastDraw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(float fraction, const char* stage) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    auto now = std::chrono::steady_clock::now();
    // Quick renders stay quiet; long ones redraw at a calm rate.
    if (now - start_ < std::chrono::milliseconds(400)) return;
    if (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100) && fraction < 1.0f) return;
    lastDraw_ = now;
    drawn_ = true;
    constexpr int kWidth = 30;
    float f = std::clamp(fraction, 0.0f, 1.0f);
    int filled = int(f * kWidth + 0.5f);
    std::string bar(size_t(filled), '#');
    bar.append(size_t(kWidth - filled), '-');
    double seconds = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r\033[K%s [%s] %3d%% %5.1fs %s", label_.c_str(), bar.c_str(), int(f * 100.0f + 0.5f),
                 seconds, stage ? stage : "");
    std::fflush(stderr);
}

void ProgressBar::finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (enabled_ && drawn_) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
    drawn_ = false;
}

int ProgressBar::callback(void* user, float fraction, const char* stage) {
    static_cast<ProgressBar*>(user)->update(fraction, stage);
    return 0;
}

}  // namespace ss::cli
