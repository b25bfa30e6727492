// How the stage benchmarks' meshes are built (bench_meshes.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "bench_meshes.h"

#include <cmath>

#include "softshadow/softshadow.h"

namespace ss::bench {

Mesh uvSphere(int m, float r, glm::vec3 c, uint32_t flags) {
    Mesh mesh;
    mesh.name = "sphere";
    const int nu = 2 * m, nv = m + 1;  // nv - 1 latitude bands
    mesh.positions.push_back(c + glm::vec3(0, 0, r));
    for (int j = 1; j < nv; ++j) {
        float th = float(M_PI) * float(j) / float(nv);
        for (int i = 0; i < nu; ++i) {
            float ph = 2.0f * float(M_PI) * float(i) / float(nu);
            mesh.positions.push_back(c + r * glm::vec3(std::sin(th) * std::cos(ph),
                                                       std::sin(th) * std::sin(ph), std::cos(th)));
        }
    }
    mesh.positions.push_back(c + glm::vec3(0, 0, -r));
    const uint32_t south = uint32_t(mesh.positions.size() - 1);
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
    ground.positions = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
    ground.triangles = {{0, 1, 2}, {0, 2, 3}};
    ground.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    ground.finalize();
    return ground;
}

}  // namespace ss::bench
