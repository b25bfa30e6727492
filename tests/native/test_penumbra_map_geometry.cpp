// Checks penumbra-map cones and sheets against hand-computed geometry and silhouette counts.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include "core/mesh.h"
#include "softshadow/softshadow.h"
#include "geometry/cones_sheets.h"
#include "geometry/silhouette.h"

namespace ss {
namespace {

// An axis-aligned box, faces wound counter-clockwise seen from outside.
Mesh box(glm::vec3 lo, glm::vec3 hi) {
    Mesh m;
    m.name = "box";
    for (int i = 0; i < 8; ++i)
        m.objectPositions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    m.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    m.finalize();
    return m;
}

// Light 2 units above the origin looking straight down, far plane at depth 10.
PenumbraLight overhead(float radius) {
    PenumbraLight l;
    l.centre = {0, 0, 2};
    l.axis = {0, 0, -1};
    l.radius = radius;
    l.nearDepth = 0.01f;
    l.farDepth = 10.0f;
    return l;
}

TEST(PenumbraMapGeometry, ConeRadiusMatchesSimilarTriangles) {
    PenumbraLight l = overhead(0.5f);
    // C_v = L_r (Z_far - Z_v) / Z_v = 0.5 * 8 / 2 = 2.
    EXPECT_FLOAT_EQ(coneRadius(l, 2.0f), 2.0f);
    // A vertex on the far plane has a point cone.
    EXPECT_FLOAT_EQ(coneRadius(l, 10.0f), 0.0f);
    EXPECT_FLOAT_EQ(coneRadius(overhead(0.0f), 2.0f), 0.0f);
}

TEST(PenumbraMapGeometry, ConeBaseIsACircleOnTheFarPlaneAroundTheVertexRay) {
    // A thin box whose top face is at z = 0 (depth 2) and spans [-1,1]^2.
    Mesh m = box({-1, -1, -0.5f}, {1, 1, 0});
    PenumbraLight l = overhead(0.5f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConeSheetSettings cs;
    cs.coneSegments = 12;
    ConesSheets g = buildConesSheets(m, sil, l, cs);
    ASSERT_EQ(g.cones(), sil.vertices.size());
    for (size_t i = 0; i < sil.vertices.size(); ++i) {
        int c = g.coneOfVertex[i];
        ASSERT_GE(c, 0);
        glm::vec3 v = m.objectPositions[sil.vertices[i].vertex];
        float zv = 2.0f - v.z;
        // Base centre: the vertex ray scaled to depth 10; radius by hand.
        glm::vec3 centre = l.centre + (v - l.centre) * (10.0f / zv);
        // Circumscribed about the true circle: its vertices at r / cos(pi / n).
        float radius = 0.5f * (10.0f - zv) / zv / std::cos(float(M_PI) / 12.0f);
        // A square's corner turns by 90 degrees: its cone is the quarter between the two sheets'
        // tangent points, widened by half a segment (30 degrees here) each side: 4 segments.
        uint32_t t0 = g.coneFirstTriangle[c];
        uint32_t t1 = size_t(c) + 1 < g.cones() ? g.coneFirstTriangle[c + 1] : g.sheetFirstTriangle[0];
        EXPECT_EQ(t1 - t0, 4u);
        for (uint32_t k = 0; k < t1 - t0; ++k) {
            const glm::uvec3& t = g.triangles[t0 + k];
            EXPECT_EQ(g.vertices[t[0]].position, v);
            for (int j = 1; j < 3; ++j) {
                const ConeSheetVertex& r = g.vertices[t[j]];
                EXPECT_NEAR(r.position.z, 2.0f - 10.0f, 1e-5f);
                EXPECT_NEAR(glm::length(r.position - centre), radius, 1e-4f * radius + 1e-5f);
                EXPECT_FLOAT_EQ(r.zv, zv);
            }
        }
    }
}

TEST(PenumbraMapGeometry, SheetCornersByHandForAnEdgeOfASquare) {
    // Top face at z = 0, light at (0,0,2): every silhouette vertex has depth 2.
    Mesh m = box({-1, -1, -0.5f}, {1, 1, 0});
    PenumbraLight l = overhead(0.25f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConesSheets g = buildConesSheets(m, sil, l);
    // The top face's four edges are the silhouette.
    ASSERT_EQ(sil.edges.size(), 4u);
    ASSERT_EQ(g.sheets(), 4u);
    for (size_t i = 0; i < sil.edges.size(); ++i) {
        int s = g.sheetOfEdge[i];
        ASSERT_GE(s, 0);
        const glm::uvec3& t = g.triangles[g.sheetFirstTriangle[s]];
        glm::vec3 p0 = g.vertices[t[0]].position, p1 = g.vertices[t[1]].position,
                  q1 = g.vertices[t[2]].position;
        // The edge end p0 = (x, y, 0) projects to 5 (x, y) at z = -8 and moves outward (away
        // from the square, along the edge's outward normal) by C = 0.25 * 8 / 2 = 1.
        glm::vec3 mid = 0.5f * (p0 + p1);
        glm::vec3 outward = std::abs(mid.x) > std::abs(mid.y) ? glm::vec3(glm::sign(mid.x), 0, 0)
                                                              : glm::vec3(0, glm::sign(mid.y), 0);
        glm::vec3 expectQ1 = glm::vec3(5.0f * p1.x, 5.0f * p1.y, -8.0f) + 1.0f * outward;
        EXPECT_NEAR(glm::length(q1 - expectQ1), 0.0f, 1e-4f)
            << "q1 = " << q1.x << "," << q1.y << "," << q1.z;
        EXPECT_FLOAT_EQ(g.vertices[t[0]].zv, 2.0f);
        EXPECT_FLOAT_EQ(g.vertices[t[2]].zv, 2.0f);
    }
}

// The angle between the normals of the sheet's two triangles.
float sheetTwist(const ConesSheets& g, const glm::uvec3& t1, const glm::uvec3& t2) {
    auto normal = [&](const glm::uvec3& t) {
        return glm::normalize(glm::cross(g.vertices[t[1]].position - g.vertices[t[0]].position,
                                         g.vertices[t[2]].position - g.vertices[t[0]].position));
    };
    return std::acos(std::clamp(glm::dot(normal(t1), normal(t2)), -1.0f, 1.0f));
}

Mesh shearedBox() {
    Mesh m = box({-1, -1, -0.5f}, {1, 1, 0});
    for (glm::vec3& p : m.objectPositions) p.z += 0.6f * p.x;  // depth now varies along x
    m.finalize();
    return m;
}

// The far-plane circle of the true cone at world point v (centre, radius).
struct FarCircle {
    glm::vec2 centre;
    float radius;
};
FarCircle farCircle(const PenumbraLight& l, const glm::vec3& v) {
    float z = lightDepth(l, v);
    glm::vec3 c = l.centre + (v - l.centre) * (l.farDepth / z);
    return {glm::vec2(c), coneRadius(l, z)};
}

TEST(PenumbraMapGeometry, TiltedEdgeSheetIsPlanarAndTangentToBothEndCones) {
    Mesh m = shearedBox();
    PenumbraLight l = overhead(0.5f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConesSheets g = buildConesSheets(m, sil, l);
    ASSERT_EQ(g.sheets(), sil.edges.size());
    size_t differentRadii = 0;
    for (size_t i = 0; i < sil.edges.size(); ++i) {
        int s = g.sheetOfEdge[i];
        ASSERT_GE(s, 0);
        const SilhouetteEdge& e = sil.edges[i];
        float za = 2.0f - m.objectPositions[e.a].z, zb = 2.0f - m.objectPositions[e.b].z;
        const glm::uvec3& t1 = g.triangles[g.sheetFirstTriangle[s]];
        const glm::uvec3& t2 = g.triangles[g.sheetFirstTriangle[s] + 1];
        // Vertices: edge end a, its far corner, edge end b, its far corner; Z_V per ruling.
        uint32_t first = t1[0];
        EXPECT_EQ(g.vertices[first].position, m.objectPositions[e.a]);
        EXPECT_EQ(g.vertices[first + 2].position, m.objectPositions[e.b]);
        EXPECT_FLOAT_EQ(g.vertices[first].zv, za);
        EXPECT_FLOAT_EQ(g.vertices[first + 1].zv, za);
        EXPECT_FLOAT_EQ(g.vertices[first + 2].zv, zb);
        EXPECT_FLOAT_EQ(g.vertices[first + 3].zv, zb);
        // One planar quad: the plane through the edge and one point of the light's disk.
        EXPECT_LT(sheetTwist(g, t1, t2), 1e-3f) << "depths " << za << " " << zb;
        // Its far edge is the two base circles' common tangent, both circles on its inner side.
        glm::vec2 qa(g.vertices[first + 1].position), qb(g.vertices[first + 3].position);
        FarCircle ca = farCircle(l, m.objectPositions[e.a]), cb = farCircle(l, m.objectPositions[e.b]);
        differentRadii += std::abs(ca.radius - cb.radius) > 0.5f;
        glm::vec2 dir = glm::normalize(qb - qa), normal(-dir.y, dir.x);
        float da = glm::dot(ca.centre - qa, normal), db = glm::dot(cb.centre - qa, normal);
        EXPECT_NEAR(std::abs(da), ca.radius, 1e-3f * (1.0f + ca.radius));
        EXPECT_NEAR(std::abs(db), cb.radius, 1e-3f * (1.0f + cb.radius));
        EXPECT_GT(da * db, 0.0f);
        EXPECT_NEAR(glm::length(qa - ca.centre), ca.radius, 1e-3f * (1.0f + ca.radius));
        EXPECT_NEAR(glm::length(qb - cb.centre), cb.radius, 1e-3f * (1.0f + cb.radius));
    }
    EXPECT_GE(differentRadii, 2u) << "the sheared box must tilt some edges";
}

// Triangles of the cones and sheets seen from the light centre, on the far plane.
struct FarTriangle {
    glm::vec2 a, b, c;
    bool contains(glm::vec2 p) const {
        auto cross = [](glm::vec2 u, glm::vec2 v) { return u.x * v.y - u.y * v.x; };
        float d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
        const float eps = 1e-5f;
        return (d1 >= -eps && d2 >= -eps && d3 >= -eps) || (d1 <= eps && d2 <= eps && d3 <= eps);
    }
};

// No sliver between a sheet and its cones: an edge whose ends lie at depths 1 and 4 under a
// wide light (far-plane cone radii 9 and 1.5). The penumbra's footprint on the outer side of
// the edge, as the light centre sees it, is the outer half of the convex hull of the two base
// circles; every sampled point of it must lie under a cone or the sheet. A sheet with each end
// pushed out by its own radius, perpendicular to the edge's image, leaves a wedge of that region
// uncovered here (378 samples); the test also counts the samples in that wedge, so it can tell.
TEST(PenumbraMapGeometry, NoSliverBetweenASheetAndItsConesWhenTheRadiiDiffer) {
    // One triangle, its long edge steep in depth: the silhouette is its three edges.
    Mesh m;
    m.name = "steep";
    m.objectPositions = {{-1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, -2.0f}, {0.0f, -1.5f, -0.5f}};
    m.triangles = {{0, 2, 1}};
    m.flags = SS_MESH_CAST;
    m.finalize();
    PenumbraLight l = overhead(1.0f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConesSheets g = buildConesSheets(m, sil, l, ConeSheetSettings{});
    std::vector<FarTriangle> tris;
    auto toFar = [&](glm::vec3 p) {
        float z = lightDepth(l, p);
        return glm::vec2(l.centre + (p - l.centre) * (l.farDepth / z));
    };
    for (const glm::uvec3& t : g.triangles)
        tris.push_back({toFar(g.vertices[t[0]].position), toFar(g.vertices[t[1]].position),
                        toFar(g.vertices[t[2]].position)});
    // The edge (0, 1): depths 1 and 4; the triangle's third vertex is on the -y side.
    size_t edge = sil.edges.size();
    for (size_t i = 0; i < sil.edges.size(); ++i) {
        const SilhouetteEdge& e = sil.edges[i];
        if ((e.a == 0 && e.b == 1) || (e.a == 1 && e.b == 0)) edge = i;
    }
    ASSERT_LT(edge, sil.edges.size());
    ASSERT_GE(g.sheetOfEdge[edge], 0);
    FarCircle A = farCircle(l, m.objectPositions[0]), B = farCircle(l, m.objectPositions[1]);
    ASSERT_NEAR(A.radius, 9.0f, 1e-4f);
    ASSERT_NEAR(B.radius, 1.5f, 1e-4f);
    glm::vec2 axis = glm::normalize(B.centre - A.centre), out(-axis.y, axis.x);
    if (out.y < 0.0f) out = -out;  // away from the triangle's third vertex
    const float D = glm::length(B.centre - A.centre);
    // The outer common tangent's normal n: n . (B - A) = rA - rB, on the outer side.
    const float cosT = (A.radius - B.radius) / D;
    const glm::vec2 n = cosT * axis + std::sqrt(1.0f - cosT * cosT) * out;
    size_t samples = 0, uncovered = 0, inOffsetWedge = 0;
    for (int i = 0; i <= 200; ++i)
        for (int j = 0; j <= 100; ++j) {
            // Points over a box around the hull's outer half, kept when inside it: on the outer
            // side of the centre line, inside the tangent line, within the hull's end caps.
            float along = -A.radius + (D + A.radius + B.radius) * float(i) / 200.0f;
            float across = A.radius * float(j) / 100.0f;
            glm::vec2 p = A.centre + along * axis + across * out;
            bool inA = glm::length(p - A.centre) < A.radius, inB = glm::length(p - B.centre) < B.radius;
            float tangent = glm::dot(p - A.centre, n) - A.radius;  // < 0 inside the tangent line
            // Between the two tangent points' rulings (the quad A, B, B + rB n, A + rA n).
            float sA = glm::dot(p - A.centre, glm::vec2(-n.y, n.x)), sB = glm::dot(p - B.centre, glm::vec2(-n.y, n.x));
            bool inQuad = tangent < 0.0f && sA * sB <= 0.0f;
            if (!(inA || inB || inQuad)) continue;
            // 1e-3 of the near radius inside the region: the boundary itself is float rounding.
            float margin = 1e-3f * A.radius;
            if (tangent > -margin || across < margin) continue;
            if ((inA && glm::length(p - A.centre) > A.radius - margin) && !inB && !inQuad) continue;
            ++samples;
            bool covered = false;
            for (const FarTriangle& t : tris) covered = covered || t.contains(p);
            uncovered += !covered;
            // The radius-offset sheet: A + rA out to B + rB out; the wedge beyond it, outside both circles.
            glm::vec2 oa = A.centre + A.radius * out, ob = B.centre + B.radius * out;
            glm::vec2 od = glm::normalize(ob - oa);
            bool beyondOffset = (od.x * (p - oa).y - od.y * (p - oa).x) > 0.0f;
            inOffsetWedge += !inA && !inB && beyondOffset;
        }
    std::printf("[penumbra_map] sliver check: %zu samples of the hull's outer half, %zu uncovered, "
                "%zu in the wedge a radius-offset sheet leaves open\n", samples, uncovered, inOffsetWedge);
    EXPECT_GT(samples, 5000u);
    EXPECT_GT(inOffsetWedge, 100u) << "the sampled region must include the radius-offset sheet's sliver";
    EXPECT_EQ(uncovered, 0u);
}

// An edge whose line passes through the light's disk has no tangent plane: its sheet passes
// through the disk's rim point nearest where the line meets the light's plane. Still one finite
// quad whose far corners lie on their cones' base circles.
TEST(PenumbraMapGeometry, EdgeAimedThroughTheLightStillGetsAFiniteSheet) {
    Mesh m;
    m.name = "aimed";
    // Edge (0, 1) lies on a line through (0.2, 0, 2), inside the light's 0.5 disk.
    m.objectPositions = {{0.3f, 0.0f, 1.0f}, {0.5f, 0.0f, -1.0f}, {1.0f, 0.8f, 0.0f}};
    m.triangles = {{0, 1, 2}};
    m.flags = SS_MESH_CAST;
    m.finalize();
    PenumbraLight l = overhead(0.5f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConesSheets g = buildConesSheets(m, sil, l);
    size_t checked = 0;
    for (size_t i = 0; i < sil.edges.size(); ++i) {
        const SilhouetteEdge& e = sil.edges[i];
        if (!((e.a == 0 && e.b == 1) || (e.a == 1 && e.b == 0))) continue;
        int s = g.sheetOfEdge[i];
        ASSERT_GE(s, 0);
        uint32_t first = g.triangles[g.sheetFirstTriangle[s]][0];
        for (int end = 0; end < 2; ++end) {
            const ConeSheetVertex& q = g.vertices[first + 2 * end + 1];
            ASSERT_TRUE(std::isfinite(q.position.x) && std::isfinite(q.position.y) && std::isfinite(q.position.z));
            FarCircle c = farCircle(l, g.vertices[first + 2 * end].position);
            EXPECT_NEAR(q.position.z, l.centre.z - l.farDepth, 1e-4f);
            EXPECT_NEAR(glm::length(glm::vec2(q.position) - c.centre), c.radius, 1e-3f * (1.0f + c.radius));
        }
        ++checked;
    }
    EXPECT_EQ(checked, 1u);
}

TEST(PenumbraMapGeometry, SheetsLieOutsideTheOccludersImage) {
    Mesh m = box({-1, -0.5f, -0.3f}, {0.7f, 1, 0.2f});
    PenumbraLight l = overhead(0.3f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConesSheets g = buildConesSheets(m, sil, l);
    // Project the box's centre to the far plane; every sheet's far corners are farther from it
    // than the far-plane images of their edge ends (the sheet points away from the box).
    glm::vec3 centre = 0.5f * (glm::vec3(-1, -0.5f, -0.3f) + glm::vec3(0.7f, 1, 0.2f));
    auto far = [&](glm::vec3 p) { return l.centre + (p - l.centre) * (10.0f / lightDepth(l, p)); };
    glm::vec3 cFar = far(centre);
    for (size_t s = 0; s < g.sheets(); ++s) {
        const glm::uvec3& t = g.triangles[g.sheetFirstTriangle[s]];
        glm::vec3 p0 = g.vertices[t[0]].position, q1 = g.vertices[t[2]].position,
                  p1 = g.vertices[t[1]].position;
        glm::vec3 edgeFar = 0.5f * (far(p0) + far(p1));
        EXPECT_GT(glm::dot(q1 - far(p1), edgeFar - cFar), 0.0f);
    }
}

TEST(PenumbraMapGeometry, VertexWithFourSilhouetteEdgesGetsOneCone) {
    // Two open triangles touching at one vertex (a bow tie): that vertex has 4 silhouette edges.
    Mesh m;
    m.name = "bowtie";
    m.objectPositions = {{0, 0, 0}, {1, 0.5f, 0}, {1, -0.5f, 0}, {-1, 0.5f, 0}, {-1, -0.5f, 0}};
    m.triangles = {{0, 2, 1}, {0, 3, 4}};
    m.flags = SS_MESH_CAST;
    m.finalize();
    PenumbraLight l = overhead(0.2f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ASSERT_EQ(sil.edges.size(), 6u);
    ConesSheets g = buildConesSheets(m, sil, l);
    size_t busiest = 0;
    for (const SilhouetteVertex& v : sil.vertices) busiest = std::max(busiest, v.edges.size());
    EXPECT_EQ(busiest, 4u);
    EXPECT_EQ(g.cones(), sil.vertices.size());
    EXPECT_EQ(g.cones(), 5u);
    EXPECT_EQ(g.sheets(), 6u);
    for (int c : g.coneOfVertex) EXPECT_GE(c, 0);
    for (int s : g.sheetOfEdge) EXPECT_GE(s, 0);
}

TEST(PenumbraMapGeometry, EverySilhouetteVertexOneConeEveryEdgeOneSheetOnAnIcosphere) {
    // A sphere-like closed mesh: build an octahedron and subdivide it twice.
    Mesh m;
    m.name = "sphere";
    m.objectPositions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int level = 0; level < 2; ++level) {
        std::vector<glm::uvec3> next;
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mids;
        auto mid = [&](uint32_t a, uint32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mids.find(key);
            if (it != mids.end()) return it->second;
            m.objectPositions.push_back(glm::normalize(m.objectPositions[a] + m.objectPositions[b]));
            return mids[key] = uint32_t(m.objectPositions.size() - 1);
        };
        for (const glm::uvec3& t : m.triangles) {
            uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
            next.insert(next.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
        }
        m.triangles = next;
    }
    for (glm::vec3& p : m.objectPositions) p = 0.5f * p + glm::vec3(0.1f, 0.2f, -1.0f);
    m.finalize();
    PenumbraLight l = overhead(0.3f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ASSERT_GT(sil.edges.size(), 8u);
    ConesSheets g = buildConesSheets(m, sil, l);
    EXPECT_EQ(g.cones(), sil.vertices.size());
    EXPECT_EQ(g.sheets(), sil.edges.size());
    // Distinct indices: no vertex or edge shares a cone or sheet.
    std::set<int> cones(g.coneOfVertex.begin(), g.coneOfVertex.end());
    std::set<int> sheets(g.sheetOfEdge.begin(), g.sheetOfEdge.end());
    EXPECT_EQ(cones.size(), g.cones());
    EXPECT_EQ(sheets.size(), g.sheets());
    for (const ConeSheetVertex& v : g.vertices) {
        EXPECT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y) &&
                    std::isfinite(v.position.z) && std::isfinite(v.zv));
    }
}

TEST(PenumbraMapGeometry, VerticesBehindTheLightGetNoCone) {
    Mesh m = box({-1, -1, 1.0f}, {1, 1, 3.0f});  // straddles the light's plane z = 2
    PenumbraLight l = overhead(0.3f);
    PointSilhouette sil = pointSilhouette(m, l.centre);
    ConesSheets g = buildConesSheets(m, sil, l);
    for (size_t i = 0; i < sil.vertices.size(); ++i) {
        float z = lightDepth(l, m.objectPositions[sil.vertices[i].vertex]);
        EXPECT_EQ(g.coneOfVertex[i] >= 0, z >= l.nearDepth) << "depth " << z;
    }
}

}  // namespace
}  // namespace ss
