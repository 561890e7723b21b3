#!/bin/sh
# `make driver-check`: the command-line contract of every bin/wrinkle-* driver.
#   1. --help (and -h) exit 0 and print a usage text on stdout.
#   2. Bad input — an unknown option, a missing input file, a malformed input — exits 2 (every
#      driver: cli.h's WR_CLI_EXIT_USAGE) with exactly ONE line on stderr (the reason) and nothing on
#      stdout. An output path that is an input file, or a FIFO/device, is bad input too.
#   4. Behaviour shared through drivers/lib/cli.c: a failed write to standard output (/dev/full)
#      gives a message and exit 3, and so does a failed file write (ulimit -f); -o DIR naming an
#      existing file is bad input (exit 2); progress on a redirected stderr is plain lines (no '\r'); no
#      'inf'/'nan' printed; plausibility warnings for the usual unit slips (metres in a millimetre
#      pattern, --thickness in mm, a resolution outside 2.5-50 mm, strains over 100 %; plausible.c).
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
    elif [ $rc != 2 ]; then bad "$name: exit $rc on bad input, want 2"; head -n 3 "$tmp/err"
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

# The validation drivers rewrite their result files when they run, so --help must print usage and
# write nothing, and an unknown argument must be refused (exit 2, one line), not ignored into a run.
mkdir -p "$tmp/vres"
for d in "$root"/bin/validate_*; do
    [ -x "$d" ] || continue
    n=$(basename "$d")
    if (cd "$tmp/cwd" && WRINKLE_RESULTS_DIR="$tmp/vres" "$d" --help) >"$tmp/out" 2>"$tmp/err" </dev/null &&
       grep -qi usage "$tmp/out" && [ -z "$(ls -A "$tmp/vres")" ]; then ok
    else bad "$n --help: non-zero exit, no usage text, or a result written"; rm -rf "$tmp/vres"/*; fi
    expect_fail "$n unknown option" env WRINKLE_RESULTS_DIR="$tmp/vres" "$d" --definitely-not-an-option
    [ -z "$(ls -A "$tmp/vres")" ] && ok || { bad "$n unknown option: a result written"; rm -rf "$tmp/vres"/*; }
done
# ... and a malformed or out-of-range value is refused the same way, never read as 0 into a run
# (issue 18: atoi/atof made "--seeds x" a run that rewrote the result file). --quick first, and a
# timeout, so that a value wrongly accepted costs a smoke run, not a full validation.
# val_bad VALIDATOR OPTION VALUE : exit 2, one line that names the option (a run that fails for
# another reason, e.g. its inputs are not found from the scratch directory, is no pass), nothing on
# stdout, no result file
val_bad() {
    vd=$root/bin/$1; vn="$*"; shift
    [ -x "$vd" ] || return 0
    expect_fail "$vn" timeout 60 env WRINKLE_RESULTS_DIR="$tmp/vres" "$vd" --quick "$@"
    grep -q -e "$1" "$tmp/err" && ok || { bad "$vn: the error does not name $1"; head -n 2 "$tmp/err"; }
    [ -z "$(ls -A "$tmp/vres")" ] && ok || { bad "$vn: a result written"; rm -rf "$tmp/vres"/*; }
}
val_bad validate_curtain --res x
val_bad validate_curtain --waves 1.5
val_bad validate_sim_curtain --seconds -1
val_bad validate_sim_curtain --case x
val_bad validate_sim_garments --seconds 0
val_bad validate_sim_garments --ref x
val_bad validate_sim_shirring --seeds x
val_bad validate_sim_shirring --seeds 0
val_bad validate_sim_shirring --seed 1.5
val_bad validate_sim_stretch --res-mask 8
val_bad validate_sim_stretch --sheet x
val_bad validate_statics_stability --grid 0.5
val_bad validate_statics_stability --grid x
# on/off flags that pick a long mode (--stvk-loop, issue 15): --help lists the flag, and the flag with
# an unknown argument is still refused (exit 2, one line) before any run, nothing written
val_flag() {
    vd=$root/bin/$1
    [ -x "$vd" ] || return 0
    (cd "$tmp/cwd" && "$vd" --help) 2>/dev/null </dev/null | grep -q -e "$2" && ok || bad "$1 --help does not list $2"
    expect_fail "$1 $2 with an unknown argument" env WRINKLE_RESULTS_DIR="$tmp/vres" "$vd" "$2" --definitely-not-an-option
    [ -z "$(ls -A "$tmp/vres")" ] && ok || { bad "$1 $2 with an unknown argument: a result written"; rm -rf "$tmp/vres"/*; }
}
val_flag validate_tfw_sheared_rectangle --stvk-loop
val_flag validate_tfw_twisted_cylinder --stvk-loop

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
    # Triangle's other outputs, refinement of a previous mesh (-r), and what is refused
    atomic wrinkle-triangulate-evn "$tmp/tri/sq.1.edge" "$tmp/tri/sq.1.neigh" "$tmp/tri/sq.1.v.node" \
        "$tmp/tri/sq.1.v.edge" -- "$B/wrinkle-triangulate" -pq30a0.01evno2Q "$tmp/tri/sq.poly"
    atomic wrinkle-triangulate-r "$tmp/tri/sq.2.node" "$tmp/tri/sq.2.ele" -- \
        "$B/wrinkle-triangulate" -rq30a0.002Q "$tmp/tri/sq.1"
    expect_fail "wrinkle-triangulate -u (an API callback)" "$B/wrinkle-triangulate" -puQ "$tmp/tri/sq.poly"
    expect_fail "wrinkle-triangulate -I with -r" "$B/wrinkle-triangulate" -rIQ "$tmp/tri/sq.1"
    cp "$tmp/tri/sq.1.node" "$tmp/tri/bad.node"; printf '2 3 0\n1 1 2 3\n2 1 3 99999\n' > "$tmp/tri/bad.ele"
    expect_fail "wrinkle-triangulate bad .ele" "$B/wrinkle-triangulate" -rQ "$tmp/tri/bad.ele"
fi
if [ -x "$B/wrinkle-mesh" ]; then
    expect_fail "wrinkle-mesh missing pattern" "$B/wrinkle-mesh" "$tmp/none.json" -o "$tmp/m0"
    printf '{"panels": [' > "$tmp/broken.json"
    expect_fail "wrinkle-mesh malformed pattern" "$B/wrinkle-mesh" "$tmp/broken.json" -o "$tmp/m0"
    for c in -2 1e999; do # a gathered line's stitch length (garment.h ON GATHERING): negative / not finite
        printf '{"fabrics": {"f": {"B": 2e-6, "E": 1e6}}, "panels": [{"name": "a", "fabric": "f", "outer": [[0, 0], [100, 0], [100, 100], [0, 100]]}], "shirring": [{"panel": "a", "line": [[10, 50], [90, 50]], "rho": 0.6, "stitch_length": %s}]}' "$c" > "$tmp/stitch.json"
        expect_fail "wrinkle-mesh stitch_length $c" "$B/wrinkle-mesh" "$tmp/stitch.json" -o "$tmp/m0"
        if grep -q 'shirring\[0\]\.stitch_length' "$tmp/err"; then ok; else bad "wrinkle-mesh stitch_length $c: no JSON path in the error"; cat "$tmp/err"; fi
    done
    if command -v gnuplot >/dev/null 2>&1; then png="$tmp/mesh/sizing.png"; nopng=""; else png=""; nopng=--no-png; fi
    atomic wrinkle-mesh "$tmp/mesh/mesh.obj" "$tmp/mesh/mesh.ply" "$tmp/mesh/summary.json" $png -- \
        "$B/wrinkle-mesh" -o "$tmp/mesh" $nopng -q --seed 1
    keep_on_failure "wrinkle-mesh malformed pattern" "$tmp/mesh/mesh.obj" "$tmp/mesh/summary.json" -- \
        "$B/wrinkle-mesh" "$tmp/broken.json" -o "$tmp/mesh"
    # issue 17, bounded time: a 10 km panel at its fabric's 6 mm and a 1 um size on a 1 m panel end
    # within 5 s with a budget error naming the CLI option
    sq='"fabrics":{"g":{"B":2.6e-6,"E":2e6}},"panels":[{"name":"p","fabric":"g","outer":[[0,0],[S,0],[S,S],[0,S]]}]}'
    echo "{\"units\":\"mm\",$sq" | sed 's/S/1e7/g' > "$tmp/km10.json"
    echo "{\"units\":\"mm\",$sq" | sed 's/S/1000/g' > "$tmp/m1.json"
    for c in "km10.json" "m1.json --uniform 0.001"; do
        set -- $c
        expect_fail "wrinkle-mesh budget ($c)" timeout 5 "$B/wrinkle-mesh" "$tmp/$1" -o "$tmp/mbud" $2 $3
        if grep -q -- "--max-vertices" "$tmp/err"; then ok; else bad "wrinkle-mesh budget ($c): no --max-vertices in the error"; fi
    done
    # per-panel progress on stderr (plain lines when redirected), none with -q
    (cd "$tmp/cwd" && "$B/wrinkle-mesh" -o "$tmp/mprog" --no-png) >/dev/null 2>"$tmp/err" </dev/null
    if grep -q "panel 1/1 'square' meshed" "$tmp/err"; then ok; else bad "wrinkle-mesh: no per-panel progress"; cat "$tmp/err"; fi
    (cd "$tmp/cwd" && "$B/wrinkle-mesh" -o "$tmp/mprog" --no-png -q) >/dev/null 2>"$tmp/err" </dev/null
    if [ -s "$tmp/err" ]; then bad "wrinkle-mesh -q: stderr not empty"; cat "$tmp/err"; else ok; fi
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
    expect_fail "wrinkle-tfw bad --wset" "$B/wrinkle-tfw" "$root/examples/scenes/tfw_stretched_sheet.json" \
        -o "$tmp/t0" --wset bogus
    expect_fail "wrinkle-tfw bad --start" "$B/wrinkle-tfw" "$root/examples/scenes/tfw_stretched_sheet.json" \
        -o "$tmp/t0" --start bogus
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
    # $.probes[i].panel (docs/scene-format.md): two panels over the same rest rectangle (front at z = 0,
    # back at z = 0.05, own vertices); probes with a name / an id selector are measured on the wrinkled
    # surface; an unknown name and a probe without a selector on the overlapping panels are refused
    # with one line naming the JSON path
    python3 -c 'import sys
nx, ny, L = 10, 4, []
for p in range(2):
    for j in range(ny + 1):
        for i in range(nx + 1): L.append("v %g %g %g\nvt %g %g" % (0.025 * i, 0.025 * j, 0.05 * p, 0.025 * i, 0.025 * j))
n = (nx + 1) * (ny + 1)
for p in range(2):
    L.append("g " + ("front", "back")[p])
    for j in range(ny):
        for i in range(nx):
            a = 1 + n * p + (nx + 1) * j + i; b, c, e = a + 1, a + nx + 2, a + nx + 1
            L.append("f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d" % (a, a, b, b, c, c, a, a, c, c, e, e))
open(sys.argv[1], "w").write("\n".join(L) + "\n")' "$tmp/two_panels.obj"
    cat > "$tmp/tfwpanel.json" <<'JSON'
{"name": "tfw_two_panels", "mesh": {"type": "obj", "path": "two_panels.obj"},
 "material": {"young": 1.0e6, "poisson": 0.5, "thickness": 1.0e-4},
 "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
  {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]}, "stretch": [1.1, 1, 1]}],
 "solver": {"load_steps": 2, "hessian": "projected"},
 "probes": [{"name": "front", "from": [0.02, 0.05], "to": [0.23, 0.05], "samples": 64, "panel": "front"},
            {"name": "back", "from": [0.02, 0.05], "to": [0.23, 0.05], "samples": 64, "panel": 1}]}
JSON
    if "$B/wrinkle-tfw" "$tmp/tfwpanel.json" -o "$tmp/tfwpanel" --quiet --levels 1 >/dev/null 2>"$tmp/err" </dev/null &&
        python3 -c 'import json, sys; p = json.load(open(sys.argv[1]))["probes"]
sys.exit(not (len(p) == 2 and all("count" in q and "error" not in q for q in p)))' "$tmp/tfwpanel/summary.json"; then ok
    else bad "wrinkle-tfw probe panel: failed or a probe without a count in summary.json"; head -n 3 "$tmp/err"; fi
    for c in 'unknown|"panel": "side"|$.probes[0].panel: no panel named "side"' \
             'none|"samples": 64|$.probes[0]: sample 0 at rest (0.02, 0.05) m lies in panels 0 and 1'; do
        n=${c%%|*}; r=${c#*|}; r=${r%%|*}; want=${c##*|}
        sed "s/\"samples\": 64, \"panel\": \"front\"/$r/" "$tmp/tfwpanel.json" > "$tmp/tfwpanel_$n.json"
        expect_fail "wrinkle-tfw probe panel $n" "$B/wrinkle-tfw" "$tmp/tfwpanel_$n.json" -o "$tmp/t0" --quiet
        grep -qF "$want" "$tmp/err" && ok || { bad "wrinkle-tfw probe panel $n: stderr does not name $want"; cat "$tmp/err"; }
    done
    # $.mesh.weld + probes on a welded sewn base (wrinkle_field.h ON SEWN BASES): the stretched sheet as
    # two panels (left, right) with the seam column x = 0.125 written twice and the charts overlapping
    # (right's u = x - 0.125); "weld": 0 sews them (60 -> 55 vertices, corner_rest), probes across the
    # wrinkles in each panel ("dir": "normal") are measured on the wrinkled surface; a negative
    # tolerance is one line naming $.mesh.weld
    python3 -c 'import sys
L, idx = [], {}
for p in range(2):
    for j in range(5):
        for i in range(6):
            x = 0.025 * (i + 5 * p); L.append("v %g %g 0\nvt %g %g" % (x, 0.025 * j, x - 0.125 * p, 0.025 * j)); idx[p, i, j] = len(idx) + 1
for p in range(2):
    L.append("g " + ("left", "right")[p])
    for j in range(4):
        for i in range(5):
            a, b, c, e = idx[p, i, j], idx[p, i + 1, j], idx[p, i + 1, j + 1], idx[p, i, j + 1]
            L.append("f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d" % (a, a, b, b, c, c, a, a, c, c, e, e))
open(sys.argv[1], "w").write("\n".join(L) + "\n")' "$tmp/sewn_parts.obj"
    cat > "$tmp/tfwsewn.json" <<'JSON'
{"name": "tfw_sewn", "mesh": {"type": "obj", "path": "sewn_parts.obj", "weld": 0},
 "material": {"young": 1.0e6, "poisson": 0.5, "thickness": 1.0e-4},
 "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
  {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]}, "stretch": [1.1, 1, 1]}],
 "solver": {"load_steps": 2, "hessian": "projected"},
 "probes": [{"name": "left", "from": [0.06, 0.005], "to": [0.06, 0.095], "samples": 64, "panel": "left", "dir": "normal"},
            {"name": "right", "from": [0.06, 0.005], "to": [0.06, 0.095], "samples": 64, "panel": "right", "dir": "normal"}]}
JSON
    if "$B/wrinkle-tfw" "$tmp/tfwsewn.json" -o "$tmp/tfwsewn" --quiet --levels 1 >/dev/null 2>"$tmp/err" </dev/null &&
        python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); p = s["probes"]
sys.exit(not (s["base_vertices"] == 55 and len(p) == 2 and all("count" in q and "error" not in q for q in p)))' "$tmp/tfwsewn/summary.json"; then ok
    else bad "wrinkle-tfw welded base: failed, not sewn, or a probe without a count in summary.json"; head -n 3 "$tmp/err"; fi
    sed 's/"weld": 0/"weld": -1e-3/' "$tmp/tfwsewn.json" > "$tmp/tfwsewn_neg.json"
    expect_fail "wrinkle-tfw negative mesh weld" "$B/wrinkle-tfw" "$tmp/tfwsewn_neg.json" -o "$tmp/t0" --quiet
    grep -qF '$.mesh.weld: must be >= 0' "$tmp/err" && ok || { bad "wrinkle-tfw mesh weld: stderr does not name the path"; cat "$tmp/err"; }
    # $.obstacles (statics.h ON MESH OBSTACLES): a sheet pinned 4 mm over the mannequin's head converges
    # and the summary reports the contact; a bad type, a missing and an unreadable OBJ path are refused
    # with one line naming the JSON path
    cat > "$tmp/tfwhead.json" <<'JSON'
{"name": "tfw_mannequin_head", "mesh": {"type": "rectangle", "width": 0.3, "height": 0.3, "nx": 8, "ny": 8},
 "material": {"young": 1e5, "poisson": 0.3, "thickness": 1e-3, "density": 200},
 "energy": {"membrane": "tft", "bending": "quadratic"}, "gravity": [0, 0, -9.81],
 "boundary": [{"name": "pin", "box": {"min": [0.14, 0.14, -0.01], "max": [0.16, 0.16, 0.01]}}],
 "obstacles": [{"type": "mannequin", "target_faces": 10000, "translate": [0.139, 0.161, -1.740]}],
 "contact": {"dhat": 2e-3}, "solver": {"load_steps": 1}}
JSON
    if (cd "$tmp/cwd" && "$B/wrinkle-tfw" "$tmp/tfwhead.json" -o "$tmp/tfwhead" --quiet --levels 0) >/dev/null 2>"$tmp/err" </dev/null &&
        python3 -c 'import json, sys; b = json.load(open(sys.argv[1]))["base"]
sys.exit(not (b["status"] == "WR_OK" and b["obstacles"] == 1 and 0 < b["min_obstacle_distance_m"] < 2e-3 and b["contact_vertices"] > 0))' \
            "$tmp/tfwhead/summary.json"; then ok
    else bad "wrinkle-tfw mannequin obstacle: failed, not converged or no contact in summary.json"; head -n 3 "$tmp/err"; fi
    for c in 'torus|"type": "torus"|$.obstacles[0].type' 'nopath|"type": "obj"|$.obstacles[0].path' \
             'unreadable|"type": "obj", "path": "missing.obj"|$.obstacles[0].path'; do
        n=${c%%|*}; r=${c#*|}; r=${r%%|*}; want=${c##*|}
        sed "s/\"type\": \"mannequin\", \"target_faces\": 10000/$r/" "$tmp/tfwhead.json" > "$tmp/tfwobs_$n.json"
        expect_fail "wrinkle-tfw obstacle $n" "$B/wrinkle-tfw" "$tmp/tfwobs_$n.json" -o "$tmp/t0" --quiet
        grep -qF "$want" "$tmp/err" && ok || { bad "wrinkle-tfw obstacle $n: stderr does not name $want"; cat "$tmp/err"; }
    done
fi
if [ -x "$B/wrinkle-sim" ]; then
    expect_fail "wrinkle-sim missing scene" "$B/wrinkle-sim" "$tmp/none.json" -o "$tmp/sim0"
    printf '{"cloth": {"mesh": {"type": "rectangle", "width": 0.1, "height": 0.1, "nx": 2, "ny": 2}, "material": {"young": 1e5, "thickness": 1e-3, "density": 100}}, "time": {"dt": -1}}' > "$tmp/badsim.json"
    expect_fail "wrinkle-sim invalid scene" "$B/wrinkle-sim" "$tmp/badsim.json" -o "$tmp/sim0"
    expect_fail "wrinkle-sim bad --every" "$B/wrinkle-sim" "$root/examples/sim/drape_ball.json" -o "$tmp/sim0" --every 0
    sed 's/"time": {"dt": -1}/"solver": {"linear_forcing": 1}/' "$tmp/badsim.json" > "$tmp/badforcing.json"
    expect_fail "wrinkle-sim linear_forcing 1" "$B/wrinkle-sim" "$tmp/badforcing.json" -o "$tmp/sim0"
    grep -qF '$.solver.linear_forcing' "$tmp/err" && ok || { bad "wrinkle-sim linear_forcing: stderr does not name the path"; cat "$tmp/err"; }
    cat > "$tmp/sim.json" <<'JSON'
{"name": "sim_small", "cloth": {"mesh": {"type": "rectangle", "width": 0.2, "height": 0.2, "nx": 4, "ny": 4},
  "material": {"young": 1e5, "poisson": 0.3, "thickness": 5e-4, "areal_density": 0.15},
  "placement": {"translate": [-0.1, -0.1, 0.06]}},
 "obstacles": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.05}],
 "gravity": [0, 0, -9.81], "time": {"duration": 0.1}}
JSON
    # an output that would overwrite the input scene is refused
    mkdir -p "$tmp/simin"; cp "$tmp/sim.json" "$tmp/simin/summary.json"
    expect_fail "wrinkle-sim output over input" "$B/wrinkle-sim" "$tmp/simin/summary.json" -o "$tmp/simin"
    atomic wrinkle-sim "$tmp/simout/frame_0000.obj" "$tmp/simout/frame_0003.obj" "$tmp/simout/summary.json" -- \
        "$B/wrinkle-sim" "$tmp/sim.json" -o "$tmp/simout" --quiet
    keep_on_failure "wrinkle-sim invalid scene" "$tmp/simout/frame_0003.obj" "$tmp/simout/summary.json" -- \
        "$B/wrinkle-sim" "$tmp/badsim.json" -o "$tmp/simout"
fi
# ---- 4. behaviour shared through cli.c ------------------------------------------------------------
# full_stdout NAME DRIVER ARGS... : stdout on /dev/full -> exit 3 and a message naming the failure
full_stdout() {
    name=$1; shift
    [ -c /dev/full ] || { note="$note $name(no /dev/full)"; return; }
    (cd "$tmp/cwd" && "$@") >/dev/full 2>"$tmp/err" </dev/null
    rc=$?
    if [ $rc != 3 ]; then bad "$name: exit $rc with stdout on /dev/full, want 3"
    elif ! grep -qi "fail" "$tmp/err"; then bad "$name: no message when stdout is full"; cat "$tmp/err"
    else ok; fi
}
# warns NAME PATTERN DRIVER ARGS... : exit 0 and a warning line matching PATTERN on stderr
warns() {
    name=$1; pat=$2; shift 2
    (cd "$tmp/cwd" && "$@") >"$tmp/out" 2>"$tmp/err" </dev/null
    rc=$?
    if [ $rc != 0 ] && [ $rc != 1 ]; then bad "$name: exit $rc"; head -n 3 "$tmp/err"
    elif ! grep "warning:" "$tmp/err" | grep -qi "$pat"; then bad "$name: no warning matching '$pat'"; head -n 5 "$tmp/err"
    else ok; fi
}
no_inf() {
    if cat "$@" | tr -c 'A-Za-z\n' ' ' | grep -qwiE 'inf|nan|infinity'; then bad "inf/nan printed in $*"; else ok; fi
}
mkfifo "$tmp/fifo" 2>/dev/null
if [ -x "$B/wrinkle-resolution" ]; then
    full_stdout "wrinkle-resolution text" "$B/wrinkle-resolution" --bending 2e-6 --young 1e6
    full_stdout "wrinkle-resolution json" "$B/wrinkle-resolution" --bending 2e-6 --young 1e6 --json
    full_stdout "wrinkle-resolution csv" "$B/wrinkle-resolution" --csv "$tmp/good.csv"
    warns "wrinkle-resolution thickness in mm" "metres" "$B/wrinkle-resolution" --thickness 0.3 --poisson 0.3 --young 1e6
    warns "wrinkle-resolution outside the band" "band" "$B/wrinkle-resolution" --bending 1e-2 --young 2e3
    warns "wrinkle-resolution warp outside the band" "band" "$B/wrinkle-resolution" --warp-bending 1e-2 \
        --warp-young 2e3 --weft-bending 2e-6 --weft-young 1e6
fi
if [ -x "$B/wrinkle-mesh" ]; then
    full_stdout "wrinkle-mesh summary line" "$B/wrinkle-mesh" -o "$tmp/mfull" --no-png
    printf '{"name": "metres", "fabrics": {"f": {"B": 2e-6, "E": 1e6}}, "panels": [{"fabric": "f", "outer": [[0, 0], [0.25, 0], [0.25, 0.1], [0, 0.1]]}]}' > "$tmp/metres.json"
    warns "wrinkle-mesh panel smaller than one edge" "smaller than one edge" "$B/wrinkle-mesh" "$tmp/metres.json" -o "$tmp/mm" --no-png -q
    printf '{"name": "stiff", "fabrics": {"f": {"B": 1e-2, "E": 2e3}}, "panels": [{"fabric": "f", "outer": [[0, 0], [900, 0], [900, 900], [0, 900]]}]}' > "$tmp/stiff.json"
    warns "wrinkle-mesh resolution outside the band" "band" "$B/wrinkle-mesh" "$tmp/stiff.json" -o "$tmp/mm" --no-png -q
    mkdir -p "$tmp/mself"; cp "$root/examples/demo/sheet.json" "$tmp/mself/mesh.obj"
    expect_fail "wrinkle-mesh output is the input" "$B/wrinkle-mesh" "$tmp/mself/mesh.obj" -o "$tmp/mself"
    expect_fail "wrinkle-mesh output dir is a FIFO" "$B/wrinkle-mesh" -o "$tmp/fifo"
fi
if [ -x "$B/wrinkle-triangulate" ]; then
    full_stdout "wrinkle-triangulate summary line" "$B/wrinkle-triangulate" -pq30 "$tmp/tri/sq.poly"
    cp "$tmp/tri/sq.poly" "$tmp/tri/sq.1.poly"; cp "$tmp/tri/sq.1.poly" "$tmp/tri/sq.2.poly"
    ln -sf "$tmp/tri/sq.1.poly" "$tmp/tri/sq.2.poly"
    expect_fail "wrinkle-triangulate output is the input" "$B/wrinkle-triangulate" -pQ "$tmp/tri/sq.1.poly"
fi
if [ -x "$B/wrinkle-report" ] && [ -x "$B/validate_table1" ]; then
    expect_fail "wrinkle-report output is an input" "$B/wrinkle-report" "$tmp/results" -o "$(ls "$tmp"/results/*.json | head -n 1)"
    expect_fail "wrinkle-report output is a FIFO" "$B/wrinkle-report" "$tmp/results" -o "$tmp/fifo"
    full_stdout "wrinkle-report summary line" "$B/wrinkle-report" "$tmp/results" -o "$tmp/REPORT3.md"
fi
if [ -x "$B/wrinkle-tfw" ]; then
    # progress redirected to a file: several plain lines, no carriage return; no inf/nan
    (cd "$tmp/cwd" && "$B/wrinkle-tfw" "$tmp/tfw.json" -o "$tmp/tfwp" --levels 1) >"$tmp/out" 2>"$tmp/err" </dev/null
    if grep -q "$(printf '\r')" "$tmp/err"; then bad "wrinkle-tfw: carriage return in redirected progress"
    elif [ "$(grep -c . "$tmp/err")" -lt 5 ]; then bad "wrinkle-tfw: progress is not one line per step"; head -c 400 "$tmp/err"
    else ok; fi
    no_inf "$tmp/err" "$tmp/out"
    sed 's/"stretch": \[1.1, 1, 1\]/"stretch": [2.5, 1, 1]/' "$tmp/tfw.json" > "$tmp/tfw_big.json"
    warns "wrinkle-tfw strain over 100 %" "100 %" "$B/wrinkle-tfw" "$tmp/tfw_big.json" -o "$tmp/tfwb" --levels 1 --quiet
    sed 's/"thickness": 1.0e-4/"thickness": 0.3/' "$tmp/tfw.json" > "$tmp/tfw_thick.json"
    warns "wrinkle-tfw thickness in mm" "metres" "$B/wrinkle-tfw" "$tmp/tfw_thick.json" -o "$tmp/tfwt" --levels 0 --quiet
    # --png renders the picture (a PNG signature)
    (cd "$tmp/cwd" && "$B/wrinkle-tfw" "$tmp/tfw.json" -o "$tmp/tfwpng" --levels 1 --quiet --png) >/dev/null 2>&1 </dev/null
    if [ "$(head -c 4 "$tmp/tfwpng/wrinkles.png" 2>/dev/null | tail -c 3)" = PNG ]; then ok; else bad "wrinkle-tfw --png: no PNG"; fi
    for f in wrinkled.ply wrinkled.vtk fields.vtk; do
        [ -s "$tmp/tfwpng/$f" ] && ok || bad "wrinkle-tfw: $f not written"
    done
    grep -q '^vn ' "$tmp/tfwpng/wrinkled.obj" && grep -q '^vt ' "$tmp/tfwpng/wrinkled.obj" && ok ||
        bad "wrinkle-tfw: wrinkled.obj without vt/vn"
    # an OBJ base keeps its panel names (g lines) on base.obj and on the wrinkled surface
    mkdir -p "$tmp/tfwg"
    sed 's/^g .*/g front panel/' "$tmp/tfw/base.obj" > "$tmp/tfwg/named.obj"
    sed 's|"mesh": {[^}]*}|"mesh": {"type": "obj", "path": "named.obj"}|' "$tmp/tfw.json" > "$tmp/tfwg/scene.json"
    "$B/wrinkle-tfw" "$tmp/tfwg/scene.json" -o "$tmp/tfwg/out" --levels 1 --quiet >/dev/null 2>&1 </dev/null
    if grep -q '^g front_panel$' "$tmp/tfwg/out/wrinkled.obj" 2>/dev/null && grep -q '^g front_panel$' "$tmp/tfwg/out/base.obj" &&
        ! grep -q '^g panel' "$tmp/tfwg/out/wrinkled.obj"; then ok; else bad "wrinkle-tfw: the input OBJ's panel name is not on base.obj / wrinkled.obj"; fi
    # per-vertex sizing on both PLYs: the 10 x 5 rectangle's edges are 25 mm, 20 mm and 32 mm diagonals,
    # so every vertex's mean edge (and its Loop average on the fine mesh) lies in [20, 32] mm
    for f in fields.ply wrinkled.ply; do
        awk '/^element vertex/ { nv = $3; next }
             /^property/ { if ($NF == "sizing") col = ++np; else if ($2 != "list") ++np; next }
             /^end_header/ { body = 1; next }
             body && n < nv && col { n++; if (!($col >= 0.0199 && $col <= 0.0321)) badv++ }
             END { exit !(col && n > 0 && n == nv && badv == 0) }' "$tmp/tfwg/out/$f" && ok ||
            bad "wrinkle-tfw: $f has no per-vertex sizing in [20, 32] mm"
    done
