// How the stage benchmarks' scenes, renderer and stage clock are made (bench_scenes.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "bench_scenes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "io/primitives.h"
#include "softshadow/softshadow.h"

namespace ss::bench {

Mesh uvSphere(int m, float r, glm::vec3 c, uint32_t flags) {
    Mesh mesh;
    mesh.name = "sphere";
    const int nu = 2 * m, nv = m + 1;  // nv - 1 latitude bands
    mesh.objectPositions.push_back(c + glm::vec3(0, 0, r));
    for (int j = 1; j < nv; ++j) {
        float th = float(M_PI) * float(j) / float(nv);
        for (int i = 0; i < nu; ++i) {
            float ph = 2.0f * float(M_PI) * float(i) / float(nu);
            mesh.objectPositions.push_back(c + r * glm::vec3(std::sin(th) * std::cos(ph),
                                                             std::sin(th) * std::sin(ph), std::cos(th)));
        }
    }
    mesh.objectPositions.push_back(c + glm::vec3(0, 0, -r));
    const uint32_t south = uint32_t(mesh.objectPositions.size() - 1);
    auto at = [&](int j, int i) { return uint32_t(1 + (j - 1) * nu + (i % nu)); };
    for (int i = 0; i < nu; ++i) mesh.triangles.push_back({0, at(1, i), at(1, i + 1)});
    for (int j = 1; j + 1 < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            mesh.triangles.push_back({at(j, i), at(j + 1, i), at(j + 1, i + 1)});
            mesh.triangles.push_back({at(j, i), at(j + 1, i + 1), at(j, i + 1)});
        }
    for (int i = 0; i < nu; ++i) mesh.triangles.push_back({south, at(nv - 1, i + 1), at(nv - 1, i)});
    mesh.flags = flags;
    mesh.finalize();
    return mesh;
}

Mesh groundSquare(float half) {
    Mesh ground;
    ground.name = "ground";
    ground.objectPositions = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
    ground.triangles = {{0, 1, 2}, {0, 2, 3}};
    ground.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    ground.finalize();
    return ground;
}

Scene sphereOverGround(int m, uint32_t sphereFlags, LightType light, int resolution) {
    Scene s;
    s.addMesh(groundSquare(6.0f));
    s.addMesh(uvSphere(m, 0.8f, {0, 0, 1.3f}, sphereFlags));
    Light l;
    l.type = light;
    l.name = light == LightType::Disk ? "Disk" : "Area";
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.8f, 4.0f));
    l.size = 1.5f;
    l.sizeY = light == LightType::Disk ? 1.5f : 1.0f;
    s.addLight(l);
    s.setCamera(makeLookAtCamera({0, -2.5f, 8}, {0, 0, 0}, {0, 1, 0}, glm::radians(40.0f), resolution, resolution,
                                 0.1f, 50.0f));
    return s;
}

namespace {

Mesh partMesh(TriangleSoup soup, const glm::mat4& placed) {
    Mesh m;
    m.name = "part";
    m.objectPositions = std::move(soup.positions);
    m.triangles = std::move(soup.triangles);
    m.objectToWorld = placed;
    m.flags = SS_MESH_CAST;
    m.finalize();
    return m;
}

Mesh boxPart(const glm::vec3& lo, const glm::vec3& hi) {
    return partMesh(makeBox(hi - lo, 1), glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)));
}

// A cylinder along z (up) or, with `alongX`, along x, centred at c.
Mesh cylinderPart(const glm::vec3& c, float radius, float length, int segments, bool alongX) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), c);
    if (alongX) m = glm::rotate(m, glm::radians(90.0f), glm::vec3(0, 1, 0));
    return partMesh(makeCylinder(radius, length, segments), m);
}

}  // namespace

Scene assembly(int tessellation, int resolution) {
    Scene s;
    s.addMesh(groundSquare(6.0f));
    const int t = std::max(1, tessellation);
    s.addMesh(boxPart({-1.0f, -0.7f, 0.60f}, {1.0f, 0.7f, 0.68f}));
    s.addMesh(boxPart({-1.0f, -0.7f, 0.68f}, {-0.92f, 0.7f, 1.20f}));
    s.addMesh(boxPart({0.92f, -0.7f, 0.68f}, {1.0f, 0.7f, 1.20f}));
    s.addMesh(cylinderPart({0.0f, 0.35f, 0.98f}, 0.07f, 2.2f, 24 * t, true));
    for (int i = 0; i < 5; ++i) s.addMesh(cylinderPart({-0.6f + 0.3f * float(i), 0.35f, 0.98f}, 0.22f, 0.04f, 32 * t, true));
    for (int i = 0; i < 24; ++i)
        s.addMesh(cylinderPart({-0.8f + 0.3f * float(i % 6), -0.55f + 0.25f * float(i / 6) * 0.5f, 0.8f}, 0.04f, 0.24f,
                               24 * t, false));
    for (int i = 0; i < 12; ++i) {
        float x = -0.8f + 0.14f * float(i);
        s.addMesh(boxPart({x, -0.1f, 0.68f}, {x + 0.02f, 0.1f, 0.95f}));
    }
    for (int i = 0; i < 8; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.6f + 0.17f * float(i), 1.32f));
        m = glm::rotate(m, glm::radians(90.0f), glm::vec3(0, 1, 0));
        s.addMesh(partMesh(makeCylinder(0.02f, 2.0f, 12 * t), m));
    }
    s.addMesh(boxPart({-1.0f, 0.05f, 1.20f}, {0.3f, 0.7f, 1.25f}));
    Light l;
    l.type = LightType::Disk;
    l.name = "Disk";
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.8f, 4.0f));
    l.size = l.sizeY = 1.5f;
    s.addLight(l);
    s.setCamera(makeLookAtCamera({0, -2.5f, 8}, {0, 0, 0}, {0, 1, 0}, glm::radians(40.0f), resolution, resolution,
                                 0.1f, 50.0f));
    return s;
}

Renderer& sharedRenderer() {
    static Renderer* r = new Renderer(SS_BACKEND_AUTO);  // joined by shutdownRenderThreads()
    return *r;
}

RenderSettings StageClock::watch(const RenderSettings& settings) {
    RenderSettings s = settings;
    marks.clear();
    s.progress = [this](float, const char* stage) {
        marks[stage] = Clock::now();
        return true;
    };
    return s;
}

double StageClock::render(const Scene& scene, const std::string& method, const RenderSettings& settings) {
    auto start = Clock::now();
    sharedRenderer().render(scene, 0, method, watch(settings), nullptr);
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double StageClock::ms(const std::string& from, const std::string& to) const {
    auto a = marks.find(from), b = marks.find(to);
    if (a == marks.end() || b == marks.end()) return 0.0;
    return std::chrono::duration<double, std::milli>(b->second - a->second).count();
}

void timeStages(benchmark::State& state, const Scene& scene, const std::string& method,
                const RenderSettings& settings, const std::vector<StageSpan>& spans,
                const std::function<void()>& beforeEach) {
    std::map<std::string, double> ms;
    StageClock clock;
    for (auto _ : state) {
        if (beforeEach) beforeEach();
        state.SetIterationTime(clock.render(scene, method, settings));
        for (const StageSpan& span : spans) ms[span.name] += clock.ms(span.from, span.to);
    }
    for (auto& [name, total] : ms) state.counters[name] = total / double(state.iterations());
}

}  // namespace ss::bench
