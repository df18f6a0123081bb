#!/usr/bin/env bash
# fuzz.sh TARGET SECONDS — build a libFuzzer target of fuzz/ with clang (ASan + UBSan +
# coverage on every library) into build-fuzz/ and run it for SECONDS on its corpus.
#
# TARGET: fixture_reader | fast_engine (fuzz/README.md describes both and their input formats).
# Corpus: fuzz/corpus/TARGET is read, never written; new entries go to a scratch directory
# (build-fuzz/scratch/TARGET, or $PDD_FUZZ_SCRATCH). Crash, timeout and OOM inputs are saved to
# fuzz/crashes/TARGET/ (not committed; minimise with `build-fuzz/bin/fuzz_TARGET
# -minimize_crash=1 -runs=10000 FILE` before adding one to the corpus as a regression).
# By default the fuzzer keeps going after a crash (libFuzzer's -fork=1 -ignore_crashes=1), so
# one known crash does not end the run; PDD_FUZZ_STOP_ON_CRASH=1 stops at the first.
# Extra arguments after SECONDS go to the fuzzer, e.g. `-only_ascii=1`.
# At the end it prints libFuzzer's coverage: cov (code edges covered) and ft (features).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

if (($# < 2)); then
  echo "usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]   (TARGET: fixture_reader | fast_engine)" >&2
  exit 2
fi
TARGET=$1 SECONDS_TO_RUN=$2
shift 2
[ -d "fuzz/corpus/$TARGET" ] || { echo "fuzz: no target '$TARGET' (fuzz/corpus/$TARGET missing)" >&2; exit 2; }

CXX_BIN=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$CXX_BIN" ] || [ ! -e "$("$CXX_BIN" -print-resource-dir)/lib/linux/libclang_rt.fuzzer-x86_64.a" ]; then
  echo "fuzz: installing clang-14 and its libFuzzer runtime (Debian packages)"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends clang-14 libclang-rt-14-dev
  CXX_BIN=$(command -v clang++-14)
fi

cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER="$CXX_BIN" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPDD_BUILD_FUZZERS=ON >/dev/null
nice cmake --build build-fuzz -j"${PDD_JOBS:-$(nproc)}" --target "fuzz_$TARGET"

SCRATCH=${PDD_FUZZ_SCRATCH:-$ROOT/build-fuzz/scratch/$TARGET}
CRASHES=$ROOT/fuzz/crashes/$TARGET
mkdir -p "$SCRATCH" "$CRASHES"
LOG=$ROOT/build-fuzz/fuzz-$TARGET.log

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
# -rss_limit_mb=4096: under ASan the merge process that replays the corpus sits at 1–1.6 GB after
# a few dozen inputs (allocator caches and quarantine: 1.0 GB after 20 inputs, 1.1 GB after 60,
# not a leak), so an input that alone peaks at 0.3 GB (oom-1399db4c..., 1.8 s, 296 MB) crosses
# libFuzzer's default 2048 MB and would be reported as an out-of-memory.
MODE=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 -rss_limit_mb=4096)
[ "${PDD_FUZZ_STOP_ON_CRASH:-0}" = 1 ] && MODE=()
MAXLEN=()
[ "$TARGET" = fast_engine ] && MAXLEN=(-max_len=256)

echo "fuzz: running fuzz_$TARGET for $SECONDS_TO_RUN s; log $LOG"
status=0
nice build-fuzz/bin/"fuzz_$TARGET" "${MODE[@]}" "${MAXLEN[@]}" -max_total_time="$SECONDS_TO_RUN" \
  -timeout=60 -print_final_stats=1 -artifact_prefix="$CRASHES/" "$@" \
  "$SCRATCH" "fuzz/corpus/$TARGET" >"$LOG" 2>&1 || status=$?

echo "fuzz: exit status $status"
echo "fuzz: last coverage line:"
grep -E 'cov: [0-9]+' "$LOG" | tail -1 || true
grep -E '^stat::' "$LOG" || true
n_new=$(find "$SCRATCH" -type f | wc -l)

echo "fuzz: scratch corpus $SCRATCH: $n_new files"
echo "fuzz: crash/timeout/oom inputs in $CRASHES: $(find "$CRASHES" -type f | wc -l) in all"
grep -E '^==[0-9]+==ERROR|SUMMARY: |runtime error|fuzz_(fast_engine|fixture_reader): ' "$LOG" | sort | uniq -c | sort -rn | head -20 || true
exit $status
