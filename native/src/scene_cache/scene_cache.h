// What every method shares for one scene: the scene, GL meshes, the camera G-buffer, one
// light-centre shadow map per light and the Embree BVH, each computed once and kept while what
// it depends on is unchanged (per-mesh, per-light, camera and geometry versions of the Scene).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "scene_cache/cache_counters.h"
#include "scene_cache/covering_triangles.h"
#include "scene_cache/moved_region.h"
#include "scene_cache/see_through.h"
#include "gl/framebuffer.h"
#include "gl/gl_functions.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "reference/trace_scene_cache.h"

namespace ss {

// One scene mesh on the GPU, in its object space (the coordinates as given) with its matrix: a
// moved mesh keeps its buffers. Vertex attribute 0 = object position (vec3); indexed triangles.
// Vertex shaders take world = uObjectToWorld * position where uTransformed is 1 and the position
// itself where it is 0 (so meshes without a transform draw exactly their world coordinates);
// face normals go to world space with mat3(uNormalToWorld) (see "common/mesh.vert.glsl").
struct GpuMesh {
    int meshIndex = 0;  // into scene.meshes()
    uint64_t shapeVersion = 0;  // the Mesh::shapeVersion these buffers hold
    uint32_t flags = 0;
    GLsizei indexCount = 0;
    bool transformed = false;           // objectToWorld is not the identity
    glm::mat4 objectToWorld{1.0f};      // the mesh's current placement
    glm::mat4 normalToWorld{1.0f};      // inverse transpose of its 3x3 part
    gl::VertexArrayHandle vao;
    gl::BufferHandle positions;    // vec3 per vertex, object space
    gl::BufferHandle indices;      // uint32 x3 per triangle
    gl::BufferHandle faceNormals;  // SSBO, vec4 per triangle (xyz unit in object space, 0 for degenerate)
    // Runs of consecutive triangles (kClusterTriangles each, the last fewer) with their bounds in
    // object space: a patch of a pass draws only the runs that reach its rectangle, so a small
    // object moved beside a large mesh does not redraw all of it (the camera pass, whole or
    // patched, tests the triangles of those runs only).
    struct Cluster {
        uint32_t firstTriangle = 0, triangleCount = 0;
        Bounds bounds;
    };
    static constexpr uint32_t kClusterTriangles = 1024;
    std::vector<Cluster> clusters;
    // Its materials where the mesh lets light through (Mesh::alpha), else null.
    std::shared_ptr<const GpuSeeThrough> seeThrough;
    bool casts() const;
    bool receives() const;
};

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

// The light-centre shadow map shared by every method for one light. Casters only
// (SS_MESH_CAST, and the light's blockers: Scene::castsFor), two-sided. Texel (u, v) = shadow
// clip xy * 0.5 + 0.5 (GL orientation).
struct ShadowMap {
    static constexpr float kEmpty = 1e30f;  // distance stored where no caster is seen
    int size = 0;                           // square, size x size texels
    bool orthographic = false;              // sun
    glm::vec3 origin{0.0f};                 // light centre (sun: a point on the near plane)
    glm::vec3 axis{0.0f, 0.0f, -1.0f};      // view direction of the map (unit)
    glm::mat4 worldToLight{1.0f};           // view matrix (looks down -Z along `axis`)
    glm::mat4 projection{1.0f};             // light view -> clip
    float nearPlane = 0.0f, farPlane = 0.0f;
    float tanHalfFov = 0.0f;   // perspective: tan of the half field of view
    float halfWidth = 0.0f;    // orthographic: half width of the square view in world units
    // False when the scene's bounds could not all fit (light inside the scene, sun looking
    // sideways...): points outside the map are then treated as unshadowed by it.
    bool coversScene = true;
    // R32F: world-space distance from the light centre to the nearest caster (perspective), or
    // distance along `axis` from `origin` (orthographic); kEmpty where no caster is seen.
    gl::Texture distance;
    gl::Texture depth;  // DEPTH_COMPONENT32F window depth of the same draw
    glm::mat4 worldToClip() const { return projection * worldToLight; }
    // World size of one texel at `distanceToLight` (perspective) or anywhere (orthographic).
    float texelWorldSize(float distanceToLight) const;
    // The quantity stored in `distance` for a world point (what a receiver compares with).
    float distanceOf(const glm::vec3& world) const;
};

// The frustum a light's shadow map uses (exposed for tests and CPU methods); no GL needed.
ShadowMap fitShadowMap(const Light& light, const Bounds& bounds, int size);
// How much larger than what can shadow the receivers in view the scene may be and still be
// what the maps fit (shadowFitBounds).
inline constexpr float kSceneFitSlack = 8.0f;
// The box a light's shadow map (and dbuffer's volumes) fit: the scene's bounds, unless they
// reach more than kSceneFitSlack times past the receivers the camera sees (`receivers`, with
// a margin for the light's extent), as one far vertex makes them; then the scene clipped to
// that region, so one outlier never spreads a map over its own extent. No GL needed.
Bounds shadowFitBounds(const Light& light, const Bounds& scene, const Bounds& receivers);

// What one frame cache drew and uploaded (scene_cache/cache_counters.h says what each counts).
struct SceneCacheStats {
    SS_SCENE_CACHE_COUNTERS(SS_COUNTER_MEMBER)
    size_t shadowMapBytes = 0;  // the cached shadow maps' bytes now (the budget's measure)
};

class SceneCache {
public:
    static constexpr int kDefaultShadowMapSize = 2048;
    // What the cached shadow maps may hold between renders: eight 2048² maps (distance +
    // depth, 32 MiB each). One render may add its own maps on top until the next trim.
    static constexpr size_t kDefaultShadowMapBudget = size_t(256) << 20;

