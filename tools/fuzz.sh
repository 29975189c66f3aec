#!/usr/bin/env bash
# Fuzzes the input parsers with libFuzzer (tests/fuzz): builds the fuzz preset (clang++ with
# ASan and UBSan) into build/fuzz, then runs each target for its share of SECONDS (default 60
# in all, 20 s a target), starting from the committed corpus, which it only reads. New inputs go
# to build/fuzz/corpus/<target>, findings (crash-*, leak-*, timeout-*, oom-*) to
# build/fuzz/findings/<target>. Exits 1 and names the input if any target finds anything.
#
#   tools/fuzz.sh [SECONDS]                   all targets (needs: apt-get install clang libclang-rt-14-dev)
#   FUZZ_TARGETS="preset points" tools/fuzz.sh 120
#   FUZZ_SECONDS_camera_path=300 tools/fuzz.sh  one target's time, overriding its share
#   tools/fuzz.sh --merge                     add build/fuzz/corpus's new coverage to tests/fuzz/corpus
#   FUZZ_SEED=0 tools/fuzz.sh 3600            a random seed (default 1: CI's runs mutate alike, so a
#                                             finding there is reproducible, not luck of the draw)
#
# A finding: reproduce it with build/fuzz/tests/fuzz/planet_fuzz_<target> FILE, then copy FILE
# into tests/fuzz/corpus/<target>/ so that the corpus replay test (ctest -L unit) fails until
# the bug is fixed, and keeps checking it afterwards. --merge is a person's step (CI never
# changes the committed corpus); commit what it adds if the corpus stays small.
set -euo pipefail
cd "$(dirname "$0")/.."

read -ra targets <<<"${FUZZ_TARGETS:-preset points camera_path scene}"
merge=0
if [[ ${1:-} == --merge ]]; then
  merge=1
  shift
fi
total=${1:-60}
if ! [[ $total =~ ^[0-9]+$ ]] || ((total < 1)); then
  echo "usage: $0 [SECONDS] | --merge   (SECONDS: a whole number, at least 1)" >&2
  exit 2
fi

if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found: apt-get install clang libclang-rt-14-dev" >&2
  exit 2
fi
if ! compgen -G "$(clang++ --print-runtime-dir)/libclang_rt.fuzzer-*.a" >/dev/null; then
  echo "fuzz: libFuzzer not found in $(clang++ --print-runtime-dir): apt-get install libclang-rt-14-dev" >&2
  exit 2
fi

echo "fuzz: building the fuzz preset (build/fuzz)"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

build=build/fuzz
# Every sanitizer report ends the run with a stack (UBSan prints none by default); leaks count.
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}

if ((merge)); then
  for target in "${targets[@]}"; do
    committed=tests/fuzz/corpus/$target
    before=$(find "$committed" -type f | wc -l)
    mkdir -p "$build/corpus/$target"
    # -merge=1 copies into the first folder only the inputs of the others that add coverage.
    "$build/tests/fuzz/planet_fuzz_$target" -merge=1 -max_len=65536 -timeout=5 -rss_limit_mb=2048 \
      "$committed" "$build/corpus/$target" >"$build/merge_$target.log" 2>&1 || {
      echo "fuzz: merging $target failed (an input crashes?); see $build/merge_$target.log" >&2
      exit 1
    }
    after=$(find "$committed" -type f | wc -l)
    echo "fuzz: $target: $committed has $after inputs ($((after - before)) new, $(du -sh "$committed" | cut -f1))"
  done
  exit 0
fi

share=$((total / ${#targets[@]}))
((share >= 1)) || share=1
failed=()
for target in "${targets[@]}"; do
  exe=$build/tests/fuzz/planet_fuzz_$target
  if [[ ! -x $exe ]]; then
    echo "fuzz: no target '$target' (known: preset points camera_path scene)" >&2
    exit 2
  fi
  override=FUZZ_SECONDS_$target
  seconds=${!override:-$share}
  scratch=$build/corpus/$target
  findings=$build/findings/$target
  log=$build/fuzz_$target.log
  mkdir -p "$scratch" "$findings"
  echo "fuzz: $target: ${seconds} s from tests/fuzz/corpus/$target ($(find tests/fuzz/corpus/"$target" -type f | wc -l) inputs)"
  status=0
  # 64 KiB is well past any real preset or path; -timeout and -rss_limit_mb make a hang or a
  # runaway allocation a finding rather than a stuck CI job.
  "$exe" -dict="tests/fuzz/$target.dict" -max_len=65536 -timeout=5 -rss_limit_mb=2048 \
    -max_total_time="$seconds" -seed="${FUZZ_SEED:-1}" -print_final_stats=1 -artifact_prefix="$findings/" \
    "$scratch" "tests/fuzz/corpus/$target" >"$log" 2>&1 || status=$?
  # libFuzzer's last status line: executions, coverage, corpus size, executions per second.
  grep -E '^#[0-9]+' "$log" | tail -n 1 | sed "s/^/fuzz: $target: /" || true
  grep -E '^stat::average_exec_per_sec' "$log" | sed "s/^stat::/fuzz: $target: /" || true
  if ((status != 0)); then
    echo "fuzz: $target: FINDING (libFuzzer exit status $status); the report, from $log:" >&2
    grep -vE '^#[0-9]+|^INFO:|NEW_FUNC' "$log" | tail -n 60 >&2
    grep -oE 'Test unit written to .*' "$log" | sed "s/^/fuzz: $target: /" >&2 || true
    failed+=("$target")
  fi
done

if ((${#failed[@]})); then
  echo "fuzz: findings in: ${failed[*]} (inputs under $build/findings)" >&2
  exit 1
fi
echo "fuzz: no findings"
