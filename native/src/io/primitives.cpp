// How plane, box, UV sphere, disk, torus and cylinder meshes are generated.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/primitives.h"

#include <cmath>
#include <map>
#include <tuple>

namespace ss {

namespace {
constexpr float kTwoPi = 6.28318530717958647692f;

// Triangles of the quad a-b-c-d given counter-clockwise as seen from its front.
void addQuad(TriangleSoup& s, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
}

uint32_t addVertex(TriangleSoup& s, const glm::vec3& p) {
    s.positions.push_back(p);
    return uint32_t(s.positions.size() - 1);
}
}  // namespace

TriangleSoup makePlane(float sizeX, float sizeY, int subdivisions) {
    TriangleSoup s;
    int n = std::max(1, subdivisions);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            addVertex(s, {(float(i) / n - 0.5f) * sizeX, (float(j) / n - 0.5f) * sizeY, 0.0f});
    auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) addQuad(s, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    return s;
}

TriangleSoup makeBox(const glm::vec3& size, int subdivisions) {
    TriangleSoup s;
    int n = std::max(1, subdivisions);
    // Surface vertices are keyed by their integer lattice point, so faces share their edges
    // exactly and the box is one closed manifold.
    std::map<std::tuple<int, int, int>, uint32_t> ids;
    auto id = [&](int x, int y, int z) {
        auto [it, inserted] = ids.emplace(std::make_tuple(x, y, z), 0u);
        if (inserted)
            it->second = addVertex(s, {(float(x) / n - 0.5f) * size.x, (float(y) / n - 0.5f) * size.y,
                                       (float(z) / n - 0.5f) * size.z});
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis) {
        int ua = (axis + 1) % 3, va = (axis + 2) % 3;  // e_u x e_v = +e_axis
        for (int side : {0, n}) {
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    uint32_t corner[4];
                    int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                    for (int k = 0; k < 4; ++k) {
                        int p[3];
                        p[axis] = side;
                        p[ua] = i + du[k];
                        p[va] = j + dv[k];
                        corner[k] = id(p[0], p[1], p[2]);
                    }
                    if (side == n) addQuad(s, corner[0], corner[1], corner[2], corner[3]);
                    else addQuad(s, corner[0], corner[3], corner[2], corner[1]);
                }
        }
    }
    return s;
}

TriangleSoup makeUvSphere(float radius, int segments, int rings) {
    TriangleSoup s;
    int S = std::max(3, segments), R = std::max(2, rings);
    uint32_t top = addVertex(s, {0, 0, radius});
    for (int r = 1; r < R; ++r) {
        float theta = float(M_PI) * float(r) / float(R);  // from the north pole
        for (int k = 0; k < S; ++k) {
            float phi = kTwoPi * float(k) / float(S);
            addVertex(s, {radius * std::sin(theta) * std::cos(phi), radius * std::sin(theta) * std::sin(phi),
                          radius * std::cos(theta)});
        }
    }
    uint32_t bottom = addVertex(s, {0, 0, -radius});
    auto id = [&](int r, int k) { return uint32_t(1 + (r - 1) * S + (k % S)); };
    for (int k = 0; k < S; ++k) {
        s.triangles.push_back({top, id(1, k), id(1, k + 1)});
        for (int r = 1; r < R - 1; ++r) addQuad(s, id(r, k), id(r + 1, k), id(r + 1, k + 1), id(r, k + 1));
        s.triangles.push_back({bottom, id(R - 1, k + 1), id(R - 1, k)});
    }
    return s;
}

TriangleSoup makeDisk(float radius, int segments) {
    TriangleSoup s;
    int S = std::max(3, segments);
    uint32_t centre = addVertex(s, {0, 0, 0});
    for (int k = 0; k < S; ++k) {
        float phi = kTwoPi * float(k) / float(S);
        addVertex(s, {radius * std::cos(phi), radius * std::sin(phi), 0.0f});
    }
    for (int k = 0; k < S; ++k) s.triangles.push_back({centre, uint32_t(1 + k), uint32_t(1 + (k + 1) % S)});
    return s;
}

TriangleSoup makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments) {
    TriangleSoup s;
    int U = std::max(3, majorSegments), V = std::max(3, minorSegments);
    for (int i = 0; i < U; ++i) {
        float u = kTwoPi * float(i) / float(U);
        for (int j = 0; j < V; ++j) {
            float v = kTwoPi * float(j) / float(V);
            float ring = majorRadius + minorRadius * std::cos(v);
            addVertex(s, {ring * std::cos(u), ring * std::sin(u), minorRadius * std::sin(v)});
        }
    }
    auto id = [&](int i, int j) { return uint32_t((i % U) * V + (j % V)); };
    // d/du x d/dv points outward from the tube for this parameterisation.
    for (int i = 0; i < U; ++i)
        for (int j = 0; j < V; ++j) addQuad(s, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    return s;
}

TriangleSoup makeCylinder(float radius, float depth, int segments) {
    TriangleSoup s;
    int S = std::max(3, segments);
    float h = 0.5f * depth;
    for (int k = 0; k < S; ++k) {
        float phi = kTwoPi * float(k) / float(S);
        addVertex(s, {radius * std::cos(phi), radius * std::sin(phi), -h});
        addVertex(s, {radius * std::cos(phi), radius * std::sin(phi), h});
    }
    uint32_t bottom = addVertex(s, {0, 0, -h});
    uint32_t top = addVertex(s, {0, 0, h});
    auto lo = [&](int k) { return uint32_t(2 * (k % S)); };
    auto hi = [&](int k) { return uint32_t(2 * (k % S) + 1); };
    for (int k = 0; k < S; ++k) {
        addQuad(s, lo(k), lo(k + 1), hi(k + 1), hi(k));
        s.triangles.push_back({top, hi(k), hi(k + 1)});
        s.triangles.push_back({bottom, lo(k + 1), lo(k)});
    }
    return s;
}

double signedVolume(const TriangleSoup& soup) {
    double v = 0.0;
    for (const glm::uvec3& t : soup.triangles) {
        glm::dvec3 a(soup.positions[t[0]]), b(soup.positions[t[1]]), c(soup.positions[t[2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

}  // namespace ss
