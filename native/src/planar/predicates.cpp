// How the exact planar predicates are evaluated with 128-bit integers (bounds: predicates.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/predicates.h"

#include <cmath>
#include <limits>

namespace ss::planar {

int orient(const IPoint& a, const IPoint& b, const IPoint& c) {
    i128 v = i128(b.x - a.x) * (c.y - a.y) - i128(b.y - a.y) * (c.x - a.x);
    return sign(v);
}

// Floating-point filters: a double evaluation decides when it is farther from zero than its
// error bound (with coordinates <= 2^21 every rounding error below is < 1e-9, the margins are
// 100x that); only close calls pay for the exact 128-bit evaluation.
int compareX(const RatX& a, const RatX& b) {
    if (a.q == 1 && b.q == 1) return sign(a.p - b.p);
    double d = a.toDouble() - b.toDouble();
    if (d > 1e-7) return 1;
    if (d < -1e-7) return -1;
    // |p| < 2^65, q <= 2^43: each product < 2^108.
    return sign(a.p * b.q - b.p * a.q);
}

// y_s(x) * dx * q, exact: |.| < 2^88.
static i128 scaledY(const ISeg& s, const RatX& x) {
    return i128(s.lo.y) * s.dx() * x.q + (x.p - i128(s.lo.x) * x.q) * s.dy();
}

RatY yAt(const ISeg& s, const RatX& x) { return RatY{scaledY(s, x), i128(s.dx()) * x.q}; }

int compareAtX(const ISeg& s, const ISeg& t, const RatX& x) {
    double xd = x.toDouble();
    double ss = double(s.dy()) / double(s.dx()), st = double(t.dy()) / double(t.dx());
    double d = (double(s.lo.y) + (xd - double(s.lo.x)) * ss) - (double(t.lo.y) + (xd - double(t.lo.x)) * st);
    double eps = 1e-7 * (1.0 + std::fabs(ss) + std::fabs(st));
    if (d > eps) return 1;
    if (d < -eps) return -1;
    // scaledY < 2^88 times dx <= 2^21: < 2^109.
    return sign(scaledY(s, x) * t.dx() - scaledY(t, x) * s.dx());
}

int compareSlope(const ISeg& s, const ISeg& t) {
    // |dy dx| <= 2^42: exact in 64 bits.
    int64_t v = s.dy() * t.dx() - t.dy() * s.dx();
    return (v > 0) - (v < 0);
}

double approxCrossingX(const ISeg& s, const ISeg& t) {
    int64_t rx = s.dx(), ry = s.dy(), ex = t.dx(), ey = t.dy();
    int64_t den = rx * ey - ry * ex;
    if (den == 0) return std::numeric_limits<double>::quiet_NaN();
    int64_t num = (t.lo.x - s.lo.x) * ey - (t.lo.y - s.lo.y) * ex;
    return double(s.lo.x) + double(num) / double(den) * double(rx);
}

bool crossingX(const ISeg& s, const ISeg& t, RatX* out) {
    int64_t rx = s.dx(), ry = s.dy(), ex = t.dx(), ey = t.dy();
    int64_t den = rx * ey - ry * ex;  // |.| <= 2^43
    if (den == 0) return false;
    int64_t num = (t.lo.x - s.lo.x) * ey - (t.lo.y - s.lo.y) * ex;
    i128 p = i128(s.lo.x) * den + i128(num) * rx;  // < 2^65
    if (den < 0) {
        p = -p;
        den = -den;
    }
    *out = RatX{p, den};
    return true;
}

static i128 floorDiv(i128 a, i128 b) {
    i128 q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
    return q;
}

int64_t roundDiv(i128 num, i128 den) { return int64_t(floorDiv(2 * num + den, 2 * den)); }

}  // namespace ss::planar
