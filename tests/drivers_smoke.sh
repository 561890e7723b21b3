#!/bin/sh
# `make driver-check`: the command-line contract of every bin/wrinkle-* driver.
#   1. --help (and -h) exit 0 and print a usage text on stdout.
#   2. Bad input — an unknown option, a missing input file, a malformed input — exits non-zero with
#      exactly ONE line on stderr (the reason) and nothing on stdout.
#   3. Outputs are atomic: traced with strace, no final output file is ever opened for writing
#      directly (only temporaries, which are renamed over it); no temporaries are left behind; a
#      failing run leaves the outputs of an earlier good run byte-identical; a run killed part-way
#      leaves every output either absent or whole (identical to a complete run).
# Drivers are run from a scratch working directory (so default output paths never land in the tree).
# Checks 1-2 run for every driver found, also ones this script does not know yet; check 3 needs a
# known invocation and strace (skipped with a note when ptrace is not permitted).
root=$(cd "$(dirname "$0")/.." && pwd) || exit 2
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0; note=""
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "driver-check FAIL $*"; }
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
STRACE=""
if command -v strace >/dev/null 2>&1 && strace -f -qq -o /dev/null true 2>/dev/null; then STRACE=strace; fi

# expect_fail NAME DRIVER ARGS... : non-zero exit, one stderr line, empty stdout
expect_fail() {
    name=$1; shift
    (cd "$tmp/cwd" && "$@") >"$tmp/out" 2>"$tmp/err" </dev/null
    rc=$?
    n=$(grep -c . "$tmp/err")
    if [ $rc = 0 ]; then bad "$name: exit 0 on bad input"
    elif [ $rc -ge 126 ]; then bad "$name: exit $rc (crash or signal)"; head -n 3 "$tmp/err"
    elif [ "$n" != 1 ]; then bad "$name: $n lines on stderr, want 1"; head -n 5 "$tmp/err"
    elif [ -s "$tmp/out" ]; then bad "$name: output on stdout with an error"
    else ok; fi
}

# atomic NAME OUTFILES... -- DRIVER ARGS... : trace a good run, then check temporaries, a failing
# rerun and a killed rerun. OUTFILES are absolute paths the run must produce.
atomic() {
    name=$1; shift
    outs=""
    while [ "$1" != "--" ]; do outs="$outs $1"; shift; done
    shift
    if [ -z "$STRACE" ]; then note="$note $name(no strace)"; return; fi
    (cd "$tmp/cwd" && strace -f -qq -e trace=openat,open,creat -o "$tmp/trace" "$@") >/dev/null 2>"$tmp/err" </dev/null
    rc=$?
    [ $rc = 0 ] || { bad "$name: good run exited $rc"; head -n 3 "$tmp/err"; return; }
    for o in $outs; do
        [ -f "$o" ] || { bad "$name: $o not written"; continue; }
        if grep -E "open(at)?\(.*\"$o\", [^)]*(O_WRONLY|O_RDWR)" "$tmp/trace" >/dev/null ||
           grep -E "creat\(\"$o\"" "$tmp/trace" >/dev/null; then
            bad "$name: $o opened for writing in place (not temp + rename)"
        else ok; fi
        d=$(dirname "$o")
        if ls -a "$d" | grep -E 'wrtmp|^\.wrinkle-' >/dev/null; then bad "$name: temporaries left in $d"; ls -a "$d"; else ok; fi
    done
    mkdir -p "$tmp/good"; for o in $outs; do cp "$o" "$tmp/good/$(echo "$o" | tr / _)"; done
    # killed part-way: every output absent or whole. Several kill delays, the run restarted clean.
    for delay in 0.02 0.1 0.3; do
        for o in $outs; do rm -f "$o"; done
        (cd "$tmp/cwd" && exec "$@") >/dev/null 2>&1 </dev/null &
        pid=$!
        sleep $delay; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
        for o in $outs; do
            [ -f "$o" ] || continue
            case "$o" in
            *.json) # carries timings, so a complete rerun differs: it must still parse whole
                python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$o" 2>/dev/null ||
                    bad "$name: killed after ${delay}s left a partial $o" ;;
            *)  cmp -s "$o" "$tmp/good/$(echo "$o" | tr / _)" ||
                    bad "$name: killed after ${delay}s left a partial/different $o" ;;
            esac
        done
    done
    ok
    # restore the good outputs, then a failing run must not touch them
    for o in $outs; do cp "$tmp/good/$(echo "$o" | tr / _)" "$o"; done
    rm -rf "$tmp/good"
}

