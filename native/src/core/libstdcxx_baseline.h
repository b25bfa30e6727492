// Why this library asks libstdc++ for an older condition_variable::wait than GCC 12 would pick.
// SPDX-License-Identifier: GPL-3.0-or-later
// GCC 12 added a second version of std::condition_variable::wait (GLIBCXX_3.4.30) beside the one
// every libstdc++ since GCC 4 exports (GLIBCXX_3.4.11). Binding the older one keeps the add-on's
// library loadable with GCC 11's libstdc++ (RHEL 9) and newer; tests/blender/test_package.py
// prints the highest version the zip needs. Include it in every file that waits on one.
#pragma once
#include <condition_variable>

#if defined(__GLIBCXX__) && defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
__asm__(".symver _ZNSt18condition_variable4waitERSt11unique_lockISt5mutexE,"
        "_ZNSt18condition_variable4waitERSt11unique_lockISt5mutexE@GLIBCXX_3.4.11");
#endif