fi
if [ -x "$B/wrinkle-statics" ]; then
    (cd "$tmp/cwd" && "$B/wrinkle-statics" "$root/examples/scenes/cantilever.json" -o "$tmp/stp" --load-steps 2) \
        >"$tmp/out" 2>"$tmp/err" </dev/null
    if grep -q "$(printf '\r')" "$tmp/err"; then bad "wrinkle-statics: carriage return in redirected progress"; else ok; fi
    no_inf "$tmp/err" "$tmp/out"
    mkdir -p "$tmp/stself"
    "$B/wrinkle-mesh" -o "$tmp/stmesh" -q --no-png --uniform 20 >/dev/null 2>&1
    cp "$tmp/stmesh/mesh.obj" "$tmp/stself/deformed.obj"
    printf '{"mesh": {"type": "obj", "path": "deformed.obj"}, "material": {"young": 1e6, "poisson": 0.3, "thickness": 1e-4}}' > "$tmp/stself/scene.json"
    expect_fail "wrinkle-statics output is the scene's mesh" "$B/wrinkle-statics" "$tmp/stself/scene.json" -o "$tmp/stself"
    # the mesher's panel name (the built-in square's "square") carried through to deformed.obj
    "$B/wrinkle-statics" "$tmp/stself/scene.json" -o "$tmp/stself/out" --load-steps 1 --quiet >/dev/null 2>&1 </dev/null
    grep -q '^g square$' "$tmp/stself/out/deformed.obj" 2>/dev/null && ok ||
        bad "wrinkle-statics: the input OBJ's panel name is not on deformed.obj"
