// What a see-through mesh's material lets through at a fragment (ss::MeshAlpha): the alpha of
// the material being drawn (SceneCache::drawSeeThroughWhere draws one material at a time), and the
// hashed alpha test that turns it into a binary coverage whose average is the alpha (the light
// side), or the camera's threshold test.
// SPDX-License-Identifier: GPL-3.0-or-later
in vec2 vAlphaUv;
flat in uint vAlphaMaterial;

uniform uint uAlphaMaterial;      // the material drawn now
uniform int uAlphaTextured;       // 1: uAlphaTexture at the UV, 0: uAlphaConstant
uniform float uAlphaConstant;
uniform sampler2D uAlphaTexture;  // R32F, its wrap and filter as the material says
uniform float uCameraAlphaThreshold;  // ss::kCameraAlphaThreshold

// The fragment's alpha (1 opaque .. 0 transparent); discards fragments of other materials.
float seeThroughAlpha() {
    if (vAlphaMaterial != uAlphaMaterial) discard;
    return uAlphaTextured != 0 ? clamp(texture(uAlphaTexture, vAlphaUv).r, 0.0, 1.0) : uAlphaConstant;
}

// A threshold in [0, 1) per pixel of the target, uniform over pixels: a 2D integer hash.
float alphaHashThreshold(vec2 pixel) {
    uvec2 p = uvec2(pixel);
    uint h = p.x * 0x8da6b343u ^ p.y * 0xd8163841u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return float(h >> 8) * (1.0 / 16777216.0);
}

// Keeps the fragment with probability alpha (EEVEE's Alpha Hashed shadows): alpha 1 always
// covers, alpha 0 never, a filtered look-up of the target sees the alpha on average.
void alphaHashedTest(float alpha) {
    if (alpha <= alphaHashThreshold(gl_FragCoord.xy)) discard;
}

// Keeps the fragment where a camera ray stops at the surface (ss::MeshAlpha::seenByCamera).
void cameraAlphaTest(float alpha) {
    if (alpha < uCameraAlphaThreshold) discard;
}
