// How plane edges are clipped to the receiver box and rounded to grid points.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/snap.h"

#include <algorithm>
#include <utility>
#include <cmath>

namespace ss::planar {

Snap::Snap(double cu, double cv, double half) : cu_(cu), cv_(cv), scale_(double(kGridLimit) / half) {}

void Snap::addEdge(double ua, double va, double ub, double vb, int weight,
                   std::vector<DirectedEdge>* out) const {
    const double L = double(kGridLimit);
    double ax = (ua - cu_) * scale_, ay = (va - cv_) * scale_;
    double bx = (ub - cu_) * scale_, by = (vb - cv_) * scale_;
    double ts[6] = {0.0, 1.0};
    int nt = 2;
    auto cut = [&](double a, double b, double line) {
        if ((a - line) * (b - line) < 0.0) ts[nt++] = (line - a) / (b - a);
    };
    cut(ax, bx, -L);
    cut(ax, bx, L);
    cut(ay, by, -L);
    cut(ay, by, L);
    for (int i = 1; i < nt; ++i)  // at most six values: insertion sort
        for (int j = i; j > 0 && ts[j] < ts[j - 1]; --j) std::swap(ts[j], ts[j - 1]);
    auto at = [&](double t) {
        double x = t == 1.0 ? bx : ax + t * (bx - ax);
        double y = t == 1.0 ? by : ay + t * (by - ay);
        x = std::clamp(x, -L, L);
        y = std::clamp(y, -L, L);
        return IPoint{int64_t(std::llround(x)), int64_t(std::llround(y))};
    };
    IPoint prev = at(ts[0]);
    for (int i = 1; i < nt; ++i) {
        IPoint p = at(ts[i]);
        if (!(p == prev)) out->push_back(DirectedEdge{prev, p, weight});
        prev = p;
    }
}

}  // namespace ss::planar
