# What the benchmark run found: bench/results/report.md (headlines, tables, SVG plots, strips)
# and foundation.md (ms per stage at 512² and 1024²), from one run's raw outputs.
# SPDX-License-Identifier: GPL-3.0-or-later
# python3 bench/report.py WORK OUT WIDTH HEIGHT TRUTH_SAMPLES QUICK   (system python3 + numpy;
# plots are written as SVG by hand so nothing beyond numpy is needed).
import glob
import json
import math
import os
import platform
import re
import subprocess
import sys


STAGES = [("mesh_upload_ms", "mesh upload"), ("camera_pass_ms", "camera pass"),
          ("shadow_map_ms", "shadow map"), ("prepare_ms", "prepare"), ("render_ms", "method render"),
          ("readback_ms", "readback (1 layer)")]
COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
          "#bcbd22", "#17becf", "#000000", "#aec7e8", "#ffbb78", "#98df8a"]


def load(path, default=None):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return default


# ---------------------------------------------------------------- SVG by hand
def svg_plot(path, title, series, xlabel, ylabel, logx=True, logy=False, lines=False):
    """series: [(label, [(x, y), ...])]. Writes a 560x360 SVG with a legend on the right."""
    pts = [(x, y) for _, s in series for x, y in s if x is not None and y is not None and x > 0
           and (y > 0 or not logy)]
    if not pts:
        return False
    W, H, L, R, T, B = 640, 360, 60, 190, 30, 45
    fx = (lambda v: math.log10(v)) if logx else (lambda v: v)
    fy = (lambda v: math.log10(v)) if logy else (lambda v: v)
    xs, ys = [fx(x) for x, _ in pts], [fy(y) for _, y in pts]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    if not logy:
        y0 = min(0.0, y0)
    if x1 - x0 < 1e-9:
        x0, x1 = x0 - 0.5, x1 + 0.5
    if y1 - y0 < 1e-9:
        y0, y1 = y0 - 0.5, y1 + 0.5
    padx, pady = 0.05 * (x1 - x0), 0.08 * (y1 - y0)
    x0, x1, y0, y1 = x0 - padx, x1 + padx, y0 - (pady if logy else 0), y1 + pady

    def px(v):
        return L + (fx(v) - x0) / (x1 - x0) * (W - L - R)

    def py(v):
        return H - B - (fy(v) - y0) / (y1 - y0) * (H - T - B)

    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" '
           'font-size="11">' % (W, H), '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="18" font-size="13">%s</text>' % (L, title),
           '<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="#888"/>' % (L, T, W - L - R, H - T - B)]

    def ticks(lo, hi, log):
        if log:
            return [10 ** k for k in range(math.floor(lo), math.ceil(hi) + 1)
                    if lo <= k <= hi] or [10 ** ((lo + hi) / 2)]
        step = 10 ** math.floor(math.log10((hi - lo) / 4 or 1))
        for m in (1, 2, 5, 10):
            if (hi - lo) / (step * m) <= 6:
                step *= m
                break
        return [k * step for k in range(math.ceil(lo / step), math.floor(hi / step) + 1)]

    for t in ticks(x0, x1, logx):
        out.append('<line x1="%.1f" x2="%.1f" y1="%d" y2="%d" stroke="#eee"/>' % (px(t), px(t), T, H - B))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">%g</text>' % (px(t), H - B + 14, t))
    for t in ticks(y0, y1, logy):
        out.append('<line x1="%d" x2="%d" y1="%.1f" y2="%.1f" stroke="#eee"/>' % (L, W - R, py(t), py(t)))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%g</text>' % (L - 4, py(t) + 4, t))
    out.append('<text x="%d" y="%d" text-anchor="middle">%s</text>' % ((L + W - R) / 2, H - 8, xlabel))
    out.append('<text x="14" y="%d" transform="rotate(-90 14 %d)" text-anchor="middle">%s</text>'
               % ((T + H - B) / 2, (T + H - B) / 2, ylabel))
    for i, (label, s) in enumerate(series):
        c = COLORS[i % len(COLORS)]
        s = [(x, y) for x, y in s if x is not None and y is not None and x > 0 and (y > 0 or not logy)]
        if lines and len(s) > 1:
            out.append('<polyline fill="none" stroke="%s" points="%s"/>'
                       % (c, " ".join("%.1f,%.1f" % (px(x), py(y)) for x, y in sorted(s))))
        for x, y in s:
            out.append('<circle cx="%.1f" cy="%.1f" r="3.5" fill="%s"/>' % (px(x), py(y), c))
        ly = T + 12 + 14 * i
        out.append('<circle cx="%d" cy="%d" r="4" fill="%s"/><text x="%d" y="%d">%s</text>'
                   % (W - R + 12, ly - 4, c, W - R + 20, ly, label))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out))
    return True


