// How merged edges are split into parts whose shadow regions do not meet: a grid over the edges
// marks the cells near an edge and the cells inside a region, and the parts are the 8-connected
// groups of marked cells.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/shadow_parts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>

namespace ss::planar {

bool edgeLess(const DirectedEdge& p, const DirectedEdge& q) {
    return std::tie(p.a.x, p.a.y, p.b.x, p.b.y, p.weight) < std::tie(q.a.x, q.a.y, q.b.x, q.b.y, q.weight);
}

bool sameEdges(std::span<const DirectedEdge> p, std::span<const DirectedEdge> q) {
    return std::equal(p.begin(), p.end(), q.begin(), q.end(), [](const DirectedEdge& e, const DirectedEdge& f) {
        return e.a == f.a && e.b == f.b && e.weight == f.weight;
    });
}

namespace {

// Cell (col, row) covers x in [x0 + col * size, x0 + (col + 1) * size), y likewise.
struct Grid {
    int64_t x0 = 0, y0 = 0, size = 1;
    int cols = 1, rows = 1;
    int col(double x) const { return std::clamp(int(std::floor((x - double(x0)) / double(size))), 0, cols - 1); }
    int row(double y) const { return std::clamp(int(std::floor((y - double(y0)) / double(size))), 0, rows - 1); }
    size_t at(int c, int r) const { return size_t(r) * size_t(cols) + size_t(c); }
};

Grid gridOver(std::span<const DirectedEdge> edges) {
    int64_t x0 = edges[0].a.x, x1 = x0, y0 = edges[0].a.y, y1 = y0;
    for (const DirectedEdge& e : edges)
        for (const IPoint& p : {e.a, e.b}) {
            x0 = std::min(x0, p.x);
            x1 = std::max(x1, p.x);
            y0 = std::min(y0, p.y);
            y1 = std::max(y1, p.y);
        }
    Grid g;
    g.x0 = x0;
    g.y0 = y0;
    g.size = std::max<int64_t>(1, (std::max(x1 - x0, y1 - y0) + kPartCells) / kPartCells);
    g.cols = int((x1 - x0) / g.size) + 1;
    g.rows = int((y1 - y0) / g.size) + 1;
    return g;
}

// x of the edge's line at height y (not horizontal).
double xAt(const DirectedEdge& e, double y) {
    return double(e.a.x) + (y - double(e.a.y)) * double(e.b.x - e.a.x) / double(e.b.y - e.a.y);
}

constexpr uint8_t kOutside = 0, kNearEdge = 1, kInside = 2;

// Marks every cell within one cell of a point of the edge: an unmarked cell holds no point of
// any edge with a cell to spare, so the winding number is the same all over it (rounding in the
// double arithmetic here is far below a cell).
void markNearEdge(const Grid& g, const DirectedEdge& e, std::vector<uint8_t>& cells) {
    const double ylo = double(std::min(e.a.y, e.b.y)), yhi = double(std::max(e.a.y, e.b.y));
    const double xlo = double(std::min(e.a.x, e.b.x)), xhi = double(std::max(e.a.x, e.b.x));
    for (int r = g.row(ylo); r <= g.row(yhi); ++r) {
        // The part of the edge inside row r's band.
        double b0 = std::max(ylo, double(g.y0 + r * g.size)), b1 = std::min(yhi, double(g.y0 + (r + 1) * g.size));
        double from = xlo, to = xhi;
        if (e.a.y != e.b.y) {
            double u = xAt(e, b0), v = xAt(e, b1);
            from = std::clamp(std::min(u, v), xlo, xhi);
            to = std::clamp(std::max(u, v), xlo, xhi);
        }
        int c0 = std::max(0, g.col(from) - 1), c1 = std::min(g.cols - 1, g.col(to) + 1);
        for (int rr = std::max(0, r - 1); rr <= std::min(g.rows - 1, r + 1); ++rr)
            std::fill(cells.begin() + ptrdiff_t(g.at(c0, rr)), cells.begin() + ptrdiff_t(g.at(c1, rr)) + 1, kNearEdge);
    }
}

struct Crossing {
    int row, col, delta;
};

// Marks the unmarked cells whose centre has a winding number other than 0. Row r's centre line
// is crossed by the edges with min y <= centre < max y; winding at an unmarked cell's centre is
// the sum of the crossings left of it (every crossing lies in a marked cell).
void markInside(const Grid& g, std::span<const DirectedEdge> edges, std::vector<uint8_t>& cells) {
    std::vector<Crossing> crossings;
    for (const DirectedEdge& e : edges) {
        if (e.a.y == e.b.y) continue;
        const int64_t lo = std::min(e.a.y, e.b.y), hi = std::max(e.a.y, e.b.y);
        const int delta = e.b.y > e.a.y ? e.weight : -e.weight;
        for (int r = g.row(double(lo)); r <= g.row(double(hi)); ++r) {
            // Twice the centre's y, so the test is exact in integers.
            int64_t centre2 = 2 * g.y0 + (2 * int64_t(r) + 1) * g.size;
            if (centre2 < 2 * lo || centre2 >= 2 * hi) continue;
            crossings.push_back({r, g.col(xAt(e, 0.5 * double(centre2))), delta});
        }
    }
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& p, const Crossing& q) { return std::tie(p.row, p.col) < std::tie(q.row, q.col); });
    size_t k = 0;
    for (int r = 0; r < g.rows; ++r) {
        int winding = 0;
        for (int c = 0; c < g.cols; ++c) {
            // Crossings in this cell lie right of its centre only if the cell is marked.
            int inCell = 0;
            while (k < crossings.size() && crossings[k].row == r && crossings[k].col == c) inCell += crossings[k++].delta;
            uint8_t& cell = cells[g.at(c, r)];
            if (cell == kOutside && winding != 0) cell = kInside;
            winding += inCell;
        }
    }
}

