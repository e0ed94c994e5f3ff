#!/usr/bin/env python3
"""Write scenes/meshes/torus_knot.obj: a (2,3) torus knot (a trefoil) as a tube of quads with vertex normals.

The centre curve is c(phi) = ((2 + cos(q phi)) cos(p phi), (2 + cos(q phi)) sin(p phi), -sin(q phi)),
phi in [0, 2 pi). The tube's cross-section circle lies in the curve's Frenet normal plane (the torus
knot's curvature never vanishes, so the frame is defined everywhere). Faces are quads
(v00, v10, v11, v01) wound so that the geometric normal points out of the tube; the loader splits each
as the fan (v0, v1, v2), (v0, v2, v3). Output is deterministic: run it again and git sees no change.

Usage: python3 scripts/make_torus_knot.py [--segments 192] [--sides 12] [--out scenes/meshes/torus_knot.obj]
"""
import argparse
import math
import os


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    return (a[0] / n, a[1] / n, a[2] / n)


def curve(phi, p, q):
    r = 2.0 + math.cos(q * phi)
    return (r * math.cos(p * phi), r * math.sin(p * phi), -math.sin(q * phi))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--segments", type=int, default=192, help="steps along the curve")
    ap.add_argument("--sides", type=int, default=12, help="steps around the tube")
    ap.add_argument("--radius", type=float, default=0.4, help="tube radius")
    ap.add_argument("--p", type=int, default=2)
    ap.add_argument("--q", type=int, default=3)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--out", default=os.path.join(here, "..", "scenes", "meshes", "torus_knot.obj"))
    a = ap.parse_args()

    verts, norms = [], []
    h = 1e-4
    for i in range(a.segments):
        phi = 2.0 * math.pi * i / a.segments
        c = curve(phi, a.p, a.q)
        # Frenet frame from central differences: tangent T, binormal B = T x T', normal N = B x T.
        c_prev, c_next = curve(phi - h, a.p, a.q), curve(phi + h, a.p, a.q)
        t = normalize(sub(c_next, c_prev))
        second = sub(sub(c_next, c), sub(c, c_prev))
        b = normalize(cross(t, second))
        n = cross(b, t)
        for j in range(a.sides):
            theta = 2.0 * math.pi * j / a.sides
            d = tuple(math.cos(theta) * n[k] + math.sin(theta) * b[k] for k in range(3))
            verts.append(tuple(c[k] + a.radius * d[k] for k in range(3)))
            norms.append(d)

    def index(i, j):  # 1-based OBJ index of ring i, side j
        return (i % a.segments) * a.sides + (j % a.sides) + 1

    with open(a.out, "w", newline="\n") as f:
        f.write("# (%d,%d) torus knot, %d x %d quads, tube radius %g; made by scripts/make_torus_knot.py\n"
                % (a.p, a.q, a.segments, a.sides, a.radius))
        f.write("o torus_knot\n")
        for v in verts:
            f.write("v %.5f %.5f %.5f\n" % v)
        for n in norms:
            f.write("vn %.5f %.5f %.5f\n" % n)
        for i in range(a.segments):
            for j in range(a.sides):
                # Side j+1 turns from d towards B, ring i+1 lies along T: (side step) x (ring step)
                # ~ B x T = N at theta = 0, so this winding's geometric normal is d, pointing out.
                q = [index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)]
                f.write("f " + " ".join("%d//%d" % (k, k) for k in q) + "\n")
    print("wrote %s: %d vertices, %d quads (%d triangles)"
          % (a.out, len(verts), a.segments * a.sides, 2 * a.segments * a.sides))


if __name__ == "__main__":
    main()
