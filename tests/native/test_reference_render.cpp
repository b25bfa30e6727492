// Checks the reference image: pixel alignment, mask rules, every light type, determinism, progress and caching.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/visibility_classes.h"
#include "core/error.h"
#include "core/scene.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "reference/render_reference.h"
#include "reference/trace_scene.h"
#include "reference/trace_scene_cache.h"
#include "softshadow/softshadow.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;

RenderSettings withSamples(int samples) {
    RenderSettings s;
    s.samples = samples;
    return s;
}

bool rayHitsBox(const Ray& r, const glm::vec3& lo, const glm::vec3& hi) {
    float t0 = 0.0f, t1 = 1e30f;
    for (int k = 0; k < 3; ++k) {
        float inv = 1.0f / r.direction[k];
        float a = (lo[k] - r.origin[k]) * inv, b = (hi[k] - r.origin[k]) * inv;
        t0 = std::max(t0, std::min(a, b));
        t1 = std::min(t1, std::max(a, b));
    }
    return t0 <= t1;
}

// Convex hull (counter-clockwise in a y-up frame) by the monotone chain.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> p) {
    std::sort(p.begin(), p.end(), [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
        h[k++] = p[i - 1];
    }
    h.resize(k - 1);
    return h;
}

// Distance from q to the polygon's boundary, positive inside, negative outside.
double signedDepth(const std::vector<glm::dvec2>& poly, glm::dvec2 q) {
    double dist = 1e300;
    bool inside = true;
    for (size_t i = 0; i < poly.size(); ++i) {
        glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()], ab = b - a;
        double side = ab.x * (q.y - a.y) - ab.y * (q.x - a.x);
        if (side < 0) inside = false;  // the hull is counter-clockwise in its frame
        double t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
        dist = std::min(dist, glm::length(q - (a + t * ab)));
    }
    return inside ? dist : -dist;
}

// The perspective camera used by the alignment check, and an orthographic one (Blender's
// ortho cameras start their rays on the near plane, not at the eye).
Camera alignmentCamera(bool orthographic) {
    Camera cam = makeLookAtCamera({0.3f, -1.0f, 9.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                  glm::radians(35.0f), 160, 120, 0.1f, 50.0f);
    if (orthographic) cam.projection = glm::ortho(-3.2f, 3.2f, -2.4f, 2.4f, 0.1f, 50.0f);
    return cam;
}

void checkHardShadowAlignment(const Camera& cam) {
    const glm::vec3 lo(-0.5f, -0.5f, 1.0f), hi(0.5f, 0.5f, 1.2f), lamp(1.0f, 0.6f, 5.0f);
    Scene scene;
    scene.addMesh(test::makeGround(4.0f, 0.0f, SS_MESH_RECEIVE));
    scene.addMesh(test::makeBox(lo, hi, SS_MESH_CAST | SS_MESH_RECEIVE));
    Light point;
    point.name = "tiny";
    point.type = LightType::Point;
    point.radius = 0.0f;
    point.lightToWorld = glm::translate(glm::mat4(1.0f), lamp);
    scene.addLight(point);
    scene.setCamera(cam);
    Layers out = renderReference(scene, 0, withSamples(1));
    const Image& v = layer(out, "V");

    // The shadow of a convex box from a point onto z = 0 is the hull of its corners' projections;
    // its image is the hull of their pixel positions (a plane-to-image map keeps lines straight).
    std::vector<glm::dvec2> corners;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 c(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        glm::vec3 onGround = lamp + (lamp.z / (lamp.z - c.z)) * (c - lamp);
        glm::vec2 px = cam.worldToPixel(onGround);
        corners.push_back({px.x, -px.y});  // y up so the hull is counter-clockwise
    }
    std::vector<glm::dvec2> hull = convexHull(corners);
    int inside = 0, outside = 0, wrong = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            if (rayHitsBox(cam.pixelRay(x + 0.5f, y + 0.5f), lo, hi)) continue;  // sees the box
            double depth = signedDepth(hull, {x + 0.5, -(y + 0.5)});
            // A margin of 0.75 px: the edge is exact, the pixel centre only rounds in float.
            if (depth > 0.75) {
                ++inside;
                if (v.at(x, y) != 0.0f) ++wrong;
            } else if (depth < -0.75) {
                ++outside;
                if (v.at(x, y) != 1.0f) ++wrong;
            }
        }
    EXPECT_GT(inside, 300);
    EXPECT_GT(outside, 10000);
    EXPECT_EQ(wrong, 0) << "pixels disagreeing with the analytic shadow outline (" << inside
                        << " inside, " << outside << " outside tested)";
}

