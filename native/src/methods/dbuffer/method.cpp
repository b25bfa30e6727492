// How the dbuffer method renders: volumes into the D-buffer from the light centre, then eq. 3 per pixel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"
#include "methods/dbuffer/geometry.h"
#include "methods/method.h"
#include "scene_cache/scene_cache.h"

namespace ss {

namespace {

// Volumes overlap: keep the surface farthest from the light (paper §4, concave and overlapping
// occluders). Both sides drawn: the soups have no consistent winding.
constexpr gl::RenderState kFarthest{"dbuffer_farthest", true, GL_GREATER, true, true, false,
                                    GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};
// The umbra volume writes R, G and the penumbra volume B, A of the one D-buffer target.
constexpr unsigned kUmbraChannels = 0x3, kPenumbraChannels = 0xC;
// The umbra "first exit" rule: the nearest umbra surface beyond the first caster.
constexpr gl::RenderState kNearest{"dbuffer_nearest", true, GL_LESS, true, true, false,
                                   GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};

// How far beyond the first caster, relative to its distance, an umbra fragment must lie to count
// as the ray's exit from the umbra (first-exit rule). The D-buffer is drawn with the shared map's
// matrix and resolution, so a caster triangle drawn again as a silhouette face lands on the same
// texels at the same distance up to float rounding (~1e-6 relative); 1e-5 is well above that.
// It must stay far below a texel (~6e-4 of the distance at 2048² on the demo scene): where a ray
// grazes the occluder next to its silhouette the real exit (a silhouette face on the far side)
// lies a millimetre or less behind the caster, and the former threshold of 1.5 texels discarded
// it, leaving "no exit" = umbra: V = 0 dots along the centre's hard-shadow boundary.
constexpr float kExitEpsilon = 1e-5f;

// One volume soup on the GPU.
struct GpuSoup {
    gl::BufferHandle buffer;
    gl::VertexArrayHandle vao;
    GLsizei count = 0;
};

GpuSoup upload(const std::vector<VolumeVertex>& soup) {
    GpuSoup s;
    s.count = GLsizei(soup.size());
    if (soup.empty()) return s;
    const gl::Functions& g = gl::api();
    s.buffer = gl::makeBuffer(soup.data(), soup.size() * sizeof(VolumeVertex));
    GLuint vao = 0;
    g.CreateVertexArrays(1, &vao);
    s.vao = gl::VertexArrayHandle(vao);
    g.VertexArrayVertexBuffer(vao, 0, s.buffer.id(), 0, sizeof(VolumeVertex));
    const GLuint offsets[4] = {offsetof(VolumeVertex, position), offsetof(VolumeVertex, edgeA),
                               offsetof(VolumeVertex, edgeB), offsetof(VolumeVertex, extrusion)};
    for (GLuint i = 0; i < 5; ++i) {
        if (i < 4) g.VertexArrayAttribFormat(vao, i, 3, GL_FLOAT, GL_FALSE, offsets[i]);
        else g.VertexArrayAttribFormat(vao, i, 1, GL_FLOAT, GL_FALSE, offsetof(VolumeVertex, kind));
        g.VertexArrayAttribBinding(vao, i, 0);
        g.EnableVertexArrayAttrib(vao, i);
    }
    return s;
}

void draw(const GpuSoup& s) {
    if (s.count == 0) return;
    const gl::Functions& g = gl::api();
    g.BindVertexArray(s.vao.id());
    g.DrawArrays(GL_TRIANGLES, 0, s.count);
    g.BindVertexArray(0);
}

// The most layers the volume passes split the parts into; the parts left over share the last
// (where the rule within a part then applies among them).
constexpr size_t kMaxPartLayers = 32;

// Parts (ShadowVolumes::parts) whose volumes' footprints in the map do not overlap, drawn together.
struct PartLayer {
    std::vector<std::pair<GLint, GLsizei>> ranges;  // vertex ranges of the umbra or penumbra soup
    std::vector<glm::ivec4> rects;                  // texel rectangles (x0, y0, x1, y1), exclusive
    glm::ivec4 bounds{0, 0, 0, 0};
};

bool overlaps(const glm::ivec4& a, const glm::ivec4& b) {
    return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
}

// The texel rectangle a part's soup covers in the map (the whole map when a vertex lies behind
// its origin). `ownImage`: only the vertices on the part itself (the near ends of its quads and
// its silhouette faces), for the umbra: the umbra lies inside the part's hard shadow, so a ray
// that matters enters the part's umbra volume through the part, inside the part's own image.
// The penumbra reaches out from it by the light's angular radius, which the far ends of the
// penumbra volume's quads and fans mark.
glm::ivec4 footprint(const std::vector<VolumeVertex>& soup, size_t first, size_t count, const ShadowMap& map,
                     bool ownImage) {
    const glm::mat4 m = map.worldToClip();
    glm::vec2 lo(1e30f), hi(-1e30f);
    auto depth = [&](const glm::vec3& p) { return glm::dot(p - map.origin, map.axis); };
    for (size_t i = first; i < first + count; ++i) {
        const VolumeVertex& v = soup[i];
        glm::vec3 p = v.position;
        if (v.kind != float(int(VolumeKind::SilhouetteFace)) && p != v.edgeA && p != v.edgeB) {
            if (ownImage) continue;
            // A far end: only as far as the map's far plane, where the last receiver can be.
            const glm::vec3 near = glm::length(p - v.edgeA) < glm::length(p - v.edgeB) ? v.edgeA : v.edgeB;
            const float dn = depth(near), dp = depth(p);
            if (dp > map.farPlane && dp > dn) p = near + (p - near) * ((map.farPlane - dn) / (dp - dn));
        }
        glm::vec4 c = m * glm::vec4(p, 1.0f);
        if (!(c.w > 0.0f)) return {0, 0, map.size, map.size};
        glm::vec2 ndc = glm::vec2(c) / c.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    if (lo.x > hi.x) return {0, 0, 0, 0};
    auto texel = [&](float ndc) { return std::clamp((ndc * 0.5f + 0.5f) * float(map.size), 0.0f, float(map.size)); };
    return {int(std::floor(texel(lo.x))) - 2, int(std::floor(texel(lo.y))) - 2, int(std::ceil(texel(hi.x))) + 2,
            int(std::ceil(texel(hi.y))) + 2};
}

// Splits the parts' umbra (or penumbra) soups into layers of non-overlapping footprints:
// largest first, each into the first layer it fits.
std::vector<PartLayer> partLayers(const DbufferGeometry& geo, const ShadowMap& map, bool penumbra) {
    struct Part {
        GLint first;
        GLsizei count;
        glm::ivec4 rect;
    };
    std::vector<Part> parts;
    size_t first = 0;
    const std::vector<VolumeVertex>& all = penumbra ? geo.volumes.penumbra : geo.volumes.umbra;
    for (const auto& [umbraCount, penumbraCount] : geo.volumes.parts) {
        const size_t count = penumbra ? penumbraCount : umbraCount;
        if (count > 0) parts.push_back({GLint(first), GLsizei(count), footprint(all, first, count, map, !penumbra)});
        first += count;
    }
    auto area = [](const glm::ivec4& r) { return int64_t(r.z - r.x) * int64_t(r.w - r.y); };
    std::stable_sort(parts.begin(), parts.end(), [&](const Part& a, const Part& b) { return area(a.rect) > area(b.rect); });
    std::vector<PartLayer> layers;
    for (const Part& part : parts) {
        const glm::ivec4& rect = part.rect;
        if (area(rect) <= 0) continue;
        PartLayer* home = nullptr;
        for (PartLayer& l : layers) {
            bool free = true;
            for (const glm::ivec4& r : l.rects) free = free && !overlaps(r, rect);
            if (free) {
                home = &l;
                break;
            }
        }
        if (!home && layers.size() < kMaxPartLayers) {
            layers.emplace_back();
            layers.back().bounds = rect;
        }
        if (!home) home = &layers.back();
        home->ranges.emplace_back(part.first, part.count);
        home->rects.push_back(rect);
        home->bounds = {std::min(home->bounds.x, rect.x), std::min(home->bounds.y, rect.y),
                        std::max(home->bounds.z, rect.z), std::max(home->bounds.w, rect.w)};
    }
    return layers;
}

constexpr SettingSpec kUmbraRule = choiceSetting("umbra_rule", "first_exit|farthest", "which exit depth bounds the umbra");
constexpr SettingSpec kSmallOccluders =
    flagSetting("small_occluders", false, "the small-occluder correction of the paper");
constexpr SettingSpec kProfile = choiceSetting("profile", "smoothstep|segment", "visibility profile across the penumbra");
constexpr SettingSpec kBiasTexels = floatSetting("bias_texels", 1.5, 0.0, 1000.0, "depth bias in shadow-map texels");
// formula=paper: eq. 2 and eq. 3 as printed (docs/methods/dbuffer.md names the repairs).
constexpr SettingSpec kFormula = choiceSetting("formula", "exact|paper", "exact, or eq. 2 and 3 as printed");
// Tests: t and V before any clamping, so a NaN or infinity stays visible.
constexpr SettingSpec kRawLayers = flagSetting("debug.raw_layers", false, "unclamped t and V layers");
// The benchmark: glFinish at each stage so the progress marks time the GPU.
constexpr SettingSpec kFinishStages = flagSetting("debug.finish_stages", false, "glFinish at each stage");

class DbufferMethod final : public Method {
public:
    DbufferMethod()
        : Method("dbuffer", MethodDevice::Gl,
                 {kShadowMapSizeSetting, kUmbraRule, kSmallOccluders, kProfile, kBiasTexels, kFormula, kRawLayers,
                  kFinishStages}) {}

    void prepare(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        settings.report(0.0f, "silhouettes and volumes");
        geometry_ = dbufferGeometry(sceneCache.scene(), lightIndex, sceneCache.shadowFitBounds(lightIndex), settings.cancel);
    }

    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        // A cache hit when prepare() ran for this light (the cache keys on scene and light).
        geometry_ = dbufferGeometry(sceneCache.scene(), lightIndex, sceneCache.shadowFitBounds(lightIndex), settings.cancel);
        const DbufferGeometry& geo = *geometry_;
        const gl::Functions& g = sceneCache.gl();
        const bool finishStages = settings.flag(kFinishStages);
        auto finishStage = [&] {
            if (finishStages) g.Finish();
        };
        finishStage();
        const bool paper = settings.choice(kFormula) == "paper";
        const bool raw = settings.flag(kRawLayers);
        const CameraPass& cam = sceneCache.cameraPass();
        finishStage();
        const ShadowMap& map = sceneCache.shadowMap(lightIndex, shadowMapSizeSetting(settings));
        finishStage();

        // D-buffer: the shared map's view, so its texels are the shadow map's texels.
        settings.report(0.3f, "D-buffer pass");
        const bool firstExit = settings.choice(kUmbraRule) == "first_exit";
        const DbufferKey key{sceneCache.scene().lightGeometryKey(lightIndex), map.size, firstExit, paper, map.worldToClip()};
        if (dbufferKey_ && *dbufferKey_ == key) {
            ++stats_.lightWorkKept;
        } else {
            dbufferKey_.reset();  // until it is drawn
            drawDbuffer(sceneCache, map, geo, firstExit, paper);
            dbufferKey_ = key;
            ++stats_.lightWorkMade;
        }
        finishStage();

        // Camera pass: eq. 3 and eq. 4 per pixel.
        settings.report(0.7f, "camera pass");
        gl::Framebuffer& out =
            raw ? gl::scratchFramebuffer("dbuffer.camera.raw", cam.width, cam.height, {GL_RGBA32F, GL_RGBA32F, GL_RGBA32F})
                : gl::scratchFramebuffer("dbuffer.camera", cam.width, cam.height, {GL_RGBA32F, GL_RGBA32F});
        out.bind();
        gl::apply(gl::states::overwrite);  // writes every pixel: no clear needed
        const gl::Program& shade = gl::program("common/fullscreen.vert.glsl", "dbuffer/camera.frag.glsl");
        shade.use();
        int unit = sceneCache.bindCameraPass(shade, 0);
        unit = sceneCache.bindShadowMap(shade, map, unit);
        shade.setTexture("uDBuffer", unit++, dbuffer_.id());
        sceneCache.setLightUniforms(shade, lightIndex);
        shade.set("uCentre", geo.disk.centre);
        shade.set("uSmallOccluders", settings.flag(kSmallOccluders) ? 1 : 0);
        std::string profile = settings.choice(kProfile);
        shade.set("uSegmentProfile", profile == "segment" ? 1 : 0);
        shade.set("uBiasTexels", settings.number(kBiasTexels));
        shade.set("uPaperFormula", paper ? 1 : 0);
        sceneCache.drawFullscreen();
        g.BindFramebuffer(GL_FRAMEBUFFER, 0);
        g.check("drawing the dbuffer camera pass");
        finishStage();

        // One read-back per attachment (top row first); without extra layers only V and mask.
        Layers layers;
        std::vector<Image> result = out.readChannels(0, settings.extraLayers ? 4 : 2);
        layers.add("V", std::move(result[0]));
        layers.add("mask", std::move(result[1]));
        if (settings.extraLayers) {
            std::vector<Image> dist = out.readChannels(1, 4);
            // Where the camera point lies inside the geometric volumes: not the umbra/penumbra
            // classes of V (core/visibility_classes.h), which the renderer adds.
            layers.add("umbra_volume", std::move(result[2]));
            layers.add("penumbra_volume", std::move(result[3]));
            layers.add("dist_occluder", std::move(dist[0]));
            layers.add("dist_umbra", std::move(dist[1]));
            layers.add("dist_penumbra", std::move(dist[2]));
            layers.add("dist_silhouette", std::move(dist[3]));
        }
        if (raw) {
            std::vector<Image> unclamped = out.readChannels(2, 2);
            layers.add("raw_t", std::move(unclamped[0]));
            layers.add("raw_V", std::move(unclamped[1]));
        }
        finishStage();
        settings.report(1.0f, "done");
        return layers;
    }

private:
    // What the D-buffer shows: the light's volumes and shadow map (both kept for the light's
    // geometry key), drawn with these settings.
    struct DbufferKey {
        Scene::LightGeometryKey geometry;
        int mapSize = 0;
        bool firstExit = true, paper = false;
        glm::mat4 mapView{1.0f};  // a map fit around what the camera sees moves with it
        bool operator==(const DbufferKey&) const = default;
    };

    // Draws the volumes into dbuffer_ (made at the map's size), with the map's matrix.
    void drawDbuffer(SceneCache& sceneCache, const ShadowMap& map, const DbufferGeometry& geo, bool firstExit, bool paper) {
        const gl::Functions& g = sceneCache.gl();
        if (dbuffer_.width() != map.size) dbuffer_ = gl::Texture(map.size, map.size, GL_RGBA32F, GL_NEAREST);
        // The depth is needed only while drawing: a scratch target's, shared with other renders.
        gl::Framebuffer target(map.size, map.size, {});
        target.attachColor(0, dbuffer_.id());
        target.attachDepth(gl::scratchFramebuffer("dbuffer.depth", map.size, map.size, {}, GL_DEPTH_COMPONENT32F)
                               .depth()
                               .id());
        target.bind();
        gl::apply(kFarthest);  // every channel written: clears honour the colour mask
        target.clearColor(0, glm::vec4(0.0f));
        const gl::Program& vol = gl::program("dbuffer/volume.vert.glsl", "dbuffer/volume.frag.glsl");
        vol.use();
        sceneCache.bindShadowMap(vol, map, 0);  // the first-exit rule reads the casters' distances
        vol.set("uWorldToClip", map.worldToClip());
        vol.set("uCentre", geo.disk.centre);
        vol.set("uNormal", geo.disk.normal);
        vol.set("uRadius", geo.disk.radius);
        // Depth = distance / uFar: anything past the far plane is clipped anyway.
        float far = glm::length(map.origin - geo.disk.centre) + map.farPlane * 2.0f + 1e-6f;
        vol.set("uFar", far);
        vol.set("uPaperFormula", paper ? 1 : 0);
        vol.set("uPartRect", glm::vec4(0.0f));
        GpuSoup umbra = upload(geo.volumes.umbra), penumbra = upload(geo.volumes.penumbra);
        // Umbra volume into R, G; then penumbra volume into B, A, each with its own depth test.
        vol.set("uBeyondOccluder", firstExit ? 1 : 0);
        vol.set("uExitEpsilon", kExitEpsilon);
        const std::vector<PartLayer> layers = firstExit ? partLayers(geo, map, false) : std::vector<PartLayer>{};
        if (layers.size() > 1) {
            drawLayers(sceneCache, map, umbra, layers, target, vol, far, false);
            target.bind();
            vol.use();
        } else {
            gl::RenderState umbraState = firstExit ? kNearest : kFarthest;
            umbraState.channels = kUmbraChannels;
            gl::apply(umbraState);
            target.clearDepth(firstExit ? 1.0f : 0.0f);
            draw(umbra);
        }
        vol.set("uBeyondOccluder", -1);  // in front of the first caster only (volume.frag.glsl)
        const std::vector<PartLayer> penumbraLayers = firstExit ? partLayers(geo, map, true) : std::vector<PartLayer>{};
        if (penumbraLayers.size() > 1) {
            drawLayers(sceneCache, map, penumbra, penumbraLayers, target, vol, far, true);
        } else {
            gl::RenderState penumbraState = kFarthest;
            penumbraState.channels = kPenumbraChannels;
            gl::apply(penumbraState);
            target.clearDepth(0.0f);
            draw(penumbra);
        }
        g.BindFramebuffer(GL_FRAMEBUFFER, 0);
        g.check("drawing the D-buffer");
    }

    // Several parts (ShadowVolumes::parts: meshes and their separate pieces). Umbra: the ray is
    // in the umbra while it is inside any part's umbra volume, so each part's exit is its own
    // nearest umbra surface beyond the first caster and the D-buffer keeps the farthest of those.
    // A single nearest exit over all parts is the exit from the first part's volume (a small part
    // near the light leaves its own umbra within centimetres) and painted the assembly's umbra as
    // penumbra. Penumbra: each part's last entry in front of the receiver (its farthest surface
    // there), and of those the nearest, the part that hides most of the light; the farthest over
    // all parts is the part whose penumbra the ray entered last, just in front of the receiver,
    // and read almost lit. Parts whose footprints overlap go to different layers: each layer is
    // drawn with the rule within a part into its own target, then merged into the D-buffer by the
    // rule across parts.
    void drawLayers(SceneCache& sceneCache, const ShadowMap& map, const GpuSoup& soup, const std::vector<PartLayer>& layers,
                    gl::Framebuffer& target, const gl::Program& vol, float far, bool penumbra) {
        const gl::Functions& g = sceneCache.gl();
        gl::Framebuffer& layerTarget =
            gl::scratchFramebuffer("dbuffer.part_layer", map.size, map.size, {GL_RG32F}, GL_DEPTH_COMPONENT32F);
        const gl::Program& merge = gl::program("common/fullscreen.vert.glsl", "dbuffer/merge_layer.frag.glsl");
        gl::RenderState within = penumbra ? kFarthest : kNearest;
        within.channels = kUmbraChannels;
        gl::RenderState across = penumbra ? kNearest : kFarthest;
        across.channels = penumbra ? kPenumbraChannels : kUmbraChannels;
        target.bind();
        gl::apply(across);
        target.clearDepth(penumbra ? 1.0f : 0.0f);
        for (const PartLayer& layer : layers) {
            const glm::ivec4 r = glm::clamp(layer.bounds, glm::ivec4(0), glm::ivec4(map.size));
            if (r.z <= r.x || r.w <= r.y) continue;
            layerTarget.bind();
            gl::apply(within);
            g.Enable(GL_SCISSOR_TEST);
            g.Scissor(r.x, r.y, r.z - r.x, r.w - r.y);
            layerTarget.clearColor(0, glm::vec4(0.0f));
            layerTarget.clearDepth(penumbra ? 0.0f : 1.0f);
            vol.use();
            g.BindVertexArray(soup.vao.id());
            for (size_t k = 0; k < layer.ranges.size(); ++k) {
                vol.set("uPartRect", glm::vec4(layer.rects[k]));
                g.DrawArrays(GL_TRIANGLES, layer.ranges[k].first, layer.ranges[k].second);
            }
            vol.set("uPartRect", glm::vec4(0.0f));
            g.BindVertexArray(0);
            target.bind();
            gl::apply(across);
            g.Enable(GL_SCISSOR_TEST);
            g.Scissor(r.x, r.y, r.z - r.x, r.w - r.y);
            merge.use();
            merge.setTexture("uLayer", 1, layerTarget.colorId(0));
            merge.set("uFar", far);
            sceneCache.drawFullscreen();
        }
        g.Disable(GL_SCISSOR_TEST);
        g.check("drawing the D-buffer's part layers");
    }

    std::shared_ptr<const DbufferGeometry> geometry_;
    // The last D-buffer drawn (map size², RGBA32F: 64 MiB at the default 2048²): the volumes
    // are drawn from the light, so a camera edit or another light's edit keeps it, and the
    // preview's orbit and a re-render shade it again without the ~0.1 s pass (1M triangles).
    // After a move it is drawn whole: a redraw scissored to the moved box's 120² texels took as
    // long as the whole pass on 1M triangles, whose cost is per volume triangle, not per texel
    // (nor the clipping at the map's far plane: with that plane pushed out it took longer).
    gl::Texture dbuffer_;
    std::optional<DbufferKey> dbufferKey_;
};

}  // namespace

std::unique_ptr<Method> makeDbufferMethod() { return std::make_unique<DbufferMethod>(); }

}  // namespace ss
