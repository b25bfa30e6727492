// Checks the reference's light sampling: stratified points, samples on each light shape, weights that integrate to known irradiance.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/light.h"
#include "core/scene.h"
#include "reference/light_sampler.h"
#include "reference/sample_sequence.h"

namespace ss {
namespace {

Light diskLight(float diameter, float height) {
    Light l;
    l.name = "disk";
    l.type = LightType::Disk;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, height));
    l.size = diameter;
    l.sizeY = diameter;
    return l;
}

// Mean of weight * cos at an upward receiver at the origin: the irradiance up to the constant
// (light area for area and sphere lights, cone solid angle for the sun) the weights leave out.
double meanIrradiance(const Light& light, const glm::vec3& point, const glm::vec3& normal, int n) {
    LightSampler sampler(light);
    SampleSequence seq(7, 3, 4);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        ShadowRay s = sampler.sample(point, seq.point(uint32_t(i)));
        sum += double(s.weight) * std::max(0.0, double(glm::dot(normal, s.toLight)));
    }
    return sum / n;
}

TEST(ReferenceSampling, PowerOfTwoPrefixIsStratifiedInEveryElementaryInterval) {
    // A (0,m,2)-net: for 256 points and every split 2^a x 2^(8-a), each cell holds exactly one
    // point. Owen scrambling must keep this for every pixel's scramble.
    for (uint32_t pixel = 0; pixel < 5; ++pixel) {
        SampleSequence seq(42, pixel, 2 * pixel + 1);
        for (int a = 0; a <= 8; ++a) {
            int nx = 1 << a, ny = 1 << (8 - a);
            std::set<int> cells;
            for (uint32_t i = 0; i < 256; ++i) {
                glm::vec2 p = seq.point(i);
                ASSERT_GE(p.x, 0.0f);
                ASSERT_LT(p.x, 1.0f);
                ASSERT_GE(p.y, 0.0f);
                ASSERT_LT(p.y, 1.0f);
                cells.insert(int(p.x * nx) * ny + int(p.y * ny));
            }
            EXPECT_EQ(cells.size(), 256u) << "pixel " << pixel << " split " << nx << "x" << ny;
        }
    }
}

TEST(ReferenceSampling, SequenceIsAPureFunctionOfSeedAndPixel) {
    SampleSequence a(9, 10, 11), b(9, 10, 11), otherPixel(9, 11, 10), otherSeed(10, 10, 11);
    int differPixel = 0, differSeed = 0;
    for (uint32_t i = 0; i < 64; ++i) {
        EXPECT_EQ(a.point(i), b.point(i));
        differPixel += a.point(i) != otherPixel.point(i);
        differSeed += a.point(i) != otherSeed.point(i);
    }
    EXPECT_GT(differPixel, 60);
    EXPECT_GT(differSeed, 60);
}

TEST(ReferenceSampling, AreaSamplesLieOnTheLightShape) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 3.0f)) *
                  glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(1.0f, 0.0f, 0.0f));
    for (LightType type : {LightType::Disk, LightType::Ellipse, LightType::Square, LightType::Rectangle}) {
        Light l;
        l.name = lightTypeName(type);
        l.type = type;
        l.lightToWorld = m;
        l.size = 2.0f;
        l.sizeY = 0.5f;
        l.validate();
        glm::vec3 ax = glm::normalize(l.halfAxisX()), ay = glm::normalize(l.halfAxisY());
        float a = glm::length(l.halfAxisX()), b = glm::length(l.halfAxisY());
        LightSampler sampler(l);
        SampleSequence seq(1, 0, 0);
        const glm::vec3 point(0.3f, -0.2f, -4.0f);
        glm::vec3 mean(0.0f);
        for (uint32_t i = 0; i < 1024; ++i) {
            ShadowRay s = sampler.sample(point, seq.point(i));
            glm::vec3 q = point + s.distance * s.toLight - l.position();
            float x = glm::dot(q, ax) / a, y = glm::dot(q, ay) / b;
            EXPECT_NEAR(glm::dot(q, l.direction()), 0.0f, 1e-4f) << l.name;  // in the plane
            bool round = type == LightType::Disk || type == LightType::Ellipse;
            float norm = round ? x * x + y * y : std::max(std::abs(x), std::abs(y));
            EXPECT_LE(norm, 1.0f + 1e-4f) << l.name;
            mean += glm::vec3(x, y, 0.0f);
        }
        // Uniform in area: the centroid is the centre (1024 stratified points: well under 0.02).
        mean /= 1024.0f;
        EXPECT_NEAR(mean.x, 0.0f, 0.02f) << l.name;
        EXPECT_NEAR(mean.y, 0.0f, 0.02f) << l.name;
    }
}

TEST(ReferenceSampling, DiskWeightsIntegrateToTheParallelDiskIrradiance) {
    // On the axis of a parallel disk of radius R at height h: E = pi R^2 / (R^2 + h^2) (per unit
    // radiance); the mean weight times the disk area must give it. 4096 stratified samples of
    // a smooth integrand: relative error far below 1e-3.
    const float R = 1.0f, h = 2.0f;
    double e = meanIrradiance(diskLight(2.0f * R, h), glm::vec3(0.0f), glm::vec3(0, 0, 1), 4096) * M_PI * R * R;
    double exact = M_PI * R * R / (R * R + h * h);
    EXPECT_NEAR(e, exact, 1e-3 * exact) << "estimate " << e << " closed form " << exact;
}