# ---------------------------------------------------------------- data
def bench_rows(path):
    data = load(path, {}) or {}
    return [b for b in data.get("benchmarks", []) if b.get("run_type", "iteration") == "iteration"]


def error_of(work, scene, key, region=""):
    """The V pass's error row against the truth: over all surfaces (region "") or, with region
    "receivers", over the receiver objects' pixels the light reaches (bench/scenes.py RECEIVERS)."""
    rows = load(os.path.join(work, "errors", scene, key + (".%s" % region if region else "") + ".json"))
    if not rows:
        return None
    for r in rows:  # the V pass (not mask/umbra/penumbra)
        if not re.search(r"_(mask|umbra|penumbra)$", r["a"]):
            return r
    return rows[0]


def cli_seconds(path, method="reference"):
    """The render report's seconds for the row that asked for `method`."""
    try:
        for line in open(path):
            parts = line.split()
            if len(parts) >= 4 and parts[1] == method:
                return float(parts[3])
    except (OSError, ValueError):
        pass
    return None


def cli_auto(path):
    """(seconds, method it took, estimated RMSE or None) from the CLI's render report of `auto`."""
    try:
        for line in open(path):
            parts = line.split()
            if len(parts) >= 5 and parts[1] == "auto":
                return float(parts[3]), parts[2], None if parts[4] == "-" else float(parts[4])
    except (OSError, ValueError):
        pass
    return None, None, None


# EEVEE Next's settings (bench/eevee_next.py SETTINGS): an artist's defaults, and 64 samples with
# jittered soft shadows and 4 rays x 16 steps.
NEXT_KEYS = ("eevee_next_default", "eevee_next_64j")
NEXT = "eevee-next-default"


def collect(work, out):
    ours = {}
    for b in bench_rows(os.path.join(out, "scene_files.json")):
        m = re.match(r"BM_SceneFile/([^/]+)/([^/]+)", b["name"])
        if m and not b.get("error_occurred"):
            ours[(m.group(1), m.group(2))] = b
    scenes = []
    for d in sorted(glob.glob(os.path.join(work, "scenes", "*", ""))):
        name = os.path.basename(os.path.dirname(d))
        info = load(os.path.join(d, "blender.json"), {}) or {}
        rows = []
        for (scene, method), b in sorted(ours.items()):
            if scene == name:
                rows.append({"key": method, "kind": "ours", "ms": b["real_time"],
                             "stages": {k: b.get(k) for k, _ in STAGES}, "err": error_of(work, name, method)})
        ours_dir = os.path.join(work, "ours", name)
        traced = load(os.path.join(ours_dir, "traced.json"), {}) or {}
        sec, took, estimate = cli_auto(os.path.join(ours_dir, "auto.txt"))
        if sec is not None:
            picked = cli_seconds(os.path.join(ours_dir, "picked.txt"), took)
            rows.append({"key": "auto", "kind": "ours-auto", "ms": sec * 1000, "stages": None, "took": took,
                         "estimate": estimate, "picked_ms": picked * 1000 if picked else None,
                         "err": error_of(work, name, "auto")})
        sec, took, estimate = cli_auto(os.path.join(ours_dir, "auto-refine.txt"))
        if sec is not None:
            picked = cli_seconds(os.path.join(ours_dir, "picked-refine.txt"), took)
            rows.append({"key": "auto-refine", "kind": "ours-refine", "ms": sec * 1000, "stages": None, "took": took,
                         "estimate": estimate, "traced": traced.get("auto-refine"),
                         "picked_ms": picked * 1000 if picked else None,
                         "err": error_of(work, name, "auto-refine")})
        s = cli_seconds(os.path.join(d, "reference.txt"))
        rows.append({"key": "reference", "kind": "ours-cpu", "ms": s * 1000 if s else None, "stages": None,
                     "err": error_of(work, name, "reference")})
        s = cli_seconds(os.path.join(ours_dir, "reference-adaptive.txt"))
        if s is not None:
            rows.append({"key": "reference-adaptive", "kind": "ours-adaptive", "ms": s * 1000, "stages": None,
                         "traced": traced.get("reference-adaptive"),
                         "err": error_of(work, name, "reference-adaptive")})
        for key, sec in sorted(info.get("renders", {}).items(),
                               key=lambda kv: (kv[0].split("_")[0], int(kv[0].split("_")[1]))):
            rows.append({"key": key.replace("_", "-"), "kind": key.split("_")[0], "ms": sec * 1000.0,
                         "stages": None, "err": error_of(work, name, key)})
        nxt = load(os.path.join(d, "blender_next.json"), {}) or {}
        for key in NEXT_KEYS:
            if key in nxt.get("renders", {}):
                rows.append({"key": key.replace("_", "-"), "kind": "eevee-next", "ms": nxt["renders"][key] * 1000.0,
                             "stages": None, "err": error_of(work, name, key)})
        for r in rows:
            r["err_recv"] = error_of(work, name, r["key"].replace("-", "_")
                                     if r["kind"] in ("eevee", "eevee-next", "cycles") else r["key"], "receivers")
        scenes.append({"name": name, "triangles": info.get("triangles"), "rows": rows,
                       "size": "%sx%s" % (info.get("width"), info.get("height")),
                       "receiver_pixels": info.get("receiver_pixels"), "next": nxt})
    return scenes


