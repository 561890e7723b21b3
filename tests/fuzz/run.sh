#!/bin/sh
# Runs libFuzzer harnesses for a bounded time each and fails on any finding (crash, sanitizer
# report, leak, timeout, out-of-memory).   usage: tests/fuzz/run.sh SECONDS harness...
# New interesting inputs go to build/fuzz/corpus/<harness>/ (the committed seeds in
# tests/fuzz/corpus/<harness>/ are read, never written); a finding is saved as
# build/fuzz/artifacts/<harness>/crash-* (or timeout-*, oom-*, leak-*) and its reproducer line printed.
cd "$(dirname "$0")/../.." || exit 1
secs=${1:?seconds}; shift
fail=0; total_execs=0
for h in "$@"; do
    bin=build/fuzz/$h
    [ -x "$bin" ] || { echo "fuzz: $bin missing" >&2; fail=1; continue; }
    mkdir -p "build/fuzz/corpus/$h" "build/fuzz/artifacts/$h" "tests/fuzz/corpus/$h"
    log=build/fuzz/$h.log
    # -timeout: one input taking > 20 s is a hang; -rss_limit_mb: runaway allocation is a finding.
    "$bin" -max_total_time="$secs" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="build/fuzz/artifacts/$h/" \
        "build/fuzz/corpus/$h" "tests/fuzz/corpus/$h" >"$log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1)
    total_execs=$((total_execs + ${execs:-0}))
    if [ $rc -ne 0 ]; then
        fail=1
        echo "fuzz $h: FINDING after ${execs:-?} runs (exit $rc); log $log"
        grep -m 3 -E 'ERROR|SUMMARY|Test unit written|fuzz_' "$log" | sed 's/^/    /'
    else
        echo "fuzz $h: ok, $secs s, ${execs:-?} runs, $cov"
    fi
done
echo "fuzz: $total_execs executions in total"
exit $fail
