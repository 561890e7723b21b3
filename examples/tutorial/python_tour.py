"""The wrinkle kit from Python in five steps (docs/tutorial-3-python.md walks through it).

    make && PYTHONPATH=python /usr/bin/python3 examples/tutorial/python_tour.py [OUTDIR]

Writes OUTDIR/tour-sizing.png and OUTDIR/tour-wrinkles.png (default OUTDIR: demo-out/python).
"""
import os
import sys

import numpy as np

import wrinkle

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("demo-out", "python")
os.makedirs(out, exist_ok=True)

# 1. Style3D Eq. 4: the edge length a full simulation of this fabric needs
r = wrinkle.resolution(bending=2e-6, young=1e6)
print("1. optimal resolution r = %.4f mm" % (1e3 * r))

# 2. a pattern (millimetres, docs/pattern-format.md) with a shirring line: the sizing map refines it
pattern = {
    "name": "tour", "fabrics": {"f": {"B": 2e-6, "E": 1e6}},
    "panels": [{"name": "panel", "fabric": "f", "outer": [[0, 0], [200, 0], [200, 120], [0, 120]]}],
    "shirring": [{"panel": "panel", "line": [[20, 60], [100, 80], [180, 60]], "rho": 0.5, "E_sh": 1e6}],
    "mesher": {"seed": 1}}
m = wrinkle.mesh_pattern(pattern)
print("2. mesh: %d vertices, %d triangles; sizing %.2f .. %.2f mm"
      % (len(m.pos), len(m.faces), 1e3 * m.sizing.min(), 1e3 * m.sizing.max()))
flat = np.column_stack([m.rest, np.zeros(len(m.rest))])
wrinkle.render_png(os.path.join(out, "tour-sizing.png"),
                   [(flat, m.faces, None, "mesh"), (flat, m.faces, 1e3 * m.sizing, "sizing map mm")],
                   size=(600, 400), view=(-90, 90))

# 3. the TFW stretched sheet: base surface by statics (tension-field membrane + quadratic bending)
sheet = {"mesh": {"type": "rectangle", "width": 0.25, "height": 0.1, "nx": 28, "ny": 17},
         "material": {"young": 1e6, "poisson": 0.5, "thickness": 1e-4, "density": 0},
         "energy": {"membrane": "tft", "bending": "quadratic"},
         "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
                      {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]},
                       "center": [0, 0, 0], "stretch": [1.1278, 1, 1]}],
         "solver": {"load_steps": 4, "grad_tol": 1e-8, "max_iter": 200, "hessian": "projected"}}
base = wrinkle.statics(sheet)
print("3. base: %d vertices, %d Newton steps, converged %s" % (len(base.pos), base.newton_iterations, base.converged))

# 4. TFW: amplitude and frequency fields, then the wrinkled surface (Eq. 19)
t = wrinkle.tfw(base.rest_pos, base.faces, base.pos, young=1e6, poisson=0.5, thickness=1e-4, levels=2)
print("4. TFW: %d SQP iterations, max amplitude %.3f mm, wrinkled mesh %d vertices"
      % (t.sqp_iterations, 1e3 * t.a.max(), len(t.wrinkled_pos)))

# 5. the wrinkle wavelength across the middle: twice the mean spacing of the height's zero crossings
#    on the vertices near x = 125 mm (the driver's FFT probe gives 12.9 mm on this scene)
mid = np.abs(t.wrinkled_pos[:, 0] - 0.5 * t.wrinkled_pos[:, 0].max()) < 0.002
order = np.argsort(t.wrinkled_pos[mid, 1])
ys, zs = t.wrinkled_pos[mid, 1][order], t.wrinkled_pos[mid, 2][order]
keep = np.abs(zs) > 0.05 * np.abs(zs).max()          # ignore the flat margins
ys, zs = ys[keep], zs[keep]
cross = ys[1:][np.diff(np.sign(zs)) != 0]
print("5. across the middle: %d zero crossings, wavelength ~ %.1f mm"
      % (len(cross), 2e3 * (cross[-1] - cross[0]) / (len(cross) - 1)))
wrinkle.render_png(os.path.join(out, "tour-wrinkles.png"),
                   [(base.pos, base.faces, None, "coarse base"),
                    (t.wrinkled_pos, t.wrinkled_faces, 1e3 * t.wrinkled_pos[:, 2], "wrinkles height mm")],
                   columns=1, size=(900, 380))
print("pictures: %s/tour-sizing.png, %s/tour-wrinkles.png" % (out, out))