# keep_on_failure NAME OUTFILES... -- DRIVER ARGS... : outputs exist; a failing run leaves them alone
keep_on_failure() {
    name=$1; shift
    outs=""
    while [ "$1" != "--" ]; do outs="$outs $1"; shift; done
    shift
    for o in $outs; do [ -f "$o" ] && cp "$o" "$o.before"; done
    (cd "$tmp/cwd" && "$@") >/dev/null 2>&1 </dev/null && bad "$name: the failing run succeeded"
    for o in $outs; do
        if [ -f "$o.before" ]; then
            if cmp -s "$o" "$o.before"; then ok; else bad "$name: failing run changed $o"; fi
            rm -f "$o.before"
        fi
    done
}

mkdir -p "$tmp/cwd"
found=0
for d in "$root"/bin/wrinkle-*; do
    [ -x "$d" ] || continue
    found=$((found + 1))
    n=$(basename "$d")
    for h in --help -h; do
        if (cd "$tmp/cwd" && "$d" $h) >"$tmp/out" 2>"$tmp/err" </dev/null && grep -qi usage "$tmp/out"; then ok
        else bad "$n $h: non-zero exit or no usage text on stdout"; fi
    done
    expect_fail "$n unknown option" "$d" --definitely-not-an-option
done
[ $found -gt 0 ] || { echo "driver-check: no drivers in bin/ (run make all)"; exit 2; }

B=$root/bin
if [ -x "$B/wrinkle-resolution" ]; then
    expect_fail "wrinkle-resolution negative B" "$B/wrinkle-resolution" --bending -1 --young 1e6
    expect_fail "wrinkle-resolution non-number" "$B/wrinkle-resolution" --bending 2e-6x --young 1e6
    expect_fail "wrinkle-resolution missing csv" "$B/wrinkle-resolution" --csv "$tmp/none.csv"
    printf 'name,B,E\ngreen,abc,2e6\n' > "$tmp/bad.csv"
    expect_fail "wrinkle-resolution malformed csv" "$B/wrinkle-resolution" --csv "$tmp/bad.csv"
    # good rows before a bad one: the whole batch is checked first, so nothing reaches stdout
    printf 'name,B,E\ngreen,2.6e-6,2e6\nwool,1e-5,1e6\nbad,-1,2e6\n' > "$tmp/late.csv"
    expect_fail "wrinkle-resolution bad csv row after good rows" "$B/wrinkle-resolution" --csv "$tmp/late.csv"
    printf 'name,B,E\ngreen,2.6e-6,2e6\nwool,1e-5,1e6\nsilk,1e-6\n' > "$tmp/late.csv"
    expect_fail "wrinkle-resolution short csv row after good rows" "$B/wrinkle-resolution" --csv "$tmp/late.csv"
    # and a good batch prints the header plus one row per fabric
    printf 'green,2.6e-6,2e6\nwool,1e-5,1e6\n' > "$tmp/good.csv"
    if (cd "$tmp/cwd" && "$B/wrinkle-resolution" --csv "$tmp/good.csv") >"$tmp/out" 2>"$tmp/err" </dev/null &&
       [ "$(grep -c . "$tmp/out")" = 3 ] && [ ! -s "$tmp/err" ]; then ok
    else bad "wrinkle-resolution good csv: want header + 2 rows and a silent stderr"; cat "$tmp/err"; fi
fi
if [ -x "$B/wrinkle-report" ] && [ -x "$B/validate_table1" ]; then
    mkdir -p "$tmp/results"
    WRINKLE_RESULTS_DIR=$tmp/results "$B/validate_table1" >/dev/null 2>&1
    expect_fail "wrinkle-report missing dir" "$B/wrinkle-report" "$tmp/none" -o "$tmp/R.md"
    atomic wrinkle-report "$tmp/REPORT.md" -- "$B/wrinkle-report" "$tmp/results" -o "$tmp/REPORT.md"
    printf '{"case": 3, "rows": [' > "$tmp/results/zz_broken.json"
    keep_on_failure "wrinkle-report broken json" "$tmp/REPORT.md" -- "$B/wrinkle-report" "$tmp/results" -o "$tmp/REPORT.md"
    expect_fail "wrinkle-report broken json" "$B/wrinkle-report" "$tmp/results" -o "$tmp/REPORT2.md"
    rm -f "$tmp/results/zz_broken.json"
fi
if [ -x "$B/wrinkle-triangulate" ]; then
    mkdir -p "$tmp/tri"
    printf '4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n' > "$tmp/tri/sq.poly"
    expect_fail "wrinkle-triangulate missing file" "$B/wrinkle-triangulate" -p "$tmp/none.poly"
    printf '4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n2 0\n1 1 9\n2 2 3\n0\n' > "$tmp/tri/badseg.poly"
    expect_fail "wrinkle-triangulate bad segment" "$B/wrinkle-triangulate" -pQ "$tmp/tri/badseg.poly"
    atomic wrinkle-triangulate "$tmp/tri/sq.1.node" "$tmp/tri/sq.1.ele" "$tmp/tri/sq.1.poly" -- \
        "$B/wrinkle-triangulate" -pq30 -a0.01 -Q "$tmp/tri/sq.poly"
