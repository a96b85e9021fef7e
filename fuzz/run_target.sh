#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# One bounded libFuzzer run of one target (ctest -L fuzz, scripts/fuzz):
#   run_target.sh FUZZER NAME SOURCE_DIR BUILD_DIR SECONDS
# Starts from the committed seeds (fuzz/corpus/NAME, read only) and a working corpus in
# BUILD_DIR/corpus/NAME (kept between runs, never committed), with fuzz/NAME.dict.
# Any finding (crash, sanitizer report, wrong exception type, broken invariant, hang over
# 10 s, more than 2 GB) fails the run and prints the reproducer's path.
set -uo pipefail
fuzzer="$1" name="$2" src="$3" build="$4" secs="$5"
work="$build/corpus/$name" art="$build/artifacts/$name"
mkdir -p "$work" "$art"
log="$build/logs/$name.log"
mkdir -p "$(dirname "$log")"
before=$(ls "$art" | wc -l)
dict=()
[ -f "$src/$name.dict" ] && dict=("-dict=$src/$name.dict")
# -max_len: the seeds are small; 16 KiB leaves room for long lines and many of them.
"$fuzzer" "$work" "$src/corpus/$name" "${dict[@]}" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
  -max_len=16384 -print_final_stats=1 -artifact_prefix="$art/" >"$log" 2>&1
rc=$?
grep -E "^#[0-9]+[[:space:]]+DONE|^stat::number_of_executed_units|^stat::peak_rss_mb" "$log" | sed "s/^/fuzz.$name: /"
after=$(ls "$art" | wc -l)
if [ $rc -ne 0 ] || [ "$after" -ne "$before" ]; then
  echo "fuzz.$name: FINDING (exit $rc); the log is $log" >&2
  grep -E "==FINDING==|ERROR: |SUMMARY: |runtime error|Test unit written to" "$log" | head -20 >&2
  for f in $(ls -t "$art" | head -n $((after - before > 0 ? after - before : 1))); do
    echo "fuzz.$name: reproducer: $art/$f   (replay: $fuzzer $art/$f)" >&2
  done
  exit 1
fi
