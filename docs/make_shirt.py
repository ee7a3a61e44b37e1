#!/usr/bin/env python3
"""A shirt for the weight transfer demo (docs/weight_transfer_demo.txt): the teddy's torso faces
(assets/default.obj), each split into four at its edge midpoints (the shirt's own triangulation), every
vertex pushed out along the body's normal by 2% of the diagonal -- what tests/test_transfer_weights_script
builds. Usage: python3 docs/make_shirt.py OUT.obj"""
import math
import sys


def main(out):
    V, F = [], []
    for line in open("assets/default.obj"):
        w = line.split()
        if w and w[0] == "v":
            V.append([float(x) for x in w[1:4]])
        elif w and w[0] == "f":
            F.append([int(x.split("/")[0]) - 1 for x in w[1:4]])
    N = [[0.0, 0.0, 0.0] for _ in V]
    for a, b, c in F:
        e1 = [V[b][k] - V[a][k] for k in range(3)]
        e2 = [V[c][k] - V[a][k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        for v in (a, b, c):
            N[v] = [N[v][k] + n[k] for k in range(3)]
    lo = [min(p[k] for p in V) for k in range(3)]
    hi = [max(p[k] for p in V) for k in range(3)]
    offset = 0.02 * math.dist(lo, hi)
    index, points, faces = {}, [], []

    def vertex(a, b):
        key = (min(a, b), max(a, b))
        if key not in index:
            n = [N[a][k] + N[b][k] for k in range(3)]
            length = math.sqrt(sum(x * x for x in n)) or 1.0
            points.append([0.5 * (V[a][k] + V[b][k]) + offset * n[k] / length for k in range(3)])
            index[key] = len(points)
        return index[key]

    for a, b, c in F:
        cx, cy = [(V[a][k] + V[b][k] + V[c][k]) / 3 for k in range(2)]
        if abs(cx) > 0.42 or cy < -0.45 or cy > 0.4:
            continue
        A, B, C = vertex(a, a), vertex(b, b), vertex(c, c)
        ab, bc, ca = vertex(a, b), vertex(b, c), vertex(c, a)
        faces += [(A, ab, ca), (ab, B, bc), (ca, bc, C), (ab, bc, ca)]
    with open(out, "w") as f:
        for p in points:
            f.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in faces:
            f.write("f %d %d %d\n" % t)


if __name__ == "__main__":
    main(sys.argv[1])
