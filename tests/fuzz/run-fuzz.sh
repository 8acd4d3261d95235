#!/usr/bin/env bash
# Builds the libFuzzer target on the model loader with clang++-14 (-fsanitize=fuzzer,address,undefined, the library
# sources instrumented too) in its own build directory, writes the seed corpus and fuzzes for the given time.
#   bash tests/fuzz/run-fuzz.sh [seconds (60)] [build directory (build-fuzz)]
# Fails if the fuzzer finds anything (crash, sanitizer report, leak, timeout, an exception other than vpException);
# the reproducer is then under <build>/fuzz/artifacts/ (replay: <build>/tests/fuzz/fuzzModelLoader <file>).
# Needs the Debian packages clang-14 and libclang-rt-14-dev (scripts/install-deps.sh).
set -euo pipefail
seconds="${1:-60}"
cd "$(dirname "$0")/../.."
build="${2:-build-fuzz}"

cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 -DVISP_PROJECTIVE_FUZZ=ON \
  -DVISP_PROJECTIVE_BUILD_TESTS=OFF -DVISP_PROJECTIVE_BUILD_TUTORIALS=OFF -DVISP_PROJECTIVE_BUILD_BENCHMARKS=OFF
cmake --build "$build" -j2 --target fuzzModelLoader makeSeedCorpus

work="$build/fuzz"
rm -rf "$work/seeds" "$work/corpus"
mkdir -p "$work/seeds" "$work/corpus" "$work/artifacts"
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
"$build/tests/fuzz/makeSeedCorpus" "$work/seeds"

# New inputs go to corpus/, the seeds are read only; -timeout: one input must not take more than 10 s.
rc=0
"$build/tests/fuzz/fuzzModelLoader" -max_total_time="$seconds" -timeout=10 -print_final_stats=1 \
  -artifact_prefix="$work/artifacts/" "$work/corpus" "$work/seeds" > "$work/fuzz.log" 2>&1 || rc=$?
if [ "$rc" -ne 0 ]; then
  tail -n 60 "$work/fuzz.log"
  echo "run-fuzz.sh: the fuzzer failed (exit $rc); log $work/fuzz.log, reproducer under $work/artifacts/" >&2
  exit "$rc"
fi
grep -E '^(INFO: seed corpus|#[0-9]+[[:space:]]+(INITED|DONE)|Done|stat::)' "$work/fuzz.log" || true
echo "run-fuzz.sh: no finding in ${seconds} s"
