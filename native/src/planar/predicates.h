// Which exact predicates the planar sweep relies on: orientation, x ordering, y ordering of
// segments at a rational x, slopes and crossings, all on integer grid coordinates.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>

namespace ss::planar {

using i128 = __int128;

// Every input coordinate is an integer with |c| <= kGridLimit. With that bound the largest
// intermediate below is < 2^110, so 128-bit integers hold every product exactly
// (docs/methods/sweep.md derives each bound).
inline constexpr int64_t kGridLimit = int64_t(1) << 20;

struct IPoint {
    int64_t x = 0, y = 0;
    friend bool operator==(const IPoint&, const IPoint&) = default;
};

// A non-vertical segment stored left to right: lo.x < hi.x.
struct ISeg {
    IPoint lo, hi;
    int64_t dx() const { return hi.x - lo.x; }
    int64_t dy() const { return hi.y - lo.y; }
};

// An exact x position p / q with q > 0: a grid x (q = 1) or the x of a crossing.
struct RatX {
    i128 p = 0;
    int64_t q = 1;
    static RatX of(int64_t x) { return RatX{x, 1}; }
    double toDouble() const { return double(p) / double(q); }
};

// A y value exact as num / den (den > 0): where a segment is at a rational x.
struct RatY {
    i128 num = 0;
    i128 den = 1;
    double toDouble() const { return double(num) / double(den); }
};

inline int sign(i128 v) { return (v > 0) - (v < 0); }

// sign of (b - a) x (c - a): +1 when a, b, c turn counter-clockwise.
int orient(const IPoint& a, const IPoint& b, const IPoint& c);
// sign(a - b)
int compareX(const RatX& a, const RatX& b);
// The segment's y at x (x inside its closed x range).
RatY yAt(const ISeg& s, const RatX& x);
// sign(y_s(x) - y_t(x)) for two segments whose closed x ranges contain x.
int compareAtX(const ISeg& s, const ISeg& t, const RatX& x);
// sign(slope(s) - slope(t)).
int compareSlope(const ISeg& s, const ISeg& t);
// The x where the lines of s and t cross; false when they are parallel. The caller knows both
// segments are present at the crossing (it only asks about neighbours in the sweep order).
bool crossingX(const ISeg& s, const ISeg& t, RatX* out);
// The crossing x in doubles (error < 1e-6 grid units), NaN for parallel lines: lets the sweep
// skip the exact crossing of neighbours that cannot cross inside the current slab.
double approxCrossingX(const ISeg& s, const ISeg& t);
// round(num / den) to the nearest integer, halves away from -infinity (den > 0).
int64_t roundDiv(i128 num, i128 den);

}  // namespace ss::planar
