// Are the sweep method's light samples on the light (every shape), deterministic for a seed,
// the requested count, with the border share on the border?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "sampling/light_samples.h"
#include "test_scenes.h"

using namespace ss;

TEST(SweepSamples, DiskSamplesLieOnTheDiskWithAQuarterOnItsBorder) {
    Light l = test::makeDiskLight({1, 2, 4}, 1.5f);
    LightSampleOptions o;
    o.count = 16;
    std::vector<LightSample> s = placeLightSamples(l, o);
    ASSERT_EQ(s.size(), 16u);
    int border = 0;
    for (const LightSample& p : s) {
        EXPECT_FALSE(p.directional);
        EXPECT_NEAR(p.point.z, 4.0, 1e-6);  // in the light's plane
        double r = std::hypot(p.point.x - 1, p.point.y - 2);
        EXPECT_LE(r, 0.75 + 1e-6);
        border += std::fabs(r - 0.75) < 1e-6;
    }
    EXPECT_EQ(border, 4);  // round(16 * 0.25)
}

TEST(SweepSamples, DeterministicForASeedAndDifferentAcrossSeeds) {
    Light l = test::makeDiskLight({0, 0, 4}, 1.0f);
    LightSampleOptions a, b;
    a.count = b.count = 9;
    b.seed = 2;
    auto s1 = placeLightSamples(l, a), s2 = placeLightSamples(l, a), s3 = placeLightSamples(l, b);
    bool differ = false;
    for (size_t i = 0; i < s1.size(); ++i) {
        EXPECT_EQ(s1[i].point, s2[i].point);
        differ |= s1[i].point != s3[i].point;
    }
    EXPECT_TRUE(differ);
}

TEST(SweepSamples, RectangleSunAndSphere) {
    Light rect = test::makeDiskLight({0, 0, 3}, 2.0f);
    rect.type = LightType::Rectangle;
    rect.sizeY = 1.0f;
    LightSampleOptions o;
    o.count = 12;
    for (const LightSample& p : placeLightSamples(rect, o)) {
        EXPECT_LE(std::fabs(p.point.x), 1.0 + 1e-6);
        EXPECT_LE(std::fabs(p.point.y), 0.5 + 1e-6);
    }
    Light sun;
    sun.type = LightType::Sun;
    sun.angle = 0.1f;  // pointing down (local -Z)
    for (const LightSample& p : placeLightSamples(sun, o)) {
        EXPECT_TRUE(p.directional);
        EXPECT_LE(std::acos(std::min(1.0, p.toLight.z)), 0.05 + 1e-6);  // within the half angle
    }
    Light point;
    point.type = LightType::Point;
    point.radius = 0.5f;
    point.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    o.viewFrom = {0, 0, 0};
    for (const LightSample& p : placeLightSamples(point, o)) {
        EXPECT_NEAR(p.point.z, 5.0, 1e-6);  // the disk facing the occluders below
        EXPECT_LE(glm::length(p.point - glm::dvec3(0, 0, 5)), 0.5 + 1e-6);
    }
    point.radius = 0.0f;
    EXPECT_EQ(placeLightSamples(point, o).size(), 1u);  // no extent: the centre only
}