TEST(ReferenceSampling, SphereLightIsADiskFacingThePoint) {
    // Cycles 3.0-3.4 samples a point light of radius r as a disk of radius r facing the shading
    // point, each sample weighing 1/d^2: the mean weight times cos at the receiver times the
    // disk area is 2 pi (1 - D / sqrt(r^2 + D^2)), whatever the point's direction.
    Light l;
    l.name = "point";
    l.type = LightType::Point;
    l.radius = 0.5f;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.0f));
    for (glm::vec3 dir : {glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, 2, 0.5f))}) {
        const float D = 3.0f;
        glm::vec3 p = D * dir;
        double e = meanIrradiance(l, p, -dir, 4096) * M_PI * 0.25;
        double exact = 2.0 * M_PI * (1.0 - D / std::sqrt(0.25 + double(D) * D));
        EXPECT_NEAR(e, exact, 1e-3 * exact) << "estimate " << e << " closed form " << exact;
        LightSampler sampler(l);
        SampleSequence seq(3, 1, 1);
        for (uint32_t i = 0; i < 256; ++i) {
            ShadowRay s = sampler.sample(p, seq.point(i));
            glm::vec3 q = p + s.distance * s.toLight;  // on the disk through the centre, facing p
            EXPECT_NEAR(glm::dot(q, dir), 0.0f, 1e-4f);
            EXPECT_LE(glm::length(q), 0.5f + 1e-4f);
        }
    }
}

TEST(ReferenceSampling, SunDirectionsFillItsConeUniformly) {
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Sun;
    sun.angle = glm::radians(10.0f);
    sun.lightToWorld = glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f));
    LightSampler sampler(sun);
    SampleSequence seq(5, 0, 0);
    const glm::vec3 toSun = -sun.direction();
    const float cosMax = std::cos(0.5f * sun.angle);
    double meanCos = 0.0;
    for (uint32_t i = 0; i < 4096; ++i) {
        ShadowRay s = sampler.sample(glm::vec3(0.0f), seq.point(i));
        EXPECT_TRUE(std::isinf(s.distance));
        EXPECT_EQ(s.weight, 1.0f);
        float c = glm::dot(s.toLight, toSun);
        EXPECT_GE(c, cosMax - 1e-6f);
        meanCos += c;
    }
    // Uniform in solid angle over a cap: E[cos] = (1 + cos a) / 2.
    meanCos /= 4096.0;
    double exact = 0.5 * (1.0 + double(cosMax));
    EXPECT_NEAR(meanCos, exact, 1e-5) << "estimate " << meanCos << " closed form " << exact;
}

TEST(ReferenceSampling, SpotWeightsFollowCyclesAttenuation) {
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.radius = 0.0f;
    spot.spotSize = glm::radians(60.0f);
    spot.spotBlend = 0.5f;
    spot.lightToWorld = glm::mat4(1.0f);  // pointing down -Z
    LightSampler sampler(spot);
    auto weightAt = [&](float angleDeg) {
        float a = glm::radians(angleDeg);
        glm::vec3 p(std::sin(a), 0.0f, -std::cos(a));  // unit distance
        return sampler.sample(p, glm::vec2(0.5f)).weight;
    };
    const float cosHalf = std::cos(glm::radians(30.0f)), smooth = (1.0f - cosHalf) * 0.5f;
    EXPECT_FLOAT_EQ(weightAt(0.0f), 1.0f);   // on the axis: cos = 1, outside the blend
    EXPECT_EQ(weightAt(31.0f), 0.0f);        // outside the cone
    float c = std::cos(glm::radians(25.0f)), t = (c - cosHalf) / smooth;
    EXPECT_NEAR(weightAt(25.0f), c * t * t * (3.0f - 2.0f * t), 1e-5f);  // in the blend
}

TEST(ReferenceSampling, OneSidedAreaLightSendsNothingBehindIt) {
    Light l = diskLight(1.0f, 2.0f);
    LightSampler sampler(l);
    SampleSequence seq(1, 0, 0);
    for (uint32_t i = 0; i < 64; ++i) {
        EXPECT_GT(sampler.sample(glm::vec3(0.0f), seq.point(i)).weight, 0.0f);             // below
        EXPECT_EQ(sampler.sample(glm::vec3(0.0f, 0.0f, 4.0f), seq.point(i)).weight, 0.0f);  // above
    }
}

TEST(ReferenceSampling, ZeroAreaLightIsRejected) {
    for (auto [type, size, sizeY] : std::vector<std::tuple<LightType, float, float>>{
             {LightType::Disk, 0.0f, 1.0f},
             {LightType::Square, -1.0f, 1.0f},
             {LightType::Rectangle, 1.0f, 0.0f},
             {LightType::Ellipse, 1.0f, 0.0f}}) {
        Light l = diskLight(1.0f, 2.0f);
        l.type = type;
        l.size = size;
        l.sizeY = sizeY;
        Scene scene;
        try {
            scene.addLight(l);
            ADD_FAILURE() << lightTypeName(type) << " of size " << size << " x " << sizeY << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.status(), SS_ERROR_INVALID_SCENE);
            EXPECT_NE(std::string(e.what()).find("size"), std::string::npos) << e.what();
        }
    }
    // A matrix that flattens the light is a zero area too.
    Light flat = diskLight(1.0f, 2.0f);
    flat.lightToWorld = glm::scale(flat.lightToWorld, glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_THROW(flat.validate(), Error);
}

}  // namespace
}  // namespace ss
