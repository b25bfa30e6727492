// The camera G-buffer every GL method shares, kept until the camera or the geometry changes
// (patched after moves alone), drawn from the triangles that may cover a pixel centre; and its
// read-back to the CPU.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/framebuffer.h"
#include "gl/objects.h"
#include "scene_cache/covering_triangles.h"
#include "scene_cache/mesh_draws.h"
#include "scene_cache/moved_region.h"

namespace ss {

// The camera G-buffer: camera resolution, drawn with the scene camera's own matrices, so GL
// fragment (x, y) is contract pixel (x, height-1-y); read-backs flip to row 0 = top.
// In shaders read it with texelFetch(tex, ivec2(gl_FragCoord.xy), 0) from a full-screen pass at
// camera resolution, or include "common/camera_gbuffer.glsl" and call SceneCache::bindCameraPass().
struct CameraPass {
    int width = 0, height = 0;
    // colour 0 RGBA32F: world position xyz at the pixel centre; w = view depth (distance along
    //                   the camera axis, > 0) where a surface is seen, 0 where none is.
    // colour 1 RGBA32F: unit geometric (face) normal turned to face the camera; w = 1 when the
    //                   surface's mesh has SS_MESH_RECEIVE, else 0.
    // colour 2 RG32F:   x = mesh index, y = triangle index within the mesh (-1, -1 background).
    // depth DEPTH_COMPONENT32F: window depth; attach it to a camera-resolution framebuffer for
    //                   depth-tested passes (with depth writes off).
    gl::Framebuffer framebuffer;
    GLuint positionDepth() const { return framebuffer.colorId(0); }
    GLuint normalReceive() const { return framebuffer.colorId(1); }
    GLuint ids() const { return framebuffer.colorId(2); }
    GLuint depth() const { return framebuffer.depth().id(); }
};

// The camera pass on the CPU, row 0 = top (index y * width + x).
struct CameraImages {
    int width = 0, height = 0;
    std::vector<glm::vec4> positionDepth, normalReceive, ids;
    size_t index(int x, int y) const { return size_t(y) * width + x; }
    bool covered(int x, int y) const { return positionDepth[index(x, y)].w > 0.0f; }
    bool receives(int x, int y) const { return normalReceive[index(x, y)].w > 0.5f; }
    glm::vec3 position(int x, int y) const { return glm::vec3(positionDepth[index(x, y)]); }
    glm::vec3 normal(int x, int y) const { return glm::vec3(normalReceive[index(x, y)]); }
};

// Which triangles the camera pass hands to GL. EachTriangle: those a CPU test finds may cover a
// pixel centre (CoveringTriangles): on llvmpipe every triangle handed to a draw costs about
// 0.1 µs, several times the test. Clusters: every triangle of the clusters that reach the redrawn
// rectangle: a GPU draws 1M triangles in about a millisecond, less than the test takes. Auto (the
// default): EachTriangle when GL_RENDERER names llvmpipe (whose sub-pixel snapping, 1/256 pixel,
// the test's margins are made for), else Clusters. The pass is the same bit for bit either way.
enum class CameraCulling { Auto, EachTriangle, Clusters };

// One scene's camera pass, its read-back and the receivers it sees.
class CameraPassCache {
public:
    void setCulling(CameraCulling culling) { culling_ = culling; }
    // Drops the pass when the camera changed, and the read-back when the geometry did too (the
    // pass itself is patched at its next use).
    void dropStale(const Scene& scene);
    // The pass as draws.scene is now: kept, redrawn only where moved meshes were and are (after
    // moves alone), or drawn whole.
    const CameraPass& get(const MeshDraws& draws);
    // The pass read back (on first call after it was drawn).
    const CameraImages& images(const MeshDraws& draws);
    // The world bounds of the receiving surfaces the pass sees (read back a band of rows at a
    // time; empty when none), kept with the pass (receivers_in_view.cpp).
    const Bounds& receiversInView(const MeshDraws& draws);
    // Drops the read-back when it holds more than `keepBytes`.
    void trimImages(size_t keepBytes);

private:
    // Draws the pass into its own targets, inside `rect` only when one is given: only the
    // triangles that may cover a pixel centre of the rectangle (listCoveringTriangles), fetched
    // by camera/gbuffer.vert.glsl.
    void draw(CameraPass& pass, const std::optional<PixelRect>& rect, const MeshDraws& draws);
    // Lists, per mesh in draws.meshes order, the triangles of its clusters that reach `rect` that
    // may cover one of its pixel centres: listed_[0] then listed_[1] (two threads list a half
    // each), and listedRanges_ gives each mesh's run in that sequence.
    void listCoveringTriangles(const Camera& camera, const PixelRect& rect, const MeshDraws& draws);
    std::unique_ptr<CameraPass> pass_;
    std::unique_ptr<CameraImages> images_;
    std::optional<Bounds> receiversInView_;        // of the pass as drawn, null until asked
    uint64_t camera_ = 0, geometry_ = 0;           // the versions the pass shows
    std::vector<MeshPlacement> placements_;        // what the pass shows
    CameraCulling culling_ = CameraCulling::Auto;  // Auto until the first pass resolves it
    CoveringTriangles coverage_[2];
    std::vector<uint32_t> listed_[2];                      // triangle indices, mesh after mesh
    std::vector<std::pair<size_t, size_t>> listedRanges_;  // per mesh: first, count in listed_
    gl::BufferHandle listedBuffer_;
    size_t listedCapacity_ = 0;  // uint32 entries listedBuffer_ holds
};

}  // namespace ss
