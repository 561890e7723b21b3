#!/bin/sh
# `make demo`: both papers end to end on a built-in example, in a few seconds, with pictures.
#
#   fabric (B, E)  --Style3D Eq. 4-->  optimal resolution r
#   pattern        --Style3D Sec. 4-->  sizing map + mesh                 (bin/wrinkle-mesh)
#   base surface   --TFW Sec. 4.1-->   TFT statics of the stretched sheet (bin/wrinkle-tfw)
#   wrinkles       --TFW Sec. 5, App. E--> amplitude, phase, wrinkled surface, rendered PNG
#
# The example is the TFW paper's stretched sheet (Fig. 6: 250 x 100 mm, clamped short edges, one
# pulled 12.78 %) cut from the Style3D cantilever fabric (Fig. 18: B = 2e-6 N*m, E = 1e6 N/m^2).
# Every step is one of the kit's drivers, so each line below can be rerun by hand.
# Outputs go to $WRINKLE_DEMO_OUT (default demo-out/).
cd "$(dirname "$0")/.." || exit 2
set -e
out=${WRINKLE_DEMO_OUT:-demo-out}
B=2e-6 E=1e6 NU=0.5 STRETCH=1.1278
t0=$(date +%s.%N)
mkdir -p "$out"
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
json() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2], {}, {"d": d}))' "$@"; }

echo "== 1. Fabric -> optimal mesh resolution (Style3D Eq. 4: c1 r^6 + c2 r^4 = B/E)"
echo "   \$ bin/wrinkle-resolution --bending $B --young $E"
r_mm=$(./bin/wrinkle-resolution --bending $B --young $E | tail -n 1)
echo "   r = $r_mm mm: the edge length a full simulation of this fabric needs to resolve its wrinkles"

echo "== 2. Sizing map and mesh of the pattern (Style3D Sec. 4: sizing, Poisson sampling, CDT)"
echo "   \$ bin/wrinkle-mesh examples/demo/sheet.json -o $out/mesh"
./bin/wrinkle-mesh examples/demo/sheet.json -o "$out/mesh" -q
echo "   sheet: $(json "$out/mesh/summary.json" 'd["vertices"]') vertices at r = $r_mm mm (uniform: no garment technique on this panel)"
echo "   \$ bin/wrinkle-mesh -o $out/fig14        (the built-in Fig. 14 square: shirring lines refine the map)"
./bin/wrinkle-mesh -o "$out/fig14" -q
echo "   fig14: $(json "$out/fig14/summary.json" 'd["vertices"]') vertices, sizing $(json "$out/fig14/summary.json" '"%.2f" % min(p["base_resolution_warp_mm"] for p in d["panels"])') mm away from the lines, finer on them"

echo "== 3. Base surface and wrinkles (TFW: TFT membrane + bending statics, then E_wf by SQP, phase, Eq. 19)"
# Shell thickness of the fabric by Kirchhoff-Love, B = E h^3 / (12 (1 - nu^2)).
h=$(awk -v B=$B -v E=$E -v nu=$NU 'BEGIN { printf "%.6g", (12 * (1 - nu * nu) * B / E) ^ (1 / 3) }')
# The base mesh is the Poisson-Delaunay mesh of step 2 (mesh.obj: positions and vt rest coordinates
# in metres), so the wrinkles below are computed on exactly the mesh the Style3D pipeline made.
cat > "$out/sheet_scene.json" <<EOF
{"name": "demo_stretched_sheet",
 "mesh": {"type": "obj", "path": "mesh/mesh.obj"},
 "material": {"young": $E, "poisson": $NU, "thickness": $h, "density": 0},
 "boundary": [
  {"name": "left",  "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
  {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]}, "center": [0, 0, 0],
   "stretch": [$STRETCH, 1, 1]}],
 "solver": {"linear": "cholmod", "load_steps": 4, "grad_tol": 1e-8, "max_iter": 200, "hessian": "projected"},
 "probes": [{"name": "mid_width", "from": [0.125, 0.0], "to": [0.125, 0.1], "samples": 512}]}
EOF
echo "   h = $h m (Kirchhoff-Love from B, E, nu = $NU); base = the step-2 mesh (r = $r_mm mm); right edge pulled to $STRETCH x"
echo "   \$ bin/wrinkle-tfw $out/sheet_scene.json -o $out/tfw --png"
./bin/wrinkle-tfw "$out/sheet_scene.json" -o "$out/tfw" --png --quiet
s=$out/tfw/summary.json
echo "   base: $(json "$s" 'd["base_vertices"]') vertices, $(json "$s" 'd["base"]["newton_iterations"]') Newton steps ($(json "$s" 'd["base"]["status"]'));" \
     "SQP: $(json "$s" 'd["sqp"]["iterations"]') iterations ($(json "$s" 'd["sqp"]["status"]'))"
echo "   wrinkled surface: $(json "$s" 'd["wrinkled_vertices"]') vertices; max amplitude $(json "$s" '"%.3f" % (1e3 * d["max_amplitude_m"])') mm"
echo "   across the middle: $(json "$s" '"%.2f wrinkles, wavelength %.1f mm" % (d["probes"][0]["count"], 1e3 * d["probes"][0]["wavelength_m"])')"

t1=$(date +%s.%N)
echo "== done in $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s. Pictures:"
echo "   $out/tfw/wrinkles.png      the coarse base (with its edges) beside the wrinkled surface"
echo "   $out/mesh/sizing.png       sizing map and mesh of the sheet"
echo "   $out/fig14/sizing.png      technique-aware sizing map (shirring lines)"
echo "   3D files for ParaView / MeshLab / Blender: $out/tfw/wrinkled.{obj,ply,vtk} (a, height, phase, W, sizing), $out/tfw/fields.{ply,vtk} (a, phase, |omega|, W, sizing)"
