// How the scene file's primitive shapes are built as triangle meshes: closed, consistently
// outward-oriented manifolds (plane and disk are open sheets facing +Z).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace ss {

struct TriangleSoup {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
};

// All centred on the origin; Blender's default sizes are the documented defaults.
TriangleSoup makePlane(float sizeX, float sizeY, int subdivisions);           // z = 0, faces +Z
TriangleSoup makeBox(const glm::vec3& size, int subdivisions);                // closed
TriangleSoup makeUvSphere(float radius, int segments, int rings);             // closed
TriangleSoup makeDisk(float radius, int segments);                            // z = 0, faces +Z
TriangleSoup makeTorus(float majorRadius, float minorRadius, int majorSegments,
                       int minorSegments);                                    // closed, around Z
TriangleSoup makeCylinder(float radius, float depth, int segments);           // closed, axis Z

// Signed volume (positive when a closed mesh is oriented outward).
double signedVolume(const TriangleSoup& soup);

}  // namespace ss
