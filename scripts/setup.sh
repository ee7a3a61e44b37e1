#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine:
#   scripts/setup.sh editor   install what is missing, build, launch the editor on the default scene
#   scripts/setup.sh test     install what is missing, build, run the whole test suite
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"
case "$mode" in editor|test|build) ;; *) echo "usage: scripts/setup.sh editor|test" >&2; exit 2 ;; esac

bash scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"

case "$mode" in
  editor)
    exec build/app/deform-editor assets/default.scene.json
    ;;
  test)
    # GL tests need a display: run the whole suite under a virtual X server (Mesa llvmpipe).
    export LIBGL_ALWAYS_SOFTWARE=1
    xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build --output-on-failure -j"$jobs"
    # Readers, hostile files and fuzz reproducers again under AddressSanitizer and
    # UndefinedBehaviorSanitizer (a separate build of the io modules only, to keep CI short).
    asan_tests=(test_util test_rig test_io_hostile test_io_roundtrip test_io_data test_mesh_info
                test_io_fuzz_inputs)
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDFM_SANITIZE=ON \
          -DDFM_BUILD_EDITOR=OFF -DDFM_BUILD_BENCH=OFF >/dev/null
    cmake --build build-asan -j"$jobs" --target "${asan_tests[@]}"
    regex="^($(IFS='|'; echo "${asan_tests[*]}"))\$"
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      ctest --test-dir build-asan --output-on-failure -j"$jobs" -R "$regex"
    ;;
esac
