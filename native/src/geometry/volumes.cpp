// How umbra quads, penumbra quads, penumbra fans and silhouette faces are built from silhouettes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/volumes.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace ss {

void ShadowVolumes::append(const ShadowVolumes& o) {
    umbra.insert(umbra.end(), o.umbra.begin(), o.umbra.end());
    penumbra.insert(penumbra.end(), o.penumbra.begin(), o.penumbra.end());
    umbraQuads += o.umbraQuads;
    penumbraQuads += o.penumbraQuads;
    fanTriangles += o.fanTriangles;
    silhouetteFaces += o.silhouetteFaces;
    trimmedCorners += o.trimmedCorners;
    multiEdgeCorners += o.multiEdgeCorners;
    openCornerEnds += o.openCornerEnds;
    insideDiskEdges += o.insideDiskEdges;
    parts.insert(parts.end(), o.parts.begin(), o.parts.end());
}

EdgeExtrusion edgeExtrusion(const glm::vec3& v1, const glm::vec3& v2, const glm::vec3& inward,
                            const Disk& disk) {
    EdgeExtrusion x;
    const glm::vec3& c = disk.centre;
    const glm::vec3& n = disk.normal;
    float r = disk.radius;
    glm::vec3 e = v2 - v1;
    if (!(r > 0.0f)) {  // a point light: both planes pass through the centre
        x.pUmbra = x.pPenumbra = c;
        return x;
    }
    glm::vec3 t1, t2;
    float en = glm::dot(e, n);
    glm::vec3 a(0.0f);
    float dist = 0.0f;
    bool useFrame = std::abs(en) <= 1e-6f * glm::length(e);
    if (!useFrame) {
        a = v1 + (glm::dot(c - v1, n) / en) * e;
        dist = glm::length(a - c);
        // Far beyond the disk the tangent points tend to those of the parallel case, and `a`
        // itself loses its float precision: switch over.
        if (dist > 1e4f * r) useFrame = true;
        if (dist <= r) {  // the line pierces the disk: no tangent plane exists
            x.insideDisk = true;
            useFrame = true;
        }
    }
    if (useFrame) {
        // Parallel case: the tangent planes touch the disk at the ends of its diameter that is
        // perpendicular to the edge (same construction for the inside-disk fallback).
        glm::vec3 m = glm::cross(n, e);
        float ml = glm::length(m);
        if (!(ml > 0.0f)) {  // the edge is along the disk normal: any diameter will do
            m = glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
            ml = glm::length(m);
        }
        m /= ml;
        t1 = c + r * m;
        t2 = c - r * m;
        x.parallel = !x.insideDisk;
    } else {
        glm::vec3 w = a - c;
        float d2 = dist * dist;
        glm::vec3 along = c + (r * r / d2) * w;
        glm::vec3 across = (r / d2) * std::sqrt(std::max(d2 - r * r, 0.0f)) * glm::cross(n, w);
        t1 = along + across;
        t2 = along - across;
    }
    // Same side of the plane through the edge and t1 for the disk centre and the occluder: t1 is
    // the umbra extrusion point.
    glm::vec3 plane = glm::cross(e, t1 - v1);
    float sc = glm::dot(plane, c - v1);
    float sb = glm::dot(plane, inward);
    if (sc * sb > 0.0f) {
        x.pUmbra = t1;
        x.pPenumbra = t2;
    } else {
        x.pUmbra = t2;
        x.pPenumbra = t1;
    }
    return x;
}

namespace {

uint32_t thirdVertex(const glm::uvec3& t, uint32_t a, uint32_t b) {
    for (int k = 0; k < 3; ++k)
        if (t[k] != a && t[k] != b) return t[k];
    return t[0];
}

// Direction from the edge into the occluder: the in-face directions of its face(s),
// perpendicular to the edge. For an open edge, just its face.
glm::vec3 inwardOf(const Mesh& mesh, const SilhouetteEdge& s) {
    glm::vec3 a = mesh.positions[s.a], b = mesh.positions[s.b];
    glm::vec3 e = glm::normalize(b - a);
    glm::vec3 mid = 0.5f * (a + b);
    glm::vec3 sum(0.0f);
    for (uint32_t f : {s.face, s.otherFace}) {
        if (f == kNoFace) continue;
        glm::vec3 d = mesh.positions[thirdVertex(mesh.triangles[f], s.a, s.b)] - mid;
        d -= glm::dot(d, e) * e;
        float l = glm::length(d);
        if (l > 0.0f) sum += d / l;
    }
    return sum;
}

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
    float l = glm::length(v);
    return l > 0.0f && std::isfinite(l) ? v / l : fallback;
}

