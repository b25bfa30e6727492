// How one mesh's BVH is built, in the coordinates the mesh was given in where its transform allows.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/mesh_bvh.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace ss {
namespace {

// A transform whose linear part keeps less than this share of a unit cube's volume (relative to
// its own scale) maps rays into object space too poorly to trace there.
constexpr double kFlatRelativeVolume = 1e-9;

bool invertible(const glm::mat4& m) {
    const glm::dmat3 linear(m);
    const double scale = std::max(glm::length(linear[0]), std::max(glm::length(linear[1]), glm::length(linear[2])));
    const double det = glm::determinant(linear);
    return std::isfinite(det) && scale > 0.0 && std::abs(det) > kFlatRelativeVolume * scale * scale * scale;
}

bool inObjectSpace(const Mesh& mesh) { return invertible(mesh.objectToWorld); }

}  // namespace

RTCDevice embreeDevice() {
    static RTCDevice device = [] {
        RTCDevice d = rtcNewDevice(nullptr);
        if (!d)
            fail(SS_ERROR_INTERNAL, "Embree could not create a device (error " +
                                        std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        return d;
    }();
    return device;
}

void checkEmbree(RTCDevice device, const char* what) {
    RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        fail(SS_ERROR_INTERNAL, std::string("Embree failed while ") + what + " (error " +
                                    std::to_string(int(e)) + ")");
}

MeshBvh::Key MeshBvh::keyOf(const Mesh& mesh) {
    return inObjectSpace(mesh) ? Key{mesh.shapeVersion, true} : Key{mesh.version, false};
}

glm::mat4 MeshBvh::toWorldOf(const Mesh& mesh) {
    return inObjectSpace(mesh) ? mesh.objectToWorld : glm::mat4(1.0f);
}

MeshBvh::MeshBvh(const Mesh& mesh) : key_(keyOf(mesh)), triangles_(mesh.triangles) {
    positions_ = key_.objectSpace ? mesh.objectPositions : mesh.positions;
    faceNormals_ = key_.objectSpace ? mesh.objectFaceNormals : mesh.faceNormals;

    RTCDevice device = embreeDevice();
    scene_.reset(rtcNewScene(device));
    checkEmbree(device, "creating a mesh scene");
    // The reference is the truth: Embree's most accurate (watertight) traversal. The filter flag
    // lets shadow rays skip the triangle they start on (the leaf intersection runs in here).
    rtcSetSceneFlags(scene(), RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
    rtcSetSceneBuildQuality(scene(), RTC_BUILD_QUALITY_HIGH);

    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), positions_.size()));
    auto* i = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(uint32_t), triangles_.size()));
    if (!v || !i) {
        rtcReleaseGeometry(g);
        checkEmbree(device, "allocating mesh buffers");
        fail(SS_ERROR_INTERNAL, "Embree returned no buffer for mesh '" + mesh.name + "'");
    }
    for (size_t k = 0; k < positions_.size(); ++k)
        for (int c = 0; c < 3; ++c) v[3 * k + c] = positions_[k][c];
    for (size_t k = 0; k < triangles_.size(); ++k)
        for (int c = 0; c < 3; ++c) i[3 * k + c] = triangles_[k][c];
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene(), g, 0);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene());
    checkEmbree(device, ("building the BVH of mesh '" + mesh.name + "'").c_str());
}

}  // namespace ss
