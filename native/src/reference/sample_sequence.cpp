// How Owen-scrambled Sobol points are computed (Burley 2020, "Practical hash-based Owen scrambling").
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/sample_sequence.h"

namespace ss {
namespace {

uint32_t reverseBits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

// Sobol dimension 0 is the base-2 radical inverse; dimension 1 uses the direction numbers of
// the primitive polynomial x + 1 (v_k = v_{k-1} ^ (v_{k-1} >> 1)).
uint32_t sobol0(uint32_t index) { return reverseBits(index); }

uint32_t sobol1(uint32_t index) {
    uint32_t result = 0;
    for (uint32_t v = 1u << 31; index; index >>= 1, v ^= v >> 1)
        if (index & 1u) result ^= v;
    return result;
}

// Laine-Karras style permutation: each bit is flipped by a function of the bits below it,
// which after bit reversal is exactly a nested uniform scramble of the bits above it.
uint32_t laineKarras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

uint32_t owenScramble(uint32_t x, uint32_t seed) {
    return reverseBits(laineKarras(reverseBits(x), seed));
}

// 24 bits so the float is exact and strictly below 1.
float toUnit(uint32_t x) { return float(x >> 8) * (1.0f / 16777216.0f); }

}  // namespace

uint32_t hashU32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

SampleSequence::SampleSequence(uint32_t seed, uint32_t x, uint32_t y) {
    uint32_t h = hashU32(seed ^ hashU32(x ^ hashU32(y + 0x9e3779b9u)));
    scrambleX_ = hashU32(h ^ 0x68bc21ebu);
    scrambleY_ = hashU32(h ^ 0x02e5be93u);
}

glm::vec2 SampleSequence::point(uint32_t index) const {
    return {toUnit(owenScramble(sobol0(index), scrambleX_)),
            toUnit(owenScramble(sobol1(index), scrambleY_))};
}

}  // namespace ss
