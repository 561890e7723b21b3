#!/bin/sh
# Runs every validation driver (bin/validate_*), then writes validation/REPORT.md.
# Exits non-zero when any driver fails or any quantity misses its pass band.
cd "$(dirname "$0")/.." || exit 2
mkdir -p validation/results validation/figures
# The solvers are single-threaded; CHOLMOD's supernodal kernels open OpenMP teams and OpenBLAS its own
# threads, which on a small shared box cost ~20 % in switching (bench_tfw, perf). OMP_NUM_THREADS does
# not cap those teams, OMP_THREAD_LIMIT does. A caller's own settings win.
: "${OMP_THREAD_LIMIT:=1}" "${OMP_NUM_THREADS:=1}" "${OPENBLAS_NUM_THREADS:=1}" "${OMP_WAIT_POLICY:=PASSIVE}"
export OMP_THREAD_LIMIT OMP_NUM_THREADS OPENBLAS_NUM_THREADS OMP_WAIT_POLICY
status=0
# The dynamic-simulator cases (validate_sim_*) run --quick here (a smoke version, its own result
# file <case>_quick.json); `sh validation/run_all.sh --long` (make validate-long) runs only them,
# in full, then rewrites the report. Their full runs take tens of CPU minutes.
long=0
[ "$1" = "--long" ] && long=1
# Cross-check drivers read other cases' result files, so they run last.
for src in $(ls validation/validate_*.c | grep -v crosscheck) $(ls validation/validate_*crosscheck*.c 2>/dev/null); do
    [ -f "$src" ] || continue
    name=$(basename "$src" .c)
    args=
    case "$name" in
        validate_sim_*) [ $long = 1 ] || args=--quick ;;
        *) [ $long = 1 ] && continue ;;
    esac
    echo "== $name $args"
    if ! "./bin/$name" $args; then
        echo "   $name: FAILED (exit $?)"
        status=1
    fi
done
./bin/wrinkle-report validation/results -o validation/REPORT.md || status=1
exit $status