def fmt(v, spec="%.4f"):
    return "—" if v is None else spec % v


# ---------------------------------------------------------------- headline
def rmse(r, region):
    e = r.get("err_recv" if region == "receivers" else "err") if r else None
    return e["rmse"] if e else None


def verdict(mine, theirs):
    if mine is None or theirs is None:
        return "—"
    return ("%.4f ≤ %.4f" if mine <= theirs else "**%.4f > %.4f**") % (mine, theirs)


# The two ways users get `auto`: a final render (F12, -a, the farm: refine=on, the add-on's
# default) and a script's render_passes (the GL pass alone).
AUTO_PATHS = (("auto-refine", "final renders", "`softshadow render -m auto --set refine=on`"),
              ("auto", "the GL pass alone", "`softshadow render -m auto`"))


def estimate_holds(r):
    """Issue 17: the estimate within ±30 % or ±0.005 of the measured RMSE (all surfaces)."""
    est, meas = r.get("estimate"), rmse(r, "all")
    return est is not None and meas is not None and (abs(est - meas) <= 0.005 or abs(est - meas) <= 0.3 * meas)


def best_of(rows, key):
    """What auto is held against: for the GL pass alone the best GL method at its defaults, for
    final renders the adaptive reference (the exact method a user would otherwise pick)."""
    if key == "auto-refine":
        exact = [r for r in rows if r["key"] == "reference-adaptive" and r["err"]]
        return exact[0] if exact else None
    gl = [r for r in rows if r["kind"] == "ours" and r["err"] and r["ms"] and "-" not in r["key"]]
    return min(gl, key=lambda r: r["err"]["rmse"]) if gl else None


NEXT_LABELS = {"eevee-next-default": "EEVEE Next defaults", "eevee-next-64j": "EEVEE Next 64 jittered 4×16"}


def headline(scene, key):
    """One auto path against EEVEE Next's defaults, EEVEE-64 and Cycles-16/64, on receivers and
    all surfaces."""
    rows = scene["rows"]
    by = {r["key"]: r for r in rows}
    auto, ee = by.get(key), by.get("eevee-64")
    parts = []
    if not auto or not auto["err"]:
        return "- **%s**: %s has no result (see the run's log)" % (scene["name"], key)
    took = (auto.get("took") or "?") + (" refine=on" if key == "auto-refine" else "")
    parts.append("**auto** took %s in %.0f ms (CLI, fresh process%s)" % (
        took, auto["ms"], ", %.1f× the %.0f ms of %s alone" % (auto["ms"] / auto["picked_ms"], auto["picked_ms"], took)
        if auto.get("picked_ms") else ""))
    nx = by.get(NEXT)
    if nx:
        parts.append("receivers %s, all surfaces %s against EEVEE Next at its defaults" % (
            verdict(rmse(auto, "receivers"), rmse(nx, "receivers")), verdict(rmse(auto, "all"), rmse(nx, "all"))))
    parts.append("receivers %s, all surfaces %s against EEVEE-64" % (
        verdict(rmse(auto, "receivers"), rmse(ee, "receivers")), verdict(rmse(auto, "all"), rmse(ee, "all"))))
    parts.append("estimate %s beside measured %.4f (all surfaces)%s" % (
        fmt(auto.get("estimate")), rmse(auto, "all"), "" if estimate_holds(auto) else " (**outside ±30 %**)"))
    cyc = ["Cycles-%s %s / %s" % (k.split("-")[1], fmt(rmse(by[k], "receivers")), fmt(rmse(by[k], "all")))
           for k in ("cycles-16", "cycles-64") if k in by]
    nxt = ["%s %s / %s in %.0f ms" % (NEXT_LABELS[k], fmt(rmse(by[k], "receivers")), fmt(rmse(by[k], "all")),
                                      by[k]["ms"]) for k in NEXT_LABELS if k in by]
    if cyc or nxt:
        parts.append("receivers / all: " + ", ".join(["EEVEE-64 %s / %s in %s ms" % (
            fmt(rmse(ee, "receivers")), fmt(rmse(ee, "all")), fmt(ee["ms"] if ee else None, "%.0f"))] + nxt + cyc))
    best = best_of(rows, key)
    if best:
        ratio = rmse(auto, "all") / best["err"]["rmse"] if best["err"]["rmse"] > 0 else float("inf")
        parts.append("best of our %s at their defaults %s %.4f: auto %.2f× it%s" % (
            "GL methods" if key == "auto" else "exact methods", best["key"], best["err"]["rmse"], ratio,
            "" if ratio <= 1.25 else " (**above the 1.25× target**)"))
    return "- **%s** (%s, %s triangles): %s" % (scene["name"], scene.get("size"), scene["triangles"], "; ".join(parts))


