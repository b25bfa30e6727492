// How the stage benchmarks' scenes, renderer and stage clock are made (bench_scenes.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "bench_scenes.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

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
