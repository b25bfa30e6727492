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


def error_of(work, scene, key):
    rows = load(os.path.join(work, "errors", scene, key + ".json"))
    if not rows:
        return None
    for r in rows:  # the V pass (not mask/umbra/penumbra)
        if not re.search(r"_(mask|umbra|penumbra)$", r["a"]):
            return r
    return rows[0]


def cli_seconds(path):
    try:
        for line in open(path):
            parts = line.split()
            if len(parts) >= 4 and parts[1] == "reference" and parts[2] == "reference":
                return float(parts[3])
    except OSError:
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
        sec, took, estimate = cli_auto(os.path.join(work, "ours", name, "auto.txt"))
        if sec is not None:
            rows.append({"key": "auto", "kind": "ours-auto", "ms": sec * 1000, "stages": None, "took": took,
                         "estimate": estimate, "err": error_of(work, name, "auto")})
        s = cli_seconds(os.path.join(d, "reference.txt"))
        rows.append({"key": "reference", "kind": "ours-cpu", "ms": s * 1000 if s else None, "stages": None,
                     "err": error_of(work, name, "reference")})
        for key, sec in sorted(info.get("renders", {}).items(),
                               key=lambda kv: (kv[0].split("_")[0], int(kv[0].split("_")[1]))):
            rows.append({"key": key.replace("_", "-"), "kind": key.split("_")[0], "ms": sec * 1000.0,
                         "stages": None, "err": error_of(work, name, key)})
        scenes.append({"name": name, "triangles": info.get("triangles"), "rows": rows})
    return scenes


def fmt(v, spec="%.4f"):
    return "—" if v is None else spec % v


# ---------------------------------------------------------------- headline
def headline(scene):
    rows = scene["rows"]
    gl = [r for r in rows if r["kind"] == "ours" and r["err"] and r["ms"]]
    ee = next((r for r in rows if r["key"] == "eevee-64" and r["err"]), None)
    cyc = sorted([r for r in rows if r["kind"] == "cycles" and r["err"]], key=lambda r: int(r["key"].split("-")[1]))
    parts = []
    auto = next((r for r in rows if r["kind"] == "ours-auto" and r["err"]), None)
    if auto:
        verdict = ""
        if ee:
            verdict = (", at or below EEVEE-64 (%.4f)" if auto["err"]["rmse"] <= ee["err"]["rmse"]
                       else ", **above** EEVEE-64 (%.4f)") % ee["err"]["rmse"]
        parts.append("**auto** took %s: RMSE %.4f (its estimate %s) in %.0f ms (CLI, whole process)%s"
                     % (auto.get("took"), auto["err"]["rmse"], fmt(auto.get("estimate")), auto["ms"], verdict))
    if ee and gl:
        within = [r for r in gl if r["err"]["rmse"] <= ee["err"]["rmse"]]
        if within:
            f = min(within, key=lambda r: r["ms"])
            parts.append("fastest of ours within EEVEE-64's error (RMSE %.4f): **%s** %.4f in %.0f ms, "
                         "%.1fx faster than EEVEE-64 (%.0f ms)" % (ee["err"]["rmse"], f["key"], f["err"]["rmse"],
                                                                   f["ms"], ee["ms"] / f["ms"], ee["ms"]))
        else:
            b = min(gl, key=lambda r: r["err"]["rmse"])
            parts.append("none of ours within EEVEE-64's error (RMSE %.4f; our best %s %.4f)"
                         % (ee["err"]["rmse"], b["key"], b["err"]["rmse"]))
    if gl and cyc:
        best = min(gl, key=lambda r: r["err"]["rmse"])
        reach = next((r for r in cyc if r["err"]["rmse"] <= best["err"]["rmse"]), None)
        if reach:
            parts.append("Cycles needs **%s spp** (%.0f ms) to reach our best (%s, RMSE %.4f, %.0f ms)"
                         % (reach["key"].split("-")[1], reach["ms"], best["key"], best["err"]["rmse"], best["ms"]))
        else:
            top = cyc[-1]
            parts.append("Cycles does not reach our best (%s, RMSE %.4f) within %s spp (RMSE %.4f, %.0f ms)"
                         % (best["key"], best["err"]["rmse"], top["key"].split("-")[1], top["err"]["rmse"], top["ms"]))
    return "- **%s** (%s triangles): %s" % (scene["name"], scene["triangles"], "; ".join(parts) or "no data")