def headline_exact(scene):
    """Issue 18: the adaptive reference and auto with refine=on against Cycles-64, same run."""
    by = {r["key"]: r for r in scene["rows"]}
    c64 = by.get("cycles-64")
    parts = []
    for key, label in (("reference-adaptive", "adaptive reference"), ("auto-refine", "auto refine=on")):
        r = by.get(key)
        if not r or not r["err"] or not r["ms"]:
            continue
        traced = r.get("traced") or {}
        share = ("%.0f %% of mask pixels traced, " % (100 * traced["traced_share"]) if "traced_share" in traced else "")
        rays = "%.0f rays per mask pixel" % traced["rays_per_mask_pixel"] if "rays_per_mask_pixel" in traced else ""
        vs = ""
        if c64 and c64["err"]:
            vs = "; Cycles-64 %.4f in %.0f ms: %s its error in %.2f× its time" % (
                c64["err"]["rmse"], c64["ms"], "at or below" if r["err"]["rmse"] <= c64["err"]["rmse"] else "**above**",
                r["ms"] / c64["ms"])
        parts.append("%s %.4f (receivers %s) in %.0f ms (%s%s)%s" % (label, r["err"]["rmse"], fmt(rmse(r, "receivers")),
                                                                     r["ms"], share, rays, vs))
    return "- **%s**: %s" % (scene["name"], "; ".join(parts)) if parts else None


def summary(scenes, key):
    """How many scenes meet issue 17's targets for one auto path, said plainly."""
    n = len(scenes)
    names = ["next_receivers", "next_all", "receivers", "all", "best", "time", "estimate"]
    counts = {k: 0 for k in names}
    missed = {k: [] for k in names}
    for sc in scenes:
        by = {r["key"]: r for r in sc["rows"]}
        auto, ee, nx = by.get(key), by.get("eevee-64"), by.get(NEXT)
        best = best_of(sc["rows"], key)
        checks = {
            "next_receivers": rmse(auto, "receivers") is not None and rmse(nx, "receivers") is not None
            and rmse(auto, "receivers") <= rmse(nx, "receivers"),
            "next_all": rmse(auto, "all") is not None and rmse(nx, "all") is not None
            and rmse(auto, "all") <= rmse(nx, "all"),
            "receivers": rmse(auto, "receivers") is not None and rmse(ee, "receivers") is not None
            and rmse(auto, "receivers") <= rmse(ee, "receivers"),
            "all": rmse(auto, "all") is not None and rmse(ee, "all") is not None
            and rmse(auto, "all") <= rmse(ee, "all"),
            "time": bool(auto and auto.get("picked_ms")) and auto["ms"] <= 2.0 * auto["picked_ms"],
            "estimate": bool(auto) and estimate_holds(auto),
            "best": bool(best) and rmse(auto, "all") is not None and rmse(auto, "all") <= 1.25 * best["err"]["rmse"],
        }
        for k in names:
            counts[k] += checks[k]
            if not checks[k]:
                missed[k].append(sc["name"])
    text = {"next_receivers": "at or below EEVEE Next at its defaults (Blender 5.x) on receivers",
            "next_all": "at or below EEVEE Next at its defaults on all surfaces",
            "receivers": "at or below EEVEE-64 (Blender 3.4, the aim) on receivers",
            "all": "at or below EEVEE-64 on all surfaces",
            "time": "in at most twice the time of the method it took (the same way, alone)",
            "estimate": "estimating its own RMSE within ±30 % (or ±0.005)",
            "best": "within 1.25× of " + ("our best GL method at its defaults" if key == "auto"
                                          else "the adaptive reference") + " (all surfaces)"}
    measured = any(NEXT in {r["key"] for r in sc["rows"]} for sc in scenes)
    return ["- `auto` is %s on **%d of %d** scenes%s." % (text[k], counts[k], n,
                                                          "; not on " + ", ".join(missed[k]) if missed[k] else "")
            for k in names if measured or not k.startswith("next_")]


