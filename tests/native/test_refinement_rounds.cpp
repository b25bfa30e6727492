// Checks refinement in rounds through the C API: each round lands in order, its error never rises, the last is the one-round result, a round can cancel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "capi_demo.h"
#include "softshadow/softshadow.h"

namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr int kRounds = 4;

struct Fixture : test::CapiDemo {
    Fixture() : CapiDemo(kWidth, kHeight) {}
};

std::vector<float> layerOf(const ss_result* result, const char* wanted) {
    for (int32_t i = 0; i < ss_result_layer_count(result); ++i) {
        const char* name = nullptr;
        const float* pixels = nullptr;
        int32_t w = 0, h = 0;
        EXPECT_EQ(ss_result_layer(result, i, &name, &pixels, &w, &h), SS_OK);
        if (std::strcmp(name, wanted) == 0) return std::vector<float>(pixels, pixels + size_t(w) * size_t(h));
    }
    ADD_FAILURE() << "no layer " << wanted;
    return {};
}

// What one round callback saw.
struct Round {
    int32_t round = 0, rounds = 0;
    std::vector<float> v, refined, rays;
    double estimate = 0.0;
    std::string method;
};

struct Heard {
    std::vector<Round> rounds;
    int stopAt = 0;          // return non-zero at this round (0: never)
    ss_context* cancel = nullptr;  // ss_context_cancel_renders at stopAt instead
    ss_context* reenter = nullptr;  // ss_render on it from inside the callback
    const ss_scene* scene = nullptr;
    ss_status reentered = SS_OK;
    std::string reenterError;
};

int hear(void* user, const ss_result* partial, int32_t round, int32_t rounds) {
    Heard& h = *static_cast<Heard*>(user);
    h.rounds.push_back({round, rounds, layerOf(partial, "V"), layerOf(partial, "refined"), layerOf(partial, "rays"),
                        ss_result_estimated_rmse(partial), ss_result_method(partial)});
    if (h.reenter) {
        ss_result* inner = nullptr;
        h.reentered = ss_render(h.reenter, h.scene, 0, "pcss", nullptr, &inner);
        h.reenterError = ss_last_error();
    }
    if (round != h.stopAt) return 0;
    if (!h.cancel) return 1;
    ss_context_cancel_renders(h.cancel);
    return 0;
}

// refineRounds: -1 for no refinement, else SS_REFINE_ON in that many rounds (0: the default, 1).
ss_status render(Fixture& f, const char* method, int32_t refineRounds, int samples, Heard* heard,
                 ss_result** out, const char* settings = nullptr) {
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = samples;
    o.settings = settings;
    if (refineRounds >= 0) {
        o.refine = SS_REFINE_ON;
        o.refine_rounds = refineRounds;
    }
    if (heard) {
        o.round = hear;
        o.round_user = heard;
    }
    return ss_render(f.context, f.scene, 0, method, &o, out);
}

// RMSE over the reference's mask.
double rmse(const std::vector<float>& v, const std::vector<float>& truth, const std::vector<float>& mask) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < v.size(); ++i)
        if (mask[i] != 0.0f) sum += double(v[i] - truth[i]) * double(v[i] - truth[i]), ++n;
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

double share(const std::vector<float>& traced) {
    double n = 0.0;
    for (float t : traced) n += t != 0.0f;
    return n / double(traced.size());
}