fi
# ---- issue 19 audit: the same behaviour in every driver -------------------------------------------
# -o DIR naming an existing file (here the scene itself) is bad input, refused before any work
# (cli.c's wr_cli_dir_outputs_ok), not a write failure (exit 3) after the run
touch "$tmp/plainfile"
[ -x "$B/wrinkle-mesh" ] && expect_fail "wrinkle-mesh -o an existing file" "$B/wrinkle-mesh" -o "$tmp/plainfile" --no-png -q
if [ -x "$B/wrinkle-statics" ]; then
    expect_fail "wrinkle-statics -o an existing file" "$B/wrinkle-statics" "$root/examples/scenes/cantilever.json" \
        -o "$tmp/plainfile" --quiet --load-steps 2
    cp "$root/examples/scenes/cantilever.json" "$tmp/stscene.json"
    expect_fail "wrinkle-statics -o the scene file" "$B/wrinkle-statics" "$tmp/stscene.json" -o "$tmp/stscene.json" --quiet
fi
if [ -x "$B/wrinkle-tfw" ]; then
    expect_fail "wrinkle-tfw -o an existing file" "$B/wrinkle-tfw" "$tmp/tfw.json" -o "$tmp/plainfile" --quiet --levels 0
fi
if [ -x "$B/wrinkle-sim" ]; then
    expect_fail "wrinkle-sim -o an existing file" "$B/wrinkle-sim" "$tmp/sim.json" -o "$tmp/plainfile" --quiet
    expect_fail "wrinkle-sim -o the scene file" "$B/wrinkle-sim" "$tmp/sim.json" -o "$tmp/sim.json" --quiet
    # a written frame that is the input (same inode through another spelling of the directory)
    mkdir -p "$tmp/simf"; cp "$tmp/sim.json" "$tmp/simf/frame_0000.obj"
    expect_fail "wrinkle-sim frame over input" "$B/wrinkle-sim" "$tmp/simf/frame_0000.obj" -o "$tmp/simf/./" --quiet
    # progress redirected: plain lines, no carriage return
    (cd "$tmp/cwd" && "$B/wrinkle-sim" "$tmp/sim.json" -o "$tmp/simp") >"$tmp/out" 2>"$tmp/err" </dev/null
    if grep -q "$(printf '\r')" "$tmp/err"; then bad "wrinkle-sim: carriage return in redirected progress"
    elif [ "$(grep -c 'frame ' "$tmp/err")" -lt 2 ]; then bad "wrinkle-sim: no per-frame progress lines"; head -c 400 "$tmp/err"
    else ok; fi
    no_inf "$tmp/err" "$tmp/out"
    # plausibility warnings shared with wrinkle-statics/-tfw (cli.c): thickness in mm, strain > 100 %
    sed 's/"thickness": 5e-4/"thickness": 0.5/' "$tmp/sim.json" > "$tmp/sim_thick.json"
    warns "wrinkle-sim thickness in mm" "metres" "$B/wrinkle-sim" "$tmp/sim_thick.json" -o "$tmp/simt" --quiet --duration 0
    cat > "$tmp/sim_soft.json" <<'JSON'
{"name": "sim_soft", "cloth": {"mesh": {"type": "rectangle", "width": 0.2, "height": 0.2, "nx": 4, "ny": 4},
  "material": {"young": 1, "poisson": 0.3, "thickness": 5e-4, "areal_density": 0.15},
  "pins": [{"box": {"min": [-1, 0.19, -1], "max": [1, 1, 1]}}]},
 "gravity": [0, 0, -9.81], "time": {"duration": 0.5}}
