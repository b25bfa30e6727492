// Whether scene files load, save and round-trip exactly, build closed outward primitives, and
// reject bad input with the file, the JSON path and the problem in the message.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/primitives.h"
#include "io/scene_file.h"

namespace ss {
namespace {

namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("ss_io_scene_" + std::to_string(getpid()) + "_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream(p) << text;
}

// A minimal valid scene with hooks to break one part of it.
std::string sceneText(const std::string& positions = "[0,0,0, 1,0,0, 0,1,0, 0,0,1]",
                      const std::string& triangles = "[0,2,1, 0,1,3, 1,2,3, 0,3,2]",
                      const std::string& lightSize = "0.5") {
    return R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"fov_y_degrees":40,"width":32,"height":24},
      "lights":[{"name":"Key","type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":)" +
           lightSize + R"(}],
      "meshes":[{"name":"Tet","positions":)" + positions + R"(,"triangles":)" + triangles + "}]}";
}

// Expects parsing to fail with `status` and every fragment in the message.
void expectError(const std::string& text, ss_status status, std::initializer_list<std::string> fragments) {
    try {
        parseSceneText(text, ".", "bad.json");
        FAIL() << "expected an error containing " << *fragments.begin();
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), status) << e.what();
        std::string msg = e.what();
        EXPECT_NE(msg.find("bad.json"), std::string::npos) << msg;
        for (const std::string& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
    }
}

TEST(IoSceneFile, ValidSceneLoads) {
    Scene s = parseSceneText(sceneText(), ".", "ok.json");
    ASSERT_EQ(s.meshes().size(), 1u);
    EXPECT_TRUE(s.meshes()[0].report.closedManifold());
    ASSERT_EQ(s.lights().size(), 1u);
    // position/direction: the light emits along its local -Z, which must be the given direction.
    glm::vec3 d = s.lights()[0].direction();
    EXPECT_NEAR(d.z, -1.0f, 1e-6f);
    EXPECT_EQ(s.camera().width, 32);
    EXPECT_EQ(s.viewLayer(), "ViewLayer");
}

TEST(IoSceneFile, ConvenienceCameraMatchesLookAt) {
    Scene s = parseSceneText(sceneText(), ".", "ok.json");
    Camera expected = makeLookAtCamera({3, -3, 3}, {0, 0, 0}, {0, 0, 1}, glm::radians(40.0f), 32, 24, 0.1f, 1000.0f);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(s.camera().worldToCamera[c][r], expected.worldToCamera[c][r], 1e-6f);
            EXPECT_NEAR(s.camera().projection[c][r], expected.projection[c][r], 1e-6f);
        }
}

TEST(IoSceneFile, DemoSceneLoads) {
    Scene s = loadSceneFile(SS_SOURCE_DIR "/examples/scenes/demo.json");
    EXPECT_EQ(s.camera().width, 640);
    EXPECT_EQ(s.camera().height, 480);
    ASSERT_EQ(s.lights().size(), 1u);
    EXPECT_EQ(s.lights()[0].type, LightType::Disk);
    ASSERT_GE(s.meshes().size(), 2u);
    for (const Mesh& m : s.meshes()) {
        if (m.name == "Ground") continue;
        EXPECT_TRUE(m.report.closedManifold()) << m.name;
    }
}