TEST(ReferenceRender, HardShadowLandsWhereTheProjectionSays) {
    checkHardShadowAlignment(alignmentCamera(false));
}

TEST(ReferenceRender, HardShadowLandsWhereTheProjectionSaysOrthographic) {
    Camera cam = alignmentCamera(true);
    ASSERT_TRUE(cam.isOrthographic());
    checkHardShadowAlignment(cam);
}

// Ground and a box that does not cast, seen from low so the upper rows see only sky.
Scene unshadowedScene(uint32_t boxFlags) {
    Scene scene;
    scene.addMesh(test::makeGround(3.0f, 0.0f, SS_MESH_RECEIVE | SS_MESH_CAST));
    scene.addMesh(test::makeBox({-0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 1.0f}, boxFlags));
    // Behind the box as the camera sees it, so its shadow falls towards the camera and its
    // -y face (facing the camera) has the whole light below its horizon.
    scene.addLight(test::makeDiskLight({0.5f, 1.5f, 4.0f}, 2.0f));
    scene.setCamera(makeLookAtCamera({0.0f, -6.0f, 2.0f}, {0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, 1.0f},
                                     glm::radians(50.0f), 96, 64, 0.1f, 50.0f));
    return scene;
}

TEST(ReferenceRender, NothingCastsMeansVIsExactlyOneAndSkyIsOutsideTheMask) {
    Scene scene = unshadowedScene(SS_MESH_RECEIVE);  // the box receives but does not cast
    Layers out = renderReference(scene, 0, withSamples(64));
    const Image &v = layer(out, "V"), &mask = layer(out, "mask");
    TraceScene trace(scene);
    int lit = 0, sky = 0, turnedAway = 0;
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x) {
            EXPECT_EQ(v.at(x, y), 1.0f) << x << "," << y;
            SurfaceHit h = trace.intersect(scene.camera().pixelRay(x + 0.5f, y + 0.5f), 0.0f, 1e30f);
            if (!h.hit) {
                ++sky;
                EXPECT_EQ(mask.at(x, y), 0.0f) << x << "," << y;
            } else if (h.mesh == 1 && h.normal.y < -0.99f) {
                ++turnedAway;
                EXPECT_EQ(mask.at(x, y), 0.0f) << x << "," << y << ": face turned away from the light";
            }
            lit += mask.at(x, y) == 1.0f;
        }
    EXPECT_GT(sky, 500);
    EXPECT_GT(turnedAway, 100);
    EXPECT_GT(lit, 2000);
    for (int x = 0; x < v.width; ++x) EXPECT_EQ(mask.at(x, 0), 0.0f);  // the top row is sky
}

TEST(ReferenceRender, NonReceivingMeshAndFacesTurnedAwayAreOutsideTheMask) {
    Scene scene = unshadowedScene(SS_MESH_CAST);  // the box casts but does not receive
    Layers out = renderReference(scene, 0, withSamples(16));
    const Image &v = layer(out, "V"), &mask = layer(out, "mask");
    TraceScene trace(scene);
    int onBox = 0, shadowed = 0;
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x) {
            SurfaceHit h = trace.intersect(scene.camera().pixelRay(x + 0.5f, y + 0.5f), 0.0f, 1e30f);
            if (h.hit && h.mesh == 1) {
                ++onBox;
                EXPECT_EQ(mask.at(x, y), 0.0f);
                EXPECT_EQ(v.at(x, y), 1.0f);
            }
            shadowed += mask.at(x, y) == 1.0f && v.at(x, y) < 0.5f;
        }
    EXPECT_GT(onBox, 100);
    EXPECT_GT(shadowed, 20);  // the box's shadow on the ground is there

    // A one-sided disk light turned to face up reaches nothing below it: E_L = 0 everywhere.
    Scene up = unshadowedScene(SS_MESH_RECEIVE);
    Light flipped = test::makeDiskLight({0.0f, 0.0f, 4.0f}, 2.0f, "up");
    flipped.lightToWorld = glm::rotate(flipped.lightToWorld, float(M_PI), glm::vec3(1, 0, 0));
    up.addLight(flipped);
    Layers back = renderReference(up, 1, withSamples(16));
    for (float m : layer(back, "mask").pixels) ASSERT_EQ(m, 0.0f);
    for (float x : layer(back, "V").pixels) ASSERT_EQ(x, 1.0f);
}

