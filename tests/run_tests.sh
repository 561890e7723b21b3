#!/bin/sh
# Runs the Criterion unit-test binary (ASan+UBSan build). Criterion's own closing
# "Synthesis" line is what CI reads.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
exec ./build/test/wrinkle_tests --jobs 2 "$@"
