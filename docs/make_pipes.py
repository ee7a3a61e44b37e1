#!/usr/bin/env python3
"""The Three Pipes of Jacobson 2013, 3.8 (after Botsch and Kobbelt 2004): one straight tube of radius 1
along y, the parameterization of 3.8.1's "straight cylinder" -- a first pipe (y in [0, 2], fixed), a free middle as
long as the quarter circle of radius B between the pipes, and a second pipe (handle) -- and the region
files for deform sculpt. Writes pipes.obj, pipes_fixed.txt, pipes_handle.txt into the folder given.
Usage: python3 docs/make_pipes.py OUT_DIR [B]"""
import math
import os
import sys

out = sys.argv[1]
B = float(sys.argv[2]) if len(sys.argv) > 2 else 2.5
around, dz = 48, 2 * math.pi / 48          # square-ish quads
pipe, arc = 2.0, math.pi / 2 * B
rings = int(round((2 * pipe + arc) / dz)) + 1
length = 2 * pipe + arc
V, F = [], []
for i in range(rings):
    z = length * i / (rings - 1)
    for j in range(around):
        a = 2 * math.pi * j / around
        V.append((math.cos(a), z, math.sin(a)))
for i in range(rings - 1):
    for j in range(around):
        a, b = i * around + j, i * around + (j + 1) % around
        c, d = a + around, b + around
        F += [(a, d, b), (a, c, d)]
os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "pipes.obj"), "w") as f:
    for v in V:
        f.write("v %.9f %.9f %.9f\n" % v)
    for t in F:
        f.write("f %d %d %d\n" % tuple(k + 1 for k in t))
eps = 1e-9
with open(os.path.join(out, "pipes_fixed.txt"), "w") as f:
    f.write("# the first pipe: y <= %g\n" % pipe)
    f.writelines("%d\n" % k for k, v in enumerate(V) if v[1] <= pipe + eps)
with open(os.path.join(out, "pipes_handle.txt"), "w") as f:
    f.write("# the second pipe: y >= %g\n" % (pipe + arc))
    f.writelines("%d\n" % k for k, v in enumerate(V) if v[1] >= pipe + arc - eps)
print("pipes: %d vertices, %d triangles; free middle %.4f long (B = %g); handle pivot y = %.6f"
      % (len(V), len(F), arc, B, pipe + arc))
