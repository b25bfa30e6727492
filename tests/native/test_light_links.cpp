// Are light and shadow links kept, checked, renumbered and carried by scene files and the C API?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/error.h"
#include "core/scene.h"
#include "io/scene_file.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

constexpr uint32_t kBoth = SS_MESH_CAST | SS_MESH_RECEIVE;

Scene threeMeshes() {
    Scene s;
    Mesh ground = test::makeGround(4.0f, 0.0f, kBoth);
    ground.name = "Ground";
    s.addMesh(ground);
    Mesh a = test::makeBox({-0.9f, -0.5f, 0.6f}, {-0.2f, 0.2f, 1.0f}, kBoth);
    a.name = "A";
    s.addMesh(a);
    Mesh b = test::makeBox({0.3f, -0.2f, 0.4f}, {0.8f, 0.5f, 0.9f}, kBoth);
    b.name = "B";
    s.addMesh(b);
    s.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "Key"));
    s.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "Fill"));
    return s;
}

LightLinks links(std::optional<std::vector<int>> blockers, std::optional<std::vector<int>> receivers) {
    LightLinks l;
    l.blockers = std::move(blockers);
    l.receivers = std::move(receivers);
    return l;
}

TEST(LightLinks, UnlinkedLightsSeeEveryMesh) {
    Scene s = threeMeshes();
    for (int m = 0; m < 3; ++m) {
        EXPECT_TRUE(s.castsFor(m, 0));
        EXPECT_TRUE(s.receivesFrom(m, 0));
    }
}

TEST(LightLinks, SetsAreSortedAndApplyToTheirLightOnly) {
    Scene s = threeMeshes();
    const uint64_t key = s.light(0).version, fill = s.light(1).version;
    s.setLightLinks(0, links(std::vector<int>{2, 0, 2}, std::vector<int>{1}));
    EXPECT_EQ(*s.light(0).links.blockers, (std::vector<int>{0, 2}));
    EXPECT_TRUE(s.castsFor(0, 0));
    EXPECT_FALSE(s.castsFor(1, 0));  // A shadows nothing of Key
    EXPECT_TRUE(s.castsFor(1, 1));   // and still shadows Fill
    EXPECT_FALSE(s.receivesFrom(0, 0));
    EXPECT_TRUE(s.receivesFrom(1, 0));
    EXPECT_TRUE(s.receivesFrom(0, 1));
    EXPECT_NE(s.light(0).version, key);  // its shadow maps are made again
    EXPECT_EQ(s.light(1).version, fill);
}

TEST(LightLinks, TheMeshFlagsStillApply) {
    Scene s;
    Mesh ground = test::makeGround(4.0f, 0.0f, SS_MESH_RECEIVE);
    s.addMesh(ground);
    s.addLight(test::makeDiskLight({0.0f, 0.0f, 4.0f}, 1.0f, "Key"));
    s.setLightLinks(0, links(std::vector<int>{0}, std::vector<int>{0}));
    EXPECT_FALSE(s.castsFor(0, 0));  // linked as a blocker, but it does not cast
    EXPECT_TRUE(s.receivesFrom(0, 0));
}

TEST(LightLinks, SettingTheSameLinksKeepsTheLightVersion) {
    Scene s = threeMeshes();
    s.setLightLinks(0, links(std::vector<int>{0, 2}, std::nullopt));
    const uint64_t version = s.light(0).version;
    s.setLightLinks(0, links(std::vector<int>{2, 0}, std::nullopt));
    EXPECT_EQ(s.light(0).version, version);
    s.setLightLinks(0, links(std::nullopt, std::nullopt));
    EXPECT_NE(s.light(0).version, version);
    EXPECT_FALSE(s.light(0).links.linked());
}

TEST(LightLinks, BadIndicesAreRefusedAndLeaveTheLinks) {
    Scene s = threeMeshes();
    s.setLightLinks(0, links(std::vector<int>{1}, std::nullopt));
    const uint64_t version = s.light(0).version;
    try {
        s.setLightLinks(0, links(std::vector<int>{0}, std::vector<int>{3}));
        FAIL() << "mesh 3 of 3 was taken";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(e.what()).find("receiver mesh index 3 is out of range"), std::string::npos) << e.what();
    }
    EXPECT_EQ(*s.light(0).links.blockers, std::vector<int>{1});
    EXPECT_EQ(s.light(0).version, version);
    EXPECT_EQ(test::statusOf([&] { s.setLightLinks(2, {}); }), SS_ERROR_INVALID_ARGUMENT);
}

TEST(LightLinks, ALightEditKeepsItsLinks) {
    Scene s = threeMeshes();
    s.setLightLinks(1, links(std::vector<int>{0}, std::vector<int>{0, 2}));
    s.updateLight(1, test::makeDiskLight({-0.5f, 0.5f, 3.5f}, 0.8f, "Fill"));
    EXPECT_EQ(*s.light(1).links.blockers, std::vector<int>{0});
    EXPECT_EQ(*s.light(1).links.receivers, (std::vector<int>{0, 2}));
}

TEST(LightLinks, RemovingAMeshRenumbersTheSets) {
    Scene s = threeMeshes();
    s.setLightLinks(0, links(std::vector<int>{0, 1, 2}, std::vector<int>{1}));
    const uint64_t version = s.light(0).version;
    s.removeMesh(1);
    EXPECT_EQ(*s.light(0).links.blockers, (std::vector<int>{0, 1}));  // B moved down to 1
    EXPECT_EQ(*s.light(0).links.receivers, std::vector<int>{});       // A left
    EXPECT_NE(s.light(0).version, version);
    const int added = s.addMesh(test::makeBox({2.0f, 2.0f, 0.2f}, {2.5f, 2.5f, 0.6f}, kBoth));
    EXPECT_FALSE(s.castsFor(added, 0));  // a later mesh is in no set of a linked light
    EXPECT_TRUE(s.castsFor(added, 1));
}