struct Quad {
    uint32_t a, b;
    glm::vec3 p;             // extrusion point
    glm::vec3 dirA, dirB;    // far-end directions at a and b (trimmed or own)
};

void pushTriangle(std::vector<VolumeVertex>& out, const glm::vec3& p0, const glm::vec3& p1,
                  const glm::vec3& p2, const glm::vec3& ea, const glm::vec3& eb, const glm::vec3& ext,
                  VolumeKind kind = VolumeKind::Quad) {
    for (const glm::vec3& p : {p0, p1, p2}) out.push_back(VolumeVertex{p, ea, eb, ext, float(int(kind))});
}

// A quad from its edge (a, b) out to `length` along its far-end directions, as two triangles.
void pushQuad(std::vector<VolumeVertex>& out, const Mesh& mesh, const Quad& q, float length) {
    glm::vec3 a = mesh.positions[q.a], b = mesh.positions[q.b];
    glm::vec3 af = a + length * q.dirA, bf = b + length * q.dirB;
    pushTriangle(out, a, b, bf, a, b, q.p);
    pushTriangle(out, a, bf, af, a, b, q.p);
}

// Component of d perpendicular to the unit vector e.
glm::vec3 perp(const glm::vec3& d, const glm::vec3& e) { return d - glm::dot(d, e) * e; }

// Builds quads for one silhouette (umbra or penumbra), with their own extrusion directions.
std::vector<Quad> buildQuads(const Mesh& mesh, const std::vector<SilhouetteEdge>& edges,
                             const Disk& disk, bool umbra, size_t* insideDisk) {
    std::vector<Quad> quads;
    quads.reserve(edges.size());
    for (const SilhouetteEdge& s : edges) {
        glm::vec3 a = mesh.positions[s.a], b = mesh.positions[s.b];
        EdgeExtrusion x = edgeExtrusion(a, b, inwardOf(mesh, s), disk);
        if (x.insideDisk) ++*insideDisk;
        Quad q;
        q.a = s.a;
        q.b = s.b;
        q.p = umbra ? x.pUmbra : x.pPenumbra;
        glm::vec3 away = safeNormalize(0.5f * (a + b) - disk.centre, disk.normal);
        q.dirA = safeNormalize(a - q.p, away);
        q.dirB = safeNormalize(b - q.p, away);
        quads.push_back(q);
    }
    return quads;
}

// Cuts two umbra quads meeting at a vertex along the line where their planes intersect, so
// neither reaches past the other (the paper's trimming). When that line does not lie inside
// both quads' wedges, or the planes (nearly) coincide, both quads take the mean of their two
// directions instead (returns false): they still share the far vertex, so the side surface
// stays closed.
bool trimCorner(const Mesh& mesh, Quad& in, Quad& out, uint32_t v) {
    glm::vec3 pv = mesh.positions[v];
    glm::vec3 eIn = glm::normalize(mesh.positions[in.a] - pv);   // along the incoming edge
    glm::vec3 eOut = glm::normalize(mesh.positions[out.b] - pv);  // along the outgoing edge
    glm::vec3 dIn = in.dirB, dOut = out.dirA;
    glm::vec3 n1 = glm::cross(eIn, dIn), n2 = glm::cross(eOut, dOut);
    glm::vec3 line = glm::cross(n1, n2);
    float l = glm::length(line);
    glm::vec3 mean = safeNormalize(dIn + dOut, dIn);
    auto share = [&](const glm::vec3& d) {
        in.dirB = d;
        out.dirA = d;
    };
    if (!(l > 1e-3f * glm::length(n1) * glm::length(n2))) return share(mean), false;
    line /= l;
    if (glm::dot(line, dIn + dOut) < 0.0f) line = -line;
    // Inside each wedge: on the same side of the quad's edge as its own extrusion direction.
    if (glm::dot(perp(line, eIn), perp(dIn, eIn)) <= 0.0f ||
        glm::dot(perp(line, eOut), perp(dOut, eOut)) <= 0.0f)
        return share(mean), false;
    in.dirB = line;
    out.dirA = line;
    return true;
}

// The corners at one silhouette vertex: each quad that ends there (b == vertex) paired with the
// quad that starts there (a == vertex) and continues the same strand of the silhouette. At a
// simple vertex that is its only other edge. Where the silhouette passes through a vertex more
// than once (3+ edges: a saddle, a star's apex, two loops touching), the partner is the edge
// that bounds the same run of "upper" faces around the vertex: from the incoming edge's upper
// face, walk around the vertex across edges that are not silhouette edges (their two faces are
// in the same class) until a silhouette edge of this vertex is reached. Ends the walk cannot
// pair (non-manifold or open edges around the vertex) are paired by the nearest far-end
// direction; an end left over (an odd count) stays open and is counted.
struct Corner {
    uint32_t in, out;  // indices into the quad list
};

