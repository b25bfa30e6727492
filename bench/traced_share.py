# How much ray tracing the exact runs of one scene did: shadow rays per mask pixel of the adaptive
# reference, the share of mask pixels auto's refine=on traced (their "rays" / "refined" layers).
# SPDX-License-Identifier: GPL-3.0-or-later
# python3 bench/traced_share.py DIR   (DIR holds reference-adaptive.exr and auto-refine.exr) -> JSON
import json
import os
import re
import subprocess
import sys


def layer_means(path):
    """{layer suffix after the method: mean over the image} from oiiotool's per-channel stats."""
    if not os.path.exists(path):
        return {}
    info = subprocess.run(["oiiotool", "--info", "-v", path], capture_output=True, text=True).stdout
    names = re.search(r"channel list: (.*)", info).group(1).replace(" ", "").split(",")
    stats = subprocess.run(["oiiotool", "--stats", path], capture_output=True, text=True).stdout
    avgs = [float(a) for a in re.search(r"Stats Avg: ([^\n]*)", stats).group(1).replace("(float)", "").split()]
    out = {}
    for name, avg in zip(names, avgs):
        m = re.match(r".*_(reference|auto)(?:_([a-z]+))?\.V$", name)
        if m:
            out[m.group(2) or "V"] = avg
    return out


def main():
    d = sys.argv[1]
    result = {}
    ref = layer_means(os.path.join(d, "reference-adaptive.exr"))
    if ref.get("mask"):
        result["reference-adaptive"] = {"rays_per_mask_pixel": ref.get("rays", 0.0) / ref["mask"]}
    ref = layer_means(os.path.join(d, "auto-refine.exr"))
    if ref.get("mask"):
        result["auto-refine"] = {"traced_share": ref.get("refined", 0.0) / ref["mask"],
                                 "rays_per_mask_pixel": ref.get("rays", 0.0) / ref["mask"]}
    print(json.dumps(result))


main()