Light lightOfType(LightType type) {
    Light l;
    l.name = lightTypeName(type);
    l.type = type;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.2f, 4.0f)) *
                     glm::rotate(glm::mat4(1.0f), -0.35f, glm::vec3(1.0f, 0.0f, 0.0f));  // towards -y
    l.size = 1.2f;
    l.sizeY = 0.6f;
    l.radius = 0.3f;
    l.spotSize = glm::radians(55.0f);
    l.spotBlend = 0.2f;
    l.angle = glm::radians(8.0f);
    return l;
}

TEST(ReferenceRender, EveryLightTypeGivesSaneVisibility) {
    for (LightType type : {LightType::Disk, LightType::Ellipse, LightType::Square, LightType::Rectangle,
                           LightType::Point, LightType::Spot, LightType::Sun}) {
        test::SceneParams p;
        p.width = 64;
        p.height = 48;
        Scene scene = test::sceneBox(p);
        int index = scene.addLight(lightOfType(type));
        Layers out = renderReference(scene, index, withSamples(16));
        addClassLayers(out);  // what the renderer adds to every method's V and mask
        const Image &v = layer(out, "V"), &mask = layer(out, "mask");
        const Image &umbra = layer(out, "umbra"), &penumbra = layer(out, "penumbra");
        int inMask = 0, dark = 0;
        for (size_t i = 0; i < v.pixels.size(); ++i) {
            float x = v.pixels[i], m = mask.pixels[i];
            ASSERT_TRUE(std::isfinite(x)) << lightTypeName(type);
            ASSERT_GE(x, 0.0f) << lightTypeName(type);
            ASSERT_LE(x, 1.0f) << lightTypeName(type);
            ASSERT_TRUE(m == 0.0f || m == 1.0f);
            if (m == 0.0f) {
                ASSERT_EQ(x, 1.0f);
            }
            inMask += m == 1.0f;
            dark += m == 1.0f && x < 0.5f;
            EXPECT_EQ(umbra.pixels[i], (m == 1.0f && x < kUmbraThreshold) ? 1.0f : 0.0f);
            EXPECT_EQ(penumbra.pixels[i], (m == 1.0f && x >= kUmbraThreshold && x <= kLitThreshold) ? 1.0f : 0.0f);
        }
        EXPECT_GT(inMask, int(v.pixels.size()) / 10) << lightTypeName(type);
        EXPECT_GT(dark, 30) << lightTypeName(type) << ": the box must cast a shadow";
        if (type == LightType::Spot) {  // a 55 degree cone from 4 m lights a ~2 m disk only
            EXPECT_LT(inMask, int(v.pixels.size()) / 2);
        }
    }
}

TEST(ReferenceRender, SameSeedSameImageWhateverTheThreadCount) {
    Scene scene = test::sceneBox({1.5f, 4.0f, 0.0f, 48, 36});
    RenderSettings one = withSamples(32), two = withSamples(32), other = withSamples(32);
    one.options["threads"] = "1";
    two.options["threads"] = "2";
    other.seed = 2;
    Layers a = renderReference(scene, 0, one), b = renderReference(scene, 0, two),
           c = renderReference(scene, 0, other);
    EXPECT_EQ(layer(a, "V").pixels, layer(b, "V").pixels);
    EXPECT_EQ(layer(a, "mask").pixels, layer(b, "mask").pixels);
    EXPECT_NE(layer(a, "V").pixels, layer(c, "V").pixels);  // the penumbra moves with the seed
    EXPECT_EQ(layer(a, "mask").pixels, layer(c, "mask").pixels);
}

TEST(ReferenceRender, ProgressIsReportedAndCanCancel) {
    Scene scene = test::sceneBox({1.5f, 4.0f, 0.0f, 64, 48});
    RenderSettings s = withSamples(8);
    std::vector<float> seen;
    s.progress = [&](float f, const char*) {
        seen.push_back(f);
        return true;
    };
    renderReference(scene, 0, s);
    ASSERT_GE(seen.size(), 2u);
    EXPECT_EQ(seen.front(), 0.0f);
    EXPECT_EQ(seen.back(), 1.0f);
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));

    s.progress = [](float, const char*) { return false; };
    try {
        renderReference(scene, 0, s);
        ADD_FAILURE() << "a cancelled render returned";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_CANCELLED);
    }
}