// The GL pass, then each round: the error against a 4096-sample reference never rises, the first
// round already removes much of it, the last meets the error target, and the last round's V is
// the one-round refinement's to the bit.
TEST(RefinementRounds, TheErrorFallsRoundByRoundToTheTargetAndTheOneRoundResult) {
    Fixture f;
    ss_result* reference = nullptr;
    ASSERT_EQ(render(f, "reference", -1, 4096, nullptr, &reference), SS_OK) << ss_last_error();
    const std::vector<float> truth = layerOf(reference, "V"), mask = layerOf(reference, "mask");
    ss_result_destroy(reference);
    for (const char* method : {"pcss", "shadow_map"}) {
        ss_result *gl = nullptr, *once = nullptr, *last = nullptr;
        ASSERT_EQ(render(f, method, -1, 0, nullptr, &gl), SS_OK) << ss_last_error();
        ASSERT_EQ(render(f, method, 0, 0, nullptr, &once), SS_OK) << ss_last_error();
        Heard heard;
        ASSERT_EQ(render(f, method, kRounds, 0, &heard, &last), SS_OK) << ss_last_error();
        ASSERT_EQ(heard.rounds.size(), size_t(kRounds - 1)) << method;
        std::vector<double> errors{rmse(layerOf(gl, "V"), truth, mask)};
        std::printf("%s: GL %.4f", method, errors.back());
        for (size_t k = 0; k < heard.rounds.size(); ++k) {
            const Round& r = heard.rounds[k];
            EXPECT_EQ(r.round, int32_t(k + 1)) << method;
            EXPECT_EQ(r.rounds, kRounds) << method;
            EXPECT_EQ(r.method, method);
            EXPECT_TRUE(std::isnan(r.estimate)) << method << ": no estimate was asked for";
            errors.push_back(rmse(r.v, truth, mask));
            std::printf(", round %d %.4f (%.1f%% traced)", r.round, errors.back(), 100.0 * share(r.refined));
            if (k > 0) {
                EXPECT_GT(share(r.refined), share(heard.rounds[k - 1].refined)) << method;
            }
        }
        const std::vector<float> final = layerOf(last, "V");
        errors.push_back(rmse(final, truth, mask));
        std::printf(", round %d %.4f\n", kRounds, errors.back());
        for (size_t k = 1; k < errors.size(); ++k)
            EXPECT_LE(errors[k], errors[k - 1]) << method << ": round " << k << " raised the error";
        EXPECT_LT(errors[1], 0.75 * errors[0]) << method << ": the first round corrects the most";
        EXPECT_LE(errors.back(), 0.01) << method;
        EXPECT_EQ(final, layerOf(once, "V")) << method;
        EXPECT_EQ(layerOf(last, "refined"), layerOf(once, "refined")) << method;
        EXPECT_EQ(layerOf(last, "rays"), layerOf(once, "rays")) << method;
        for (ss_result* r : {gl, once, last}) ss_result_destroy(r);
    }
}

double sum(const std::vector<float>& values) {
    double s = 0.0;
    for (float v : values) s += v;
    return s;
}

// Rays where a pixel was not traced adaptively: the check of the pixels the pass called certain.
double checkRays(const Round& r) {
    double s = 0.0;
    for (size_t i = 0; i < r.rays.size(); ++i)
        if (r.refined[i] == 0.0f) s += r.rays[i];
    return s;
}

// The first round lands on the uncertain pixels' largest corrections alone: no ray of the check of
// the certain pixels yet, and a small share of the rays the result rests on. The rays of each round
// rest on more than the last's; the check comes in the rounds after the uncertain pixels'.
TEST(RefinementRounds, TheFirstRoundRestsOnAFewOfTheRaysAndTheCheckComesAfter) {
    Fixture f;
    for (const char* method : {"pcss", "shadow_map"}) {
        Heard heard;
        ss_result* last = nullptr;
        ASSERT_EQ(render(f, method, 4, 0, &heard, &last), SS_OK) << ss_last_error();
        ASSERT_EQ(heard.rounds.size(), 3u) << method;
        Round final{4, 4, layerOf(last, "V"), layerOf(last, "refined"), layerOf(last, "rays")};
        const double total = sum(final.rays);
        std::printf("%s: rays per round", method);
        for (const Round& r : heard.rounds) std::printf(" %.0f (check %.0f)", sum(r.rays), checkRays(r));
        std::printf(", last %.0f (check %.0f)\n", total, checkRays(final));
        EXPECT_EQ(checkRays(heard.rounds[0]), 0.0) << method << ": round 1 waits for no check";
        EXPECT_EQ(checkRays(heard.rounds[1]), 0.0) << method << ": round 2 is the uncertain pixels' rest";
        EXPECT_GT(checkRays(heard.rounds[2]), 0.25 * total) << method << ": round 3 checks the certain pixels";
        EXPECT_EQ(checkRays(heard.rounds[2]), checkRays(final)) << method << ": one check in all";
        EXPECT_LE(sum(heard.rounds[0].rays), 0.5 * total) << method;
        for (size_t k = 1; k < heard.rounds.size(); ++k)
            EXPECT_GE(sum(heard.rounds[k].rays), sum(heard.rounds[k - 1].rays)) << method << " round " << k + 1;
        EXPECT_GE(total, sum(heard.rounds.back().rays)) << method;
        ss_result_destroy(last);
    }
}