JSON
    warns "wrinkle-sim strain over 100 %" "100 %" "$B/wrinkle-sim" "$tmp/sim_soft.json" -o "$tmp/sims" --quiet
    # a transient: E = 150 Pa overshoots to ~150 % strain near frame 10 and swings back to ~87 % by the
    # last frame (0.6 s, 18 frames; measured per frame from the OBJs): warned, with the worst frame named
    sed 's/"young": 1,/"young": 150,/; s/"duration": 0.5/"duration": 0.6/' "$tmp/sim_soft.json" > "$tmp/sim_swing.json"
    warns "wrinkle-sim transient strain over 100 %" "of frame [0-9]* is" "$B/wrinkle-sim" "$tmp/sim_swing.json" -o "$tmp/simw" --quiet
    # a garment whose pattern is in metres in a millimetre file: warned as wrinkle-mesh does
    python3 - "$root/examples/sim" "$tmp" <<'PY'
import json, sys
src, tmp = sys.argv[1], sys.argv[2]
def metres(o):  # every [x, y] point of the panels divided by 1000
    if isinstance(o, list):
        if len(o) == 2 and all(isinstance(v, (int, float)) for v in o): return [v * 1e-3 for v in o]
        return [metres(v) for v in o]
    if isinstance(o, dict): return {k: (v if k in ("fabrics", "mesher") else metres(v)) for k, v in o.items()}
    return o
