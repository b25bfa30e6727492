# Where does each method's error against the truth concentrate: its squared error split by region.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Splits each GL method's squared error against the reference on the benchmark scenes by where it
falls, and draws one error strip per method. This is how docs/methods/*.md "Where the error is"
were made:

  blender -b --factory-startup --python bench/error_regions.py -- \
      --cli build/softshadow --work /tmp/er SCENE_DIR... [--methods a,b] [--images DIR] [--json F]

Each SCENE_DIR holds a scene.json (exported by the add-on from bench/scenes.py). Into WORK/<scene>/
it renders, unless already there: the truth (reference, 1024 samples), each method (its defaults),
and the helper renders below; then it prints a table per method and writes WORK/regions.json.
Blender's Python is used for numpy only; the renders go through the CLI.

Regions (all inside the truth's mask, the pixels the light reaches, as `make bench` scores):
- receivers / casters: the pixel's surface is / is not a receiver object (bench/scenes.py
  RECEIVERS), from a copy of the scene where only those receive and a point light sits at the
  camera (it reaches every surface the camera sees);
- lit / penumbra / umbra: the truth's V = 1, 0 < V < 1, V = 0 (at 1024 samples);
- too dark / too light: the method's V below / above the truth's;
- sharp penumbra on receivers: receiver pixels where the truth changes by >= SHARP per pixel to a
  4-neighbour that is also a receiver pixel (penumbrae narrower than about 1/SHARP pixels: where
  an occluder touches or nearly touches the receiver);
- terminator band on casters: caster pixels within TERMINATOR_PX pixels of a caster pixel the
  camera sees but the light does not reach (the caster's own lit/unlit boundary);
- overlapping occluders: receiver pixels that at least two separate occluders (connected components of
  the casting meshes) each shadow, from one render per component with only it casting
  (OCCLUDER_SAMPLES samples: an occluder hiding less than about 1/OCCLUDER_SAMPLES of the light
  may be missed).
"""
import argparse
import copy
import json
import os
import struct
import subprocess
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "blender"))
import exr_reader  # noqa: E402

RECEIVERS = ("Ground", "Receiver", "Steps")  # as bench/scenes.py
METHODS = ("shadow_map", "pcss", "dbuffer", "sweep", "penumbra_map", "occlusion_textures")
TRUTH_SAMPLES = 1024
OCCLUDER_SAMPLES = 32
SHARP = 0.1
TERMINATOR_PX = 4
MAX_OCCLUDERS = 100
ERROR_GAIN = 4.0  # the pictures show |error| x 4, clipped at 1
TILE = 256


def render(cli, scene, method, out, samples=None, may_refuse=False):
    """Renders unless out exists; the CLI's error message when a method refuses the scene (and
    may_refuse), else None."""
    if os.path.exists(out):
        return None
    args = [cli, "render", scene, "-m", method, "-o", out]
    if samples:
        args += ["--samples", str(samples)]
    done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        if may_refuse:
            return done.stderr.strip()
        raise RuntimeError("%s failed: %s" % (" ".join(args), done.stderr.strip()))
    return None


def pass_name(light):
    return light.replace(".", "_").replace(" ", "_")


def channel(path, light, method, layer="V"):
    ch = exr_reader.read(path)
    suffix = "" if layer == "V" else "_" + layer
    return ch["ViewLayer.%s_%s%s.V" % (pass_name(light), method, suffix)].astype(np.float64)


def is_receiver(mesh):
    return mesh["name"].split(".")[0] in RECEIVERS


def camera_pose(scene):
    """The camera's position and viewing direction (its -Z) in world space."""
    cam = scene["camera"]
    if "look_from" in cam:
        return list(cam["look_from"]), (np.array(cam["look_at"]) - np.array(cam["look_from"])).tolist()
    m = cam["world_to_camera"]  # column-major
    r = np.array([[m[c * 4 + r] for c in range(3)] for r in range(3)])
    t = np.array([m[12], m[13], m[14]])
    return (-r.T @ t).tolist(), (-r[2]).tolist()


def camera_lit_copy(scene, receive):
    """The scene seen with a point light at the camera and nothing casting: its mask is every
    surface the camera sees on the meshes for which receive(mesh) holds."""
    s = copy.deepcopy(scene)
    position, direction = camera_pose(scene)
    s["lights"] = [{"name": "Cam", "type": "point", "radius": 0.01, "position": position, "direction": direction}]
    for m in s["meshes"]:
        m["cast"] = False
        m["receive"] = bool(receive(m))
    return s


def components(mesh):
    """Vertex-connected components of an inline mesh, as lists of triangle indices."""
    tris = np.array(mesh["triangles"]).reshape(-1, 3)
    parent = list(range(len(mesh["positions"]) // 3))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b, c in tris:
        ra = find(a)
        parent[find(b)] = ra
        parent[find(c)] = ra
    groups = {}
    for i, (a, _, _) in enumerate(tris):
        groups.setdefault(find(a), []).append(i)
    return list(groups.values())


def split_occluders(scene):
    """A copy with every casting mesh split into its components, and the component names."""
    s = copy.deepcopy(scene)
    meshes, names = [], []
    for m in scene["meshes"]:
        if not m.get("cast", True) or "positions" not in m:
            meshes.append(m)
            if m.get("cast", True):
                names.append(m["name"])  # primitives and external files stay one occluder
            continue
        tris = np.array(m["triangles"]).reshape(-1, 3)
        for k, group in enumerate(components(m)):
            part = dict(m)
            part["name"] = "%s#%d" % (m["name"], k)
            part["triangles"] = tris[group].reshape(-1).tolist()
            meshes.append(part)
            names.append(part["name"])
    s["meshes"] = meshes
    return s, names


def write_json(path, data):
    with open(path, "w") as f:
        json.dump(data, f)


def helper_renders(cli, scene_path, work):
    """Masks of receiver and of all visible surfaces, and the count of occluders shadowing each
    pixel (None when the scene has more than MAX_OCCLUDERS components)."""
    with open(scene_path) as f:
        scene = json.load(f)
    out = {}
    for key, receive in (("receivers", is_receiver), ("surfaces", lambda m: True)):
        js, exr = os.path.join(work, key + ".json"), os.path.join(work, key + ".exr")
        write_json(js, camera_lit_copy(scene, receive))
        render(cli, js, "reference", exr, samples=1)
        out[key] = channel(exr, "Cam", "reference", "mask") > 0.5
    split, names = split_occluders(scene)
    out["occluders"] = None
    if len(names) <= MAX_OCCLUDERS:
        count = None
        for k, name in enumerate(names):
            one = copy.deepcopy(split)
            for m in one["meshes"]:
                m["cast"] = m["name"] == name
            js, exr = os.path.join(work, "occluder_%d.json" % k), os.path.join(work, "occluder_%d.exr" % k)
            write_json(js, one)
            render(cli, js, "reference", exr, samples=OCCLUDER_SAMPLES)
            shadowed = (channel(exr, scene["lights"][0]["name"], "reference") < 1.0).astype(np.int32)
            count = shadowed if count is None else count + shadowed
        out["occluders"] = count
        out["occluder_count"] = len(names)
    return out


def dilate(mask, px):
    out = mask.copy()
    for _ in range(px):
        grown = out.copy()
        grown[1:, :] |= out[:-1, :]
        grown[:-1, :] |= out[1:, :]
        grown[:, 1:] |= out[:, :-1]
        grown[:, :-1] |= out[:, 1:]
        grown[1:, 1:] |= out[:-1, :-1]
        grown[:-1, :-1] |= out[1:, 1:]
        grown[1:, :-1] |= out[:-1, 1:]
        grown[:-1, 1:] |= out[1:, :-1]
        out = grown
    return out


def sharp_steps(truth, region):
    """Pixels of region whose truth differs by >= SHARP from a 4-neighbour also in region."""
    out = np.zeros_like(region)
    for axis in (0, 1):
        diff = np.abs(np.diff(truth, axis=axis))
        both = np.logical_and(np.take(region, range(region.shape[axis] - 1), axis=axis),
                              np.take(region, range(1, region.shape[axis]), axis=axis))
        step = np.logical_and(diff >= SHARP, both)
        if axis == 0:
            out[:-1, :] |= step
            out[1:, :] |= step
        else:
            out[:, :-1] |= step
            out[:, 1:] |= step
    return out


def regions(truth, mask, helpers):
    receivers = mask & helpers["receivers"]
    casters = mask & ~helpers["receivers"]
    unlit_casters = helpers["surfaces"] & ~helpers["receivers"] & ~mask
    lit = mask & (truth >= 1.0)
    umbra = mask & (truth <= 0.0)
    penumbra = mask & ~lit & ~umbra
    r = {
        "all": mask, "receivers": receivers, "casters": casters,
        "lit": lit, "penumbra": penumbra, "umbra": umbra,
        "receivers lit": receivers & lit, "receivers penumbra": receivers & penumbra,
        "receivers umbra": receivers & umbra,
        "casters lit": casters & lit, "casters penumbra": casters & penumbra,
        "casters umbra": casters & umbra,
        "sharp penumbra on receivers": sharp_steps(truth, receivers),
        "terminator band on casters": casters & dilate(unlit_casters, TERMINATOR_PX),
    }
    if helpers["occluders"] is not None and helpers["occluder_count"] > 1:
        r["receivers under two or more occluders"] = receivers & (helpers["occluders"] >= 2)
        r["receivers under one occluder"] = receivers & (helpers["occluders"] == 1)
    return r


def split_error(err, regs):
    total = float(np.sum(err[regs["all"]] ** 2))
    n_all = int(np.count_nonzero(regs["all"]))
    rows = {}
    for name, reg in regs.items():
        e = err[reg]
        n = int(e.size)
        se = float(np.sum(e ** 2))
        rows[name] = {
            "pixels": n / n_all,
            "share": se / total if total > 0 else 0.0,
            "rmse": float(np.sqrt(se / n)) if n else 0.0,
            "too_dark_share": float(np.sum(e[e < 0] ** 2)) / total if total > 0 else 0.0,
            "too_light_share": float(np.sum(e[e > 0] ** 2)) / total if total > 0 else 0.0,
        }
    return rows


def reduction(shape):
    """The whole factor that brings the image's longer side down to about TILE, and the tile's size."""
    f = max(1, max(shape) // TILE)
    return f, shape[0] // f, shape[1] // f


def heat_tile(truth, mask, err):
    """RGB tile: grey shows the truth (darker outside the mask), red where the method is too dark,
    blue where too light, at |error| x ERROR_GAIN; each f x f block keeps its largest |error| so
    one-pixel lines of error survive the reduction."""
    f, th, tw = reduction(err.shape)

    def blocks(a):
        return a[:th * f, :tw * f].reshape(th, f, tw, f).transpose(0, 2, 1, 3).reshape(th, tw, f * f)

    e = blocks(np.where(mask, err, 0.0))
    pick = np.take_along_axis(e, np.argmax(np.abs(e), axis=2)[..., None], axis=2)[..., 0]
    t = blocks(truth).mean(axis=2)
    m = blocks(mask.astype(np.float64)).mean(axis=2) > 0.5
    grey = np.where(m, 0.55 + 0.4 * t, 0.25)
    a = np.clip(np.abs(pick) * ERROR_GAIN, 0.0, 1.0)
    too_dark = pick < 0
    red = np.where(too_dark, 0.85, 0.1)
    blue = np.where(too_dark, 0.1, 0.85)
    rgb = np.stack([grey * (1 - a) + red * a, grey * (1 - a) + 0.1 * a, grey * (1 - a) + blue * a], axis=2)
    return (np.clip(rgb, 0, 1) * 255 + 0.5).astype(np.uint8)


def refused_tile(shape):
    """A plain dark tile where the method does not take the scene."""
    _, th, tw = reduction(shape)
    return np.full((th, tw, 3), 64, np.uint8)


def write_png(path, rgb):
    h, w, _ = rgb.shape
    raw = b"".join(b"\0" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def measure(cli, work_root, scene_dirs, methods, truth_samples=TRUTH_SAMPLES):
    """{scene: {"pixels": {region: count}, method: {region: numbers} or {"refused": message}}} and
    {method: [error tile per scene]}, rendering into work_root/<scene>/ what is not there yet."""
    results, tiles = {}, {m: [] for m in methods}
    for scene_dir in scene_dirs:
        name = os.path.basename(os.path.normpath(scene_dir))
        work = os.path.join(work_root, name)
        os.makedirs(work, exist_ok=True)
        scene_path = os.path.join(scene_dir, "scene.json")
        with open(scene_path) as f:
            light = json.load(f)["lights"][0]["name"]
        truth_path = os.path.join(work, "truth.exr")
        render(cli, scene_path, "reference", truth_path, samples=truth_samples)
        truth = channel(truth_path, light, "reference")
        mask = channel(truth_path, light, "reference", "mask") > 0.5
        regs = regions(truth, mask, helper_renders(cli, scene_path, work))
        results[name] = {"pixels": {k: int(np.count_nonzero(v)) for k, v in regs.items()}}
        for method in methods:
            out = os.path.join(work, method + ".exr")
            refused = render(cli, scene_path, method, out, may_refuse=True)
            if refused:
                results[name][method] = {"refused": refused}
                tiles[method].append(refused_tile(truth.shape))
                continue
            err = channel(out, light, method) - truth
            results[name][method] = split_error(err, regs)
            tiles[method].append(heat_tile(truth, mask, err))
    return results, tiles


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--images", help="write error_<method>.png strips here")
    ap.add_argument("--markdown", help="write the docs' tables here")
    ap.add_argument("scenes", nargs="+")
    a = ap.parse_args(argv)
    methods = a.methods.split(",")
    results, tiles = measure(a.cli, a.work, a.scenes, methods)
    for scene, per_method in results.items():
        for method in methods:
            if "refused" in per_method[method]:
                print("\n%s / %s: %s" % (scene, method, per_method[method]["refused"]))
            else:
                print_table(scene, method, per_method[method])
    write_json(os.path.join(a.work, "regions.json"), results)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(markdown(results, methods))
    if a.images:
        os.makedirs(a.images, exist_ok=True)
        for method in methods:
            write_png(os.path.join(a.images, "error_%s.png" % method), np.concatenate(tiles[method], axis=1))


DOC_ROWS = (("receivers", "receivers"), ("casters", "casters"), ("lit", "truth lit (V = 1)"),
            ("penumbra", "truth penumbra"), ("umbra", "truth umbra (V = 0)"),
            ("sharp penumbra on receivers", "sharp penumbra on receivers"),
            ("terminator band on casters", "terminator band on casters"),
            ("receivers under one occluder", "receivers under one occluder"),
            ("receivers under two or more occluders", "receivers under two or more occluders"))
SUMMARY_COLUMNS = ("receivers penumbra", "receivers umbra", "casters", "terminator band on casters",
                   "sharp penumbra on receivers", "receivers under two or more occluders")


def cell(row):
    if row["share"] == 0.0 and row["pixels"] == 0.0:
        return "—"
    return "%.0f %% (%.3f)" % (100 * row["share"], row["rmse"])


def markdown(results, methods):
    scenes = list(results)
    head = "| | " + " | ".join(scenes) + " |\n|---|" + "---|" * len(scenes) + "\n"
    out = ["## Pixels in each region (share of the truth's mask)\n\n" + head]
    for key, label in DOC_ROWS:
        out.append("| %s | %s |\n" % (label, " | ".join(
            "%.1f %%" % (100.0 * results[s]["pixels"].get(key, 0) / results[s]["pixels"]["all"])
            if key in results[s]["pixels"] else "—" for s in scenes)))
    for method in methods:
        out.append("\n## %s: share of the squared error (RMSE there)\n\n" % method + head)
        rows = [("all surfaces: RMSE", lambda r: "%.4f" % r["all"]["rmse"]),
                ("too dark / too light", lambda r: "%.0f %% / %.0f %%" % (
                    100 * r["all"]["too_dark_share"], 100 * r["all"]["too_light_share"]))]
        rows += [(label, lambda r, k=key: cell(r[k]) if k in r else "—") for key, label in DOC_ROWS]
        for label, fmt in rows:
            out.append("| %s | %s |\n" % (label, " | ".join(
                "refused" if "refused" in results[s][method] else fmt(results[s][method]) for s in scenes)))
    out.append("\n## Summary: share of the squared error (RMSE there)\n\n| method | scene | RMSE | "
               + " | ".join(SUMMARY_COLUMNS) + " |\n|---|---|---|" + "---|" * len(SUMMARY_COLUMNS) + "\n")
    for method in methods:
        for s in scenes:
            r = results[s][method]
            if "refused" in r:
                out.append("| %s | %s | refused |%s\n" % (method, s, " |" * len(SUMMARY_COLUMNS)))
                continue
            out.append("| %s | %s | %.4f | %s |\n" % (method, s, r["all"]["rmse"], " | ".join(
                cell(r[k]) if k in r else "—" for k in SUMMARY_COLUMNS)))
    return "".join(out)


def print_table(scene, method, rows):
    print("\n%s / %s: RMSE %.4f" % (scene, method, rows["all"]["rmse"]))
    print("%-30s %8s %8s %8s %9s %9s" % ("region", "pixels", "SE share", "RMSE", "too dark", "too light"))
    for name, r in rows.items():
        print("%-30s %7.1f%% %7.1f%% %8.4f %8.1f%% %8.1f%%" % (
            name, 100 * r["pixels"], 100 * r["share"], r["rmse"],
            100 * r["too_dark_share"], 100 * r["too_light_share"]))


if __name__ == "__main__":
    main()
