#!/usr/bin/env bash
# Runs every fuzz target (BIN_DIR/fuzz_*) for SECONDS from its seed corpus fuzz/corpus/<target>/,
# and exits non-zero on the first finding (crash, sanitizer report, leak, time-out, out of
# memory). Inputs it finds new go to WORK_DIR/<target>/corpus, findings to
# WORK_DIR/<target>/artifacts, its output to WORK_DIR/<target>/log. Run by
# scripts/test.sh --sanitize.
#   fuzz/run_all.sh BIN_DIR WORK_DIR [SECONDS]
set -euo pipefail

if [ $# -lt 2 ]; then
  sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
FUZZ_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin_dir=$1
work_dir=$2
seconds=${3:-20}

targets=("$bin_dir"/fuzz_*)
if [ ! -x "${targets[0]}" ]; then
  echo "fuzz: no fuzz target in $bin_dir" >&2
  exit 1
fi
# Reports go to the log of the run (stderr), not to the sanitizer log files of the tests.
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for target in "${targets[@]}"; do
  name=$(basename "$target")
  seeds="$FUZZ_DIR/corpus/$name"
  if [ ! -d "$seeds" ]; then
    echo "fuzz: $name has no seed corpus $seeds" >&2
    exit 1
  fi
  out="$work_dir/$name"
  rm -rf "$out"
  mkdir -p "$out/corpus" "$out/artifacts"
  dict=()
  [ -f "$FUZZ_DIR/$name.dict" ] && dict=(-dict="$FUZZ_DIR/$name.dict")
  if ! "$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$out/artifacts/" "${dict[@]}" "$out/corpus" "$seeds" >"$out/log" 2>&1; then
    tail -n 60 "$out/log"
    echo "fuzz: $name found a problem (input in $out/artifacts/, log $out/log)" >&2
    exit 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/log")
  coverage=$(grep -E "^#[0-9]+.*(DONE|pulse|NEW|REDUCE)" "$out/log" | tail -n 1 |
    sed -n 's/.*\(cov: [0-9]* ft: [0-9]*\).*/\1/p')
  echo "fuzz: $name: ${runs:-?} inputs in ${seconds} s, ${coverage:-no coverage line}, no finding"
done
echo "fuzz: ${#targets[@]} targets passed"
