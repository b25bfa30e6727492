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

// The see-through surfaces one shadow ray counts before it is taken as blocked.
constexpr uint32_t kMaxSeeThroughHits = 64;


// The shadow-ray context: the triangle the ray starts on is ignored. Meshes are instances
// (instance ID == mesh index), each holding one geometry. Where a mesh lets light through
// (`alpha` non-null), a hit there is multiplied into the ray's transmission and rejected, so the
// traversal goes on to the next; an opaque hit ends it (Embree then sets tfar to -inf).
struct ShadowContext {
    RTCIntersectContext base;
    uint32_t skipMesh, skipTriangle;
    const std::shared_ptr<const MeshAlpha>* alpha = nullptr;  // per mesh index; null: all opaque
    // The ray's transmission so far and the see-through hits already counted (one ray per
    // query: Embree's packet traversal through instances does not tell a filter which lane of
    // the caller's packet a hit belongs to). With spatial splits one triangle may sit in several
    // BVH leaves and be reported once per leaf; each must count once.
    struct Seen {
        uint32_t count = 0;
        uint32_t mesh[kMaxSeeThroughHits], triangle[kMaxSeeThroughHits];
    };
    float* transmission = nullptr;
    Seen* seen = nullptr;
};

void shadowFilter(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const ShadowContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const uint32_t mesh = RTCHitN_instID(args->hit, args->N, i, 0);
        const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
        if (mesh == ctx->skipMesh && triangle == ctx->skipTriangle) {
            args->valid[i] = 0;
            continue;
        }
        if (!ctx->alpha || !ctx->alpha[mesh]) continue;  // opaque: the ray is blocked
        const float t = ctx->alpha[mesh]->transmission(triangle, RTCHitN_u(args->hit, args->N, i),
                                                       RTCHitN_v(args->hit, args->N, i));
        if (!(t > 0.0f)) continue;
        if (t >= 1.0f) {  // a hole: as if nothing were there
            args->valid[i] = 0;
            continue;
        }
        ShadowContext::Seen& seen = *ctx->seen;
        bool counted = false;
        for (uint32_t k = 0; k < seen.count && !counted; ++k)
            counted = seen.mesh[k] == mesh && seen.triangle[k] == triangle;
        if (!counted) {
            // Past kMaxSeeThroughHits surfaces the ray counts as blocked (Cycles stops at its
            // transparent bounce limit too).
            if (seen.count == kMaxSeeThroughHits) continue;
            seen.mesh[seen.count] = mesh, seen.triangle[seen.count] = triangle, ++seen.count;
            *ctx->transmission *= t;
            if (!(*ctx->transmission > 0.0f)) continue;
        }
        args->valid[i] = 0;
    }
}

// The camera-ray context: a hit on a see-through mesh where the camera sees through it
// (MeshAlpha::seenByCamera: a cut-out's hole) is rejected, so the ray goes on to what lies behind.
struct CameraContext {
    RTCIntersectContext base;
    const std::shared_ptr<const MeshAlpha>* alpha = nullptr;  // per mesh index
};

