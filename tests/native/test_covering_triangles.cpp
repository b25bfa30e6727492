// Does the camera pass's triangle test leave out only triangles that cover no pixel centre of the
// rectangle, and does it leave out most of a dense mesh's sub-pixel triangles?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/camera.h"
#include "scene_cache/covering_triangles.h"

namespace ss {
namespace {

// Whether the triangle, projected in double precision with each vertex free to move by `slack`
// pixels, may contain a pixel centre of `rect` (edges included, either orientation).
bool mayCoverCentre(const CoverageView& view, const glm::vec3 (&corners)[3], double slack) {
    glm::dmat4 toClip = glm::dmat4(view.worldToClip);
    if (view.transformed) toClip = toClip * glm::dmat4(view.objectToWorld);
    glm::dvec2 p[3];
    for (int k = 0; k < 3; ++k) {
        const glm::dvec4 c = toClip * glm::dvec4(glm::dvec3(corners[k]), 1.0);
        if (!(c.w > 0.0)) return true;  // reaches behind the eye: not checked here
        p[k] = glm::dvec2((c.x / c.w + 1.0) * 0.5 * view.width, (c.y / c.w + 1.0) * 0.5 * view.height);
    }
    const glm::dvec2 lo = glm::min(p[0], glm::min(p[1], p[2])) - slack, hi = glm::max(p[0], glm::max(p[1], p[2])) + slack;
    const PixelRect& r = view.rect;
    // Centres within the grown bounding box (the moved triangle stays inside it).
    for (int y = std::max(int(std::ceil(lo.y - 0.5)), r.y0); y <= std::min(int(std::floor(hi.y - 0.5)), r.y1 - 1); ++y)
        for (int x = std::max(int(std::ceil(lo.x - 0.5)), r.x0); x <= std::min(int(std::floor(hi.x - 0.5)), r.x1 - 1); ++x) {
            const glm::dvec2 q(x + 0.5, y + 0.5);
            bool allIn = true, allOut = true;  // signed distances within slack of each edge
            for (int k = 0; k < 3; ++k) {
                const glm::dvec2 a = p[k], b = p[(k + 1) % 3];
                const glm::dvec2 e = b - a;
                const double len = glm::length(e);
                const double cross = e.x * (q.y - a.y) - e.y * (q.x - a.x);
                const double margin = slack * (len + 2.0 * glm::length(q - a)) + 4.0 * slack * slack;
                allIn = allIn && cross >= -margin;
                allOut = allOut && cross <= margin;
            }
            if (allIn || allOut) return true;
        }
    return false;
}

struct RandomTriangles {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
};

// Tiny triangles scattered in a box around the origin: sub-pixel ones, a few pixels wide, slivers
// and degenerate (collinear) ones, every one with its own three vertices.
RandomTriangles scatter(uint32_t seed, int count, float spread, float size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    RandomTriangles out;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 c(unit(rng) * spread, unit(rng) * spread, unit(rng) * spread * 0.3f);
        const float s = size * (0.05f + 0.95f * std::abs(unit(rng)));
        glm::vec3 a = c + s * glm::vec3(unit(rng), unit(rng), unit(rng));
        glm::vec3 b = c + s * glm::vec3(unit(rng), unit(rng), unit(rng));
        glm::vec3 d = c + s * glm::vec3(unit(rng), unit(rng), unit(rng));
        switch (i % 4) {
            case 1: d = a + (b - a) * 1e-3f + glm::vec3(0.0f, 0.0f, s * 1e-3f); break;  // sliver
            case 2: d = a + (b - a) * 0.37f; break;                                  // collinear
            default: break;
        }
        const uint32_t v = uint32_t(out.positions.size());
        out.positions.insert(out.positions.end(), {a, b, d});
        out.triangles.emplace_back(v, v + 1, v + 2);
    }
    return out;
}

// Lists the triangles of `tris` for `view`; checks that every one left out covers no centre
// even with its vertices moved by 1/256 pixel (the GPU's sub-pixel snapping is half that), and
// returns how many were listed.
size_t checkConservative(const CoverageView& view, const RandomTriangles& tris) {
    CoveringTriangles coverage;
    std::vector<uint32_t> listed;
    coverage.beginMesh(view, tris.positions);
    coverage.append(tris.triangles, 0, uint32_t(tris.triangles.size()), listed);
    std::vector<bool> kept(tris.triangles.size(), false);
    for (size_t i = 0; i < listed.size(); ++i) {
        if (i > 0) {
            EXPECT_LT(listed[i - 1], listed[i]) << "listed in order";
        }
        kept[listed[i]] = true;
    }
    int wrong = 0;
    for (size_t t = 0; t < tris.triangles.size(); ++t) {
        if (kept[t]) continue;
        const glm::uvec3& tri = tris.triangles[t];
        const glm::vec3 corners[3] = {tris.positions[tri.x], tris.positions[tri.y], tris.positions[tri.z]};
        if (mayCoverCentre(view, corners, 1.0 / 256.0) && ++wrong <= 5) {
            ADD_FAILURE() << "triangle " << t << " was left out but may cover a pixel centre";
        }
    }
    EXPECT_EQ(wrong, 0);
    return listed.size();
}

TEST(CoveringTriangles, LeavesOutOnlyTrianglesThatCoverNoPixelCentre) {
    const Camera cam = makeLookAtCamera({0.3f, -4.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, 1}, glm::radians(40.0f), 64, 48,
                                        0.1f, 100.0f);
    const RandomTriangles tris = scatter(7, 200000, 1.6f, 0.04f);
    CoverageView view{cam.worldToClip(), false, glm::mat4(1.0f), cam.width, cam.height, PixelRect{0, 0, 64, 48}};
    const size_t whole = checkConservative(view, tris);
    // Triangles of about a pixel or less: most cover no centre and are left out.
    std::printf("listed %zu of %zu triangles\n", whole, tris.triangles.size());
    EXPECT_LT(whole, tris.triangles.size() / 2);
    EXPECT_GT(whole, tris.triangles.size() / 50);

    // A rectangle of the pass (a tenth of it, where the triangles are densest): only triangles
    // that may cover one of its centres.
    view.rect = PixelRect{20, 10, 37, 29};
    EXPECT_LT(checkConservative(view, tris), whole / 2);

    // The same triangles placed by a matrix: moved 50 away and back, then 5000 away and back
    // (large terms that cancel: the GPU's rounding is larger, so is the margin).
    for (float offset : {50.0f, 5000.0f}) {
        const glm::mat4 away = glm::translate(glm::mat4(1.0f), glm::vec3(offset, -0.6f * offset, 0.04f * offset));
        RandomTriangles moved = tris;
        for (glm::vec3& p : moved.positions) p = glm::vec3(away * glm::vec4(p, 1.0f));
        const CoverageView placed{cam.worldToClip(), true, glm::inverse(away), cam.width, cam.height, PixelRect{0, 0, 64, 48}};
        const size_t listed = checkConservative(placed, moved);
        std::printf("placed %g away: listed %zu\n", offset, listed);
        if (offset < 100.0f) EXPECT_LT(listed, tris.triangles.size() / 2);
    }
}

TEST(CoveringTriangles, KeepsWhatTheNearPlaneClipsAndDropsWhatIsBehindTheEye) {
    const Camera cam = makeLookAtCamera({0.0f, 0.0f, 1.0f}, {0.0f, 10.0f, 1.0f}, {0, 0, 1}, glm::radians(50.0f), 32, 24,
                                        0.5f, 100.0f);
    const CoverageView view{cam.worldToClip(), false, glm::mat4(1.0f), cam.width, cam.height, PixelRect{0, 0, 32, 24}};
    // Ground triangles: one crossing the near plane and the eye's side plane, one wholly behind
    // the eye, one ahead beside the view, one far ahead in view.
    const std::vector<glm::vec3> positions = {
        {-3.0f, -1.0f, 0.0f}, {3.0f, -1.0f, 0.0f}, {0.0f, 8.0f, 0.0f},       // crosses the near plane
        {-3.0f, -6.0f, 0.0f}, {3.0f, -6.0f, 0.0f}, {0.0f, -3.0f, 0.0f},      // behind
        {40.0f, 5.0f, 0.0f}, {45.0f, 5.0f, 0.0f}, {42.0f, 8.0f, 0.0f},       // beside
        {-5.0f, 6.0f, 0.0f}, {5.0f, 6.0f, 0.0f}, {0.0f, 12.0f, 0.0f},        // ahead
    };
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}};
    CoveringTriangles coverage;
    std::vector<uint32_t> listed;
    coverage.beginMesh(view, positions);
    coverage.append(triangles, 0, 4, listed);
    EXPECT_EQ(listed, (std::vector<uint32_t>{0, 3}));
}

}  // namespace
}  // namespace ss
