#!/usr/bin/env python3
"""Where a cube's level error sits (issue 16): corners, lines or flat faces.

Reads crease_bench's CREASE_BENCH_DUMP files for the cube shape ([-1, 1]^3):
DIR/cube-on-L.off (the level's mesh) and DIR/cube-on-L.dist (each vertex's
offset to its nearest point of the true mesh).  Each triangle is classed by
its centroid (within 0.1 of a corner; within 0.01 / 0.05 / 0.2 of an edge;
else a face) and weighted by its area, with the mean of its vertices'
distances: an area-weighted proxy of the two-sided error, in model units.

Why a script and not crease_rise_probe --bins: that probe classes odd
vertices by count, which puts most of the weight near the lines (the aligned
mesh is dense there); this weighs by area, as the error measure does.

usage: CREASE_BENCH_DUMP=DIR build/bin/crease_bench --on-only --seed S cube
       bench/crease_regions.py DIR/cube 0,1,3
"""
import math
import sys


def region(p):
    near = sorted(1 - abs(c) for c in p)  # distances to the three nearest face planes
    if near[2] < 0.1:
        return "corner<0.1"
    if near[1] < 0.01:
        return "edge<0.01"
    if near[1] < 0.05:
        return "edge<0.05"
    if near[1] < 0.2:
        return "edge<0.2"
    return "face"


def main():
    prefix, levels = sys.argv[1], [int(x) for x in sys.argv[2].split(",")]
    for level in levels:
        lines = open(f"{prefix}-on-{level}.off").read().split("\n")
        nv, nt, _ = map(int, lines[1].split())
        pos = [tuple(map(float, lines[2 + i].split())) for i in range(nv)]
        tri = [tuple(map(int, lines[2 + nv + i].split()[1:])) for i in range(nt)]
        dist = [math.sqrt(sum(float(x) ** 2 for x in row.split())) for row in open(f"{prefix}-on-{level}.dist") if row.strip()]
        acc, corners = {}, {}
        for t in tri:
            a, b, c = (pos[i] for i in t)
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            area = 0.5 * math.sqrt(sum(x * x for x in cross))
            centroid = tuple(sum(pos[i][k] for i in t) / 3 for k in range(3))
            err = sum(dist[i] for i in t) / 3
            k = region(centroid)
            s = acc.setdefault(k, [0.0, 0.0])
            s[0] += area
            s[1] += area * err
            if k == "corner<0.1":
                s = corners.setdefault(tuple(1 if x > 0 else -1 for x in centroid), [0.0, 0.0])
                s[0] += area
                s[1] += area * err
        total = sum(s[1] for s in acc.values())
        area = sum(s[0] for s in acc.values())
        print(f"level {level}: area-weighted mean vertex distance {total / area:.3e}")
        for k, s in sorted(acc.items()):
            print(f"  {k:12s} area {s[0] / area:.3f} share {s[1] / total:.3f} mean {s[1] / s[0]:.2e}")
        print("  per corner:", " ".join(f"{k}:{s[1] / s[0]:.1e}" for k, s in sorted(corners.items())))


if __name__ == "__main__":
    main()