fi
if [ -x "$B/wrinkle-mesh" ]; then
    expect_fail "wrinkle-mesh missing pattern" "$B/wrinkle-mesh" "$tmp/none.json" -o "$tmp/m0"
    printf '{"panels": [' > "$tmp/broken.json"
    expect_fail "wrinkle-mesh malformed pattern" "$B/wrinkle-mesh" "$tmp/broken.json" -o "$tmp/m0"
    if command -v gnuplot >/dev/null 2>&1; then png="$tmp/mesh/sizing.png"; nopng=""; else png=""; nopng=--no-png; fi
    atomic wrinkle-mesh "$tmp/mesh/mesh.obj" "$tmp/mesh/mesh.ply" "$tmp/mesh/summary.json" $png -- \
        "$B/wrinkle-mesh" -o "$tmp/mesh" $nopng -q --seed 1
    keep_on_failure "wrinkle-mesh malformed pattern" "$tmp/mesh/mesh.obj" "$tmp/mesh/summary.json" -- \
        "$B/wrinkle-mesh" "$tmp/broken.json" -o "$tmp/mesh"
fi
if [ -x "$B/wrinkle-statics" ]; then
    expect_fail "wrinkle-statics missing scene" "$B/wrinkle-statics" "$tmp/none.json" -o "$tmp/s0"
    printf '{"mesh": {"type": "rectangle"}, "material": {"young": -1}}' > "$tmp/badscene.json"
    expect_fail "wrinkle-statics invalid scene" "$B/wrinkle-statics" "$tmp/badscene.json" -o "$tmp/s0"
    atomic wrinkle-statics "$tmp/st/deformed.obj" "$tmp/st/fields.ply" "$tmp/st/summary.json" -- \
        "$B/wrinkle-statics" "$root/examples/scenes/cantilever.json" -o "$tmp/st" --quiet --load-steps 2
    keep_on_failure "wrinkle-statics invalid scene" "$tmp/st/deformed.obj" "$tmp/st/summary.json" -- \
        "$B/wrinkle-statics" "$tmp/badscene.json" -o "$tmp/st"
fi
if [ -x "$B/wrinkle-tfw" ]; then
    expect_fail "wrinkle-tfw missing scene" "$B/wrinkle-tfw" "$tmp/none.json" -o "$tmp/t0"
    printf '{"mesh": {"type": "rectangle"}, "material": {"young": -1}}' > "$tmp/badscene.json"
    expect_fail "wrinkle-tfw invalid scene" "$B/wrinkle-tfw" "$tmp/badscene.json" -o "$tmp/t0"
    expect_fail "wrinkle-tfw bad --levels" "$B/wrinkle-tfw" "$root/examples/scenes/tfw_stretched_sheet.json" \
        -o "$tmp/t0" --levels 9
    expect_fail "wrinkle-tfw bad --kappa" "$B/wrinkle-tfw" "$root/examples/scenes/tfw_stretched_sheet.json" \
        -o "$tmp/t0" --kappa bogus
    # a slack base (pushed in from one end, free sides: no tension anywhere) is refused with the reason
    cat > "$tmp/slack.json" <<'JSON'
{"name": "tfw_slack", "mesh": {"type": "rectangle", "width": 0.25, "height": 0.1, "nx": 10, "ny": 5},
 "material": {"young": 1.0e6, "poisson": 0.5, "thickness": 1.0e-4},
 "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
  {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]}, "stretch": [0.9, 1, 1]}],
 "solver": {"load_steps": 2, "hessian": "projected"}}
JSON
    expect_fail "wrinkle-tfw slack base" "$B/wrinkle-tfw" "$tmp/slack.json" -o "$tmp/t0" --quiet
    cat > "$tmp/tfw.json" <<'JSON'
{"name": "tfw_small", "mesh": {"type": "rectangle", "width": 0.25, "height": 0.1, "nx": 10, "ny": 5},
 "material": {"young": 1.0e6, "poisson": 0.5, "thickness": 1.0e-4},
 "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
  {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]}, "stretch": [1.1, 1, 1]}],
 "solver": {"load_steps": 2, "hessian": "projected"}}
JSON
    atomic wrinkle-tfw "$tmp/tfw/base.obj" "$tmp/tfw/wrinkled.obj" "$tmp/tfw/fields.ply" "$tmp/tfw/summary.json" -- \
        "$B/wrinkle-tfw" "$tmp/tfw.json" -o "$tmp/tfw" --quiet --levels 1
    keep_on_failure "wrinkle-tfw invalid scene" "$tmp/tfw/wrinkled.obj" "$tmp/tfw/summary.json" -- \
        "$B/wrinkle-tfw" "$tmp/badscene.json" -o "$tmp/tfw"
fi
echo "driver-check: $pass passed, $fail failed, $found drivers${note:+; skipped:$note}"
[ $fail = 0 ]
