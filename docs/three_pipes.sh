#!/usr/bin/env bash
# The Three Pipes (Jacobson 2013, 3.8; issue 37) with deform sculpt: a straight tube (3.8.1's cylinder
# parameterization), its first pipe fixed, its second pipe (the handle) turned a quarter about z and
# moved to meet the first at a right angle with a bend of radius 2.5; the free middle solved biharmonic
# (C1) and triharmonic (C2) with region conditions from the straight pipes (3.8.2), then the three
# drawn side by side: docs/three_pipes.png. Run from the repository root (needs a display: xvfb-run).
set -euo pipefail
out=${1:-/tmp/three_pipes}
python3 docs/make_pipes.py "$out" 2.5
for order in 2 3; do
  build/app/deform sculpt "$out/pipes.obj" --fixed "$out/pipes_fixed.txt" --handle "$out/pipes_handle.txt" \
    --rotate 0 0 1 -90 --about 0 5.926991 0 --move 2.5 -1.426991 0 --order $order -o "$out/pipes_order$order.obj"
done
build/app/deform manifold --keyframes "$out/pipes.obj" "$out/pipes_order2.obj" "$out/pipes_order3.obj" --frames 3 \
  --strip docs/three_pipes.png
