#!/usr/bin/env python3
"""Writes scenes/flatland/dense_strokes.json: 1,000 random polylines of 10 segments each (10,000 segments)
in a 100 x 100 square, with a few denser clumps, reproducible (seed 2026). The flatland benchmark scene: the
ray dragged through it re-traces every structure over 20,000 triangles."""
import json
import math
import random
import sys

random.seed(2026)
clumps = [(25, 70, 12), (70, 30, 9), (60, 75, 6)]
objects = []
for i in range(1000):
    if i % 3 == 0:
        cx, cy, r = random.choice(clumps)
        x, y = cx + random.gauss(0, r), cy + random.gauss(0, r)
    else:
        x, y = random.uniform(2, 98), random.uniform(2, 98)
    a = random.uniform(0, 2 * math.pi)
    points = []
    for _ in range(11):
        x = min(100.0, max(0.0, x))
        y = min(100.0, max(0.0, y))
        points.append([round(x, 2), round(y, 2)])
        a += random.gauss(0, 0.6)
        step = random.uniform(0.3, 1.2)
        x, y = x + step * math.cos(a), y + step * math.sin(a)
    objects.append({"type": "polyline", "points": points})
scene = {
    "description": "Flatland: 10,000 segments (1,000 strokes of ten), evenly spread with three clumps: the dense "
                   "scene for speed (dragging the ray re-traces it at once) and for the structures' adaptivity. "
                   "Made by scripts/make_dense_flatland.py.",
    "dimensions": 2,
    "objects": objects,
    "ray": {"origin": [0.5, 12.0], "direction": [1, 0.63]},
    "render": {"size": [500, 500]},
}
text = json.dumps(scene, separators=(",", ":"))
text = text.replace('},{"type"', '},\n{"type"')
out = sys.argv[1] if len(sys.argv) > 1 else "scenes/flatland/dense_strokes.json"
with open(out, "w") as f:
    f.write(text + "\n")
