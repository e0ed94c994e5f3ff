#!/usr/bin/env python3
"""Write a big mesh for load tests and benchmarks (never committed: write it to /tmp).

MESH is subdivided LEVELS times, each triangle into four at its edges' midpoints (a midpoint is shared
between the two triangles of an edge, so a watertight mesh stays watertight), then COPIES copies are laid
side by side along x (a gap of a tenth of the width between them). The bunny (69,451 triangles) twice
subdivided, two copies: 2,222,432 triangles, 1,114,328 vertices, 88 MB. Deterministic: the same
arguments give the same bytes.

Usage: python3 scripts/make_big_mesh.py [--levels 2] [--copies 2] [--out /tmp/big.obj] [MESH]
       (MESH: default /work/shared/meshes/stanford-bunny.obj)
"""
import argparse


def read_obj(path):
    v, f = [], []
    with open(path) as src:
        for line in src:
            p = line.split()
            if not p:
                continue
            if p[0] == 'v':
                v.append(tuple(float(x) for x in p[1:4]))
            elif p[0] == 'f':
                idx = [int(x.split('/')[0]) for x in p[1:]]
                idx = [i - 1 if i > 0 else len(v) + i for i in idx]
                for k in range(1, len(idx) - 1):  # the fan split, as raystep's reader does
                    f.append((idx[0], idx[k], idx[k + 1]))
    return v, f


def subdivide(v, f):
    mid, nf = {}, []

    def m(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in mid:
            mid[key] = len(v)
            v.append(tuple((x + y) / 2 for x, y in zip(v[a], v[b])))
        return mid[key]

    for a, b, c in f:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        nf += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return nf


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('mesh', nargs='?', default='/work/shared/meshes/stanford-bunny.obj')
    ap.add_argument('--levels', type=int, default=2)
    ap.add_argument('--copies', type=int, default=2)
    ap.add_argument('--out', default='/tmp/big.obj')
    a = ap.parse_args()
    v, f = read_obj(a.mesh)
    for _ in range(a.levels):
        f = subdivide(v, f)
    lo = [min(p[i] for p in v) for i in range(3)]
    hi = [max(p[i] for p in v) for i in range(3)]
    step = (hi[0] - lo[0]) * 1.1
    with open(a.out, 'w') as o:
        for c in range(a.copies):
            o.writelines('v %.9g %.9g %.9g\n' % (x + c * step, y, z) for x, y, z in v)
        for c in range(a.copies):
            base = c * len(v) + 1
            o.writelines('f %d %d %d\n' % (p + base, q + base, r + base) for p, q, r in f)
    print('mesh: %s subdivided %d times, %d copies: %d triangles, %d vertices -> %s' %
          (a.mesh, a.levels, a.copies, len(f) * a.copies, len(v) * a.copies, a.out))


if __name__ == '__main__':
    main()