std::filesystem::path tempDir(const std::string& name) {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("ss_light_links_" + std::to_string(getpid()) + "_" + name);
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

TEST(LightLinks, SceneFilesCarryThem) {
    Scene s = threeMeshes();
    s.setLightLinks(0, links(std::vector<int>{0, 2}, std::nullopt));
    s.setLightLinks(1, links(std::nullopt, std::vector<int>{1}));
    const std::filesystem::path dir = tempDir("round_trip");
    saveSceneFile(s, (dir / "s.json").string());
    Scene back = loadSceneFile((dir / "s.json").string());
    EXPECT_EQ(back.light(0).links, s.light(0).links);
    EXPECT_EQ(back.light(1).links, s.light(1).links);
    std::filesystem::remove_all(dir);
}

std::string linkedSceneText(const std::string& lightLinks, const std::string& secondMeshName = "A") {
    return R"({"format": "softshadow-scene", "version": 1,
      "lights": [{"name": "Key", "type": "disk", "position": [0, 0, 4], "direction": [0, 0, -1], )" +
           lightLinks + R"(}],
      "meshes": [{"name": "Ground", "primitive": {"type": "plane", "size": 8}},
                 {"name": ")" + secondMeshName + R"(", "primitive": {"type": "box", "size": 1}, "translate": [0, 0, 1]}]})";
}

TEST(LightLinks, SceneFilesNameMeshesByIndexOrName) {
    Scene s = parseSceneText(linkedSceneText(R"("blockers": ["Ground"], "receivers": [1, "Ground"])"), ".", "l.json");
    EXPECT_EQ(*s.light(0).links.blockers, std::vector<int>{0});
    EXPECT_EQ(*s.light(0).links.receivers, (std::vector<int>{0, 1}));
    EXPECT_FALSE(parseSceneText(linkedSceneText("\"size\": 1"), ".", "l.json").light(0).links.linked());
}

TEST(LightLinks, SceneFileLinkErrorsNameTheirPath) {
    auto message = [](const std::string& text) {
        try {
            parseSceneText(text, ".", "l.json");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("loaded");
    };
    EXPECT_NE(message(linkedSceneText(R"("blockers": ["Nope"])")).find("lights[0].blockers[0]: no mesh is named 'Nope'"),
              std::string::npos);
    EXPECT_NE(message(linkedSceneText(R"("blockers": ["Ground"])", "Ground")).find("two meshes are named 'Ground'"),
              std::string::npos);
    EXPECT_NE(message(linkedSceneText(R"("receivers": [2])")).find("lights[0].receivers[0]"), std::string::npos);
}

TEST(LightLinks, CApiSetsAndReadsThem) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_create(&scene), SS_OK);
    const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t tri[] = {0, 1, 2};
    for (const char* name : {"a", "b", "c"})
        ASSERT_EQ(ss_scene_add_mesh(scene, name, xyz, 3, tri, 1, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr), SS_OK);
    ss_light_desc light{};
    light.name = "Key";
    light.type = SS_LIGHT_DISK;
    for (int i = 0; i < 4; ++i) light.light_to_world[i * 5] = 1.0f;
    light.size = light.size_y = 1.0f;
    light.cast_shadows = 1;
    ASSERT_EQ(ss_scene_add_light(scene, &light, nullptr), SS_OK);

    const int32_t blockers[] = {2, 0};
    ASSERT_EQ(ss_scene_set_light_links(scene, 0, blockers, 2, nullptr, 0), SS_OK);
    int32_t b[3] = {-7, -7, -7}, r[3] = {-7, -7, -7}, nb = 0, nr = 0;
    ASSERT_EQ(ss_scene_get_light_links(scene, 0, b, 3, &nb, r, 3, &nr), SS_OK);
    EXPECT_EQ(nb, 2);
    EXPECT_EQ(b[0], 0);
    EXPECT_EQ(b[1], 2);
    EXPECT_EQ(nr, 0);  // an empty receiver list: the light lights nothing

    ASSERT_EQ(ss_scene_set_light_links(scene, 0, nullptr, -1, nullptr, -1), SS_OK);
    ASSERT_EQ(ss_scene_get_light_links(scene, 0, b, 3, &nb, r, 3, &nr), SS_OK);
    EXPECT_EQ(nb, -1);
    EXPECT_EQ(nr, -1);

    EXPECT_EQ(ss_scene_set_light_links(scene, 0, blockers, -2, nullptr, -1), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ss_last_error()).find("-1 means every mesh"), std::string::npos) << ss_last_error();
    EXPECT_EQ(ss_scene_set_light_links(scene, 0, nullptr, 1, nullptr, -1), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_scene_set_light_links(scene, 1, nullptr, -1, nullptr, -1), SS_ERROR_INVALID_ARGUMENT);
    const int32_t outside[] = {3};
    EXPECT_EQ(ss_scene_set_light_links(scene, 0, outside, 1, nullptr, -1), SS_ERROR_INVALID_ARGUMENT);
    ASSERT_EQ(ss_scene_set_light_links(scene, 0, blockers, 2, nullptr, -1), SS_OK);
    EXPECT_EQ(ss_scene_get_light_links(scene, 0, b, 1, &nb, r, 3, &nr), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ss_last_error()).find("needs room for 2"), std::string::npos) << ss_last_error();
    ss_scene_destroy(scene);
}

}  // namespace
}  // namespace ss
