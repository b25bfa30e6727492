// Where occlusion_textures cuts the scene: the kernel light, the offset slicing camera fitted to it.
// SPDX-License-Identifier: GPL-3.0-or-later
// The slice planes, and where a shaded point looks up each slice (CPU side, mirrored in GLSL).
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "core/light.h"
#include "core/scene.h"

namespace ss::occlusion {

// The rectangle the method integrates over (paper: a rectangular light). Other shapes become
// the equal-area rectangle with the same axes and aspect (see kernelLight()).
struct KernelLight {
    glm::vec3 centre{0.0f};
    glm::vec3 axisX{1, 0, 0}, axisY{0, 1, 0};  // unit, in the light's plane
    glm::vec3 normal{0, 0, -1};                 // unit, towards the scene
    float halfX = 0.5f, halfY = 0.5f;           // half sizes of the rectangle along the axes
    glm::vec3 toLocal(const glm::vec3& world) const;  // (along axisX, along axisY, depth)
    bool operator==(const KernelLight&) const = default;
};

// Disk/ellipse: equal-area rectangle (half sizes x sqrt(pi)/2). Point/spot: the sphere's disk
// facing the scene centre (spot: its axis), then as a disk. Sun: a square far away
// (10 scene diagonals) whose size subtends the sun's angle, equal area with its disk.
KernelLight kernelLight(const Light& light, const Bounds& sceneBounds);

enum class Fade {
    Below,  // a slice fades in while the point crosses the next slice (default: no self-shadow)
    Paper   // the slice containing the point fades in towards its lower plane (paper, Sec. 3.4)
};

enum class Projection {
    Perspective,  // the paper's: centre of projection d behind the light, frustum fitted to it
    Orthographic  // along the light's normal over the whole scene (the paper's figure 4, left)
};

struct SliceSetup {
    KernelLight light;
    Projection projection = Projection::Perspective;
    float d = 1.0f;              // centre of projection sits d behind the light, on its normal
    glm::vec2 orthoHalf{1.0f};   // orthographic: the half sizes (light axes) the textures cover
    std::vector<float> planes;   // count + 1 depths below the light plane, increasing
    int width = 256, height = 256;  // occlusion texture size (aspect of the light)
    glm::mat4 worldToClip{1.0f};    // the slicing camera (COP) for the slicing pass
    float receiverDepthMax = 0.0f;  // the deepest receiving vertex in front of the light
    int lightIndex = -1;  // the scene light whose blockers are sliced (-1: every casting mesh)
    // Casting meshes left out of the slices (sorted mesh indices): planes not parallel to the
    // light that cannot shadow anything, every other caster and receiver and the light's
    // rectangle lying on their lit side (a ground under a tilted light). Such a plane spans the
    // whole depth range, so slicing it would spread the slices over the ground instead of the
    // occluders (and flatten each occluder onto one far plane).
    std::vector<int> unsliced;
    bool sliced(int mesh) const;
    int count() const { return int(planes.size()) - 1; }
    bool operator==(const SliceSetup&) const = default;
    // Slice holding depth z (clamped to the range).
    int sliceOf(float z) const;
    // Normalised device units per world unit along the light's axes, in the plane at `depth`.
    glm::vec2 ndcPerUnit(float depth) const;
};

// Fits the slicing camera: d so that every casting or receiving vertex in front of the light is
// inside the frustum (half-angle capped at 80 degrees), slices spread uniformly in depth over
// the sliced casters' depth range (SliceSetup::unsliced left out). Orthographic: the textures cover every casting or receiving vertex
// in front of the light (and the light), with the light's aspect. Throws ss::Error when no
// geometry lies in front of the light. With `lightIndex`, the casters and receivers are that
// light's (Scene::castsFor, Scene::receivesFrom: its light and shadow linking).
SliceSetup fitSlices(const Scene& scene, const KernelLight& light, int sliceCount, int resolution,
                     Projection projection = Projection::Perspective, int lightIndex = -1);

// How a point (light-local) reads slice k: texture centre (uv in [0, 1]), kernel size in
// texels (w, h) and the slice's weight (0: not used).
struct SliceLookup {
    glm::vec2 uv{0.0f};
    glm::vec2 kernelTexels{0.0f};
    float weight = 0.0f;
};
SliceLookup lookupSlice(const SliceSetup& setup, const glm::vec3& local, int k, Fade fade);

// Where a light-local point lands in the occlusion textures when sliced (uv in [0, 1]).
glm::vec2 sliceUv(const SliceSetup& setup, const glm::vec3& local);

}  // namespace ss::occlusion
