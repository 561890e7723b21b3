"""Tests of the Python binding (python/wrinkle): each checks a number the C kit or a closed form
fixes, so a broken marshalling (wrong shape, order, units, dtype) fails. Run by `make test`:
    PYTHONPATH=python python3 -m unittest discover -s python/tests -v
"""
import json
import math
import os
import tempfile
import unittest

import numpy as np

import wrinkle

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def square_pattern(side_mm=100.0, B=2e-6, E=1e6):
    return {"name": "square", "fabrics": {"f": {"B": B, "E": E}},
            "panels": [{"name": "sq", "fabric": "f",
                        "outer": [[0, 0], [side_mm, 0], [side_mm, side_mm], [0, side_mm]]}],
            "mesher": {"seed": 1}}


class Resolution(unittest.TestCase):
    def test_paper_value(self):
        # Style3D Eq. 4 for the cantilever fabric (Fig. 18); the C driver prints 6.4578 mm
        self.assertAlmostEqual(wrinkle.resolution(bending=2e-6, young=1e6), 0.0064578, delta=5e-8)

    def test_root_of_eq4(self):
        # independent check: r solves c1 r^6 + c2 r^4 = B/E with the paper's constants
        r = wrinkle.resolution(2.6e-6, 2e6)
        c1, c2 = 32.0751, -0.000187669  # printed by wrinkle-resolution (6 digits)
        self.assertAlmostEqual((c1 * r ** 6 + c2 * r ** 4) / (2.6e-6 / 2e6), 1.0, delta=1e-4)

    def test_bad_input_raises(self):
        with self.assertRaises(wrinkle.Error) as cm:
            wrinkle.resolution(-1.0, 1e6)
        self.assertIn("B", str(cm.exception))


class Mesher(unittest.TestCase):
    def test_square(self):
        r = wrinkle.resolution(2e-6, 1e6)
        m = wrinkle.mesh_pattern(square_pattern())
        self.assertEqual(m.pos.shape[1], 3)
        self.assertEqual(m.faces.shape[1], 3)
        self.assertGreater(len(m.pos), 100)
        # millimetres in, metres out: the square spans 0.1 m
        self.assertAlmostEqual(m.rest[:, 0].max(), 0.1, delta=1e-9)
        self.assertAlmostEqual(m.rest[:, 1].min(), 0.0, delta=1e-9)
        # uniform panel: sizing is r everywhere, and the panel's base resolution is r
        self.assertAlmostEqual(m.panel_resolution[0], r, delta=1e-12)
        np.testing.assert_allclose(m.sizing, r, rtol=1e-9)
        np.testing.assert_allclose(m.sizing_at(0, [[0.05, 0.05], [0.01, 0.02]]), r, rtol=1e-9)
        # mean edge length near the sizing (the mesher's report: mean edge/sizing ~ 1, +-15 %)
        e = np.vstack([m.faces[:, [0, 1]], m.faces[:, [1, 2]], m.faces[:, [2, 0]]])
        L = np.linalg.norm(m.rest[e[:, 0]] - m.rest[e[:, 1]], axis=1)
        self.assertLess(abs(L.mean() / r - 1.0), 0.15)
        # faces counter-clockwise in the rest domain, total area = the square's
        a = m.rest[m.faces]
        area = 0.5 * ((a[:, 1, 0] - a[:, 0, 0]) * (a[:, 2, 1] - a[:, 0, 1])
                      - (a[:, 2, 0] - a[:, 0, 0]) * (a[:, 1, 1] - a[:, 0, 1]))
        self.assertTrue((area > 0).all())
        self.assertAlmostEqual(area.sum(), 0.01, delta=1e-12)

    def test_bad_pattern_names_the_path(self):
        p = square_pattern()
        p["panels"][0]["outer"] = [[0, 0], [1, 0]]
        with self.assertRaises(wrinkle.Error) as cm:
            wrinkle.mesh_pattern(p)
        self.assertIn("panels[0]", str(cm.exception))


class Triangulate(unittest.TestCase):
    def test_square_two_triangles(self):
        pts, tri = wrinkle.triangulate([[0, 0], [1, 0], [1, 1], [0, 1]])
        self.assertEqual(len(pts), 4)
        self.assertEqual(len(tri), 2)

    def test_quality_refinement(self):
        sq = [[0, 0], [1, 0], [1, 1], [0, 1]]
        pts, tri = wrinkle.triangulate(sq, segments=[[0, 1], [1, 2], [2, 3], [3, 0]], min_angle=30,
                                       max_area=0.01)
        p = pts[tri]
        area = 0.5 * ((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                      - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
        self.assertTrue((area > 0).all(), "counter-clockwise")
        self.assertAlmostEqual(area.sum(), 1.0, delta=1e-12)
        self.assertLessEqual(area.max(), 0.01 * (1 + 1e-12))
        ang = []
        for k in range(3):
            u = p[:, (k + 1) % 3] - p[:, k]
            v = p[:, (k + 2) % 3] - p[:, k]
            c = (u * v).sum(1) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1)
            ang.append(np.degrees(np.arccos(np.clip(c, -1, 1))))
        self.assertGreaterEqual(np.min(ang), 30.0 - 1e-9)

    def test_hole(self):
        outer = [[0, 0], [4, 0], [4, 4], [0, 4]]
        inner = [[1, 1], [3, 1], [3, 3], [1, 3]]
        segs = [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]]
        pts, tri = wrinkle.triangulate(outer + inner, segments=segs, holes=[[2, 2]])
        p = pts[tri]
        area = 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                            - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
        self.assertAlmostEqual(area.sum(), 16.0 - 4.0, delta=1e-12)


