#!/usr/bin/env python3
"""The meshes of the slanted scenes (BSP against kd-tree): scenes/meshes/subdivided_box.obj, a unit box
whose faces are split into N x N quads (the scene turns it about a slanted axis), and scenes/meshes/thin_strips.obj,
rows of long thin triangles in the plane z = 0 (the scene tilts it). Deterministic: no randomness."""
import argparse
import os

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, "..", "scenes", "meshes")


def subdivided_box(n):
    verts, faces, index = [], [], {}

    def vid(p):
        if p not in index:
            index[p] = len(verts) + 1
            verts.append(p)
        return index[p]

    # Each face by its fixed axis, side, and the two axes it spans (counter-clockwise seen from outside).
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0, 0, 0]
                        p[axis], p[u], p[v] = side, i + di, j + dj
                        quad.append(vid(tuple(p)))
                    if side == 0:
                        quad.reverse()
                    faces.append(quad)
    lines = ["# a box of %d x %d quads per face, coordinates k / %d - 0.5 (scripts/make_slanted.py)" % (n, n, n)]
    lines += ["v %.6g %.6g %.6g" % tuple(c / n - 0.5 for c in p) for p in verts]
    lines += ["f " + " ".join(str(k) for k in f) for f in faces]
    return "\n".join(lines) + "\n"


def thin_strips(rows, per_row):
    lines = ["# %d rows of %d long thin triangles in z = 0 (scripts/make_slanted.py)" % (rows, per_row)]
    faces = []
    k = 0
    for r in range(rows):
        for i in range(per_row):
            x, y = -2 + 4.0 * i / per_row, -2 + 4.0 * r / rows
            w, h = 4.0 / per_row, 4.0 / rows
            # a needle: almost the row's height, three tenths of a column wide
            lines.append("v %.6g %.6g 0" % (x, y))
            lines.append("v %.6g %.6g 0" % (x + 0.3 * w, y))
            lines.append("v %.6g %.6g 0" % (x + 0.15 * w, y + 0.95 * h))
            faces.append("f %d %d %d" % (k + 1, k + 2, k + 3))
            k += 3
    return "\n".join(lines + faces) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--box", type=int, default=12, help="quads per box face edge")
    ap.add_argument("--rows", type=int, default=8)
    ap.add_argument("--per-row", type=int, default=60)
    a = ap.parse_args()
    with open(os.path.join(MESHES, "subdivided_box.obj"), "w") as f:
        f.write(subdivided_box(a.box))
    with open(os.path.join(MESHES, "thin_strips.obj"), "w") as f:
        f.write(thin_strips(a.rows, a.per_row))


if __name__ == "__main__":
    main()