    explicit SceneCache(const Scene& scene);
    ~SceneCache();
    SceneCache(const SceneCache&) = delete;
    SceneCache& operator=(const SceneCache&) = delete;

    const Scene& scene() const { return *scene_; }
    const Camera& camera() const { return scene_->camera(); }
    // Which triangles the camera pass hands to GL. EachTriangle: those a CPU test finds may
    // cover a pixel centre (CoveringTriangles): on llvmpipe every triangle handed to a draw
    // costs about 0.1 µs, several times the test. Clusters: every triangle of the clusters that
    // reach the redrawn rectangle: a GPU draws 1M triangles in about a millisecond, less than the
    // test takes. Auto (the default): EachTriangle when GL_RENDERER names llvmpipe (whose
    // sub-pixel snapping, 1/256 pixel, the test's margins are made for), else Clusters. The pass
    // is the same bit for bit either way.
    enum class CameraCulling { Auto, EachTriangle, Clusters };
    void setCameraCulling(CameraCulling culling) { culling_ = culling; }
    // The same scene (same id) after edits: passes whose inputs changed are redrawn on their
    // next use, the rest are kept (a mesh's buffers by its version, a shadow map by its light's
    // version and the geometry version, the camera pass by the camera and geometry versions).
    void setScene(const Scene& scene) { scene_ = &scene; }
    const Light& light(int index) const;  // throws ss::Error(SS_ERROR_INVALID_ARGUMENT)
    // The GL function table; throws ss::Error(SS_ERROR_GL) when called off the render thread
    // (CPU methods run on the caller's thread and have no GL).
    const gl::Functions& gl() const;

    // ---- shared passes (GL methods only; each computed once per frame) ----
    const std::vector<GpuMesh>& meshes();
    const CameraPass& cameraPass();
    const CameraImages& cameraImages();  // read back on first call
    // The world bounds of the receiving surfaces the camera pass sees (read back a band of
    // rows at a time; empty when none), kept with the camera pass.
    const Bounds& receiversInView();
    // shadowFitBounds for light `lightIndex` with the scene and receiversInView().
    Bounds shadowFitBounds(int lightIndex);
    // size 0 = kDefaultShadowMapSize; one map per (light, size), kept until trimCache() evicts
    // it. The reference stays valid until the next trimCache().
    const ShadowMap& shadowMap(int lightIndex, int size = 0);
    // Drops the least recently used shadow maps until the rest fit in `budgetBytes`. Called
    // between renders (never during one, so the maps a render holds stay alive). Reads no scene:
    // the renderer trims frames of other scenes too.
    void trimCache(size_t budgetBytes);
    // Drops the passes whose inputs changed and the maps of lights edited or removed since. Needs
    // the scene: only after setScene() with the scene as it is now.
    void dropStale();
    size_t shadowMapBytes() const { return stats_.shadowMapBytes; }
    // Drops the CPU copy of the camera pass (cameraImages(), 48 bytes a pixel) when it holds more
    // than `keepBytes`: called between renders, so a large one lives for one render only.
    void trimCameraImages(size_t keepBytes);

    // ---- the ray tracer's scene (no GL; any thread) ----
    // The one Embree BVH of this scene's geometry: the reference, refine=on and the sparse check
    // all trace it. Built on first use, rebuilt after a mesh edit (not a light or camera edit);
    // builds() counts the builds.
    TraceSceneCache& traceScenes() { return traceScenes_; }
    const TraceSceneCache& traceScenes() const { return traceScenes_; }

