// How light samples are placed: a border ring plus an area-uniform jittered inside, mapped onto
// each light shape.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "sampling/light_samples.h"

#include <algorithm>
#include <cmath>

namespace ss {

namespace {

// splitmix64: a tiny generator whose stream depends only on the seed.
struct Rng {
    uint64_t state;
    explicit Rng(uint32_t seed) : state(0x9E3779B97F4A7C15ull * (uint64_t(seed) + 1)) {}
    double uniform() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return double(z >> 11) * (1.0 / 9007199254740992.0);
    }
};

// A point on the border of the unit disk or square at perimeter fraction t in [0, 1).
glm::dvec2 borderPoint(bool square, double t) {
    if (!square) return {std::cos(2 * M_PI * t), std::sin(2 * M_PI * t)};
    double s = 8.0 * t;  // perimeter of [-1,1]^2
    if (s < 2) return {-1 + s, -1};
    if (s < 4) return {1, -1 + (s - 2)};
    if (s < 6) return {1 - (s - 4), 1};
    return {-1, 1 - (s - 6)};
}

}  // namespace

std::vector<glm::dvec2> unitSamplePattern(bool square, int count, uint32_t seed, double borderShare, int set,
                                          int sets) {
    std::vector<glm::dvec2> out;
    if (count <= 1) {
        out.push_back({0.0, 0.0});
        return out;
    }
    Rng rng(seed);
    int border = count <= 3 ? count : std::clamp(int(std::lround(count * borderShare)), 3, count);
    int inside = count - border;
    // Where this set sits inside each stratum, and how far it jitters there: one set spans the
    // stratum's middle 60 % (border: 30 %, inside disk: 40 %), `sets` sets a slice each.
    sets = std::max(sets, 1);
    const double offset = (std::clamp(set, 0, sets - 1) + 0.5) / sets - 0.5, narrow = 1.0 / sets;
    // The rows take the sets in the reverse order of the columns, so no two sets share both.
    const double offsetY = -offset;
    // Border: evenly spaced with a random rotation and a small jitter, so the set is irregular.
    double phase = rng.uniform();
    for (int i = 0; i < border; ++i) {
        double t = (i + phase + offset + 0.3 * narrow * (rng.uniform() - 0.5)) / border;
        out.push_back(borderPoint(square, t - std::floor(t)));
    }
    // Inside: stratified by area (golden-angle spiral in the disk, jittered grid in the square),
    // kept off the border band the border samples already cover.
    const double shrink = 1.0 - 0.5 / std::sqrt(double(count));
    if (!square) {
        for (int i = 0; i < inside; ++i) {
            double r = shrink * std::sqrt((i + 0.5 + offset + 0.4 * narrow * (rng.uniform() - 0.5)) / inside);
            double a = i * 2.39996322972865332 + 2 * M_PI * phase;
            out.push_back({r * std::cos(a), r * std::sin(a)});
        }
    } else {
        int cols = std::max(1, int(std::ceil(std::sqrt(double(inside)))));
        for (int i = 0; i < inside; ++i) {
            int cx = i % cols, cy = i / cols;
            int rows = (inside + cols - 1) / cols;
            double x = (cx + 0.5 + offset + 0.6 * narrow * (rng.uniform() - 0.5)) / cols * 2 - 1;
            double y = (cy + 0.5 + offsetY + 0.6 * narrow * (rng.uniform() - 0.5)) / rows * 2 - 1;
            out.push_back({shrink * x, shrink * y});
        }
    }
    return out;
}

std::vector<LightSample> placeLightSamples(const Light& light, const LightSampleOptions& options) {
    std::vector<LightSample> out;
    const glm::dvec3 centre(light.position());
    int count = std::max(options.count, 1);
    if (light.type == LightType::Sun) {
        const glm::dvec3 axis = -glm::dvec3(light.direction());
        double half = light.sunHalfAngle();
        if (!(half > 0.0)) count = 1;
        glm::dvec3 e1 = glm::normalize(glm::cross(axis, std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        glm::dvec3 e2 = glm::cross(axis, e1);
        double t = std::tan(half);
        for (const glm::dvec2& p : unitSamplePattern(false, count, options.seed, options.borderShare, options.set, options.sets)) {
            LightSample s;
            s.directional = true;
            s.toLight = glm::normalize(axis + t * (p.x * e1 + p.y * e2));
            out.push_back(s);
        }
        return out;
    }
    glm::dvec3 ax, ay;
    bool square = false;
    if (light.isArea()) {
        ax = glm::dvec3(light.halfAxisX());
        ay = glm::dvec3(light.halfAxisY());
        square = light.type == LightType::Square || light.type == LightType::Rectangle;
    } else {
        // A sphere seen from the occluders is a disk of the same radius facing them.
        glm::dvec3 view = options.viewFrom - centre;
        glm::dvec3 n = glm::length(view) > 0 ? glm::normalize(view) : glm::dvec3(0, 0, -1);
        glm::dvec3 e1 = glm::normalize(glm::cross(n, std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        ax = double(light.radius) * e1;
        ay = double(light.radius) * glm::cross(n, e1);
        if (!(light.radius > 0.0f)) count = 1;
    }
    for (const glm::dvec2& p : unitSamplePattern(square, count, options.seed, options.borderShare, options.set, options.sets)) {
        LightSample s;
        s.point = centre + p.x * ax + p.y * ay;
        out.push_back(s);
    }
    return out;
}

}  // namespace ss
