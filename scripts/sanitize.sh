#!/usr/bin/env bash
# sanitize.sh — build the whole project (every test) with AddressSanitizer and
# UndefinedBehaviorSanitizer into build-san/ and run its CTest suite. Exits non-zero on any
# sanitizer report (every report aborts the process: -fno-sanitize-recover=all, halt_on_error)
# or on any failing test. Used by CI (.ci/run) after the Release test suite.
#
# Compiler: clang++-14 (installed by setup.sh), so that CI builds the project with both
# compilers: GCC 12 in the Release build, clang 14 here. Without clang: g++.
# Override with PDD_SAN_CXX=clang++-14 or PDD_SAN_CXX=g++.
# Extra CTest arguments are passed through and also decide what is built: with none, the whole
# project; with a selection (e.g. `bash scripts/sanitize.sh -L fast`, CTest labels in
# cmake/pddTesting.cmake), only the targets its tests run: the selected tests' labels, as
# CTest lists them, each built by its target pdd_tests_<label>.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
start=$(date +%s)

SAN_FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -O1 -g"

pick_compiler() {
  if [ -n "${PDD_SAN_CXX:-}" ]; then echo "$PDD_SAN_CXX"; return; fi
  command -v clang++-14 || command -v clang++ || echo g++
}
CXX_BIN=$(pick_compiler)
echo "sanitize: compiler $CXX_BIN ($("$CXX_BIN" --version | head -1))"

cmake -S . -B build-san \
  -DCMAKE_CXX_COMPILER="$CXX_BIN" \
  -DCMAKE_BUILD_TYPE=Sanitize \
  -DCMAKE_CXX_FLAGS="$SAN_FLAGS" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DPDD_SANITIZE=ON >/dev/null
if (($#)); then
  # The labels of the tests this selection runs (CTest reads them from the configured tree).
  labels=$(ctest --test-dir build-san --show-only=json-v1 "$@" | python3 -c '
import json, sys
labels = set()
for t in json.load(sys.stdin)["tests"]:
    for p in t.get("properties", []):
        if p["name"] == "LABELS": labels.update(p["value"])
print(" ".join("pdd_tests_" + l for l in sorted(labels)))')
  if [ -z "$labels" ]; then
    echo "sanitize: no test matches: $*" >&2
    exit 2
  fi
  echo "sanitize: building $labels"
  # shellcheck disable=SC2086
  nice cmake --build build-san -j"${PDD_JOBS:-$(nproc)}" --target $labels
else
  nice cmake --build build-san -j"${PDD_JOBS:-$(nproc)}"
fi
built=$(date +%s)
echo "sanitize: build took $((built - start)) s"

# Every report is fatal. Suppressions apply to third-party libraries only (see the files).
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_odr_violation=2${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$ROOT/scripts/sanitize/ubsan.supp${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$ROOT/scripts/sanitize/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

status=0
# Sanitized tests run several times slower than in Release (reference_tests alone takes ~6 min
# there); CTest's default limit of 1500 s per test would cut them off. The other tests run
# beside it (-j), so the wall time is about reference_tests' own.
# --timeout is CTest's default only: a test with its own TIMEOUT property keeps it (mesh_tests,
# overlap_filter_tests 900 s, contact_energy_tests 600 s, resolve_tests 300 s, the compare
# harness tests), and under the sanitizers on 2 shared cores those can be cut off before their
# end. Run such a test's binary directly (build-san/bin/<name>, from its WORKING_DIRECTORY, with
# the *SAN_OPTIONS above), or one Boost.Test case at a time with --run_test=<case>.
ctest --test-dir build-san --output-on-failure -j"${PDD_JOBS:-$(nproc)}" --timeout "${PDD_SAN_TEST_TIMEOUT:-7200}" "$@" || status=$?
end=$(date +%s)
echo "sanitize: ctest took $((end - built)) s; total $((end - start)) s; exit $status"
exit $status
