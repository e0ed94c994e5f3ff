#!/usr/bin/env python3
"""Write scenes/moire.json: white bars on black whose frequency rises from left to right (a chirp).

The bars are slanted parallelograms (quads) in the z = 0 plane under an orthographic camera, one world unit
per pixel, lit only by ambient light (as scenes/aliasing.json: a pixel's true value is the fraction of it the
bars cover). Across the picture the bars' frequency rises linearly from --f0 to --f1 cycles per pixel, so
every sampling rate meets bars finer than it can resolve somewhere: regular sampling turns them into false
coarse stripes (moire), jittered sampling into noise. Output is deterministic.

Usage: python3 scripts/make_moire.py [--f0 0.25] [--f1 1.6] [--out scenes/moire.json]
"""
import argparse
import json
import os

WIDTH, HEIGHT = 160, 80


def compact(value):
    return json.dumps(value, separators=(", ", ": "))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--f0", type=float, default=0.25, help="cycles per pixel at the left edge")
    ap.add_argument("--f1", type=float, default=1.6, help="cycles per pixel at the right edge")
    ap.add_argument("--slant", type=float, default=0.2, help="horizontal shift of a bar per unit of height")
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--out", default=os.path.join(here, "..", "scenes", "moire.json"))
    a = ap.parse_args()

    # Sheared coordinate u = x - slant (y - HEIGHT/2); frequency f(u) = f0 + (f1 - f0) u / WIDTH, phase
    # phi(u) = integral of f from u_lo. A bar is white where phi is in [n, n + 1/2).
    u_lo, u_hi = -12.0, WIDTH + 12.0
    k = (a.f1 - a.f0) / WIDTH

    def phi(u):
        return a.f0 * (u - u_lo) + k / 2 * (u * u - u_lo * u_lo)

    def solve(target):  # phi is increasing on [u_lo, u_hi]: bisection
        lo, hi = u_lo, u_hi
        for _ in range(60):
            mid = (lo + hi) / 2
            if phi(mid) < target:
                lo = mid
            else:
                hi = mid
        return round((lo + hi) / 2, 5)

    y0, y1 = -2.0, HEIGHT + 2.0
    objects = []
    n = 0
    while n + 0.5 <= phi(u_hi):
        ua, ub = solve(n), solve(n + 0.5)
        quad = [[round(u + a.slant * (y - HEIGHT / 2), 5), y, 0] for u, y in ((ua, y0), (ub, y0), (ub, y1), (ua, y1))]
        objects.append({"type": "quad", "name": "bar %d" % n, "material": "white", "vertices": quad})
        n += 1

    scene = {
        "description": "Moire (lesson 3): %d white bars on black, slanted, whose frequency rises linearly from %g "
                       "cycles per pixel at the left to %g at the right, under an orthographic camera with one world "
                       "unit per pixel and only ambient light, so that a pixel's true value is the fraction the bars "
                       "cover. Written by scripts/make_moire.py." % (len(objects), a.f0, a.f1),
        "camera": {"type": "orthographic", "eye": [WIDTH / 2, HEIGHT / 2, 10], "look_at": [WIDTH / 2, HEIGHT / 2, 0],
                   "up": [0, 1, 0], "height": HEIGHT},
        "lights": [],
        "materials": {"white": {"diffuse": 1}},
        "objects": objects,
        "render": {"size": [WIDTH, HEIGHT], "aa": "none", "ambient": 1, "background": 0, "max_depth": 0},
    }
    lines = ["{"]
    for key in ("description", "camera", "lights", "materials"):
        lines.append('  "%s": %s,' % (key, compact(scene[key])))
    lines.append('  "objects": [')
    lines.append(",\n".join("    " + compact(o) for o in objects))
    lines.append("  ],")
    lines.append('  "render": %s' % compact(scene["render"]))
    lines.append("}")
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s: %d bars, %d triangles" % (a.out, len(objects), 2 * len(objects)))


if __name__ == "__main__":
    main()