json.dump(metres(json.load(open(src + "/skirt_pattern.json"))), open(tmp + "/skirt_m.json", "w"))
s = json.load(open(src + "/skirt_on_mannequin.json"))
s["garment"]["pattern"] = "skirt_m.json"; s["time"]["duration"] = 0
json.dump(s, open(tmp + "/garment_m.json", "w"))
PY
    warns "wrinkle-sim garment pattern in metres" "smaller than one edge" "$B/wrinkle-sim" "$tmp/garment_m.json" -o "$tmp/simg" --quiet
    # $.garment.gravity_hold (garment.h ON HOLDING): the example skirt, 2 frames with gravity held
    # 0.05 s and ramped over 0.1 s -> the summary carries the hold and frame 1's gravity factor is 0;
    # a negative delay is one line naming its path (exit 2)
    python3 - "$root/examples/sim" "$tmp" <<'PY'
import json, sys
src, tmp = sys.argv[1], sys.argv[2]
s = json.load(open(src + "/skirt_on_mannequin.json"))
s["garment"]["pattern"] = src + "/skirt_pattern.json"; s["time"]["duration"] = 2 / 30 + 1e-12
s["garment"]["gravity_hold"] = {"delay": 0.05, "ramp": 0.1}
json.dump(s, open(tmp + "/garment_hold.json", "w"))
s["garment"]["gravity_hold"] = {"delay": -0.05}
json.dump(s, open(tmp + "/garment_hold_bad.json", "w"))
PY
    if (cd "$tmp/cwd" && "$B/wrinkle-sim" "$tmp/garment_hold.json" -o "$tmp/simh" --quiet) >/dev/null 2>"$tmp/err" </dev/null &&
       python3 - "$tmp/simh/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
