#!/bin/sh
# `make memcheck`: every driver's smoke invocation under valgrind memcheck. Fails on any memory
# error or any definite/indirect leak (still-reachable and possibly-lost blocks — e.g. OpenBLAS
# thread buffers inside CHOLMOD — are not counted). A driver's own exit status is checked against
# the expected one; valgrind's verdict uses the distinct exit code 99.
# Drivers that do not exist yet are skipped with a note, so this grows with bin/.
cd "$(dirname "$0")/.." || exit 2
command -v valgrind >/dev/null 2>&1 || { echo "memcheck: valgrind not installed (apt-get install valgrind)" >&2; exit 2; }
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
VG="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect --track-origins=yes"
pass=0; fail=0; skip=0

# run EXPECTED_EXIT NAME -- command...  (stdin from /dev/null unless redirected by the caller)
run() {
    want=$1; name=$2; shift 3
    log=$tmp/$name.log
    start=$(date +%s)
    $VG "$@" >"$log" 2>&1
    rc=$?
    secs=$(( $(date +%s) - start ))
    if [ $rc = 99 ]; then
        fail=$((fail + 1)); echo "memcheck FAIL $name: valgrind reported errors or leaks (${secs}s)"; grep '^==' "$log" | head -n 30
    elif [ "$rc" != "$want" ]; then
        fail=$((fail + 1)); echo "memcheck FAIL $name: exit $rc, expected $want (${secs}s)"; tail -n 5 "$log"
    else
        pass=$((pass + 1)); echo "memcheck ok   $name (exit $rc, ${secs}s)"
    fi
}
have() { [ -x "bin/$1" ] || { skip=$((skip + 1)); echo "memcheck skip $1 (not built yet)"; return 1; }; }

if have wrinkle-resolution; then
    run 0 resolution_BE -- bin/wrinkle-resolution --bending 2e-6 --young 1e6
    run 0 resolution_json -- bin/wrinkle-resolution --thickness 1e-4 --poisson 0.3 --young 1e6 --json
    run 0 resolution_ortho -- bin/wrinkle-resolution --warp-bending 2e-6 --warp-young 1e6 --weft-bending 1e-6 --weft-young 5e5
    run 0 resolution_calibrate -- bin/wrinkle-resolution --calibrate
    run 0 resolution_inverse -- bin/wrinkle-resolution --inverse-mm 10
    printf 'name,B,E\ngreen,2.6e-6,2.0e6\ndenim,1e-5,5e6\n' > "$tmp/fabrics.csv"
    run 0 resolution_csv -- bin/wrinkle-resolution --csv "$tmp/fabrics.csv"
    run 2 resolution_bad -- bin/wrinkle-resolution --bending -1 --young 1e6
    printf 'name,B,E\ngreen,2.6e-6,2e6\nwool,1e-5,1e6\nbad,-1,2e6\n' > "$tmp/late.csv"
    run 2 resolution_csv_bad_row -- bin/wrinkle-resolution --csv "$tmp/late.csv"   # buffered rows freed
fi
if have wrinkle-report && [ -x bin/validate_table1 ]; then
    mkdir -p "$tmp/results"
    WRINKLE_RESULTS_DIR=$tmp/results bin/validate_table1 >/dev/null 2>&1
    run 0 report -- bin/wrinkle-report "$tmp/results" -o "$tmp/REPORT.md"
    run 2 report_missing_dir -- bin/wrinkle-report "$tmp/no-such-dir" -o "$tmp/R2.md"
fi
if have wrinkle-triangulate; then
    # bin/wrinkle-triangulate is linked statically (Makefile TRI_LDFLAGS), which valgrind cannot
    # check; its dynamically linked twin from the same objects is checked instead
    tri=bin/wrinkle-triangulate
    [ -x build/dyn/wrinkle-triangulate ] && tri=build/dyn/wrinkle-triangulate
    cat > "$tmp/sq.poly" <<'POLY'
8 2 0 1
1 0 0 1
2 4 0 1
3 4 4 1
4 0 4 1
5 1 1 2
6 3 1 2
7 3 3 2
8 1 3 2
8 1
1 1 2 1
2 2 3 1
3 3 4 1
4 4 1 1
5 5 6 2
6 6 7 2
7 7 8 2
8 8 5 2
1
1 2 2
POLY
    run 0 triangulate_pq -- "$tri" -pq30 -a0.05 -Q "$tmp/sq.poly"
    printf '3 2 0 0\n1 0 0\n2 1 0\n' > "$tmp/bad.node"
    run 2 triangulate_bad -- "$tri" -Q "$tmp/bad.node"
fi
if have wrinkle-mesh; then
    run 0 mesh_builtin -- bin/wrinkle-mesh -o "$tmp/mesh" --no-png -q
    run 0 mesh_seams_sew -- bin/wrinkle-mesh tests/fuzz/corpus/fuzz_pattern/two_panels_seam.json -o "$tmp/mesh3" \
        --no-png -q --sew
    run 2 mesh_bad -- bin/wrinkle-mesh "$tmp/no-such.json" -o "$tmp/mesh2"
fi
if have wrinkle-statics; then
    run 0 statics_cantilever -- bin/wrinkle-statics examples/scenes/cantilever.json -o "$tmp/cant" --quiet --load-steps 2
    run 2 statics_bad -- bin/wrinkle-statics "$tmp/no-such.json" -o "$tmp/st2" --quiet
fi
if have wrinkle-tfw; then
    # a small stretched sheet (the examples/scenes/tfw_stretched_sheet.json set-up on a 10 x 5 grid)
    cat > "$tmp/tfw.json" <<'JSON'
{"name": "tfw_small", "mesh": {"type": "rectangle", "width": 0.25, "height": 0.1, "nx": 10, "ny": 5},
 "material": {"young": 1.0e6, "poisson": 0.5, "thickness": 1.0e-4},
 "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
  {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]}, "stretch": [1.1, 1, 1]}],
 "solver": {"load_steps": 2, "hessian": "projected"},
 "probes": [{"name": "mid", "from": [0.125, 0.0], "to": [0.125, 0.1], "samples": 64}]}
JSON
    run 0 tfw_small -- bin/wrinkle-tfw "$tmp/tfw.json" -o "$tmp/tfw" --quiet --levels 1 --png
    run 2 tfw_bad -- bin/wrinkle-tfw "$tmp/no-such.json" -o "$tmp/tfw2" --quiet
fi
echo "memcheck: $pass passed, $fail failed, $skip skipped"
[ $fail = 0 ]
