# How the exact-penumbrae rows (bench/exact_penumbrae.sh) become bench/results/exact_penumbrae.md.
# SPDX-License-Identifier: GPL-3.0-or-later
# python3 bench/exact_penumbrae_table.py ROWS.jsonl OUT.md OUT.json CYCLES_SAMPLES COMMIT
import json
import sys

rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
cycles = "Cycles-" + sys.argv[4]
json.dump(rows, open(sys.argv[3], "w"), indent=1)
base = {(r["scene"], r["size"]): r for r in rows if r["run"] == cycles}
out = ["# Exact penumbrae against %s" % cycles, "",
       "bench/exact_penumbrae.sh, one run on this machine (2 cores shared with other jobs: seconds are rough).",
       "%s: direct light only, as bench/scenes.py renders it; seconds of its shadowed render in Blender." % cycles,
       "Ours: the CLI's total (render, BVH build, GL start, EXR write; not process start or scene load).",
       "RMSE of V against `reference` at the truth's samples, over the truth's mask. Target (issue 18): RMSE",
       "at or below %s's in at most 1/5 of its time. Traced: for the adaptive reference the share of mask" % cycles,
       "pixels past the first round of 16 rays, for refine the share of mask pixels re-traced.",
       "Ours built from commit %s." % sys.argv[5], "",
       "| scene | size | triangles | run | seconds | RMSE | speed-up vs %s | rays per mask pixel | traced "
       "| target met |" % cycles,
       "|---|---|---|---|---|---|---|---|---|---|"]
met = {}
for r in rows:
    c = base[(r["scene"], r["size"])]
    if r["run"] == cycles:
        out.append("| %s | %d² | %d | %s | %.2f | %.4f | 1.0× | %.0f | 100%% | |" % (
            r["scene"], r["size"], r["triangles"], r["run"], r["seconds"], r["rmse"], r["rays_per_mask_pixel"]))
        continue
    ok = r["rmse"] <= c["rmse"] and r["seconds"] <= c["seconds"] / 5
    met.setdefault(r["run"], []).append(ok)
    out.append("| %s | %d² | %d | %s | %.2f | %.4f | %.1f× | %.1f | %.1f%% | %s |" % (
        r["scene"], r["size"], r["triangles"], r["run"], r["seconds"], r["rmse"], c["seconds"] / r["seconds"],
        r["rays_per_mask_pixel"], 100 * r["traced_share"], "yes" if ok else "no"))
out += ["", "Target met per run: " + "; ".join("%s %d of %d" % (k, sum(v), len(v)) for k, v in met.items())]
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
