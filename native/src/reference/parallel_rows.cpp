// How rows are handed to worker threads while the caller reports progress.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/parallel_rows.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/libstdcxx_baseline.h"

namespace ss {
namespace {

int threadCount(const RenderSettings& settings, int rows) {
    int n = settings.integer(kThreadsSetting);
    if (n <= 0) n = int(std::max(1u, std::thread::hardware_concurrency()));
    return std::clamp(n, 1, std::max(1, rows));
}

}  // namespace

void forEachRow(const RenderSettings& settings, int rows, const char* stage, float progressFrom,
                float progressTo, const std::function<void(int)>& rowFn) {
    std::atomic<int> nextRow{0}, rowsDone{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::condition_variable finished;
    int workersLeft = threadCount(settings, rows);
    std::exception_ptr error;
    std::vector<std::thread> workers;
    for (int t = 0, n = workersLeft; t < n; ++t)
        workers.emplace_back([&] {
            try {
                for (int y; !stop && (y = nextRow++) < rows; ++rowsDone) rowFn(y);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                if (!error) error = std::current_exception();
                stop = true;
            }
            std::lock_guard<std::mutex> lock(mutex);
            if (--workersLeft == 0) finished.notify_all();
        });
    auto joinAll = [&] {
        for (std::thread& w : workers) w.join();
    };
    auto fraction = [&] {
        return progressFrom + (progressTo - progressFrom) * float(rowsDone) / float(std::max(1, rows));
    };
    try {
        std::unique_lock<std::mutex> lock(mutex);
        while (workersLeft > 0) {
            finished.wait_for(lock, std::chrono::milliseconds(50));
            if (workersLeft == 0) break;
            lock.unlock();
            settings.report(fraction(), stage);
            lock.lock();
        }
    } catch (...) {
        stop = true;
        joinAll();
        throw;
    }
    joinAll();
    if (error) std::rethrow_exception(error);
    settings.report(progressTo, stage);
}

}  // namespace ss