TEST(IoSceneFile, ClosedPrimitivesAreOutwardManifolds) {
    struct Case {
        const char* name;
        TriangleSoup soup;
        double volume, tolerance;  // closed-form volume; the tolerance covers faceting
    };
    const double pi = M_PI;
    std::vector<Case> cases = {
        {"box", makeBox({1, 2, 3}, 3), 6.0, 1e-5},
        // A 64x32 UV sphere inscribes the sphere: within 1 % of 4/3 pi r^3.
        {"uv_sphere", makeUvSphere(1.0f, 64, 32), 4.0 / 3.0 * pi, 0.01 * 4.0 / 3.0 * pi},
        {"torus", makeTorus(1.0f, 0.25f, 96, 32), 2.0 * pi * pi * 1.0 * 0.0625, 0.01 * 2 * pi * pi * 0.0625},
        {"cylinder", makeCylinder(0.5f, 2.0f, 96), pi * 0.25 * 2.0, 0.01 * pi * 0.5},
    };
    for (Case& c : cases) {
        Mesh m;
        m.name = c.name;
        m.objectPositions = c.soup.positions;
        m.triangles = c.soup.triangles;
        m.finalize();
        EXPECT_TRUE(m.report.closedManifold()) << c.name << ": open " << m.report.openEdges << " non-manifold "
                                               << m.report.nonManifoldEdges << " inconsistent "
                                               << m.report.inconsistentEdges;
        EXPECT_EQ(m.report.degenerateFaces, 0u) << c.name;
        EXPECT_NEAR(signedVolume(c.soup), c.volume, c.tolerance) << c.name << " (positive = outward)";
    }
}

TEST(IoSceneFile, OpenPrimitivesFacePlusZ) {
    for (TriangleSoup soup : {makePlane(2, 3, 4), makeDisk(1, 16)}) {
        Mesh m;
        m.objectPositions = soup.positions;
        m.triangles = soup.triangles;
        m.finalize();
        EXPECT_EQ(m.report.inconsistentEdges, 0u);
        EXPECT_EQ(m.report.nonManifoldEdges, 0u);
        for (const glm::vec3& n : m.faceNormals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
    }
}

// A placed mesh keeps its object-space vertices and its matrix, as the C API's meshes do: the
// triangles stay as given (a mirroring matrix included) and the world vertices are derived.
TEST(IoSceneFile, TransformIsTheMeshsMatrix) {
    std::string text = R"({"format":"softshadow-scene","version":1,"meshes":[
        {"name":"B","primitive":{"type":"box","size":1},"translate":[1,2,3],"rotate_deg":[10,20,30],"scale":[-1,2,0.5]}]})";
    const Scene scene = parseSceneText(text, ".", "t.json");
    const Mesh& m = scene.meshes()[0];
    TriangleSoup box = makeBox({1, 1, 1}, 1);
    EXPECT_EQ(m.objectPositions, box.positions);
    EXPECT_EQ(m.triangles, box.triangles);
    glm::mat4 expected = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3));
    expected = glm::rotate(expected, glm::radians(30.0f), glm::vec3(0, 0, 1));
    expected = glm::rotate(expected, glm::radians(20.0f), glm::vec3(0, 1, 0));
    expected = glm::rotate(expected, glm::radians(10.0f), glm::vec3(1, 0, 0));
    expected = glm::scale(expected, glm::vec3(-1, 2, 0.5f));
    EXPECT_EQ(m.objectToWorld, expected);
    for (size_t i = 0; i < m.positions.size(); ++i)
        EXPECT_EQ(m.positions[i], glm::vec3(expected * glm::vec4(box.positions[i], 1.0f))) << i;
}

TEST(IoSceneFile, TransformMustBeAffine) {
    std::string text = R"({"format":"softshadow-scene","version":1,"meshes":[
        {"name":"B","primitive":{"type":"box"},"transform":[1,0,0,0, 0,1,0,0, 0,0,1,0.5, 0,0,0,1]}]})";
    try {
        parseSceneText(text, ".", "t.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_IO);
        EXPECT_NE(std::string(e.what()).find("meshes[0].transform: is not affine"), std::string::npos) << e.what();
    }
}

