#!/usr/bin/env python3
"""Write scenes/spheres.json: a mirror sphere, a glass sphere and a diffuse one over a checker floor.

The floor is n x n square tiles (quads) of two materials, which would be tedious to type by hand; the
rest of the scene is written out literally below. Output is deterministic.

Usage: python3 scripts/make_spheres.py [--tiles 6] [--out scenes/spheres.json]
"""
import argparse
import json
import os


def compact(value):
    return json.dumps(value, separators=(", ", ": "))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tiles", type=int, default=6, help="tiles per side of the floor")
    ap.add_argument("--tile-size", type=float, default=1.5)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--out", default=os.path.join(here, "..", "scenes", "spheres.json"))
    a = ap.parse_args()

    scene = {
        "description": "Spheres and planes: a mirror sphere, a glass sphere (transparency 0.9, ior 1.5) and a "
                       "diffuse red sphere over a %dx%d checker floor of quads, before a back wall. "
                       "Written by scripts/make_spheres.py." % (a.tiles, a.tiles),
        "camera": {"type": "pinhole", "eye": [0, 2.4, 7.5], "look_at": [0, 0.9, 0], "up": [0, 1, 0], "fov": 45},
        "lights": [
            {"type": "point", "position": [-4, 6, 5], "intensity": 0.8},
            {"type": "point", "position": [5, 4, 3], "color": [0.9, 0.9, 1.0], "intensity": 0.4},
        ],
        "materials": {
            "light tile": {"diffuse": 0.85},
            "dark tile": {"diffuse": 0.15},
            "wall": {"diffuse": [0.55, 0.6, 0.7]},
            "mirror": {"diffuse": 0.05, "specular": 0.9, "shininess": 300, "mirror": 0.9},
            "glass": {"diffuse": 0.0, "specular": 1.0, "shininess": 300, "mirror": 0.1,
                      "transparency": 0.9, "ior": 1.5},
            "red": {"diffuse": [0.8, 0.1, 0.08], "specular": 0.3, "shininess": 40},
        },
        "objects": [],
        "render": {"size": [400, 300], "aa": "none", "max_depth": 6, "min_weight": 0.01,
                   "ambient": 0.1, "background": [0.1, 0.12, 0.18]},
    }
    objects = [
        {"type": "sphere", "name": "mirror sphere", "material": "mirror", "center": [-1.3, 1, -0.3], "radius": 1},
        {"type": "sphere", "name": "glass sphere", "material": "glass", "center": [1.2, 0.8, 1.0], "radius": 0.8},
        {"type": "sphere", "name": "red sphere", "material": "red", "center": [0.6, 0.5, -2.2], "radius": 0.5},
        {"type": "quad", "name": "back wall", "material": "wall",
         "vertices": [[-6, 0, -4.5], [6, 0, -4.5], [6, 6, -4.5], [-6, 6, -4.5]]},
    ]
    half = a.tiles * a.tile_size / 2
    for i in range(a.tiles):
        for j in range(a.tiles):
            x0, z0 = -half + i * a.tile_size, -half + j * a.tile_size
            x1, z1 = x0 + a.tile_size, z0 + a.tile_size
            objects.append({"type": "quad", "name": "tile %d %d" % (i, j),
                            "material": "light tile" if (i + j) % 2 == 0 else "dark tile",
                            "vertices": [[x0, 0, z1], [x1, 0, z1], [x1, 0, z0], [x0, 0, z0]]})

    lines = ["{"]
    for key in ["description", "camera", "lights", "materials"]:
        if key == "materials":
            lines.append('  "materials": {')
            items = list(scene["materials"].items())
            for k, (name, m) in enumerate(items):
                lines.append("    %s: %s%s" % (json.dumps(name), compact(m), "," if k + 1 < len(items) else ""))
            lines.append("  },")
        elif key == "lights":
            lines.append('  "lights": [')
            for k, l in enumerate(scene["lights"]):
                lines.append("    %s%s" % (compact(l), "," if k + 1 < len(scene["lights"]) else ""))
            lines.append("  ],")
        else:
            lines.append("  %s: %s," % (json.dumps(key), compact(scene[key])))
    lines.append('  "objects": [')
    for k, o in enumerate(objects):
        lines.append("    %s%s" % (compact(o), "," if k + 1 < len(objects) else ""))
    lines.append("  ],")
    lines.append('  "render": %s' % compact(scene["render"]))
    lines.append("}")
    with open(a.out, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    json.load(open(a.out))  # the output must be valid JSON
    print("wrote %s: %d objects" % (a.out, len(objects)))


if __name__ == "__main__":
    main()