std::vector<Corner> cornersAt(const Mesh& mesh, const std::vector<SilhouetteEdge>& edges,
                              const std::vector<Quad>& quads, const SilhouetteVertex& sv,
                              size_t* unpaired) {
    std::vector<Corner> corners;
    std::vector<uint32_t> ins, outs;
    for (uint32_t i : sv.edges) {
        if (quads[i].b == sv.vertex) ins.push_back(i);
        else if (quads[i].a == sv.vertex) outs.push_back(i);
    }
    if (ins.size() == 1 && outs.size() == 1 && sv.edges.size() == 2) {
        corners.push_back({ins[0], outs[0]});
        return corners;
    }
    const auto& adj = mesh.adjacency;
    auto silhouetteAt = [&](uint32_t meshEdge) -> int {
        for (uint32_t i : sv.edges)
            if (edges[i].edge == meshEdge) return int(i);
        return -1;
    };
    std::vector<bool> outUsed(outs.size(), false);
    std::vector<uint32_t> leftIns;
    for (uint32_t in : ins) {
        uint32_t face = edges[in].face, from = edges[in].edge;
        int found = -1;
        for (size_t step = 0; face != kNoFace && step <= mesh.triangles.size() && step < 256; ++step) {
            uint32_t next = kNoFace;
            for (int k = 0; k < 3; ++k) {
                uint32_t e = adj.faceEdges[face][k];
                if (e != from && (adj.edges[e].v0 == sv.vertex || adj.edges[e].v1 == sv.vertex)) next = e;
            }
            if (next == kNoFace) break;
            int s = silhouetteAt(next);
            if (s >= 0) {
                found = s;
                break;
            }
            const Edge& e = adj.edges[next];
            if (!e.isManifold()) break;
            face = e.faces[0] == face ? e.faces[1] : e.faces[0];
            from = next;
        }
        size_t slot = outs.size();
        for (size_t k = 0; k < outs.size(); ++k)
            if (found >= 0 && outs[k] == uint32_t(found) && !outUsed[k]) slot = k;
        if (slot < outs.size()) {
            outUsed[slot] = true;
            corners.push_back({in, outs[slot]});
        } else {
            leftIns.push_back(in);
        }
    }
    for (uint32_t in : leftIns) {
        size_t best = outs.size();
        float bestDot = -2.0f;
        for (size_t k = 0; k < outs.size(); ++k) {
            float d = glm::dot(quads[in].dirB, quads[outs[k]].dirA);
            if (!outUsed[k] && d > bestDot) bestDot = d, best = k;
        }
        if (best == outs.size()) {
            ++*unpaired;
            continue;
        }
        outUsed[best] = true;
        corners.push_back({in, outs[best]});
    }
    for (bool used : outUsed) *unpaired += used ? 0 : 1;
    return corners;
}

// Angle of a rim point around the disk centre in the frame (u, w).
float rimAngle(const glm::vec3& p, const Disk& disk, const glm::vec3& u, const glm::vec3& w) {
    glm::vec3 d = p - disk.centre;
    return std::atan2(glm::dot(d, w), glm::dot(d, u));
}

}  // namespace

