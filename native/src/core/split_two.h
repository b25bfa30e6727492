// How a loop over [0, count) runs on two threads when it is large enough to pay for a thread start.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <thread>

namespace ss {

// Runs body(begin, end) over [0, count): as body(0, count) below `minCount` items, else as
// body(0, half) here and body(half, count) on a second thread (a thread start costs about
// 20 µs). `body` must not throw.
template <class Body>
void splitTwo(size_t count, Body body, size_t minCount = 50000) {
    if (count < minCount) {
        body(size_t(0), count);
        return;
    }
    const size_t half = count / 2;
    std::thread other([&] { body(half, count); });
    body(size_t(0), half);
    other.join();
}

}  // namespace ss