// Saving writes the object-space vertices and the matrix ("transform"), the identity not at all,
// so a saved scene loads as the very meshes it was, and a file without transforms stays one.
TEST(IoSceneFile, SaveKeepsTheTransform) {
    fs::path dir = tempDir("transform");
    std::string text = R"({"format":"softshadow-scene","version":1,"meshes":[
        {"name":"Moved","primitive":{"type":"uv_sphere","segments":7,"rings":5},"rotate_deg":[33,-71,12.5],"scale":0.3,
         "translate":[0.1,0.7,-2.9]},
        {"name":"Still","positions":[0,0,0, 1,0,0, 0,1,0],"triangles":[0,1,2]}]})";
    Scene a = parseSceneText(text, ".", "t.json");
    saveSceneFile(a, (dir / "s.json").string());
    nlohmann::json saved = nlohmann::json::parse(std::ifstream(dir / "s.json"));
    EXPECT_EQ(saved["meshes"][0]["transform"].size(), 16u);
    EXPECT_FALSE(saved["meshes"][1].contains("transform"));
    EXPECT_EQ(saved["meshes"][0]["positions"].size(), 3 * a.meshes()[0].objectPositions.size());
    Scene b = loadSceneFile((dir / "s.json").string());
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(b.meshes()[i].objectPositions, a.meshes()[i].objectPositions);
        EXPECT_EQ(b.meshes()[i].objectToWorld, a.meshes()[i].objectToWorld);
        EXPECT_EQ(b.meshes()[i].positions, a.meshes()[i].positions);
        EXPECT_EQ(b.meshes()[i].faceNormals, a.meshes()[i].faceNormals);
    }
    EXPECT_TRUE(a.meshes()[0].transformed());
    EXPECT_FALSE(b.meshes()[1].transformed());
    fs::remove_all(dir);
}

// A negative scale mirrors the mesh as Blender does (its outside stays outside); saving keeps
// its triangles in their given order and the matrix, so it loads as the same mirrored mesh.
TEST(IoSceneFile, AMirroringScaleIsOutwardAndSavedAsGiven) {
    fs::path dir = tempDir("mirror");
    std::string text = R"({"format":"softshadow-scene","version":1,"meshes":[
        {"name":"Mirrored","primitive":{"type":"uv_sphere","segments":7,"rings":5},"scale":[-0.5,0.3,0.4],
         "translate":[0.1,0.7,-2.9]}]})";
    Scene a = parseSceneText(text, ".", "t.json");
    const Mesh& m = a.meshes()[0];
    ASSERT_TRUE(m.mirrored);
    const glm::vec3 centre(0.1f, 0.7f, -2.9f);
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        if (m.faceNormals[f] == glm::vec3(0.0f)) continue;
        const glm::uvec3& t = m.triangles[f];
        const glm::vec3 middle = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0f;
        EXPECT_GT(glm::dot(m.faceNormals[f], middle - centre), 0.0f) << "face " << f << " points inward";
    }
    saveSceneFile(a, (dir / "s.json").string());
    Scene b = loadSceneFile((dir / "s.json").string());
    EXPECT_EQ(b.meshes()[0].triangles, m.triangles);
    EXPECT_EQ(b.meshes()[0].objectToWorld, m.objectToWorld);
    EXPECT_TRUE(b.meshes()[0].mirrored);
    EXPECT_EQ(b.meshes()[0].faceNormals, m.faceNormals);
    fs::remove_all(dir);
}

TEST(IoSceneFile, PrimitiveTransformInFile) {
    std::string text = R"({"format":"softshadow-scene","version":1,"meshes":[
        {"name":"B","primitive":{"type":"box","size":1},"translate":[0,0,5],"rotate_deg":[0,0,90],"scale":2}]})";
    Scene s = parseSceneText(text, ".", "t.json");
    Bounds b = s.bounds();
    EXPECT_NEAR(b.lo.z, 4.0f, 1e-5f);
    EXPECT_NEAR(b.hi.z, 6.0f, 1e-5f);
    EXPECT_NEAR(b.hi.x, 1.0f, 1e-5f);
}

