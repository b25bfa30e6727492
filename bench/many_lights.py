# Which scene measures memory against the light count: a ring of N disk lights over a plane and
# a box (256x192), written to a scene file for `softshadow render`.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: python3 bench/many_lights.py N OUT.json
import json
import math
import sys

count, out = int(sys.argv[1]), sys.argv[2]
lights = []
for i in range(count):
    a = 2 * math.pi * i / count
    lights.append({"name": "L%04d" % i, "type": "disk",
                   "position": [3 * math.cos(a), 3 * math.sin(a), 4 + (i % 7) * 0.1],
                   "direction": [-0.3 * math.cos(a), -0.3 * math.sin(a), -1], "size": 0.5})
scene = {"format": "softshadow-scene", "version": 1,
         "camera": {"look_from": [6, -6, 5], "look_at": [0, 0, 0], "fov_y_degrees": 40, "width": 256, "height": 192},
         "lights": lights,
         "meshes": [{"name": "Ground", "primitive": {"type": "plane", "size": 10}},
                    {"name": "Box", "primitive": {"type": "box", "size": [1, 1, 1]}, "translate": [0, 0, 0.5]}]}
with open(out, "w") as f:
    json.dump(scene, f)