SHEET = {"name": "sheet", "mesh": {"type": "rectangle", "width": 0.25, "height": 0.1, "nx": 28, "ny": 17},
         "material": {"young": 1.0e6, "poisson": 0.5, "thickness": 1.0e-4, "density": 0,
                      },
         "energy": {"membrane": "tft", "bending": "quadratic"},
         "boundary": [{"name": "left", "box": {"min": [-1e-9, -1, -1], "max": [1e-9, 1, 1]}},
                      {"name": "right", "box": {"min": [0.249999999, -1, -1], "max": [1, 1, 1]},
                       "center": [0, 0, 0], "stretch": [1.1278, 1, 1]}],
         "solver": {"linear": "cholmod", "load_steps": 4, "grad_tol": 1e-8, "max_iter": 200,
                    "hessian": "projected"}}


class StaticsAndTFW(unittest.TestCase):
    def test_cantilever_sags(self):
        with open(os.path.join(ROOT, "examples", "scenes", "cantilever.json")) as f:
            sc = json.load(f)
        s = wrinkle.statics(sc)
        self.assertTrue(s.converged)
        self.assertEqual(s.pos.shape, s.rest_pos.shape)
        clamp = s.rest_pos[:, 0] <= 0.005000001
        np.testing.assert_allclose(s.pos[clamp], s.rest_pos[clamp], atol=1e-12)  # held
        self.assertLess(s.pos[:, 2].min(), -0.005)  # the free end hangs down (gravity -z)

    def test_stretched_sheet_wrinkles(self):
        # the TFW stretched sheet (Fig. 6): base by statics (TFT + quadratic bending), then TFW. The
        # C driver gives max amplitude 0.349 mm and 58 SQP iterations on this scene.
        s = wrinkle.statics(SHEET)
        self.assertTrue(s.converged)
        right = s.rest_pos[:, 0] > 0.249999999
        np.testing.assert_allclose(s.pos[right, 0], 0.25 * 1.1278, rtol=1e-12)  # prescribed stretch
        t = wrinkle.tfw(s.rest_pos, s.faces, s.pos, 1e6, 0.5, 1e-4, levels=1)
        self.assertEqual(t.a.shape, (len(s.pos),))
        self.assertEqual(t.phi.shape, (len(s.faces), 3))
        self.assertEqual(len(t.edges), len(t.omega))
        self.assertAlmostEqual(t.a.max(), 3.49e-4, delta=0.1e-4)
        # Loop level 1: V' = V + E, F' = 4F
        self.assertEqual(len(t.wrinkled_faces), 4 * len(s.faces))
        self.assertEqual(len(t.wrinkled_pos), len(s.pos) + len(t.edges))
        # wrinkles are out of plane, about the amplitude
        self.assertGreater(np.abs(t.wrinkled_pos[:, 2]).max(), 0.5 * t.a.max())
        # the fine fields: the base is flat (z = 0) and Loop keeps it flat, so the height over it is the
        # z coordinate, Eq. 19's a cos(phi) with the normal +z, vertex by vertex
        self.assertLess(np.abs(s.pos[:, 2]).max(), 1e-12)
        self.assertEqual(t.wrinkled_phase.shape, (len(t.wrinkled_pos),))
        self.assertTrue(np.all((t.wrinkled_phase > -np.pi) & (t.wrinkled_phase <= np.pi)))
        np.testing.assert_allclose(t.wrinkled_pos[:, 2], t.wrinkled_a * np.cos(t.wrinkled_phase), rtol=0, atol=1e-15)
        w = t.wrinkled_wrinkle_free
        self.assertTrue(np.all(t.wrinkled_a[w] == 0) and np.all(t.wrinkled_phase[w] == 0))

    def test_tfw_rejects_mismatch(self):
        with self.assertRaises(wrinkle.Error):
            wrinkle.tfw(np.zeros((3, 3)), [[0, 1, 2]], np.zeros((4, 3)), 1e6, 0.5, 1e-4)


class Render(unittest.TestCase):
    def test_png(self):
        pos = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.2], [0, 1, 0.2]], float)
        f = np.array([[0, 1, 2], [0, 2, 3]])
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "x.png")
            wrinkle.render_png(p, [(pos, f, None, "plain"), (pos, f, pos[:, 2] - 0.1, "signed")], size=(200, 150))
            with open(p, "rb") as fh:
                head = fh.read(24)
            self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n")
            w, h = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
            self.assertEqual(w, 400)  # two 200 px views side by side
            self.assertGreater(h, 150)  # plus title and legend rows
        with self.assertRaises(wrinkle.Error):
            wrinkle.render_png("/tmp/x.png", [(pos, [[0, 1, 7]], None, "bad")])


if __name__ == "__main__":
    unittest.main()