void expectSameScene(const Scene& a, const Scene& b) {
    ASSERT_EQ(a.meshes().size(), b.meshes().size());
    for (size_t i = 0; i < a.meshes().size(); ++i) {
        EXPECT_EQ(a.meshes()[i].name, b.meshes()[i].name);
        EXPECT_EQ(a.meshes()[i].flags, b.meshes()[i].flags);
        EXPECT_EQ(a.meshes()[i].objectPositions, b.meshes()[i].objectPositions);  // bit-exact floats
        EXPECT_EQ(a.meshes()[i].objectToWorld, b.meshes()[i].objectToWorld);
        EXPECT_EQ(a.meshes()[i].positions, b.meshes()[i].positions);
        EXPECT_EQ(a.meshes()[i].triangles, b.meshes()[i].triangles);
    }
    ASSERT_EQ(a.lights().size(), b.lights().size());
    for (size_t i = 0; i < a.lights().size(); ++i) {
        EXPECT_EQ(a.lights()[i].name, b.lights()[i].name);
        EXPECT_EQ(a.lights()[i].type, b.lights()[i].type);
        EXPECT_EQ(a.lights()[i].lightToWorld, b.lights()[i].lightToWorld);
        EXPECT_EQ(a.lights()[i].size, b.lights()[i].size);
        EXPECT_EQ(a.lights()[i].castShadows, b.lights()[i].castShadows);
    }
    EXPECT_EQ(a.camera().worldToCamera, b.camera().worldToCamera);
    EXPECT_EQ(a.camera().projection, b.camera().projection);
    EXPECT_EQ(a.camera().width, b.camera().width);
    EXPECT_EQ(a.viewLayer(), b.viewLayer());
}

TEST(IoSceneFile, SaveLoadRoundTripIsExactInline) {
    fs::path dir = tempDir("inline");
    Scene a = loadSceneFile(SS_SOURCE_DIR "/examples/scenes/demo.json");
    saveSceneFile(a, (dir / "s.json").string());
    Scene b = loadSceneFile((dir / "s.json").string());
    expectSameScene(a, b);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
    fs::remove_all(dir);
}

TEST(IoSceneFile, SaveLoadRoundTripIsExactWithExternalFiles) {
    fs::path dir = tempDir("external");
    Scene a = loadSceneFile(SS_SOURCE_DIR "/examples/scenes/demo.json");
    saveSceneFile(a, (dir / "s.json").string(), 0);  // every mesh external
    EXPECT_TRUE(fs::exists(dir / "s.0.positions.f32"));
    EXPECT_EQ(fs::file_size(dir / "s.1.triangles.u32"), a.meshes()[1].triangles.size() * 12);
    Scene b = loadSceneFile((dir / "s.json").string());
    expectSameScene(a, b);
    fs::remove_all(dir);
}

