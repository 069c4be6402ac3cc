#!/usr/bin/env bash
# Builds the loaders' fuzz targets with clang (libFuzzer, ASan, UBSan) in build-asan/, the build
# the sanitizer run shares (scripts/asan_build.sh), and runs each for SECONDS (default 30),
# starting from the seed corpus in fuzz/corpus/<format>/. Prints each target's execution count;
# exits non-zero on the first crash, leak, hang or sanitizer report, leaving the input in
# build-asan/fuzz-artifacts/.
#
#   fuzz/run_all.sh [SECONDS]        JOBS=N sets the build's parallelism (default: nproc)
set -euo pipefail
seconds="${1:-30}"
root="$(cd "$(dirname "$0")/.." && pwd)"
formats=(obj mtl stl gltf hdr assimp)

source "$root/scripts/asan_build.sh"
build=$(configure_asan_build "$root")
targets=()
for f in "${formats[@]}"; do targets+=("tessera_fuzz_$f"); done
cmake --build "$build" -j"${JOBS:-$(nproc)}" --target "${targets[@]}"

mkdir -p "$build/fuzz-artifacts"
# Leaks inside Debian's libassimp, which we cannot fix, are suppressed (scripts/lsan.supp).
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp"
# One fuzzer: its execution count on success; the end of its log and a failure otherwise.
fuzz_one() {  # format
  local f="$1"
  # New inputs go to a scratch corpus: the seeds in the repository stay as they are.
  local work="$build/fuzz-corpus/$f"
  mkdir -p "$work"
  local log="$build/logs/fuzz_$f.log"
  # -timeout: an input taking 10 s counts as a hang, except for assimp's formats, which are read
  # in a child process stopped after 30 s (assimp_loader.cpp): one of assimp's own hangs is then
  # tessera's clear error, not a fuzzer timeout; -rss_limit_mb: libFuzzer's 2 GiB default,
  # stated; -max_len: room for small glTF files with embedded buffers.
  # A dictionary of the format's keywords helps the fuzzer past its syntax.
  local timeout=10
  [ "$f" = assimp ] && timeout=45
  local dict=()
  [ -f "$root/fuzz/dict/$f.dict" ] && dict=(-dict="$root/fuzz/dict/$f.dict")
  if "$build/fuzz/tessera_fuzz_$f" "$work" "$root/fuzz/corpus/$f" "${dict[@]}" \
      -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=16384 \
      -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$f-" >"$log" 2>&1; then
    local runs
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    echo "fuzz $f: ${runs:-?} executions in ${seconds} s"
  else
    echo "fuzz $f: FAILED (log: $log)" >&2
    tail -40 "$log" >&2
    return 1
  fi
}

# Each fuzzer is one process on one core: as many at a time as there are cores.
status=0
parallel="${JOBS:-$(nproc)}"
pids=()
for f in "${formats[@]}"; do
  fuzz_one "$f" &
  pids+=($!)
  if [ "${#pids[@]}" -ge "$parallel" ]; then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
exit $status