# ---------------------------------------------------------------- foundation.md
def foundation(out):
    rows = bench_rows(os.path.join(out, "foundation.json"))
    lines = ["# Per-stage timings of our methods (ms per frame)", "",
             "Every row is one cold frame (new Frame: meshes uploaded, camera pass and light-centre "
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
          "- `sweep` shades the receiver plane only (its mask is the plane: here the ground); its errors are "
          "over those pixels, the other methods' over every surface the light reaches, occluders included, "
          "where self-shadowing near terminators costs them.",
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

    md = ["# softshadow benchmark: our methods against EEVEE, Cycles and the converged reference", ""]
    md.append("Machine: %s. **All figures below come from one run of `make bench`** (bench/run.sh)%s." %
              (machine(), " in BENCH_QUICK mode (a tiny subset)" if quick == "1" else ""))
    md.append("")
    md.append("## Headlines (per scene)")
    md.append("")
    md += [headline(s) for s in scenes]
    md += ["", "## How it was measured", "",
           "- Scenes built by `bench/scenes.py` in Blender 3.4 (nothing downloaded), exported with the add-on's "
           "exporter; every renderer sees the same scene, camera and resolution: **%sx%s**." % (width, height),
           "- Truth: `reference` (Embree) at **%s light samples per pixel**. Errors: `softshadow compare --json` "
           "over the pixels both masks keep: RMSE, 99th-percentile absolute error, umbra IoU (V<0.05), lit IoU (V>0.95)."
           % truth,
           "- EEVEE (soft shadows, 16/64 samples) and Cycles (CPU, 1-256 spp, no denoising, no adaptive sampling, "
           "direct light only, 0.01 px filter): V = Diffuse Direct with shadows / Diffuse Direct with the light's "
           "shadows off (same samples and seed), mask where the unshadowed pass > 0. Time = the shadowed render "
           "inside Blender (`bpy.ops.render.render`, Blender start-up and scene build excluded); the unshadowed "
           "render is not counted.",
           "- Ours (GL methods): per-frame time of a cold frame (meshes uploaded, camera pass and shadow map drawn, "
           "prepare, render incl. read-back) with the GL context and shaders warm (softshadow_bench, "
           "BM_SceneFile, mean of 2 frames). `reference`: the CLI's render time at its default samples.",
           ""]
    md += reading_notes(work, scenes)
    md += ["## Tables", ""]
    for s in scenes:
        md += ["### %s (%s triangles)" % (s["name"], s["triangles"]), "",
               "| method / setting | ms per frame | RMSE | p99 | umbra IoU | lit IoU | stages (ms): upload / camera / "
               "shadow map / prepare / render |", "|---|---|---|---|---|---|---|"]
        for r in s["rows"]:
            e = r["err"] or {}
            st = r["stages"]
            stages = " / ".join("%.1f" % (st.get(k) or 0.0) for k, _ in STAGES[:5]) if st else ""
            md.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                r["key"], fmt(r["ms"], "%.1f"), fmt(e.get("rmse")), fmt(e.get("p99")), fmt(e.get("umbra_iou"), "%.3f"),
                fmt(e.get("lit_iou"), "%.3f"), stages))
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
    summary = {"scenes": [{"name": s["name"], "triangles": s["triangles"],
                           "rows": [{k: r.get(k) for k in ("key", "kind", "ms", "err", "stages", "took", "estimate")}
                                    for r in s["rows"]]}
                          for s in scenes]}
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print("\n".join(md[:6 + len(scenes)]))


main()