TEST(IoSceneFile, MissingFileIsNamed) {
    try {
        loadSceneFile("/nonexistent/scene.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_IO);
        EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
    }
}

TEST(IoSceneFile, MalformedJson) {
    expectError("{\"format\": \"softshadow-scene\", \"version\": 1,", SS_ERROR_IO, {"malformed JSON"});
    expectError(sceneText("[0,0,0, 1,0,NaN, 0,1,0, 0,0,1]"), SS_ERROR_IO, {"malformed JSON"});
}

TEST(IoSceneFile, NonNumberVertexNamesItsPath) {
    expectError(sceneText("[0,0,0, 1,0,\"NaN\", 0,1,0, 0,0,1]"), SS_ERROR_IO,
                {"meshes[0].positions[5]", "expected a number, got a string"});
    expectError(sceneText("[0,0,0, 1,0,0, 0,1,null, 0,0,1]"), SS_ERROR_IO,
                {"meshes[0].positions[8]", "expected a number, got null"});
    expectError(sceneText("[0,0,0, 1,0,0, 0,1e300,0, 0,0,1]"), SS_ERROR_IO,
                {"meshes[0].positions[7]", "out of range"});
}

TEST(IoSceneFile, IndexOutOfRangeNamesItsPath) {
    expectError(sceneText("[0,0,0, 1,0,0, 0,1,0, 0,0,1]", "[0,2,1, 0,1,3, 1,2,9, 0,3,2]"),
                SS_ERROR_INVALID_SCENE, {"meshes[0].triangles[8]", "vertex index 9", "4 vertices"});
    expectError(sceneText("[0,0,0, 1,0,0, 0,1,0, 0,0,1]", "[0,2,1, 0,1,-3, 1,2,3, 0,3,2]"), SS_ERROR_IO,
                {"meshes[0].triangles[5]"});
}

TEST(IoSceneFile, ZeroSizeLightNamesIt) {
    expectError(sceneText("[0,0,0, 1,0,0, 0,1,0, 0,0,1]", "[0,2,1, 0,1,3, 1,2,3, 0,3,2]", "0"),
                SS_ERROR_INVALID_SCENE, {"lights[0]", "light 'Key'", "size greater than zero"});
}

TEST(IoSceneFile, StructureErrors) {
    expectError(R"({"format":"other","version":1})", SS_ERROR_IO, {"format", "softshadow-scene"});
    expectError(R"({"format":"softshadow-scene","version":2})", SS_ERROR_IO, {"version 2 is newer"});
    expectError(R"({"format":"softshadow-scene"})", SS_ERROR_IO, {"version: is missing"});
    expectError(R"({"format":"softshadow-scene","version":1,"meshes":[{"name":"m","postions":[]}]})",
                SS_ERROR_IO, {"meshes[0]", "unknown key 'postions'"});
    expectError(R"({"format":"softshadow-scene","version":1,"lights":[{"name":"L","type":"area"}]})",
                SS_ERROR_IO, {"lights[0].type", "unknown light type 'area'"});
    expectError(R"({"format":"softshadow-scene","version":1,"meshes":[{"name":"m","primitive":{"type":"cone"}}]})",
                SS_ERROR_IO, {"meshes[0].primitive.type", "unknown primitive 'cone'"});
    expectError(R"({"format":"softshadow-scene","version":1,"meshes":[{"name":"m","positions":[0,0,0]}]})",
                SS_ERROR_IO, {"meshes[0].triangles: is missing"});
    expectError(R"({"format":"softshadow-scene","version":1,"camera":{"world_to_camera":[1,0,0,0],"projection":[],"width":4,"height":4}})",
                SS_ERROR_IO, {"camera.world_to_camera", "16 numbers"});
}

TEST(IoSceneFile, ExternalFileErrors) {
    fs::path dir = tempDir("external_bad");
    float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t tri[3] = {0, 1, 7};
    std::ofstream(dir / "p.f32", std::ios::binary).write(reinterpret_cast<char*>(xyz), sizeof xyz);
    std::ofstream(dir / "t.u32", std::ios::binary).write(reinterpret_cast<char*>(tri), sizeof tri);
    std::ofstream(dir / "short.u32", std::ios::binary).write(reinterpret_cast<char*>(tri), 5);
    auto scene = [&](const std::string& t) {
        return R"({"format":"softshadow-scene","version":1,"meshes":[{"name":"m","positions_file":"p.f32","triangles_file":")" +
               t + "\"}]}";
    };
    writeText(dir / "a.json", scene("missing.u32"));
    writeText(dir / "b.json", scene("short.u32"));
    writeText(dir / "c.json", scene("t.u32"));
    auto message = [&](const char* file) {
        try {
            loadSceneFile((dir / file).string());
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("a.json").find("meshes[0].triangles_file: mesh file"), std::string::npos) << message("a.json");
    EXPECT_NE(message("a.json").find("missing.u32' does not exist"), std::string::npos);
    EXPECT_NE(message("b.json").find("5 bytes"), std::string::npos) << message("b.json");
    EXPECT_NE(message("c.json").find("meshes[0]"), std::string::npos) << message("c.json");
    EXPECT_NE(message("c.json").find("vertex index 7"), std::string::npos) << message("c.json");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace ss
