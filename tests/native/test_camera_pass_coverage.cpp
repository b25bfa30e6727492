// Is the camera pass, drawn from only the triangles that may cover a pixel centre, the pass drawn
// from every triangle bit for bit (positions, normals, ids and depth), whole and patched, and
// does it see through a cut-out's holes where the reference's camera rays do?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <cstring>
#include <iostream>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scene_cache/scene_cache.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/render_state.h"
#include "gl/render_thread.h"
#include "reference/camera_rays.h"
#include "reference/trace_scene.h"
#include "test_scenes.h"

namespace ss {
namespace {

constexpr uint32_t kBoth = SS_MESH_CAST | SS_MESH_RECEIVE;

struct GBuffer {
    std::vector<glm::vec4> colour[3];
    Image depth;
};

GBuffer read(const gl::Framebuffer& fb) {
    GBuffer out;
    for (int i = 0; i < 3; ++i) out.colour[i] = fb.readRgba(i);
    out.depth = fb.readDepth();
    return out;
}

// The camera pass drawn the plain way: every triangle of every mesh, one indexed draw per mesh
// (tests/shaders/camera/every_triangle.frag.glsl); see-through meshes whole, one draw per
// material, with the camera's alpha test.
GBuffer drawEveryTriangle(SceneCache& sceneCache, const Camera& cam) {
    gl::Framebuffer fb(cam.width, cam.height, {GL_RGBA32F, GL_RGBA32F, GL_RG32F}, GL_DEPTH_COMPONENT32F);  // as the camera pass
    fb.bind();
    fb.clearColor(0, glm::vec4(0.0f));
    fb.clearColor(1, glm::vec4(0.0f));
    fb.clearColor(2, glm::vec4(-1.0f, -1.0f, 0.0f, 0.0f));
    fb.clearDepth(1.0f);
    gl::apply(gl::states::opaque);
    const gl::Program& p = gl::program("common/mesh.vert.glsl", "camera/every_triangle.frag.glsl");
    const gl::Program& q = gl::program("camera/every_triangle_see_through.vert.glsl", "camera/every_triangle.frag.glsl",
                                       {"SEE_THROUGH"});
    const glm::mat4 cameraToWorld = glm::inverse(cam.worldToCamera);
    for (const gl::Program* prog : {&p, &q}) {
        prog->set("uWorldToClip", cam.worldToClip());
        prog->set("uWorldToView", cam.worldToCamera);
        prog->set("uCameraPosition", glm::vec3(cameraToWorld[3]));
        prog->set("uCameraForward", glm::normalize(-glm::vec3(cameraToWorld[2])));
        prog->set("uOrthographic", cam.isOrthographic() ? 1 : 0);
    }
    q.set("uCameraAlphaThreshold", kCameraAlphaThreshold);
    auto ids = [&](const gl::Program& prog) {
        return [&](const GpuMesh& m) {
            prog.set("uMeshIndex", m.meshIndex);
            prog.set("uReceives", m.receives() ? 1.0f : 0.0f);
        };
    };
    p.use();
    sceneCache.drawMeshesWhere(p, 0, std::nullopt, ids(p), -1, true);
    q.use();
    sceneCache.drawSeeThroughWhere(q, 0, ids(q));
    GBuffer out = read(fb);
    sceneCache.gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
    return out;
}

// Floats (of the three colours and the depth) whose bits differ.
size_t differences(const GBuffer& a, const GBuffer& b) {
    size_t n = 0;
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(a.colour[i].size(), b.colour[i].size());
        for (size_t p = 0; p < std::min(a.colour[i].size(), b.colour[i].size()); ++p)
            n += std::memcmp(&a.colour[i][p], &b.colour[i][p], sizeof(glm::vec4)) != 0;
    }
    EXPECT_EQ(a.depth.pixels.size(), b.depth.pixels.size());
    for (size_t p = 0; p < std::min(a.depth.pixels.size(), b.depth.pixels.size()); ++p)
        n += std::memcmp(&a.depth.pixels[p], &b.depth.pixels[p], sizeof(float)) != 0;
    return n;
}

// A dense torus and sphere (most triangles smaller than a pixel at 80 x 60) with a box and a
// ground; the sphere does not receive.
Scene denseScene() {
    Scene s;
    s.addMesh(test::makeGround(6.0f, 0.0f, kBoth));
    s.addMesh(test::makeTorus({0.3f, 0.2f, 0.8f}, 1.2f, 0.4f, 256, 128, kBoth));
    s.addMesh(test::makeUvSphere({-1.5f, -1.0f, 0.6f}, 0.5f, 96, 192, SS_MESH_CAST));
    s.addMesh(test::makeBox({1.2f, -1.8f, 0.0f}, {1.8f, -1.2f, 0.5f}, kBoth));
    s.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f));
    s.setCamera(test::makeTopCamera(80, 60));
    return s;
}

size_t triangleCount(const Scene& s) {
    size_t n = 0;
    for (const Mesh& m : s.meshes()) n += m.triangles.size();
    return n;
}

