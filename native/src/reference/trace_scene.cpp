// How Embree scenes are built from an ss::Scene and queried for camera and shadow rays.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/trace_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"

namespace ss {
namespace {

// One Embree device for the whole process: it owns the build threads, and devices are
// expensive to create. Errors are collected per call through rtcGetDeviceError.
RTCDevice sharedDevice() {
    static RTCDevice device = [] {
        RTCDevice d = rtcNewDevice(nullptr);
        if (!d)
            fail(SS_ERROR_INTERNAL, "Embree could not create a device (error " +
                                        std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        return d;
    }();
    return device;
}

void checkDevice(RTCDevice device, const char* what) {
    RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        fail(SS_ERROR_INTERNAL, std::string("Embree failed while ") + what + " (error " +
                                    std::to_string(int(e)) + ")");
}

// The shadow-ray context: the triangle the ray starts on is ignored.
struct ShadowContext {
    RTCIntersectContext base;
    uint32_t skipMesh, skipTriangle;
};

void skipOwnTriangle(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const ShadowContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        if (RTCHitN_geomID(args->hit, args->N, i) == ctx->skipMesh &&
            RTCHitN_primID(args->hit, args->N, i) == ctx->skipTriangle)
            args->valid[i] = 0;
    }
}

// Single-precision error bound factor gamma(n) = n u / (1 - n u) (pbrt), u = 2^-24.
constexpr float gammaBound(int n) {
    constexpr float u = 0.5f * std::numeric_limits<float>::epsilon();
    return n * u / (1.0f - n * u);
}

// One packet width's worth of shadow rays: RTCRay8 / RTCRay16 share their field names.
template <int N, typename RayN, void (*OccludedN)(const int*, RTCScene, RTCIntersectContext*, RayN*)>
void occludedPackets(RTCScene scene, ShadowContext* ctx, const glm::vec3& origin,
                     const glm::vec3* dirs, const float* tFar, size_t n, uint8_t* hidden) {
    for (size_t start = 0; start < n; start += N) {
        alignas(64) int valid[N];
        alignas(64) RayN r;
        for (int i = 0; i < N; ++i) {
            size_t k = start + size_t(i);
            bool used = k < n;
            valid[i] = used ? -1 : 0;
            glm::vec3 d = used ? dirs[k] : glm::vec3(0.0f, 0.0f, 1.0f);
            r.org_x[i] = origin.x, r.org_y[i] = origin.y, r.org_z[i] = origin.z;
            r.dir_x[i] = d.x, r.dir_y[i] = d.y, r.dir_z[i] = d.z;
            r.tnear[i] = 0.0f;
            r.tfar[i] = used ? tFar[k] : 0.0f;
            r.time[i] = 0.0f;
            r.mask[i] = 0xffffffffu;
            r.id[i] = 0;
            r.flags[i] = 0;
        }
        OccludedN(valid, scene, &ctx->base, &r);
        for (int i = 0; i < N && start + size_t(i) < n; ++i) hidden[start + size_t(i)] = r.tfar[i] < 0.0f;
    }
}

}  // namespace

struct TraceScene::Impl {
    struct MeshCopy {
        std::vector<glm::vec3> positions;
        std::vector<glm::uvec3> triangles;
        std::vector<glm::vec3> faceNormals;
    };
    RTCDevice device = nullptr;
    RTCScene all = nullptr;      // camera rays
    RTCScene casters = nullptr;  // shadow rays
    bool filterSupported = false;
    int packetWidth = 1;  // the widest packet the CPU traces natively
    std::vector<MeshCopy> meshes;

    ~Impl() {
        if (all) rtcReleaseScene(all);
        if (casters) rtcReleaseScene(casters);
    }

    void attach(RTCScene scene, const Mesh& mesh, uint32_t id) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
        auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangles.size()));
        if (!v || !t) {
            rtcReleaseGeometry(g);
            checkDevice(device, "allocating mesh buffers");
            fail(SS_ERROR_INTERNAL, "Embree returned no buffer for mesh '" + mesh.name + "'");
        }
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) v[3 * i + k] = mesh.positions[i][k];
        for (size_t i = 0; i < mesh.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh.triangles[i][k];
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene, g, id);  // geomID == mesh index in both scenes
        rtcReleaseGeometry(g);
        checkDevice(device, ("adding mesh '" + mesh.name + "'").c_str());
    }
};