int findRoot(std::vector<int>& parent, int i) {
    while (parent[size_t(i)] != i) {
        parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
        i = parent[size_t(i)];
    }
    return i;
}

void join(std::vector<int>& parent, int i, int j) {
    i = findRoot(parent, i);
    j = findRoot(parent, j);
    if (i != j) parent[size_t(std::max(i, j))] = std::min(i, j);
}

}  // namespace

std::vector<std::vector<DirectedEdge>> separateShadowParts(std::span<const DirectedEdge> merged) {
    if (merged.empty()) return {};
    const Grid g = gridOver(merged);
    std::vector<uint8_t> cells(size_t(g.cols) * size_t(g.rows), kOutside);
    for (const DirectedEdge& e : merged) markNearEdge(g, e, cells);
    markInside(g, merged, cells);
    // Closed regions that touch only at a corner of two cells still meet: 8-connected.
    std::vector<int> parent(cells.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            if (cells[g.at(c, r)] == kOutside) continue;
            const int here = int(g.at(c, r));
            for (auto [dc, dr] : {std::pair{1, 0}, std::pair{-1, 1}, std::pair{0, 1}, std::pair{1, 1}}) {
                int nc = c + dc, nr = r + dr;
                if (nc < 0 || nc >= g.cols || nr >= g.rows || cells[g.at(nc, nr)] == kOutside) continue;
                join(parent, here, int(g.at(nc, nr)));
            }
        }
    std::vector<std::pair<int, DirectedEdge>> labelled;
    labelled.reserve(merged.size());
    for (const DirectedEdge& e : merged)
        labelled.emplace_back(findRoot(parent, int(g.at(g.col(double(e.a.x)), g.row(double(e.a.y))))), e);
    std::sort(labelled.begin(), labelled.end(), [](const auto& p, const auto& q) {
        return p.first != q.first ? p.first < q.first : edgeLess(p.second, q.second);
    });
    std::vector<std::vector<DirectedEdge>> parts;
    for (size_t i = 0; i < labelled.size(); ++i) {
        if (i == 0 || labelled[i].first != labelled[i - 1].first) parts.emplace_back();
        parts.back().push_back(labelled[i].second);
    }
    std::sort(parts.begin(), parts.end(),
              [](const auto& p, const auto& q) { return edgeLess(p.front(), q.front()); });
    return parts;
}

}  // namespace ss::planar
