// What a scene is: placed meshes, lights and the camera, validated as they enter.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/mesh.h"

namespace ss {

struct Bounds {
    glm::vec3 lo{1e30f}, hi{-1e30f};
    void extend(const glm::vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    bool empty() const { return lo.x > hi.x; }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
    std::vector<glm::vec3> corners() const {
        std::vector<glm::vec3> c;
        for (int i = 0; i < 8; ++i)
            c.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        return c;
    }
};

class Scene {
public:
    // Each adder validates its input (throws ss::Error) and bumps the revision. A mesh comes
    // with its objectPositions, triangles and objectToWorld; the rest is derived here.
    int addMesh(Mesh mesh);
    int addLight(Light light);
    void setCamera(const Camera& camera);
    void setViewLayer(const std::string& name);

    // Incremental edits of a persistent scene (the preview's): each changes one thing, gives it
    // a new version and leaves every other mesh's and light's version (and caches) alone.
    // Indices out of range throw ss::Error(SS_ERROR_INVALID_ARGUMENT) naming them.
    // New geometry for mesh `index` (`mesh.objectPositions`, triangles, flags; its name and
    // transform are kept, its materials are cleared).
    void updateMesh(int index, Mesh mesh);
    // Moves mesh `index` (Mesh::place): its shape and the caches keyed by it stay.
    void setMeshTransform(int index, const glm::mat4& objectToWorld);
    // Mesh `index`'s materials (validated against its triangles); an opaque set clears them.
    // A new shape for the mesh: what depends on its triangles is rebuilt.
    void setMeshAlpha(int index, MeshAlpha alpha);
    void removeMesh(int index);  // later meshes move down one index
    void updateLight(int index, Light light);
    void removeLight(int index);  // later lights move down one index
    // Light and shadow linking of light `index` (LightLinks): a new light version, so its
    // shadow maps and prepared geometry are made again; the others' are kept. Mesh indices are
    // checked against the scene's meshes now; a mesh added later is in neither set of a light
    // that has sets, and a removed mesh leaves them (later indices move down).
    void setLightLinks(int index, LightLinks links);
    // Whether mesh `mesh` shadows light `light` (it casts, and the light's blockers hold it),
    // and whether its pixels are in the light's mask (it receives, and the light lights it).
    bool castsFor(int mesh, int light) const;
    bool receivesFrom(int mesh, int light) const;

    const std::vector<Mesh>& meshes() const { return meshes_; }
    const std::vector<Light>& lights() const { return lights_; }
    // Throw ss::Error(SS_ERROR_INVALID_ARGUMENT) naming `where` (a C function, an edit), the
    // index and the count (checkedIndex in core/error.h).
    const Light& light(int index, const std::string& where = "") const;
    const Mesh& mesh(int index, const std::string& where = "") const;
    const Camera& camera() const;  // throws when the scene has no camera
    bool hasCamera() const { return camera_.has_value(); }
    const std::string& viewLayer() const { return viewLayer_; }
    int findLight(const std::string& name) const;  // -1 when absent
    Bounds bounds() const;                         // of all meshes
    // Changes whenever the scene changes (caches key on the finer versions below, with the id).
    // A copy is another scene (the two may diverge with equal versions), so it gets an id of its own.
    uint64_t revision() const { return revision_; }
    uint64_t id() const { return id_.value; }
    // Change with any mesh edit (what the camera pass and every shadow map depend on) and with
    // any camera edit, respectively; unique over the process like the mesh and light versions.
    uint64_t geometryVersion() const { return geometryVersion_; }
    uint64_t cameraVersion() const { return cameraVersion_; }
    // What a light's CPU geometry (silhouettes, volumes, cones and sheets, sweeps) depends on.
    struct LightGeometryKey {
        uint64_t sceneId = 0, geometryVersion = 0, lightVersion = 0;
        int lightIndex = -1;
        bool operator==(const LightGeometryKey&) const = default;
    };
    // The key methods keep their prepared geometry under: a camera edit, or another light's,
    // keeps it; a mesh edit (a move included) or this light's edit changes it.
    LightGeometryKey lightGeometryKey(int lightIndex) const;
    // A fresh version stamp (process-wide counter).
    static uint64_t nextVersion();

private:
    std::vector<Mesh> meshes_;
    std::vector<Light> lights_;
    std::optional<Camera> camera_;
    std::string viewLayer_ = "ViewLayer";
    uint64_t revision_ = 0;
    uint64_t geometryVersion_ = nextVersion();
    uint64_t cameraVersion_ = nextVersion();
    static uint64_t nextId();
    // Copying makes a new id; moving hands the id over and gives the emptied source a new one.
    struct Identity {
        uint64_t value = nextId();
        Identity() = default;
        Identity(const Identity&) : value(nextId()) {}
        Identity(Identity&& other) noexcept : value(other.value) { other.value = nextId(); }
        Identity& operator=(const Identity&) {
            value = nextId();
            return *this;
        }
        Identity& operator=(Identity&& other) noexcept {
            value = other.value;
            other.value = nextId();
            return *this;
        }
    } id_;
};

}  // namespace ss