void cameraFilter(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const CameraContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const uint32_t mesh = RTCHitN_instID(args->hit, args->N, i, 0);
        const MeshAlpha* alpha = ctx->alpha[mesh].get();
        if (alpha && !alpha->seenByCamera(RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                                          RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

// Single-precision error bound factor gamma(n) = n u / (1 - n u) (pbrt), u = 2^-24.
constexpr float gammaBound(int n) {
    constexpr float u = 0.5f * std::numeric_limits<float>::epsilon();
    return n * u / (1.0f - n * u);
}

// One packet width's worth of shadow rays past opaque casters only (transmission 0 or 1):
// RTCRay8 / RTCRay16 share their field names.
template <int N, typename RayN, void (*OccludedN)(const int*, RTCScene, RTCIntersectContext*, RayN*)>
void occludedPackets(RTCScene scene, ShadowContext* ctx, const glm::vec3& origin,
                     const glm::vec3* dirs, const float* tFar, size_t n, float* transmission) {
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
        for (int i = 0; i < N && start + size_t(i) < n; ++i)
            transmission[start + size_t(i)] = r.tfar[i] < 0.0f ? 0.0f : 1.0f;
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
    // Per mesh index, what it lets through; empty when every caster is opaque.
    std::vector<std::shared_ptr<const MeshAlpha>> alpha;
    // Per mesh index, the materials of the meshes camera rays may pass through; empty when none.
    std::vector<std::shared_ptr<const MeshAlpha>> cameraAlpha;

    void start(ShadowContext* ctx, uint32_t skipMesh, uint32_t skipTriangle) const {
        rtcInitIntersectContext(&ctx->base);
        if (filterSupported) ctx->base.filter = shadowFilter;
        ctx->skipMesh = skipMesh;
        ctx->skipTriangle = skipTriangle;
        ctx->alpha = alpha.empty() ? nullptr : alpha.data();
    }

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
    rtcSetSceneFlags(m.all, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST |
                                          (m.filterSupported ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : 0)));
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
        if (mesh.casts() && mesh.seeThrough()) {
            m.alpha.resize(meshes.size());
            m.alpha[i] = mesh.alpha;
        }
        if (!(mesh.flags & SS_MESH_CAMERA_HIDDEN) && mesh.seeThrough() && mesh.alpha->cameraSeesThrough()) {
            m.cameraAlpha.resize(meshes.size());
            m.cameraAlpha[i] = mesh.alpha;
        }
        if (!(mesh.flags & SS_MESH_CAMERA_HIDDEN)) Impl::instance(device, m.all, in, uint32_t(i));
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
    CameraContext ctx;
    rtcInitIntersectContext(&ctx.base);
    if (impl_->filterSupported && !impl_->cameraAlpha.empty()) {
        ctx.base.filter = cameraFilter;
        ctx.alpha = impl_->cameraAlpha.data();
    }
    RTCRayHit rh{};
    rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
    rh.ray.tnear = tNear;
    rh.ray.tfar = tFar;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->all, &ctx.base, &rh);

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

float TraceScene::transmission(const glm::vec3& origin, const glm::vec3& dir, float tFar, uint32_t skipMesh,
                               uint32_t skipTriangle) const {
    ShadowContext ctx;
    impl_->start(&ctx, skipMesh, skipTriangle);
    float through = 1.0f;
    ShadowContext::Seen seen;
    ctx.transmission = &through;
    ctx.seen = &seen;
    RTCRay r{};
    r.org_x = origin.x, r.org_y = origin.y, r.org_z = origin.z;
    r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z;
    r.tnear = 0.0f;
    r.tfar = tFar;
    r.mask = 0xffffffffu;
    r.id = 0;
    rtcOccluded1(impl_->casters, &ctx.base, &r);
    return r.tfar < 0.0f ? 0.0f : through;  // Embree sets tfar to -inf on a hit
}

void TraceScene::transmissionMany(const glm::vec3& origin, const glm::vec3* dirs, const float* tFar, size_t n,
                                  uint32_t skipMesh, uint32_t skipTriangle, float* transmission) const {
    ShadowContext ctx;
    // One pixel's shadow rays share their origin and aim at one light, yet the packets are
    // traced without RTC_INTERSECT_CONTEXT_FLAG_COHERENT: with instances, Embree 3.13 looped
    // without end on some packets in that mode (SparseCheck.EqualsTheReferenceImageAtItsPixels).
    impl_->start(&ctx, skipMesh, skipTriangle);
    if (!impl_->alpha.empty()) {
        // See-through casters: one ray at a time, each with its own transmission.
        for (size_t i = 0; i < n; ++i) transmission[i] = this->transmission(origin, dirs[i], tFar[i], skipMesh, skipTriangle);
        return;
    }
    if (impl_->packetWidth == 16)
        occludedPackets<16, RTCRay16, rtcOccluded16>(impl_->casters, &ctx, origin, dirs, tFar, n, transmission);
    else if (impl_->packetWidth == 8)
        occludedPackets<8, RTCRay8, rtcOccluded8>(impl_->casters, &ctx, origin, dirs, tFar, n, transmission);
    else
        for (size_t i = 0; i < n; ++i) transmission[i] = this->transmission(origin, dirs[i], tFar[i], skipMesh, skipTriangle);
}

}  // namespace ss
