// Does lightReaches() say "reached" exactly where the reference's light samples carry weight?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/visibility_contract.h"
#include "reference/light_sampler.h"

namespace ss {
namespace {

// A light at `position` emitting along `dir` (its local -Z), like Blender's matrix_world.
Light aimedLight(LightType type, const glm::vec3& position, const glm::vec3& dir) {
    Light l;
    l.name = lightTypeName(type);
    l.type = type;
    glm::vec3 z = -glm::normalize(dir);
    glm::vec3 helper = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 x = glm::normalize(glm::cross(helper, z));
    glm::vec3 y = glm::cross(z, x);
    l.lightToWorld = glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), glm::vec4(position, 1));
    return l;
}

// Whether any of n x n stratified samples of the light sends weight to P above its horizon:
// the reference's own E_L > 0 (visibility_estimator.cpp keeps a sample when cos > 0, w > 0).
bool samplesReach(const Light& light, const glm::vec3& P, const glm::vec3& N, int n) {
    LightSampler sampler(light);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            ShadowRay s = sampler.sample(P, {(i + 0.5f) / n, (j + 0.5f) / n});
            if (s.weight > 0.0f && glm::dot(N, s.toLight) > 0.0f) return true;
        }
    return false;
}

// The same light made smaller by `scale` about its centre (size, radius or angle).
Light shrunk(Light l, float scale) {
    l.size *= scale;
    l.sizeY *= scale;
    l.radius *= scale;
    l.angle *= scale;
    return l;
}

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    for (;;) {
        glm::vec3 v(g(rng), g(rng), g(rng));
        float len = glm::length(v);
        if (len > 1e-3f) return v / len;
    }
}

struct Counts {
    int points = 0, reached = 0, falseReach = 0, missed = 0;
};

// Random shading points around the light with random normals. Two properties:
// (1) when lightReaches() says no, no sample carries weight (24 x 24 samples);
// (2) when the light and the light shrunk by 3% are reached, 64 x 64 (or else 256 x 256)
//     samples of the full light find weight (a sliver of the light thinner than 3% of its size
//     can hold too few of 4096 samples: a circular segment of depth 0.03 r is 0.3% of the disk).
Counts probe(const Light& light, uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(0.1f, 6.0f);
    Counts c;
    glm::vec3 centre = light.type == LightType::Sun ? glm::vec3(0.0f) : light.position();
    Light small = shrunk(light, 0.97f);
    float spread = 1.5f * std::tan(std::min(0.5f * light.spotSize, 1.2f)) + 0.3f;
    for (int k = 0; k < count; ++k) {
        // Spots: directions scattered around the axis out to past the cone, so narrow cones
        // get their share of points on both sides of the rim.
        glm::vec3 dir = randomUnit(rng);
        if (light.type == LightType::Spot)
            dir = glm::normalize(light.direction() + spread * dir);
        glm::vec3 P = centre + dist(rng) * dir;
        glm::vec3 N = randomUnit(rng);
        ++c.points;
        bool analytic = lightReaches(light, P, N);
        c.reached += analytic;
        if (!analytic && samplesReach(light, P, N, 24)) ++c.falseReach;
        // Where the cone's rim, the disk's rim and the horizon meet, the lens can be thinner
        // than the shrunk light suggests: look again with 16 times the samples before failing.
        if (analytic && lightReaches(small, P, N) && !samplesReach(light, P, N, 64) &&
            !samplesReach(light, P, N, 256))
            ++c.missed;
    }
    return c;
}

void expectAgreement(const Light& light, uint32_t seed, int count) {
    Counts c = probe(light, seed, count);
    SCOPED_TRACE(light.name);
    EXPECT_EQ(c.falseReach, 0) << "samples carry weight where lightReaches() says no";
    EXPECT_EQ(c.missed, 0) << "lightReaches() says yes where no sample carries weight";
    // Both answers must occur, or the probe tested nothing.
    EXPECT_GT(c.reached, c.points / 20);
    EXPECT_LT(c.reached, c.points - c.points / 20);
}

TEST(VisibilityContract, PointLightIsTheDiskFacingThePointNotTheSphere) {
    Light l = aimedLight(LightType::Point, {0.2f, -0.1f, 1.0f}, {0, 0, -1});
    l.radius = 0.8f;
    // Beside the light, face tilted away: the centre is 0.7 below P's tangent plane, the
    // sphere's top above it (0.8 > 0.7), but the disk facing P reaches only 0.8 * sin(angle
    // between N and the disk's normal) = 0.8 * 0.714 = 0.57 < 0.7 above the centre.
    glm::vec3 centre = l.position();
    glm::vec3 P = centre + glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 N = glm::normalize(glm::vec3(0.7f, 0.0f, 0.71414f));
    ASSERT_GT(glm::dot(N, centre - P) + l.radius, 0.0f);  // the old sphere test said yes
    EXPECT_FALSE(lightReaches(l, P, N));
    EXPECT_FALSE(samplesReach(l, P, N, 64));
    // Inside the sphere nothing is reached (the reference gives every sample weight 0).
    EXPECT_FALSE(lightReaches(l, centre + glm::vec3(0.5f, 0.0f, 0.0f), glm::vec3(-1, 0, 0)));
}