TraceScene::TraceScene(const Scene& scene)
    : impl_(std::make_unique<Impl>()), sceneId_(scene.id()), geometryVersion_(scene.geometryVersion()) {
    Impl& m = *impl_;
    m.device = sharedDevice();
    m.filterSupported = rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) != 0;
    if (rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) m.packetWidth = 16;
    else if (rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) m.packetWidth = 8;
    m.all = rtcNewScene(m.device);
    m.casters = rtcNewScene(m.device);
    checkDevice(m.device, "creating scenes");
    // The reference is the truth: keep Embree's most accurate (watertight) traversal.
    rtcSetSceneFlags(m.all, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneFlags(m.casters, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST |
                                              (m.filterSupported ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : 0)));
    rtcSetSceneBuildQuality(m.casters, RTC_BUILD_QUALITY_HIGH);

    const auto& meshes = scene.meshes();
    m.meshes.resize(meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i) {
        const Mesh& mesh = meshes[i];
        for (const glm::vec3& p : mesh.positions)
            extent_ = std::max(extent_, std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
        m.meshes[i] = {mesh.positions, mesh.triangles, mesh.faceNormals};
        if (mesh.triangles.empty()) continue;
        m.attach(m.all, mesh, uint32_t(i));
        if (mesh.casts()) m.attach(m.casters, mesh, uint32_t(i));
    }
    rtcCommitScene(m.all);
    checkDevice(m.device, "building the camera-ray scene");
    rtcCommitScene(m.casters);
    checkDevice(m.device, "building the shadow-ray scene");
}

TraceScene::~TraceScene() = default;

SurfaceHit TraceScene::intersect(const Ray& ray, float tNear, float tFar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
    rh.ray.tnear = tNear;
    rh.ray.tfar = tFar;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->all, &ctx, &rh);

    SurfaceHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    const Impl::MeshCopy& mesh = impl_->meshes[rh.hit.geomID];
    const glm::uvec3& tri = mesh.triangles[rh.hit.primID];
    h.hit = true;
    h.mesh = rh.hit.geomID;
    h.triangle = rh.hit.primID;
    // Embree's (u, v) weight vertices 1 and 2.
    float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    glm::vec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y], p2 = mesh.positions[tri.z];
    h.point = b0 * p0 + b1 * p1 + b2 * p2;
    h.pointError = gammaBound(7) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
    glm::vec3 n = mesh.faceNormals[rh.hit.primID];
    if (n == glm::vec3(0.0f)) {
        glm::vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        float len = glm::length(ng);
        n = len > 0.0f ? ng / len : -ray.direction;  // a sliver: face the viewer
    }
    h.normal = glm::dot(n, ray.direction) > 0.0f ? -n : n;
    return h;
}

bool TraceScene::occluded(const glm::vec3& origin, const glm::vec3& dir, float tFar,
                          uint32_t skipMesh, uint32_t skipTriangle) const {
    ShadowContext ctx;
    rtcInitIntersectContext(&ctx.base);
    if (impl_->filterSupported) ctx.base.filter = skipOwnTriangle;
    ctx.skipMesh = skipMesh;
    ctx.skipTriangle = skipTriangle;
    RTCRay r{};
    r.org_x = origin.x, r.org_y = origin.y, r.org_z = origin.z;
    r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z;
    r.tnear = 0.0f;
    r.tfar = tFar;
    r.mask = 0xffffffffu;
    rtcOccluded1(impl_->casters, &ctx.base, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void TraceScene::occludedMany(const glm::vec3& origin, const glm::vec3* dirs, const float* tFar,
                              size_t n, uint32_t skipMesh, uint32_t skipTriangle,
                              uint8_t* hidden) const {
    ShadowContext ctx;
    rtcInitIntersectContext(&ctx.base);
    // One pixel's shadow rays share their origin and aim at one light: coherent packets.
    ctx.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    if (impl_->filterSupported) ctx.base.filter = skipOwnTriangle;
    ctx.skipMesh = skipMesh;
    ctx.skipTriangle = skipTriangle;
    if (impl_->packetWidth == 16)
        occludedPackets<16, RTCRay16, rtcOccluded16>(impl_->casters, &ctx, origin, dirs, tFar, n, hidden);
    else if (impl_->packetWidth == 8)
        occludedPackets<8, RTCRay8, rtcOccluded8>(impl_->casters, &ctx, origin, dirs, tFar, n, hidden);
    else
        for (size_t i = 0; i < n; ++i)
            hidden[i] = occluded(origin, dirs[i], tFar[i], skipMesh, skipTriangle);
}

}  // namespace ss
