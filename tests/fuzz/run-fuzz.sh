#!/usr/bin/env bash
# Builds the libFuzzer targets on the model loader and on the session reader with clang++-14
# (-fsanitize=fuzzer,address,undefined, the library's parsers instrumented too) in their own build directory, writes
# the seed corpora and fuzzes both at once, each for half the given time (the total stays the given time).
#   bash tests/fuzz/run-fuzz.sh [seconds (60)] [build directory (build-fuzz)]
# A build directory already configured with -DVISP_PROJECTIVE_FUZZ=ON (for instance a clang++-14 sanitizer build of the
# tests configured with both -DVISP_PROJECTIVE_SANITIZE=ON and -DVISP_PROJECTIVE_FUZZ=ON, as CI's build-asan) is used
# as it is: its library's parsers are already instrumented for libFuzzer, only the fuzz targets are built there.
# Fails if a fuzzer finds anything (crash, sanitizer report, leak, timeout, an exception other than vpException, a
# broken property); the reproducer is then under <build>/fuzz/<target>/artifacts/ (replay:
# <build>/tests/fuzz/<target> <file>).
# Needs the Debian packages clang-14 and libclang-rt-14-dev (scripts/install-deps.sh).
set -euo pipefail
seconds="${1:-60}"
cd "$(dirname "$0")/../.."
build="${2:-build-fuzz}"

if ! grep -qs '^VISP_PROJECTIVE_FUZZ:BOOL=ON$' "$build/CMakeCache.txt"; then
  cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 \
    -DVISP_PROJECTIVE_FUZZ=ON -DVISP_PROJECTIVE_BUILD_TESTS=OFF -DVISP_PROJECTIVE_BUILD_TUTORIALS=OFF \
    -DVISP_PROJECTIVE_BUILD_BENCHMARKS=OFF
fi
cmake --build "$build" -j2 --target fuzzModelLoader fuzzSessionReader makeSeedCorpus

export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
rm -rf "$build/fuzz"
for target in fuzzModelLoader fuzzSessionReader; do
  mkdir -p "$build/fuzz/$target/seeds" "$build/fuzz/$target/corpus" "$build/fuzz/$target/artifacts"
done
"$build/tests/fuzz/makeSeedCorpus" "$build/fuzz/fuzzModelLoader/seeds" "$build/fuzz/fuzzSessionReader/seeds"

# The time split between the two targets; new inputs go to corpus/, the seeds are read only; -timeout: one input must
# not take more than 10 s. The two targets fuzz at the same time, each on its own core (one process each), each for
# its own share of the time: the wall time is half the given time, the fuzzing time is the given time.
first=$(( (seconds + 1) / 2 ))
pids=()
for target in fuzzModelLoader fuzzSessionReader; do
  work="$build/fuzz/$target"
  budget=$first
  if [ "$target" = fuzzSessionReader ]; then
    budget=$(( seconds - first > 0 ? seconds - first : 1 ))
  fi
  "$build/tests/fuzz/$target" -max_total_time="$budget" -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$work/artifacts/" "$work/corpus" "$work/seeds" > "$work/fuzz.log" 2>&1 &
  pids+=($!)
done
status=0
index=0
for target in fuzzModelLoader fuzzSessionReader; do
  work="$build/fuzz/$target"
  rc=0
  wait "${pids[$index]}" || rc=$?
  index=$((index + 1))
  if [ "$rc" -ne 0 ]; then
    tail -n 60 "$work/fuzz.log"
    echo "run-fuzz.sh: $target failed (exit $rc); log $work/fuzz.log, reproducer under $work/artifacts/" >&2
    status=$rc
    continue
  fi
  echo "$target:"
  grep -E '^(INFO: seed corpus|#[0-9]+[[:space:]]+(INITED|DONE)|Done|stat::)' "$work/fuzz.log" || true
done
if [ "$status" -ne 0 ]; then
  exit "$status"
fi
echo "run-fuzz.sh: no finding in ${seconds} s (${first} s on the model loader, the rest on the session reader)"
