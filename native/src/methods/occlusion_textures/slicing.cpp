// How occlusion_textures fits its kernel light, slicing camera and slice planes to a scene.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/occlusion_textures/slicing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "methods/sweep/receiver.h"

namespace ss::occlusion {

namespace {
// A box with the area of the ellipse inscribed in it: pi a b = 4 (k a)(k b), k = sqrt(pi) / 2.
constexpr float kEqualAreaBox = 0.88622692545f;
constexpr float kMaxHalfAngle = 80.0f * float(M_PI) / 180.0f;

// Two unit axes completing `normal` to a right-handed frame with axisX x axisY = -normal.
void frameAround(const glm::vec3& normal, glm::vec3* x, glm::vec3* y) {
    glm::vec3 z = -normal;
    glm::vec3 helper = std::abs(z.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    *x = glm::normalize(glm::cross(helper, z));
    *y = glm::cross(z, *x);
}
// The casting planes, not parallel to the light, that no ray from a caster or receiver to the
// light can cross: every other mesh
// that casts or receives and the light's rectangle lie on the plane's lit side (within `tol`), so
// a segment between two such points meets the plane at most at an end. Each mesh is first
// tested by its bounding box's corners, vertex by vertex only when a corner dips below.
template <class Casts, class Receives>
std::vector<int> planesThatCannotShadow(const Scene& scene, const KernelLight& light, const Casts& casts,
                                        const Receives& receives) {
    const auto& meshes = scene.meshes();
    std::vector<Bounds> boxes(meshes.size());
    Bounds all;
    for (size_t i = 0; i < meshes.size(); ++i) {
        if (!casts(i) && !receives(i)) continue;
        for (const glm::vec3& p : meshes[i].positions) boxes[i].extend(p);
        if (!boxes[i].empty()) all.extend(boxes[i].lo), all.extend(boxes[i].hi);
    }
    const double tol = 1e-5 * std::max(double(all.diagonal()), 1e-30);
    std::vector<int> out;
    for (size_t i = 0; i < meshes.size(); ++i) {
        glm::dvec3 o, n;
        if (!casts(i) || !planeOfMesh(meshes[i], &o, &n)) continue;
        auto height = [&](const glm::vec3& p) { return glm::dot(glm::dvec3(p) - o, n); };
        // A plane parallel to the light lies at one depth, past the occluders over it: it stays
        // sliced (the bottom slice, which fade=below never lets it shadow itself through).
        if (std::abs(glm::dot(n, glm::dvec3(light.normal))) > 1.0 - 1e-7) continue;
        const double lightHeight = height(light.centre);
        if (std::abs(lightHeight) <= tol) continue;
        if (lightHeight < 0) n = -n;
        bool lit = true;
        for (float sx : {-1.0f, 1.0f})
            for (float sy : {-1.0f, 1.0f})
                lit = lit && height(light.centre + sx * light.halfX * light.axisX + sy * light.halfY * light.axisY) >= -tol;
        for (size_t j = 0; lit && j < meshes.size(); ++j) {
            if (j == i || boxes[j].empty()) continue;
            bool corners = true;
            for (const glm::vec3& c : boxes[j].corners()) corners = corners && height(c) >= -tol;
            if (corners) continue;
            for (const glm::vec3& p : meshes[j].positions)
                if (height(p) < -tol) {
                    lit = false;
                    break;
                }
        }
        if (lit) out.push_back(int(i));
    }
    return out;
}

}  // namespace

bool SliceSetup::sliced(int mesh) const { return !std::binary_search(unsliced.begin(), unsliced.end(), mesh); }

glm::vec3 KernelLight::toLocal(const glm::vec3& world) const {
    glm::vec3 r = world - centre;
    return {glm::dot(r, axisX), glm::dot(r, axisY), glm::dot(r, normal)};
}

KernelLight kernelLight(const Light& light, const Bounds& sceneBounds) {
    KernelLight k;
    float diagonal = std::max(sceneBounds.diagonal(), 1e-3f);
    switch (light.type) {
        case LightType::Square:
        case LightType::Rectangle:
        case LightType::Disk:
        case LightType::Ellipse: {
            k.centre = light.position();
            k.normal = light.direction();
            k.axisX = glm::normalize(light.halfAxisX());
            k.axisY = glm::normalize(glm::cross(-k.normal, k.axisX));
            float scale = light.type == LightType::Disk || light.type == LightType::Ellipse ? kEqualAreaBox : 1.0f;
            k.halfX = scale * glm::length(light.halfAxisX());
            k.halfY = scale * glm::length(light.halfAxisY());
            break;
        }
        case LightType::Point:
        case LightType::Spot: {
            k.centre = light.position();
            glm::vec3 toScene = sceneBounds.empty() ? glm::vec3(0.0f) : sceneBounds.center() - k.centre;
            k.normal = light.type == LightType::Spot || glm::length(toScene) < 1e-6f ? light.direction()
                                                                                  : glm::normalize(toScene);
            frameAround(k.normal, &k.axisX, &k.axisY);
            k.halfX = k.halfY = kEqualAreaBox * std::max(light.radius, 1e-5f * diagonal);
            break;
        }
        case LightType::Sun: {
            k.normal = light.direction();
            float distance = 10.0f * diagonal;
            k.centre = sceneBounds.center() - distance * k.normal;
            frameAround(k.normal, &k.axisX, &k.axisY);
            float half = distance * std::tan(0.5f * std::clamp(light.angle, 0.0f, 3.0f));
            k.halfX = k.halfY = kEqualAreaBox * std::max(half, 1e-5f * diagonal);
            break;
        }
    }
    return k;
}

int SliceSetup::sliceOf(float z) const {
    float t = (z - planes.front()) / (planes.back() - planes.front());
    return std::clamp(int(std::floor(t * float(count()))), 0, count() - 1);
}

glm::vec2 SliceSetup::ndcPerUnit(float depth) const {
    if (projection == Projection::Orthographic) return 1.0f / orthoHalf;
    return glm::vec2(1.0f / light.halfX, 1.0f / light.halfY) * (d / (d + depth));
}

SliceSetup fitSlices(const Scene& scene, const KernelLight& light, int sliceCount, int resolution,
                     Projection projection, int lightIndex) {
    if (sliceCount < 1 || sliceCount > 16)
        fail(SS_ERROR_INVALID_ARGUMENT, "occlusion_textures: slices = " + std::to_string(sliceCount) +
                                            " is outside 1..16");
    if (resolution < 16 || resolution > 4096)
        fail(SS_ERROR_INVALID_ARGUMENT, "occlusion_textures: resolution = " + std::to_string(resolution) +
                                            " is outside 16..4096");
    auto casts = [&](size_t i) { return lightIndex < 0 ? scene.meshes()[i].casts() : scene.castsFor(int(i), lightIndex); };
    auto receives = [&](size_t i) {
        return lightIndex < 0 ? scene.meshes()[i].receives() : scene.receivesFrom(int(i), lightIndex);
    };
    std::vector<int> unsliced = planesThatCannotShadow(scene, light, casts, receives);
    const float inf = std::numeric_limits<float>::infinity();
    float zAllMax = 0.0f, zCastMin = inf, zCastMax = 0.0f, zReceiveMax = 0.0f;
    float d = inf;
    float coverX = light.halfX, coverY = light.halfY;  // orthographic: the extent to cover
    for (size_t i = 0; i < scene.meshes().size(); ++i) {
        const Mesh& mesh = scene.meshes()[i];
        const bool sliced = casts(i) && !std::binary_search(unsliced.begin(), unsliced.end(), int(i));
        const bool receiving = receives(i);
        if (!sliced && !receiving) continue;
        for (const glm::vec3& p : mesh.positions) {
            glm::vec3 q = light.toLocal(p);
            if (q.z <= 0.0f) continue;
            zAllMax = std::max(zAllMax, q.z);
            coverX = std::max(coverX, std::abs(q.x)), coverY = std::max(coverY, std::abs(q.y));
            if (sliced) zCastMin = std::min(zCastMin, q.z), zCastMax = std::max(zCastMax, q.z);
            if (receiving) zReceiveMax = std::max(zReceiveMax, q.z);
            // Inside the frustum when |x| <= a (z + d) / d, i.e. d <= a z / (|x| - a).
            if (std::abs(q.x) > light.halfX) d = std::min(d, light.halfX * q.z / (std::abs(q.x) - light.halfX));
            if (std::abs(q.y) > light.halfY) d = std::min(d, light.halfY * q.z / (std::abs(q.y) - light.halfY));
        }
    }
    if (!(zAllMax > 0.0f))
        fail(SS_ERROR_UNSUPPORTED, "occlusion_textures: no casting or receiving geometry lies in front of the light");
    if (!(zCastMax > 0.0f)) {
        // Nothing shadows this light (its blockers are elsewhere or none): empty slices over the
        // receivers' depths, so every receiver reads V = 1.
        zCastMin = 0.5f * zAllMax;
        zCastMax = zAllMax;
    }
    float dMin = std::max(light.halfX, light.halfY) / std::tan(kMaxHalfAngle);
    SliceSetup s;
    s.light = light;
    s.projection = projection;
    // A kernel's centre and corners are convex combinations of the point and the light's
    // corners, so covering both covers every lookup.
    const float cover = 1.001f * std::max(coverX / light.halfX, coverY / light.halfY);
    s.orthoHalf = glm::vec2(light.halfX, light.halfY) * cover;
    s.d = std::clamp(d, dMin, std::max(dMin, 4.0f * zAllMax));
    s.receiverDepthMax = zReceiveMax;
    s.lightIndex = lightIndex;
    s.unsliced = std::move(unsliced);
    // Vertices touching the light plane would make the first slice start at 0 depth; keep a
    // thin gap so the slicing camera's near plane stays positive.
    float z0 = std::max(zCastMin, 1e-4f * zCastMax);
    float z1 = std::max(zCastMax, z0 * (1.0f + 1e-4f));
    s.planes.resize(size_t(sliceCount) + 1);
    for (int k = 0; k <= sliceCount; ++k) s.planes[size_t(k)] = z0 + (z1 - z0) * float(k) / float(sliceCount);
    float aspect = light.halfY / light.halfX;
    s.width = aspect <= 1.0f ? resolution : std::max(16, int(std::lround(resolution / aspect)));
    s.height = aspect <= 1.0f ? std::max(16, int(std::lround(resolution * aspect))) : resolution;

    if (projection == Projection::Orthographic) {
        glm::mat4 lightToWorld(glm::vec4(light.axisX, 0.0f), glm::vec4(light.axisY, 0.0f),
                               glm::vec4(-light.normal, 0.0f), glm::vec4(light.centre, 1.0f));
        float margin = 1e-3f * (z1 - z0);
        s.worldToClip = glm::ortho(-s.orthoHalf.x, s.orthoHalf.x, -s.orthoHalf.y, s.orthoHalf.y,
                                   std::max(z0 - margin, 0.5f * z0), z1 + margin) *
                        glm::inverse(lightToWorld);
        return s;
    }
    glm::vec3 eye = light.centre - s.d * light.normal;
    glm::mat4 cameraToWorld(glm::vec4(light.axisX, 0.0f), glm::vec4(light.axisY, 0.0f),
                            glm::vec4(-light.normal, 0.0f), glm::vec4(eye, 1.0f));
    float margin = 1e-3f * (z1 - z0);
    float nearZ = s.d + std::max(z0 - margin, 0.5f * z0), farZ = s.d + z1 + margin;
    float sx = light.halfX * nearZ / s.d, sy = light.halfY * nearZ / s.d;
    s.worldToClip = glm::frustum(-sx, sx, -sy, sy, nearZ, farZ) * glm::inverse(cameraToWorld);
    return s;
}

glm::vec2 sliceUv(const SliceSetup& s, const glm::vec3& local) {
    glm::vec2 ndc = glm::vec2(local.x, local.y) * s.ndcPerUnit(local.z);
    return 0.5f * ndc + 0.5f;
}

SliceLookup lookupSlice(const SliceSetup& s, const glm::vec3& local, int k, Fade fade) {
    SliceLookup out;
    float top = s.planes[size_t(k)], bottom = s.planes[size_t(k) + 1], thickness = bottom - top;
    float z = local.z;
    if (fade == Fade::Paper)
        out.weight = std::clamp((z - top) / thickness, 0.0f, 1.0f);
    else
        out.weight = std::clamp((z - bottom) / thickness, 0.0f, 1.0f);
    if (out.weight <= 0.0f || z <= 0.0f) return SliceLookup{};
    // The occluders of slice k lie on its lower plane; the light seen from the point covers
    // a rectangle there, centred on the line from the light centre through the point.
    float ratio = bottom / z;
    out.uv = sliceUv(s, glm::vec3(local.x * ratio, local.y * ratio, bottom));
    // The footprint's half size over the texture's half size: full kernel size in texels.
    glm::vec2 halfNdc = std::abs(z - bottom) / z * glm::vec2(s.light.halfX, s.light.halfY) * s.ndcPerUnit(bottom);
    out.kernelTexels = halfNdc * glm::vec2(float(s.width), float(s.height));
    return out;
}

}  // namespace ss::occlusion