# ---------------------------------------------------------------- foundation.md
def foundation(out):
    rows = bench_rows(os.path.join(out, "foundation.json"))
    lines = ["# Per-stage timings of our methods (ms per frame)", "",
             "Every row is one cold frame (new SceneCache: meshes uploaded, camera pass and light-centre "
             "shadow map drawn again) after a warm-up frame (shaders compiled), mean of the timed "
             "frames; glFinish closes each GL stage. `method render` includes the method's own "
             "read-back; `readback (1 layer)` is the separately measured cost of reading one float "
             "layer at camera resolution. `reference` is CPU-only (Embree, default samples, one frame, "
             "no warm-up): it uses none of the GL passes.", "",
             "| scene | resolution | method | triangles | " + " | ".join(n for _, n in STAGES) + " | total |",
             "|---|---|---|---|" + "---|" * (len(STAGES) + 1)]
    other = []
    for b in rows:
        m = re.match(r"BM_Foundation/scene:(\d)/res:(\d+)/method:(\d+)", b["name"])
        if not m:
            other.append(b)
            continue
        label = b.get("label", "")
        if b.get("error_occurred"):
            lines.append("| %s | %s² | %s | | skipped: %s |" % ("example" if m.group(1) == "0" else "torus100k",
                                                                m.group(2), label, b.get("error_message", "")))
            continue
        scene, method = label.split(" ", 1) if " " in label else (label, "?")
        vals = [b.get(k, 0.0) for k, _ in STAGES]
        lines.append("| %s | %s² | %s | %d | %s | %.1f |" % (scene, m.group(2), method, b.get("triangles", 0),
                                                             " | ".join("%.1f" % v for v in vals), sum(vals[:5])))
    if other:
        lines += ["", "## The method engineers' own stage benchmarks (same run)", "",
                  "| benchmark | label | ms (manual time, mean) | counters |", "|---|---|---|---|"]
        for b in other:
            counters = ", ".join("%s=%.4g" % (k, v) for k, v in b.items()
                                 if isinstance(v, (int, float)) and k not in
                                 ("real_time", "cpu_time", "iterations", "repetitions", "repetition_index",
                                  "threads", "family_index", "per_family_instance_index"))
            lines.append("| %s | %s | %.1f | %s |" % (b["name"], b.get("label", ""), b.get("real_time", 0.0), counters))
    with open(os.path.join(out, "foundation.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return rows


def open_casters(scene_json):
    """Names of the scene's meshes that are not closed 2-manifolds (from `softshadow report`)."""
    try:
        cli = os.path.join(os.environ.get("SOFTSHADOW_BUILD", ""), "softshadow")
        rep = json.loads(subprocess.run([cli, "report", "--json", scene_json], capture_output=True,
                                        text=True, check=True).stdout)
        return ["%s (%d open edges)" % (m["mesh"], m["open_edges"]) for m in rep.get("meshes", [])
                if not m.get("closed_manifold") and m["mesh"].lower() not in ("ground", "receiver")]
    except Exception:
        return []


def reading_notes(work, scenes):
    """What a reader must know to compare the rows fairly."""
    md = ["## Reading the tables", "",
          "- `sweep` shades the receiver plane only (its mask is the plane: here the ground) and leaves every "
          "other surface at V = 1: the casters' own shadows, and where a receiver is not one plane (`stepped`, "
          "`curved_receiver`) the rest of it. Both columns count those pixels, as `auto`'s estimate does.",
          "- `penumbra_map` draws the whole penumbra outside the hard shadow (its umbra is the hard shadow, "
          "too big by construction); by default it shades it with the share of the light disk seen past the "
          "edge, and `penumbra_map-paper` with the paper's 3I² − 2I³, which is too dark: its RMSE is above "
          "`shadow_map`'s (docs/methods/penumbra_map.md). Under an occluder smaller than the light "
          "(small_occluder) both keep a black hard shadow where the truth has no umbra.",
          "- Our methods run at their defaults (`occlusion_textures` 8 slices of 512², SAT; `pcss` 16 blocker and "
          "32 PCF samples; `sweep` 16 light samples, irradiance weights) and, as `occlusion_textures-16`, "
          "`pcss-64` and `sweep-64`, at the next setting a user would try (16 slices; 32 + 64 samples; 64 light "
          "samples). The image strips show the defaults."]
    for s in scenes:
        opened = open_casters(os.path.join(work, "scenes", s["name"], "scene.json"))
        if opened:
            md.append("- **%s**: %s not closed, so `dbuffer` extrudes volumes from a mesh the paper assumes "
                      "closed (`auto` never gives dbuffer such a caster)." % (s["name"], ", ".join(opened)))
    return md + [""]


def next_notes(work, scenes):
    """How EEVEE Next ran (version, GPU, settings, CPU seconds), or why it did not."""
    done = [s for s in scenes if s["next"].get("renders")]
    if not done:
        why = "see the run's eevee_next.log"
        try:
            lines = [ln.strip() for ln in open(os.path.join(work, "eevee_next.log")) if ln.strip()]
            said = [ln for ln in lines if "not measured" in ln or "Error" in ln]
            why = (said or lines or [why])[-1]
        except OSError:
            pass
        return ["- **EEVEE Next was not measured in this run**: %s." % why]
    first = done[0]["next"]
    md = ["- EEVEE Next: Blender %s (engine `%s`) in the version matrix's Debian sid root file system "
          "(bench/eevee_next.sh), `--background`, GPU %s, on the `.blend` each scene was saved as in 3.4 (same "
          "geometry, light, camera, resolution, no pixel filter). V as for EEVEE (bench/visibility_pass.py): "
          "Diffuse Direct with the light's shadows / without (one sample, the unshadowed area light being analytic). "
          "Its renders ran in the background beside steps 3-4d of the run (our methods, auto, memory, warm path), "
          "so its times and ours share the load given at the top."
          % (first.get("blender"), first.get("engine"), first.get("gpu"))]
    for key in NEXT_KEYS:
        used = [s["next"]["settings"][key] for s in done if key in s["next"].get("settings", {})]
        skipped = [s["name"] for s in scenes if key in s["next"].get("skipped", [])]
        if used:
            u = used[0]
            md.append("  - `%s`: %s samples, shadow rays %s × steps %s, jitter %s (overblur %s), filter radius %s, "
                      "resolution scale %s, ray tracing %s; shadowed render seconds (wall / process CPU): %s%s" % (
                          key.replace("_", "-"), u["taa_render_samples"], u["shadow_ray_count"], u["shadow_step_count"],
                          "on" if u["use_shadow_jitter"] else "off", u["shadow_jitter_overblur"],
                          u["shadow_filter_radius"], u["shadow_resolution_scale"],
                          "on" if u["use_raytracing"] else "off",
                          ", ".join("%s %.0f / %.0f" % (s["name"], s["next"]["renders"][key],
                                                        s["next"]["settings"][key]["cpu_seconds"])
                                    for s in done if key in s["next"].get("renders", {})),
                          "; **not rendered** (past BENCH_NEXT_BUDGET_S) on " + ", ".join(skipped) if skipped else ""))
        elif skipped:
            md.append("  - `%s`: **not rendered** (past BENCH_NEXT_BUDGET_S) on %s"
                      % (key.replace("_", "-"), ", ".join(skipped)))
    return md


def load_line(work):
    """The load average at the run's start and end (`uptime`): the times are from a shared machine."""
    try:
        ups = [ln.strip() for ln in open(os.path.join(work, "load.txt")) if ln.strip()]
    except OSError:
        return "load not recorded"
    loads = [u.split("load average:")[-1].strip() for u in ups]
    return "load average (1, 5, 15 min) %s at the start of the run, %s at its end" % (
        loads[0], loads[-1] if len(loads) > 1 else "—")


def machine():
    cpu = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    renderer = ""
    try:
        cli = os.path.join(os.environ.get("SOFTSHADOW_BUILD", ""), "softshadow")
        info = json.loads(subprocess.run([cli, "info", "--json"], capture_output=True, text=True).stdout)
        renderer = "%s, %s (%s)" % (info.get("backend"), info.get("renderer"), info.get("version"))
    except Exception:
        renderer = "llvmpipe (Mesa)"
    return "%d cores (%s), no GPU: GL through %s; %s" % (os.cpu_count() or 0, cpu, renderer, platform.platform())


def main():
    work, out, width, height, truth, quick = sys.argv[1:7]
    scenes = collect(work, out)
    frows = foundation(out)

    md = ["# softshadow benchmark: our methods against EEVEE, EEVEE Next, Cycles and the converged reference",
          ""]
    md.append("Machine: %s; %s (every time below is wall time on that machine). **All figures below come from "
              "one run of `make bench`** (bench/run.sh)%s." %
              (machine(), load_line(work), " in BENCH_QUICK mode (a tiny subset)" if quick == "1" else ""))
    md.append("")
    md.append("## Headline: `auto` (what users get) against EEVEE Next's defaults and EEVEE-64, per scene")
    md.append("")
    md.append("Issues 17 and 28's targets, RMSE against the truth on the receivers and over all surfaces, for the "
              "two ways users get `auto`: against EEVEE Next (Blender 5.x, what artists use today) as an artist has "
              "it, and against EEVEE-64 (Blender 3.4, soft shadows, 64 samples) as the aim.")
    for key, label, how in AUTO_PATHS:
        md += ["", "### `auto` in %s (%s)" % (label, how), ""]
        if key == "auto-refine":
            md += ["Final renders (F12, `blender -b -a`, the farm) refine by default (the light's *Refine Final "
                   "Renders*): the GL pass auto picks, its uncertain pixels and the certain ones a few rays "
                   "contradict ray traced.", ""]
        else:
            md += ["A script's `render_passes` and final renders with *Refine Final Renders* off: the GL pass alone "
                   "(the viewport preview picks by the light's shape instead, to stay interactive).", ""]
        md += summary(scenes, key)
        md.append("")
        md += [headline(s, key) for s in scenes]
    exact = [h for h in (headline_exact(s) for s in scenes) if h]
    if exact:
        md += ["", "## Exact penumbrae (issue 18): adaptive reference and refine against Cycles-64, per scene", ""]
        md += exact
    md += ["", "## How it was measured", "",
           "- Scenes built by `bench/scenes.py` in Blender 3.4 (nothing downloaded), exported with the add-on's "
           "exporter; every renderer sees the same scene, camera and resolution: **%sx%s** (`dense` at 1024x1024, "
           "the triangle-count series `scaled_*` at %s, its job being time against triangles). `concave`, `dense` "
           "and `scaled_*` are Blender's own Suzanne (`primitive_monkey_add`, open: its eyes are separate shells), "
           "subdivided (`dense`: four of them); `stepped` is a four-step receiver. One light per scene. The full run "
           "renders concave, foliage, curved_receiver, stepped and dense (bench/scenes.py FULL_SCENES, to fit in "
           "about 20 minutes on 2 cores); the others with BENCH_SCENES." % (
               width, height, "256x192" if quick != "1" else "the same size"),
           "- Truth: `reference` (Embree) at **%s light samples per pixel**. Errors: `softshadow compare --json` "
           "over every pixel the light reaches (`--mask <light>_reference_mask`, the truth's mask) whatever the "
           "method's own mask, since a composite multiplies by V everywhere (V = 1 outside a method's mask): "
           "RMSE, 99th-percentile absolute error, umbra IoU (V<0.05), lit IoU (V>0.95)."
           % truth,
           "- **Receivers**: the pixels whose centre sees a receiver object (the ground, the curved receiver, the "
           "steps: `RECEIVERS` in bench/scenes.py), taken from Cycles' object-index pass at one sample with a "
           "0.01 px filter, and which the light reaches (the truth's mask). run.sh adds that mask to a copy of the "
           "truth as the pass `receivers` and compares with `softshadow compare --mask receivers`. \"All surfaces\" "
           "adds the casters themselves, where self-shadowing near terminators costs every method.",
           "- `auto`: `softshadow render -m auto` (a fresh process: GL start, the sparse check and the candidates "
           "it renders), and the method it took alone through the same command, for the time ratio; the same "
           "with `--set refine=on` for final renders. Its estimate is the CLI's `est.rmse`, over all surfaces.",
           "- EEVEE (soft shadows, 64 samples, 2048 shadow cube, no pixel filter; at 512² on llvmpipe it takes about "
           "1.4 s per sample, so EEVEE-16 is left out) and Cycles (CPU, 16/64 spp, no denoising, no adaptive sampling, "
           "direct light only, 0.01 px filter): V = Diffuse Direct with shadows / Diffuse Direct with the light's "
           "shadows off (Cycles: same samples and seed; EEVEE: one sample, its unshadowed area light being analytic), "
           "mask where the unshadowed pass > 0. Time = the shadowed render "
           "inside Blender (`bpy.ops.render.render`, Blender start-up and scene build excluded); the unshadowed "
           "render is not counted."]
    md += next_notes(work, scenes)
    md += ["- Ours (GL methods): per-frame time of a cold frame (meshes uploaded, camera pass and shadow map drawn, "
           "prepare, render incl. read-back) with the GL context and shaders warm (softshadow_bench, "
           "BM_SceneFile, mean of 2 frames). `reference`: the CLI's render time at its default samples.",
           ""]
    md += reading_notes(work, scenes)
    md += ["## Tables", ""]
    for s in scenes:
        md += ["### %s (%s triangles)" % (s["name"], s["triangles"]), "",
               "| method / setting | ms per frame | RMSE receivers | RMSE all | p99 | umbra IoU | lit IoU | "
               "stages (ms): upload / camera / shadow map / prepare / render |", "|---|---|---|---|---|---|---|---|"]
        for r in s["rows"]:
            e = r["err"] or {}
            st = r["stages"]
            stages = " / ".join("%.1f" % (st.get(k) or 0.0) for k, _ in STAGES[:5]) if st else ""
            if r.get("took"):
                stages = "took %s, estimate %s" % (r["took"], fmt(r.get("estimate")))
            md.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["key"], fmt(r["ms"], "%.1f"), fmt(rmse(r, "receivers")), fmt(e.get("rmse")), fmt(e.get("p99")),
                fmt(e.get("umbra_iou"), "%.3f"), fmt(e.get("lit_iou"), "%.3f"), stages))
        md.append("")

    # Plots: error vs time per scene, time vs triangles, time vs resolution.
    md += ["## Plots", ""]
    for s in scenes:
        series = [(r["key"], [(r["ms"], r["err"]["rmse"])]) for r in s["rows"] if r["err"] and r["ms"]]
        fn = "error_vs_time_%s.svg" % s["name"]
        if svg_plot(os.path.join(out, fn), "%s: RMSE vs time" % s["name"], series, "ms per frame (log)", "RMSE"):
            md.append("![%s](%s)" % (fn, fn))
    md.append("")
    keys = []
    for s in scenes:
        for r in s["rows"]:
            if r["key"] not in keys:
                keys.append(r["key"])
    tri = [(k, [(s["triangles"], r["ms"]) for s in scenes if s["name"].startswith("scaled") and s["triangles"]
                for r in s["rows"] if r["key"] == k and r["ms"]]) for k in keys]
    if svg_plot(os.path.join(out, "time_vs_triangles.svg"), "Time vs triangle count (scaled Suzanne, %sx%s)"
                % (width, height), tri, "triangles (log)", "ms per frame (log)", logy=True, lines=True):
        md += ["![time vs triangles](time_vs_triangles.svg)", ""]
    res = {}
    for b in frows:
        m = re.match(r"BM_Foundation/scene:(\d)/res:(\d+)/method:(\d+)", b["name"])
        if m and not b.get("error_occurred"):
            label = b.get("label", "?")
            res.setdefault(label, []).append((int(m.group(2)) ** 2, b["real_time"]))
    if svg_plot(os.path.join(out, "time_vs_resolution.svg"), "Time vs resolution (512², 1024²)",
                sorted(res.items()), "pixels (log)", "ms per frame (log)", logy=True, lines=True):
        md += ["![time vs resolution](time_vs_resolution.svg)", ""]

    md += ["## Image strips (method | truth | 4 x |error| inside the mask)", ""]
    for s in scenes:
        png = "strip_%s.png" % s["name"]
        labels = os.path.join(out, "strip_%s.txt" % s["name"])
        if os.path.exists(os.path.join(out, png)):
            order = open(labels).read().split("\n") if os.path.exists(labels) else []
            md += ["**%s** — rows, top to bottom: %s" % (s["name"], ", ".join(o for o in order if o)), "",
                   "![%s](%s)" % (png, png), ""]
    md += ["Per-stage native timings at 512² and 1024²: [foundation.md](foundation.md)."]
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    results = {"scenes": [{"name": s["name"], "triangles": s["triangles"], "size": s.get("size"),
                           "rows": [{k: r.get(k) for k in ("key", "kind", "ms", "err", "err_recv", "stages", "took",
                                                           "estimate", "picked_ms", "traced")}
                                    for r in s["rows"]]}
                          for s in scenes]}
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    print("\n".join(md[:md.index("## How it was measured")]))


main()
