#!/bin/sh
# `make demo`: the flagship job on built-in examples. Grows as the pipeline grows.
cd "$(dirname "$0")/.." || exit 1
set -e
if [ -x bin/validate_table1 ]; then
    echo "== Style3D Table 1: optimal resolution from bending stiffness B and Young's modulus E"
    WRINKLE_RESULTS_DIR=${WRINKLE_RESULTS_DIR:-validation/results} ./bin/validate_table1
fi
if [ -x bin/wrinkle-resolution ]; then
    echo "== built-in fabric (the paper's cantilever fabric, Fig. 18): B = 2.0e-6 N·m, E = 1.0e6 N/m²"
    ./bin/wrinkle-resolution --bending 2e-6 --young 1e6
fi
if [ -x bin/wrinkle-mesh ]; then
    echo "== meshing the built-in example (Fig. 14: square with curved shirring lines) into demo-out/"
    ./bin/wrinkle-mesh -o demo-out
fi