g, f = s["garment"], s["per_frame"]
sys.exit(0 if g["gravity_delay"] == 0.05 and g["gravity_ramp"] == 0.1 and len(f) == 2 and f[0]["gravity_scale"] == 0
         and abs(f[1]["gravity_scale"] - (2 / 30 - 0.05) / 0.1) < 1e-9 else 1)
PY
    then ok; else bad "wrinkle-sim garment gravity_hold: run failed or summary without the hold"; head -n 3 "$tmp/err"; fi
    expect_fail "wrinkle-sim negative gravity_hold.delay" "$B/wrinkle-sim" "$tmp/garment_hold_bad.json" -o "$tmp/simhb" --quiet
    grep -qF '$.garment.gravity_hold.delay' "$tmp/err" && ok || { bad "wrinkle-sim gravity_hold.delay: stderr does not name the path"; cat "$tmp/err"; }
    # --weld-final FILE: the last frame sewn (2 frames of the example skirt: the seams still open, so
    # warned): one vertex per seam pair fewer than the frames, vt per face corner, the panels' names as
    # groups, written atomically; refused (exit 2, one line) on a cloth scene and over the scene file
    python3 - "$root/examples/sim" "$tmp" <<'PY'
import json, sys
src, tmp = sys.argv[1], sys.argv[2]
s = json.load(open(src + "/skirt_on_mannequin.json"))
s["garment"]["pattern"] = src + "/skirt_pattern.json"; s["time"]["duration"] = 2 / 30 + 1e-12
json.dump(s, open(tmp + "/garment_weld.json", "w"))
PY
    warns "wrinkle-sim --weld-final seams open" "not welded" "$B/wrinkle-sim" "$tmp/garment_weld.json" -o "$tmp/simwf" \
        --quiet --weld-final "$tmp/simwf_sewn.obj"
    if python3 - "$tmp/simwf/frame_0002.obj" "$tmp/simwf_sewn.obj" "$tmp/simwf/summary.json" <<'PY'