TEST(VisibilityContract, SpotConeIsWidenedByTheDiskSeenFromThePoint) {
    Light l = aimedLight(LightType::Spot, {0.0f, 0.0f, 4.0f}, {0, 0, -1});
    l.radius = 1.0f;
    l.spotSize = glm::radians(50.0f);
    l.spotBlend = 0.5f;
    glm::vec3 up(0, 0, 1);
    // On the ground at 2.5 from the axis: 32 deg off axis, outside the 25 deg cone, but the
    // disk seen from there spans atan(1 / 4.72) = 12 deg, so its near rim is inside the cone.
    glm::vec3 P(2.5f, 0.0f, 0.0f);
    EXPECT_TRUE(lightReaches(l, P, up));
    EXPECT_TRUE(samplesReach(l, P, up, 64));
    // At 3.5 from the axis (41 deg; disk 11 deg) the whole disk is outside the cone.
    glm::vec3 Q(3.5f, 0.0f, 0.0f);
    EXPECT_FALSE(lightReaches(l, Q, up));
    EXPECT_FALSE(samplesReach(l, Q, up, 64));
    // Radius 0: the plain cone.
    l.radius = 0.0f;
    EXPECT_FALSE(lightReaches(l, P, up));
    EXPECT_TRUE(lightReaches(l, glm::vec3(1.8f, 0.0f, 0.0f), up));  // 24.2 deg
}

// One sample must be both inside the cone and above the horizon: here the part of the disk
// inside the cone (towards the axis) and the part above the horizon are on opposite sides.
TEST(VisibilityContract, SpotNeedsOnePartOfTheDiskInTheConeAndAboveTheHorizon) {
    Light spot = aimedLight(LightType::Spot, {0.0f, 0.0f, 4.0f}, {0, 0, -1});
    spot.radius = 1.0f;
    spot.spotSize = glm::radians(60.0f);
    spot.spotBlend = 0.2f;
    Light point = spot;
    point.type = LightType::Point;
    // 36.6 deg off the axis, the disk spans 9.1 deg: its inner rim is inside the 30 deg cone.
    glm::vec3 P(3.3f, -1.7f, -1.0f);
    glm::vec3 N(-0.8f, 0.0f, -0.6f);  // the centre is 0.36 below the horizon, the rim 0.998 above
    glm::vec3 towardsLight = glm::normalize(spot.position() - P);
    ASSERT_TRUE(lightReaches(spot, P, towardsLight));  // the cone alone is met
    ASSERT_TRUE(lightReaches(point, P, N));            // the horizon alone is met
    EXPECT_FALSE(lightReaches(spot, P, N));
    EXPECT_FALSE(samplesReach(spot, P, N, 256));
}

TEST(VisibilityContract, AgreesWithTheReferenceSamplerOnRandomPoints) {
    int n = 3000;
    Light point = aimedLight(LightType::Point, {0.3f, 0.2f, 0.5f}, {0, 0, -1});
    point.radius = 0.7f;
    expectAgreement(point, 1, n);
    Light tiny = point;
    tiny.radius = 0.0f;
    expectAgreement(tiny, 2, n);

    for (float spotDeg : {20.0f, 75.0f, 160.0f}) {
        Light spot = aimedLight(LightType::Spot, {-0.2f, 0.4f, 1.0f}, {0.3f, -0.2f, -1.0f});
        spot.name = "spot " + std::to_string(int(spotDeg));
        spot.radius = 0.6f;
        spot.spotSize = glm::radians(spotDeg);
        spot.spotBlend = 0.7f;
        expectAgreement(spot, 10 + uint32_t(spotDeg), n);
    }

    Light disk = aimedLight(LightType::Disk, {0.1f, 0.0f, 0.2f}, {0.2f, 0.1f, -1.0f});
    disk.size = disk.sizeY = 1.5f;
    expectAgreement(disk, 3, n);
    Light ellipse = disk;
    ellipse.name = "ellipse";
    ellipse.type = LightType::Ellipse;
    ellipse.sizeY = 0.4f;
    expectAgreement(ellipse, 4, n);
    Light rect = aimedLight(LightType::Rectangle, {0.0f, 0.3f, 0.0f}, {-0.5f, 0.2f, -1.0f});
    rect.size = 2.0f;
    rect.sizeY = 0.7f;
    expectAgreement(rect, 5, n);

    Light sun = aimedLight(LightType::Sun, {0, 0, 10}, {0.4f, 0.1f, -1.0f});
    sun.angle = glm::radians(20.0f);
    expectAgreement(sun, 6, n);
}

}  // namespace
}  // namespace ss