    // ---- helpers ----
    // Draws every mesh whose flags contain all of `requiredFlags` with `program` (in use) and the
    // bound framebuffer, setting its uObjectToWorld, uNormalToWorld and uTransformed; `before`
    // runs for each mesh first (e.g. to set a per-mesh uniform). Binds each mesh's face normals
    // to SSBO binding 0.
    void drawMeshes(const gl::Program& program, uint32_t requiredFlags,
                    const std::function<void(const GpuMesh&)>& before = {});
    // Draws as drawMeshes does; with a region, only the clusters whose bounds, where their mesh
    // is now, may cover a pixel of its rectangle (a patch after moves: movedBoxes,
    // boxesOnScreen). With `castingFor` a light index, only the meshes that shadow that light
    // (Scene::castsFor: its shadow linking). With `skipSeeThrough` set, the see-through meshes
    // (GpuMesh::seeThrough) are left out: drawSeeThroughWhere draws them with that program.
    void drawMeshesWhere(const gl::Program& program, uint32_t requiredFlags,
                         const std::optional<PatchRegion>& region,
                         const std::function<void(const GpuMesh&)>& before, int castingFor = -1,
                         bool skipSeeThrough = false);
    // Draws the see-through meshes that have `requiredFlags` (and, with `castingFor` a light
    // index, shadow that light), whole, one material at a time:
    // unindexed, three vertices per triangle, with a vertex stage that includes
    // "common/see_through_vertex.glsl" and a fragment stage that includes
    // "common/see_through.glsl" (its uniforms and texture unit kAlphaTextureUnit are set here).
    // Placement uniforms, `before` and SSBO 0 as drawMeshesWhere; SSBOs 2..5 are the mesh's.
    void drawSeeThroughWhere(const gl::Program& program, uint32_t requiredFlags,
                             const std::function<void(const GpuMesh&)>& before, int castingFor = -1);
    static constexpr int kAlphaTextureUnit = 15;
    // Where each of the scene's meshes is now (what a pass drawn now shows: movedBoxes).
    std::vector<MeshPlacement> placements() const;
    // Draws one triangle covering the viewport (vertex shader "common/fullscreen.vert.glsl").
    void drawFullscreen();
    // Binds the camera pass textures to units firstUnit.. and sets the samplers of
    // "common/camera_gbuffer.glsl" (uCamPositionDepth, uCamNormalReceive, uCamIds).
    // Returns the next free texture unit.
    int bindCameraPass(const gl::Program& program, int firstUnit = 0);
    // Sets the uLight uniforms of "common/light.glsl" for light `lightIndex`.
    void setLightUniforms(const gl::Program& program, int lightIndex) const;
    // Sets uShadowDistance (texture) and uShadow* of "common/shadow_map.glsl"; returns next unit.
    int bindShadowMap(const gl::Program& program, const ShadowMap& map, int unit) const;

    const SceneCacheStats& stats() const { return stats_; }

private:
    void bindShadowMapUniforms(const gl::Program& program, const ShadowMap& map) const;
    // Binds a vertex array with no attributes (draws that make their vertices from gl_VertexID).
    void bindEmptyVertexArray();
    // Drops the camera pass and shadow maps whose inputs changed since they were drawn; after
    // moves alone the passes are kept and patched where the moved meshes were and are.
    void dropStalePasses();
    // Draws the camera pass (or the shadow map) into its own targets, inside `rect` only when
    // one is given. The camera pass draws only the triangles that may cover a pixel centre of
    // the rectangle (listCoveringTriangles), fetched by camera/gbuffer.vert.glsl.
    void drawCameraPass(CameraPass& pass, const std::optional<PixelRect>& rect);
    // Lists, per mesh in meshes_ order, the triangles of its clusters that reach `rect` that may
    // cover one of its pixel centres: listed_[0] then listed_[1] (two threads list a half each),
    // and listedRanges_ gives each mesh's run in that sequence.
    void listCoveringTriangles(const Camera& camera, const PixelRect& rect);
    void drawShadowMap(ShadowMap& map, int lightIndex, const std::optional<PixelRect>& rect);
    const Scene* scene_;
    std::vector<GpuMesh> meshes_;
    uint64_t meshesGeometryVersion_ = 0;  // 0: never uploaded
    std::unique_ptr<CameraPass> camera_;
    std::unique_ptr<CameraImages> cameraImages_;
    std::optional<Bounds> receiversInView_;  // of the camera pass as drawn, null until asked
    uint64_t cameraPassCamera_ = 0, cameraPassGeometry_ = 0;  // versions the camera pass shows
    std::vector<MeshPlacement> cameraPlacements_;            // what the camera pass shows
    uint64_t shadowMapsGeometry_ = 0;                         // the geometry the maps show
    std::vector<MeshPlacement> shadowMapPlacements_;          // (with their pending boxes)
    Bounds shadowMapBounds_;                                  // the scene bounds the maps are fit to
    struct CachedShadowMap {
        std::unique_ptr<ShadowMap> map;
        uint64_t lastUse = 0;
        size_t bytes = 0;
        std::vector<Bounds> pending;  // world boxes moved meshes touched since it was drawn
        Bounds fit;                   // the box it was fit to (shadowFitBounds)
    };
    std::map<std::pair<uint64_t, int>, CachedShadowMap> shadowMaps_;  // (Light::version, size)
    uint64_t useClock_ = 0;
    gl::VertexArrayHandle emptyVao_;
    CameraCulling culling_ = CameraCulling::Auto;  // Auto until the first camera pass resolves it
    CoveringTriangles coverage_[2];
    std::vector<uint32_t> listed_[2];                       // triangle indices, mesh after mesh
    std::vector<std::pair<size_t, size_t>> listedRanges_;  // per mesh: first, count in listed_
    gl::BufferHandle listedBuffer_;
    size_t listedCapacity_ = 0;                             // uint32 entries listedBuffer_ holds
    SceneCacheStats stats_;
    TraceSceneCache traceScenes_;
};

}  // namespace ss