import json, sys
def obj(p):
    L = open(p).read().split("\n")
    return [sum(1 for l in L if l.startswith(k + " ")) for k in ("v", "vt", "f")], [l[2:] for l in L if l.startswith("g ")]
(fv, fvt, ff), _ = obj(sys.argv[1])
(wv, wvt, wf), g = obj(sys.argv[2])
pairs = json.load(open(sys.argv[3]))["garment"]["seam_pairs"]
sys.exit(0 if wv == fv - pairs and wf == ff and wvt == 3 * wf and g == ["front", "back"] else 1)
PY
    then ok; else bad "wrinkle-sim --weld-final: the sewn OBJ is not the frame with its pairs merged"; fi
    atomic "wrinkle-sim --weld-final" "$tmp/simwf2_sewn.obj" -- "$B/wrinkle-sim" "$tmp/garment_weld.json" -o "$tmp/simwf2" \
        --quiet --weld-final "$tmp/simwf2_sewn.obj"
    expect_fail "wrinkle-sim --weld-final on a cloth scene" "$B/wrinkle-sim" "$root/examples/sim/drape_ball.json" -o "$tmp/simwc" \
        --weld-final "$tmp/simwc.obj"
    expect_fail "wrinkle-sim --weld-final over the scene" "$B/wrinkle-sim" "$tmp/garment_weld.json" -o "$tmp/simwo" \
        --weld-final "$tmp/garment_weld.json"
    # ... and before any frame is run, into a folder that does not exist or onto a file the run writes itself
    expect_fail "wrinkle-sim --weld-final into a missing folder" "$B/wrinkle-sim" "$tmp/garment_weld.json" -o "$tmp/simwm" \
        --quiet --weld-final "$tmp/no_such_dir/sewn.obj"
    grep -qF 'no such folder' "$tmp/err" && ok || { bad "wrinkle-sim --weld-final missing folder: stderr does not say so"; cat "$tmp/err"; }
    expect_fail "wrinkle-sim --weld-final onto its own frame" "$B/wrinkle-sim" "$tmp/garment_weld.json" -o "$tmp/simwl" \
        --quiet --weld-final "$tmp/simwl/frame_0002.obj"
    grep -qF 'the run itself writes' "$tmp/err" && ok || { bad "wrinkle-sim --weld-final onto a frame: stderr does not say so"; cat "$tmp/err"; }
    [ ! -e "$tmp/simwl/summary.json" ] && ok || bad "wrinkle-sim --weld-final onto a frame: the run went ahead"
