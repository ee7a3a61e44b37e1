#!/bin/sh
# libFuzzer targets for every reader, built with clang++ directly (no need to build the whole project
# with clang). Usage:
#   tests/fuzz/run_fuzz.sh build OUT               build OUT/fuzz_<reader> for every reader
#   tests/fuzz/run_fuzz.sh run OUT READER SECONDS  fuzz one reader: -seed=1, seed corpus tests/fuzz/corpus/READER
#   tests/fuzz/run_fuzz.sh all OUT SECONDS         build, then fuzz every reader
# Crashes land in OUT/crashes/; copy them to tests/fuzz/crashes/<reader>/ so test_io_fuzz_inputs
# replays them in the normal suite. Exit status is non-zero when a fuzzer finds a crash.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
READERS="obj off ply stl mesh tetgen dmat tgf points scene glb bvh"
CXX=${FUZZ_CXX:-$(command -v clang++-14 || command -v clang++ || true)}

build() {
  out=$1
  [ -n "$CXX" ] || { echo "run_fuzz.sh: clang++ not found (apt-get install clang-14 libclang-rt-14-dev)" >&2; exit 1; }
  mkdir -p "$out/obj"
  flags="-std=c++17 -O1 -g -fno-omit-frame-pointer -I$ROOT -isystem /usr/include/eigen3"
  objs=""
  # The scene reader needs rig/ and skin/ (handle counts, skin method names), the in-between method and
  # Laplacian weights' names and the space-time edits' checks, but not bind/, the solvers or the GL; the glTF import its reader (tinygltf, linked) and the importers' table;
  # the BVH import Assimp (linked: Debian's, not instrumented, so only our side of it is fuzzed).
  for src in "$ROOT"/core/util/*.cpp "$ROOT"/core/mesh/*.cpp "$ROOT"/core/rig/*.cpp "$ROOT"/core/skin/*.cpp \
             "$ROOT"/core/anim/inbetween_method.cpp "$ROOT"/core/anim/manifold_laplacian_names.cpp \
             "$ROOT"/core/scene/scene_file.cpp "$ROOT"/core/scene/scene_reader.cpp "$ROOT"/core/scene/space_time_edit.cpp \
             "$ROOT"/core/scene/scene_import.cpp "$ROOT"/core/export/gltf_import.cpp "$ROOT"/core/export/gltf_scene_import.cpp \
             "$ROOT"/core/export/gltf_rig_extras.cpp "$ROOT"/core/export/rig_import.cpp "$ROOT"/core/export/assimp_read.cpp \
             "$ROOT"/core/export/bvh_motion.cpp; do
    o="$out/obj/$(basename "$src" .cpp).o"
    # Rebuilt when the source or any header it includes (its -MM dependency list) is newer.
    if [ ! -f "$o.d" ]; then "$CXX" $flags -MM -MT "$o" "$src" > "$o.d"; fi
    stale=0
    [ -f "$o" ] || stale=1
    for dep in $(sed -e 's/^[^:]*://' -e 's/\\$//' "$o.d"); do
      [ "$stale" = 1 ] && break
      [ "$dep" -nt "$o" ] && stale=1
    done
    if [ "$stale" = 1 ]; then
      "$CXX" $flags -fsanitize=fuzzer-no-link,address,undefined -MMD -MF "$o.d" -c "$src" -o "$o"
    fi
    objs="$objs $o"
  done
  # One program; its name (fuzz_<reader>) picks the reader.
  "$CXX" $flags -fsanitize=fuzzer,address,undefined "$HERE/fuzz_reader.cpp" $objs -ltinygltf -lassimp -o "$out/dfm_fuzz"
  for r in $READERS; do ln -sf dfm_fuzz "$out/fuzz_$r"; done
}

run() {
  out=$1 r=$2 secs=$3
  work="$out/corpus/$r"
  mkdir -p "$work" "$out/crashes"
  # A scratch copy of the seeds: libFuzzer adds what it finds to the first corpus folder.
  cp "$HERE/corpus/$r"/* "$work"/ 2>/dev/null || true
  # Third-party leaks (Assimp's BVH loader) are suppressed as in the test suite.
  LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$ROOT/tests/sanitizer/lsan.supp:print_suppressions=0} \
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$out/fuzz_$r" -seed=1 -max_total_time="$secs" -rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout=10 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$out/crashes/$r-" "$work"
}

case "${1:-}" in
  build) build "$2" ;;
  run) run "$2" "$3" "$4" ;;
  all)
    build "$2"
    status=0
    for r in $READERS; do run "$2" "$r" "$3" || status=1; done
    exit $status ;;
  *) sed -n '2,10p' "$0"; exit 2 ;;
esac