TEST(ReferenceRender, EmbreeSceneIsBuiltOncePerGeometry) {
    Scene scene = test::sceneBox({1.5f, 4.0f, 0.0f, 16, 12});
    TraceSceneCache cache;
    renderReference(scene, 0, withSamples(4), &cache);
    renderReference(scene, 0, withSamples(4), &cache);
    EXPECT_EQ(cache.builds(), 1);
    scene.updateLight(0, scene.lights()[0]);  // a light edit: the BVH holds meshes only
    renderReference(scene, 0, withSamples(4), &cache);
    EXPECT_EQ(cache.builds(), 1);
    scene.addMesh(test::makeBox({2.0f, 2.0f, 0.5f}, {2.5f, 2.5f, 1.0f}, SS_MESH_CAST));
    renderReference(scene, 0, withSamples(4), &cache);
    EXPECT_EQ(cache.builds(), 2);
}

// Two levels: a moved mesh keeps its BVH (its instance alone changes) and is traced where it is
// now, as in a scene built with it there; one flattened by its transform (no inverse to trace it
// in its own coordinates) is traced in world space, from a BVH of its own.
TEST(ReferenceRender, AMovedMeshKeepsItsBvhAndIsTracedWhereItIsNow) {
    const test::SceneParams p{1.5f, 4.0f, 0.0f, 48, 36};
    Scene scene = test::sceneBox(p);
    ASSERT_EQ(scene.meshes().size(), 2u);
    TraceSceneCache cache;
    const Layers before = renderReference(scene, 0, withSamples(16), &cache);
    EXPECT_EQ(cache.meshBvhBuilds(), 2);
    // A scene built with the box's moved coordinates given as they are.
    auto builtThere = [&](const Scene& moved) {
        Scene fresh = test::sceneBox(p);
        Mesh box = moved.meshes()[1];
        box.objectPositions = box.positions;  // fresh's box has the identity, kept by updateMesh
        fresh.updateMesh(1, box);
        return fresh;
    };

    for (const glm::mat4& transform :
         {glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, -0.3f, 0.2f)),
          glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0.0f, 0.0f, 1.0f))}) {
        scene.setMeshTransform(1, transform);
        cache.dropStale(scene);  // as the renderer does between renders
        const Layers moved = renderReference(scene, 0, withSamples(16), &cache);
        EXPECT_EQ(cache.meshBvhBuilds(), 2);

        const Layers there = renderReference(builtThere(scene), 0, withSamples(16));
        const Image& a = layer(moved, "V");
        const Image& b = layer(there, "V");
        int differ = 0, shadowed = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            differ += std::abs(a.pixels[i] - b.pixels[i]) > 1e-6f;
            shadowed += b.pixels[i] < 1.0f;
        }
        EXPECT_GT(shadowed, 50);
        EXPECT_LE(differ, 2) << "of " << shadowed << " shadowed pixels";
        EXPECT_EQ(layer(moved, "mask").pixels, layer(there, "mask").pixels);
        EXPECT_NE(a.pixels, layer(before, "V").pixels);
    }

    scene.setMeshTransform(1, glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, 0.0f)));
    cache.dropStale(scene);
    const Layers flat = renderReference(scene, 0, withSamples(16), &cache);
    EXPECT_EQ(cache.meshBvhBuilds(), 3);
    EXPECT_EQ(layer(flat, "V").pixels, layer(renderReference(builtThere(scene), 0, withSamples(16)), "V").pixels);
}

TEST(ReferenceRender, BadLightIndexIsRejected) {
    Scene scene = test::sceneBox({1.5f, 4.0f, 0.0f, 16, 12});
    try {
        renderReference(scene, 3, withSamples(4));
        ADD_FAILURE() << "light 3 of 1 accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
    }
}

TEST(ReferenceRender, RunsThroughTheRendererWithoutGl) {
    std::unique_ptr<Method> method = createMethod("reference");
    EXPECT_STREQ(method->name(), "reference");
    EXPECT_FALSE(method->needsGl());
    Scene scene = test::sceneBox({1.5f, 4.0f, 0.0f, 40, 30});
    RenderSettings s = withSamples(16);
    Renderer renderer(SS_BACKEND_AUTO);
    std::string used;
    Layers viaRenderer = renderer.render(scene, 0, "reference", s, &used);
    EXPECT_EQ(used, "reference");
    Layers direct = renderReference(scene, 0, s);
    EXPECT_EQ(layer(viaRenderer, "V").pixels, layer(direct, "V").pixels);
    EXPECT_EQ(layer(viaRenderer, "mask").pixels, layer(direct, "mask").pixels);
}

}  // namespace
}  // namespace ss
