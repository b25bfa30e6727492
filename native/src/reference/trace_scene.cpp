// How Embree scenes are built from an ss::Scene and queried for camera and shadow rays.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/trace_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "reference/mesh_bvh.h"

namespace ss {
namespace {

// The shadow-ray context: the triangle the ray starts on is ignored. Meshes are instances
// (instance ID == mesh index), each holding one geometry.
struct ShadowContext {
    RTCIntersectContext base;
    uint32_t skipMesh, skipTriangle;
};

void skipOwnTriangle(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const ShadowContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        if (RTCHitN_instID(args->hit, args->N, i, 0) == ctx->skipMesh &&
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
    // One mesh as the rays see it: its BVH and the transform above it.
    struct Instance {
        std::shared_ptr<const MeshBvh> bvh;  // null for a mesh without triangles
        glm::mat4 toWorld{1.0f};
        glm::mat3 normalToWorld{1.0f};  // inverse transpose of toWorld's linear part
        glm::mat3 absLinear{1.0f};      // |toWorld's linear part|, for error bounds
        glm::vec3 absTranslation{0.0f};
    };
    RTCScene all = nullptr;      // camera rays
    RTCScene casters = nullptr;  // shadow rays
    bool filterSupported = false;
    int packetWidth = 1;  // the widest packet the CPU traces natively
    std::vector<Instance> instances;  // per mesh index

    ~Impl() {
        if (all) rtcReleaseScene(all);
        if (casters) rtcReleaseScene(casters);
    }

    static void instance(RTCDevice device, RTCScene scene, const Instance& in, uint32_t id) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, in.bvh->scene());
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &in.toWorld[0][0]);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene, g, id);  // instID == mesh index in both scenes
        rtcReleaseGeometry(g);
        checkEmbree(device, "placing a mesh");
    }
};

TraceScene::TraceScene(const Scene& scene, const std::vector<std::shared_ptr<const MeshBvh>>& reusable,
                       int castersOf)
    : impl_(std::make_unique<Impl>()), sceneId_(scene.id()), geometryVersion_(scene.geometryVersion()) {
    if (castersOf >= 0) blockers_ = scene.light(castersOf, "TraceScene").links.blockers;
    Impl& m = *impl_;
    RTCDevice device = embreeDevice();
    m.filterSupported = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) != 0;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) m.packetWidth = 16;
    else if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) m.packetWidth = 8;
    m.all = rtcNewScene(device);
    m.casters = rtcNewScene(device);
    checkEmbree(device, "creating scenes");
    rtcSetSceneFlags(m.all, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneFlags(m.casters, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST |
                                              (m.filterSupported ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : 0)));

    std::unordered_map<uint64_t, std::shared_ptr<const MeshBvh>> kept;
    for (const auto& bvh : reusable) kept.emplace(bvh->key().packed(), bvh);
    const auto& meshes = scene.meshes();
    m.instances.resize(meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i) {
        const Mesh& mesh = meshes[i];
        for (const glm::vec3& p : mesh.positions)
            extent_ = std::max(extent_, std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
        if (mesh.triangles.empty()) continue;
        Impl::Instance& in = m.instances[i];
        const MeshBvh::Key key = MeshBvh::keyOf(mesh);
        if (auto found = kept.find(key.packed()); found != kept.end() && found->second->key() == key)
            in.bvh = found->second;
        if (!in.bvh) {
            in.bvh = std::make_shared<const MeshBvh>(mesh);
            ++meshBvhBuilds_;
        }
        in.toWorld = MeshBvh::toWorldOf(mesh);
        const glm::mat3 linear(in.toWorld);
        in.normalToWorld = glm::transpose(glm::inverse(linear));
        for (int c = 0; c < 3; ++c) in.absLinear[c] = glm::abs(linear[c]);
        in.absTranslation = glm::abs(glm::vec3(in.toWorld[3]));
        Impl::instance(device, m.all, in, uint32_t(i));
        if (castersOf < 0 ? mesh.casts() : scene.castsFor(int(i), castersOf))
            Impl::instance(device, m.casters, in, uint32_t(i));
    }
    rtcCommitScene(m.all);
    checkEmbree(device, "building the camera-ray scene");
    rtcCommitScene(m.casters);
    checkEmbree(device, "building the shadow-ray scene");
}

TraceScene::~TraceScene() = default;

std::vector<std::shared_ptr<const MeshBvh>> TraceScene::meshBvhs() const {
    std::vector<std::shared_ptr<const MeshBvh>> out;
    for (const Impl::Instance& in : impl_->instances)
        if (in.bvh) out.push_back(in.bvh);
    return out;
}

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
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->all, &ctx, &rh);

    SurfaceHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    const Impl::Instance& in = impl_->instances[rh.hit.instID[0]];
    const glm::uvec3& tri = in.bvh->triangles()[rh.hit.primID];
    h.hit = true;
    h.mesh = rh.hit.instID[0];
    h.triangle = rh.hit.primID;
    // Embree's (u, v) weight vertices 1 and 2; the point in the BVH's coordinates, then in the
    // world, each step's rounding in the bound (pbrt's, gamma(3) for the matrix product).
    float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    const std::vector<glm::vec3>& pos = in.bvh->positions();
    glm::vec3 p0 = pos[tri.x], p1 = pos[tri.y], p2 = pos[tri.z];
    const glm::vec3 local = b0 * p0 + b1 * p1 + b2 * p2;
    const glm::vec3 localError = gammaBound(7) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
    h.point = glm::vec3(in.toWorld * glm::vec4(local, 1.0f));
    h.pointError = in.absLinear * localError +
                   gammaBound(4) * (in.absLinear * (glm::abs(local) + localError) + in.absTranslation);
    glm::vec3 n = in.bvh->faceNormals()[rh.hit.primID];
    n = n == glm::vec3(0.0f) ? n : in.normalToWorld * n;
    const float nLen = glm::length(n);
    if (!(nLen > 0.0f) || !std::isfinite(nLen)) {
        // Embree leaves an instance hit's Ng in the instanced scene's coordinates.
        glm::vec3 ng = in.normalToWorld * glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        float len = glm::length(ng);
        n = len > 0.0f ? ng / len : -ray.direction;  // a sliver: face the viewer
    } else {
        n /= nLen;
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
    // One pixel's shadow rays share their origin and aim at one light, yet the packets are
    // traced without RTC_INTERSECT_CONTEXT_FLAG_COHERENT: with instances, Embree 3.13 looped
    // without end on some packets in that mode (SparseCheck.EqualsTheReferenceImageAtItsPixels).
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
