// How trapezoids of the merged sweep get their intensities and become triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/penumbra_fill.h"

#include <algorithm>

namespace ss::planar {

namespace {

// A side of a region with count c facing count d across it: the inner ring (c+1) when d is
// larger, the region's own ring (c) when d is smaller. Seen from the count-c region, a ring of
// level k sits at (k-1)/(n-1), so a strip between rings c and c+1 spans both intensities and a
// bay (the same ring on both sides) is flat.
float sideIntensity(int c, int d, int n) {
    if (d > c) return ringIntensity(c + 1, n);
    return ringIntensity(c, n);
}

}  // namespace

ShadowMesh fillShadow(std::span<const SweepSegment> merged, int samples, FillMode mode) {
    ShadowMesh mesh;
    const int n = std::max(samples, 1);
    auto clampCount = [n](int c) { return std::clamp(c, 0, n); };
    std::vector<Trapezoid> traps = trapezoids(merged, [](int w) { return w >= 1; });
    std::vector<Triangle2> tris;
    for (const Trapezoid& t : traps) {
        int c = clampCount(t.winding);
        float bottom, top;
        if (mode == FillMode::Steps || n == 1) {
            bottom = top = float(c) / float(n);
        } else {
            bottom = sideIntensity(c, clampCount(t.windingBelow), n);
            top = sideIntensity(c, clampCount(t.windingAbove), n);
        }
        bool umbra = c >= n;
        double area = t.area();
        mesh.shadowArea += area;
        if (umbra) mesh.umbraArea += area;
        tris.clear();
        triangulate(t, &tris);
        for (const Triangle2& tri : tris) {
            for (int k = 0; k < 3; ++k) {
                // A vertex on the bottom side has the bottom's intensity. Which side a vertex is
                // on is known exactly from triangulate(): compare with the trapezoid's sides.
                bool onBottom = (tri.x[k] == t.x0 && tri.y[k] == t.yBottom0) ||
                                (tri.x[k] == t.x1 && tri.y[k] == t.yBottom1);
                mesh.indices.push_back(uint32_t(mesh.vertices.size()));
                mesh.vertices.push_back(ShadowVertex{tri.x[k], tri.y[k], onBottom ? bottom : top});
            }
            (umbra ? mesh.umbraTriangles : mesh.penumbraTriangles)++;
        }
    }
    return mesh;
}

}  // namespace ss::planar