namespace {

// Umbra: quads, trimmed at every corner where two meet, plus silhouette faces.
void extrudeUmbra(const Mesh& mesh, const DiskSilhouette& sil, const Disk& disk, float length,
                  ShadowVolumes& vol) {
    std::vector<Quad> uq = buildQuads(mesh, sil.umbraEdges, disk, true, &vol.insideDiskEdges);
    for (const SilhouetteVertex& sv : sil.umbraVertices)
        for (const Corner& c : cornersAt(mesh, sil.umbraEdges, uq, sv, &vol.openCornerEnds)) {
            if (trimCorner(mesh, uq[c.in], uq[c.out], sv.vertex)) ++vol.trimmedCorners;
            if (sv.edges.size() > 2) ++vol.multiEdgeCorners;
        }
    for (const Quad& q : uq) pushQuad(vol.umbra, mesh, q, length);
    vol.umbraQuads += uq.size();
    // Silhouette faces of both kinds close the gap between the two silhouettes (§3.3). Their
    // "edge" for eq. 2 is the line through their vertex nearest to the light, parallel to the
    // light plane within the face (VolumeVertex): seen from a receiver in the hard shadow next to
    // a box, the edge that bounds the visible part of the light is the top edge of the side face.
    for (const auto* list : {&sil.silhouetteFacesCentreBack, &sil.silhouetteFacesCentreFront})
        for (uint32_t f : *list) {
            const glm::uvec3& t = mesh.triangles[f];
            glm::vec3 p0 = mesh.positions[t[0]], p1 = mesh.positions[t[1]], p2 = mesh.positions[t[2]];
            glm::vec3 near = p0;
            for (const glm::vec3& p : {p1, p2})
                if (glm::dot(p - disk.centre, disk.normal) < glm::dot(near - disk.centre, disk.normal))
                    near = p;
            glm::vec3 n = mesh.faceNormals[f];
            glm::vec3 along = safeNormalize(glm::cross(n, disk.normal), glm::vec3(1, 0, 0));
            pushTriangle(vol.umbra, p0, p1, p2, near, near + along, n, VolumeKind::SilhouetteFace);
            ++vol.silhouetteFaces;
        }
}

// A fan at silhouette vertex `pv` from the far edge of `in` to that of `out`: directions run
// along the shorter disk-rim arc from one quad's p_p to the next one's, at most `step` apart; the
// last far vertex is exactly `out`'s, so the side surface stays closed.
void pushFan(const glm::vec3& pv, const Quad& in, const Quad& out, const Disk& disk, float length,
             float step, ShadowVolumes& vol) {
    glm::vec3 u = glm::normalize(glm::cross(disk.normal, std::abs(disk.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    glm::vec3 w = glm::cross(disk.normal, u);
    float t0 = rimAngle(in.p, disk, u, w), t1 = rimAngle(out.p, disk, u, w);
    float span = t1 - t0;
    while (span > float(M_PI)) span -= 2.0f * float(M_PI);
    while (span < -float(M_PI)) span += 2.0f * float(M_PI);
    if (std::abs(span) < 1e-6f) return;
    int steps = std::max(1, int(std::ceil(std::abs(span) / step)));
    glm::vec3 prev = pv + length * in.dirB;
    for (int k = 1; k <= steps; ++k) {
        glm::vec3 next;
        if (k == steps) {
            next = pv + length * out.dirA;
        } else {
            float ang = t0 + span * float(k) / float(steps);
            glm::vec3 rim = disk.centre + disk.radius * (std::cos(ang) * u + std::sin(ang) * w);
            next = pv + length * safeNormalize(pv - rim, in.dirB);
        }
        pushTriangle(vol.penumbra, pv, prev, next, pv, pv, disk.centre, VolumeKind::Fan);
        ++vol.fanTriangles;
        prev = next;
    }
}

// Penumbra: quads with their own directions, closed by a fan at every corner.
void extrudePenumbra(const Mesh& mesh, const DiskSilhouette& sil, const Disk& disk, float length,
                     float fanStepRadians, ShadowVolumes& vol) {
    std::vector<Quad> pq = buildQuads(mesh, sil.penumbraEdges, disk, false, &vol.insideDiskEdges);
    for (const Quad& q : pq) pushQuad(vol.penumbra, mesh, q, length);
    vol.penumbraQuads += pq.size();
    if (!(disk.radius > 0.0f)) return;
    for (const SilhouetteVertex& sv : sil.penumbraVertices)
        for (const Corner& c : cornersAt(mesh, sil.penumbraEdges, pq, sv, &vol.openCornerEnds)) {
            if (sv.edges.size() > 2) ++vol.multiEdgeCorners;
            pushFan(mesh.positions[sv.vertex], pq[c.in], pq[c.out], disk, length, fanStepRadians, vol);
        }
}

}  // namespace

ShadowVolumes extrudeVolumes(const Mesh& mesh, const DiskSilhouette& sil, const Disk& disk,
                             float length, float fanStepRadians) {
    // The two volumes are independent: on large silhouettes build them on both cores.
    ShadowVolumes vol, pen;
    if (sil.umbraEdges.size() + sil.penumbraEdges.size() > 4000) {
        std::thread other([&] { extrudePenumbra(mesh, sil, disk, length, fanStepRadians, pen); });
        extrudeUmbra(mesh, sil, disk, length, vol);
        other.join();
    } else {
        extrudeUmbra(mesh, sil, disk, length, vol);
        extrudePenumbra(mesh, sil, disk, length, fanStepRadians, pen);
    }
    vol.append(pen);
    vol.parts = {{vol.umbra.size(), vol.penumbra.size()}};
    return vol;
}

}  // namespace ss
