// Does every scene, copies included, have an identity of its own for the caches?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <utility>

#include <gtest/gtest.h>

#include "core/scene.h"
#include "test_scenes.h"

namespace ss {
namespace {

TEST(SceneIdentity, ACopyIsAnotherSceneForTheCaches) {
    Scene a = test::sceneBox();
    Scene b = a;
    // Equal now, but each may change on its own while the revisions stay equal: (id, revision)
    // must never name both.
    EXPECT_EQ(a.revision(), b.revision());
    EXPECT_NE(a.id(), b.id());
    b.addLight(test::makeDiskLight({0.0f, 0.0f, 3.0f}, 0.5f, "Extra"));
    a.addLight(test::makeDiskLight({2.0f, 0.0f, 3.0f}, 0.5f, "Other"));
    EXPECT_EQ(a.revision(), b.revision());
    EXPECT_NE(a.id(), b.id());

    Scene c;
    const uint64_t before = c.id();
    c = a;  // assigned: its contents changed, so its identity did too
    EXPECT_NE(c.id(), a.id());
    EXPECT_NE(c.id(), before);
}

TEST(SceneIdentity, AMoveHandsTheIdentityOver) {
    Scene a = test::sceneBox();
    const uint64_t id = a.id();
    Scene b = std::move(a);
    EXPECT_EQ(b.id(), id);
    EXPECT_NE(a.id(), id);  // the emptied source is not the scene it was
}

}  // namespace
}  // namespace ss