fi
if [ -x "$B/wrinkle-resolution" ]; then
    # an answer that overflows is refused, never printed as "inf" (text) or null (JSON)
    expect_fail "wrinkle-resolution --inverse-mm overflow" "$B/wrinkle-resolution" --inverse-mm 1e300
    expect_fail "wrinkle-resolution --inverse-mm overflow json" "$B/wrinkle-resolution" --inverse-mm 1e60 --json
fi
if [ -x "$B/wrinkle-triangulate" ]; then
    # -I writes name.node/.ele beside name.poly: a rerun must not take the first run's name.ele
    # (not read without -r) for an input and refuse to replace it
    cp "$tmp/tri/sq.poly" "$tmp/tri/sqI.poly"
    for run in 1 2; do
        if (cd "$tmp/cwd" && "$B/wrinkle-triangulate" -pIQ "$tmp/tri/sqI.poly") >/dev/null 2>"$tmp/err" </dev/null; then ok
        else bad "wrinkle-triangulate -pI run $run refused"; cat "$tmp/err"; fi
    done
    # ... but name.node IS read when the .poly has no vertices of its own: -I would replace it
    printf '0 2 0 0\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n' > "$tmp/tri/sqn.poly"
    printf '4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n' > "$tmp/tri/sqn.node"
    expect_fail "wrinkle-triangulate -I over name.node" "$B/wrinkle-triangulate" -pIq30a0.01Q "$tmp/tri/sqn.poly"
fi
if [ -x "$B/wrinkle-report" ]; then
    # "done with a caveat" (exit 1: a quantity missed) with a lost stdout is a failure too (exit 3)
    mkdir -p "$tmp/resmiss"
    printf '{"case": "zz_miss", "title": "a missed quantity", "generated": "2026-01-01T00:00:00Z", "machine": "m", "failed": 1, "quantities": [{"name": "q", "unit": "mm", "paper": 1.0, "ours": 2.0, "tolerance": "[0.9, 1.1]", "lo": 0.9, "hi": 1.1, "pass": false}]}\n' > "$tmp/resmiss/zz_miss.json"
    (cd "$tmp/cwd" && "$B/wrinkle-report" "$tmp/resmiss" -o "$tmp/RMISS.md") >/dev/null 2>"$tmp/err" </dev/null
    rc=$?
    if [ $rc = 1 ]; then ok; else bad "wrinkle-report with a missed quantity: exit $rc, want 1"; cat "$tmp/err"; fi
    full_stdout "wrinkle-report a miss, stdout full" "$B/wrinkle-report" "$tmp/resmiss" -o "$tmp/RMISS.md"
    # a file whose own "failed" total disagrees with its rows is refused (exit 2), not reported as a pass
    mkdir -p "$tmp/reslie"
    sed 's/"failed": 1/"failed": 0/' "$tmp/resmiss/zz_miss.json" > "$tmp/reslie/zz_lie.json"
    expect_fail "wrinkle-report failed count disagrees with rows" "$B/wrinkle-report" "$tmp/reslie" -o "$tmp/RLIE.md"
    if [ ! -e "$tmp/RLIE.md" ]; then ok; else bad "wrinkle-report wrote a report from an inconsistent file"; fi
fi
# a failed file write (ulimit -f with SIGXFSZ ignored: write() fails with EFBIG, as on a full disk)
# -> exit 3 and a message, every driver that writes files
full_file() {
    name=$1; shift
    (cd "$tmp/cwd" && trap '' XFSZ && ulimit -f 8 && exec "$@") >/dev/null 2>"$tmp/err" </dev/null
    rc=$?
    if [ $rc != 3 ]; then bad "$name: exit $rc when a file write fails, want 3"; head -n 3 "$tmp/err"
    elif ! grep -qi "fail" "$tmp/err"; then bad "$name: no message when a file write fails"; cat "$tmp/err"
    else ok; fi
}
if (trap '' XFSZ && ulimit -f 8) 2>/dev/null; then
    [ -x "$B/wrinkle-mesh" ] && full_file "wrinkle-mesh file write" "$B/wrinkle-mesh" -o "$tmp/ff1" --no-png -q
    [ -x "$B/wrinkle-statics" ] && full_file "wrinkle-statics file write" "$B/wrinkle-statics" \
        "$root/examples/scenes/cantilever.json" -o "$tmp/ff2" --quiet --load-steps 2 --resolution 0.002
    [ -x "$B/wrinkle-tfw" ] && full_file "wrinkle-tfw file write" "$B/wrinkle-tfw" "$tmp/tfw.json" -o "$tmp/ff3" --quiet --levels 2
    [ -x "$B/wrinkle-sim" ] && full_file "wrinkle-sim file write" "$B/wrinkle-sim" "$root/examples/sim/drape_ball.json" \
        -o "$tmp/ff4" --quiet --duration 0
    [ -x "$B/wrinkle-triangulate" ] && full_file "wrinkle-triangulate file write" "$B/wrinkle-triangulate" \
        -pq30a0.0001Q "$tmp/tri/sq.poly"
    [ -x "$B/wrinkle-resolution" ] && { for i in $(seq 1 400); do echo "f$i,2e-6,1e6"; done > "$tmp/big.csv"
        full_file "wrinkle-resolution stdout to a file" sh -c 'exec "$0" --csv "$1" > "$2"' "$B/wrinkle-resolution" \
            "$tmp/big.csv" "$tmp/big.out"; }
else note="$note file-write(no ulimit -f)"; fi
echo "driver-check: $pass passed, $fail failed, $found drivers${note:+; skipped:$note}"
[ $fail = 0 ]