// auto's rounds carry the method it chose and the estimate its result carries, which falls
// round by round to the final one.
TEST(RefinementRounds, AutoHandsOutItsChoiceAndAnEstimateThatFalls) {
    Fixture f;
    Heard heard;
    ss_result* result = nullptr;
    ASSERT_EQ(render(f, "auto", 3, 0, &heard, &result), SS_OK) << ss_last_error();
    ASSERT_EQ(heard.rounds.size(), 2u);
    double before = INFINITY;
    for (const Round& r : heard.rounds) {
        EXPECT_EQ(r.method, ss_result_method(result));
        EXPECT_TRUE(std::isfinite(r.estimate)) << "round " << r.round;
        EXPECT_LE(r.estimate, before) << "round " << r.round;
        before = r.estimate;
    }
    EXPECT_LE(ss_result_estimated_rmse(result), before);
    std::printf("auto (%s): estimates %.4f, %.4f, final %.4f\n", ss_result_method(result), heard.rounds[0].estimate,
                heard.rounds[1].estimate, ss_result_estimated_rmse(result));
    ss_result_destroy(result);
}

// A round's callback stops the render by its return value or by cancelling the context; the
// context renders on afterwards. A call that would wait on the render is refused from inside.
TEST(RefinementRounds, ARoundCancelsTheRenderAndTheContextGoesOn) {
    Fixture f;
    for (bool byContext : {false, true}) {
        Heard heard;
        heard.stopAt = 2;
        heard.cancel = byContext ? f.context : nullptr;
        heard.reenter = f.context;
        heard.scene = f.scene;
        ss_result* result = nullptr;
        EXPECT_EQ(render(f, "pcss", 5, 0, &heard, &result), SS_ERROR_CANCELLED)
            << (byContext ? "ss_context_cancel_renders" : "a non-zero return");
        EXPECT_EQ(result, nullptr);
        EXPECT_EQ(heard.rounds.size(), 2u) << "no round after the cancel";
        EXPECT_EQ(heard.reentered, SS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(heard.reenterError.find("called from a progress callback"), std::string::npos) << heard.reenterError;
        ASSERT_EQ(render(f, "pcss", 1, 0, nullptr, &result), SS_OK) << ss_last_error();
        ss_result_destroy(result);
    }
    // Without a callback the rounds change nothing.
    ss_result *one = nullptr, *three = nullptr;
    ASSERT_EQ(render(f, "shadow_map", 0, 0, nullptr, &one), SS_OK);
    ASSERT_EQ(render(f, "shadow_map", 3, 0, nullptr, &three), SS_OK);
    EXPECT_EQ(layerOf(one, "V"), layerOf(three, "V"));
    ss_result_destroy(one);
    ss_result_destroy(three);
}

// Refinement is the option's: a count or a refine value out of range is refused naming the
// field, and "refine" or "refine_rounds" in the settings string are keys no method has.
TEST(RefinementRounds, TheOptionIsCheckedAndTheSettingsKeysAreGone) {
    Fixture f;
    for (int32_t rounds : {-2, 65}) {
        ss_result* bad = nullptr;
        ss_render_options o;
        ss_render_options_default(&o);
        o.refine = SS_REFINE_ON;
        o.refine_rounds = rounds;
        EXPECT_EQ(ss_render(f.context, f.scene, 0, "pcss", &o, &bad), SS_ERROR_INVALID_ARGUMENT) << rounds;
        EXPECT_NE(std::string(ss_last_error()).find("refine_rounds must be in 0..64"), std::string::npos)
            << ss_last_error();
        EXPECT_EQ(bad, nullptr);
    }
    ss_render_options o;
    ss_render_options_default(&o);
    EXPECT_EQ(o.refine, SS_REFINE_OFF);
    EXPECT_EQ(o.refine_rounds, 0);
    o.refine = ss_refine(2);
    ss_result* bad = nullptr;
    EXPECT_EQ(ss_render(f.context, f.scene, 0, "pcss", &o, &bad), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ss_last_error()).find("refine must be SS_REFINE_OFF or SS_REFINE_ON"),
              std::string::npos)
        << ss_last_error();
    for (const char* settings : {"refine=on", "refine_rounds=2"}) {
        EXPECT_EQ(render(f, "pcss", -1, 0, nullptr, &bad, settings), SS_ERROR_INVALID_ARGUMENT) << settings;
        const std::string key = std::string(settings).substr(0, std::string(settings).find('='));
        EXPECT_NE(std::string(ss_last_error()).find("has no setting '" + key + "'"), std::string::npos)
            << ss_last_error();
    }
}

}  // namespace