TEST(CameraPassCoverage, TheListedTrianglesDrawTheSamePassAsEveryTriangle) {
    Scene scene = denseScene();
    const size_t total = triangleCount(scene);
    gl::RenderThread thread(SS_BACKEND_AUTO);
    thread.run([&] {
        SceneCache sceneCache(scene);
        auto check = [&](const char* view) {
            const size_t before = sceneCache.stats().cameraPassTriangles;
            const GBuffer pass = read(sceneCache.cameraPass().framebuffer);
            const size_t drawn = sceneCache.stats().cameraPassTriangles - before;
            EXPECT_EQ(differences(pass, drawEveryTriangle(sceneCache, scene.camera())), 0u) << view;
            return drawn;
        };
        // From above: the torus and the sphere are mostly sub-pixel triangles, left out.
        EXPECT_LT(check("from above"), total / 3);

        // Low inside the scene: the ground crosses the near plane and reaches behind the eye.
        scene.setCamera(makeLookAtCamera({-3.5f, -3.0f, 0.25f}, {0.3f, 0.2f, 0.6f}, {0, 0, 1}, glm::radians(60.0f), 80,
                                         60, 0.5f, 40.0f));
        check("low, near plane crossing the ground");

        // Orthographic, looking along a slant.
        Camera ortho;
        ortho.worldToCamera = glm::lookAt(glm::vec3(4.0f, -5.0f, 4.0f), glm::vec3(0.0f), glm::vec3(0, 0, 1));
        ortho.projection = glm::ortho(-3.0f, 3.0f, -2.25f, 2.25f, 0.1f, 30.0f);
        ortho.width = 96;
        ortho.height = 72;
        scene.setCamera(ortho);
        ASSERT_TRUE(scene.camera().isOrthographic());
        check("orthographic");

        // The torus turned and moved by its matrix: the pass is patched where it was and is.
        scene.setCamera(test::makeTopCamera(80, 60));
        check("from above again");
        const int patched = sceneCache.stats().cameraPassesPatched;
        scene.setMeshTransform(1, glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, 0.3f, 0.2f)), 0.4f,
                                              glm::vec3(0.3f, 0.2f, 1.0f)));
        sceneCache.setScene(scene);
        check("torus moved by its matrix");
        EXPECT_EQ(sceneCache.stats().cameraPassesPatched, patched + 1);
    });
}

// What a GPU gets (CameraCulling::Clusters): every triangle of the clusters that reach
// the rectangle, the same pass; and Auto on this machine's llvmpipe tests each triangle.
TEST(CameraPassCoverage, AGpuIsHandedEveryTriangleOfTheClustersAndDrawsTheSamePass) {
    Scene scene = denseScene();
    const size_t total = triangleCount(scene);
    gl::RenderThread thread(SS_BACKEND_AUTO);
    thread.run([&] {
        SceneCache tested(scene), clusters(scene);
        clusters.setCameraCulling(CameraCulling::Clusters);
        const GBuffer a = read(tested.cameraPass().framebuffer);
        const GBuffer b = read(clusters.cameraPass().framebuffer);
        EXPECT_EQ(differences(a, b), 0u);
        EXPECT_LT(tested.stats().cameraPassTriangles, total / 3) << "llvmpipe: each triangle tested";
        EXPECT_EQ(clusters.stats().cameraPassTriangles, total) << "every mesh is in view from above";
    });
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {

// A cut-out card (test::sceneCardWithHole) beside the dense torus: the listed pass alpha-tests
// the card as the every-triangle pass does, and at each pixel it shows the surface the
// reference's camera ray meets (TraceScene::intersect passes the hole the same way).
TEST(CameraPassCoverage, ACutOutCardIsAlphaTestedAsTheCameraRaysSeeIt) {
    Scene scene = test::sceneCardWithHole(true, 96, 72);
    scene.addMesh(test::makeTorus({1.6f, 0.9f, 0.5f}, 0.5f, 0.2f, 128, 64, kBoth));
    gl::RenderThread thread(SS_BACKEND_AUTO);
    thread.run([&] {
        SceneCache sceneCache(scene);
        const GBuffer pass = read(sceneCache.cameraPass().framebuffer);
        EXPECT_EQ(differences(pass, drawEveryTriangle(sceneCache, scene.camera())), 0u);
        const CameraImages& images = sceneCache.cameraImages();
        const Camera& cam = scene.camera();
        TraceScene trace(scene);
        const CameraRays rays(cam);
        size_t disagree = 0, throughHole = 0, cardSeen = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                Ray ray;
                float tNear, tFar;
                ASSERT_TRUE(rays.span(x, y, &ray, &tNear, &tFar));
                const SurfaceHit hit = trace.intersect(ray, tNear, tFar);
                const int traced = hit.hit ? int(hit.mesh) : -1;
                const int drawn = int(images.ids[images.index(x, y)].x);
                disagree += traced != drawn;
                // The card's plane crossed inside the hole: the ground shows.
                const float t = (test::kCardHeight - ray.origin.z) / ray.direction.z;
                const glm::vec3 p = ray.origin + t * ray.direction;
                const bool inHole = std::abs(p.x) < test::kCardHoleHalf && std::abs(p.y) < test::kCardHoleHalf;
                throughHole += inHole && drawn == 0;
                cardSeen += drawn == 1;
            }
        EXPECT_GT(throughHole, 300u);
        EXPECT_GT(cardSeen, 300u);
        // Only pixel centres within rounding of an edge (the card's, the hole's, the torus') may
        // go either way.
        EXPECT_LE(disagree, 8u) << "of " << cam.width * cam.height << " pixels";
        std::cout << "  " << disagree << " pixels where the pass and the camera rays disagree, " << throughHole
                  << " seen through the hole\n";
    });
}

}  // namespace
}  // namespace ss
