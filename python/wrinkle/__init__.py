"""wrinkle — Python binding of the wrinkle kit (Style3D optimal cloth mesh resolution, TFW fine
wrinkles on coarse shells), for teaching and quick experiments.

The computations are the C library's (build/libwrinkle.so, built by `make`); this module only moves
numpy arrays in and out through ctypes. Units are SI as in the C headers: metres, N·m, N/m², radians.

    >>> import wrinkle
    >>> round(wrinkle.resolution(bending=2e-6, young=1e6), 7)     # Style3D Eq. 4, metres
    0.0064578

Functions
    resolution(bending, young)                      optimal edge length r [m] (Style3D Eq. 4)
    mesh_pattern(pattern)                           sizing map + mesh of a garment pattern (dict in the
                                                    docs/pattern-format.md layout, millimetres) -> PatternMesh
    triangulate(points, segments, holes, min_angle, max_area)   constrained Delaunay -> (points, triangles)
    statics(scene, base_dir=".")                    equilibrium of a scene (dict, docs/scene-format.md) -> Statics
    tfw(rest_pos, faces, base_pos, young, poisson, thickness, levels=2, rest=None)   TFW wrinkles -> TFW
    render_png(path, views, columns, size, view)    pictures through the kit's renderer (PNG)

Errors from the library raise wrinkle.Error (a ValueError) with the library's one-line message.
The library is found at $WRINKLE_LIB, else ../../build/libwrinkle.so next to this package, else on
the system library path.
"""
import ctypes as _C
import json as _json
import os as _os

import numpy as _np

__all__ = ["Error", "resolution", "mesh_pattern", "triangulate", "statics", "tfw", "render_png",
           "PatternMesh", "Statics", "TFW"]


class Error(ValueError):
    """A wrinkle library call failed; the message is the library's (it names the offending item)."""


def _load():
    cands = []
    if _os.environ.get("WRINKLE_LIB"):
        cands.append(_os.environ["WRINKLE_LIB"])
    here = _os.path.dirname(_os.path.abspath(__file__))
    cands.append(_os.path.join(here, "..", "..", "build", "libwrinkle.so"))
    cands.append("libwrinkle.so")
    last = None
    for c in cands:
        try:
            return _C.CDLL(c)
        except OSError as e:  # try the next place
            last = e
    raise ImportError("wrinkle: cannot load libwrinkle.so (run `make` in the kit, or set WRINKLE_LIB): %s" % last)


_lib = _load()
_D = _C.POINTER(_C.c_double)
_I = _C.POINTER(_C.c_int32)
_U8 = _C.POINTER(_C.c_uint8)
_VP = _C.c_void_p
_i32 = _C.c_int32


def _sig(name, res, *args):
    f = getattr(_lib, name)
    f.restype = res
    f.argtypes = list(args)
    return f


_resolution = _sig("wr_py_resolution", _C.c_int, _C.c_double, _C.c_double, _D, _C.c_char_p, _C.c_int)
_mesher_run = _sig("wr_py_mesher_run", _VP, _C.c_char_p, _C.c_char_p, _C.c_int)
_mesher_sizes = _sig("wr_py_mesher_sizes", None, _VP, _I, _I, _I)
_mesher_get = _sig("wr_py_mesher_get", None, _VP, _D, _D, _I, _I, _D, _D)
_mesher_sizing = _sig("wr_py_mesher_sizing", None, _VP, _i32, _D, _i32, _D)
_mesher_free = _sig("wr_py_mesher_free", None, _VP)
_triangulate = _sig("wr_py_triangulate", _VP, _D, _i32, _I, _i32, _D, _i32, _C.c_double, _C.c_double,
                    _C.c_char_p, _C.c_int)
_cdt_sizes = _sig("wr_py_cdt_sizes", None, _VP, _I, _I)
_cdt_get = _sig("wr_py_cdt_get", None, _VP, _D, _I)
_cdt_free = _sig("wr_py_cdt_free", None, _VP)
_statics = _sig("wr_py_statics", _VP, _C.c_char_p, _C.c_char_p, _C.c_char_p, _C.c_int)
_statics_sizes = _sig("wr_py_statics_sizes", None, _VP, _I, _I, _I, _I)
_statics_get = _sig("wr_py_statics_get", None, _VP, _D, _D, _D, _I)
_statics_free = _sig("wr_py_statics_free", None, _VP)
_tfw = _sig("wr_py_tfw", _VP, _i32, _D, _D, _i32, _I, _D, _C.c_double, _C.c_double, _C.c_double, _i32,
            _C.c_char_p, _C.c_int)
_tfw_sizes = _sig("wr_py_tfw_sizes", None, _VP, _I, _I, _I, _I, _I)
_tfw_edges = _sig("wr_py_tfw_edges", None, _VP, _I)
_tfw_get = _sig("wr_py_tfw_get", None, _VP, _D, _D, _D, _U8, _D, _I, _D)
_tfw_fine = _sig("wr_py_tfw_fine", None, _VP, _D, _U8)
_tfw_free = _sig("wr_py_tfw_free", None, _VP)
_render = _sig("wr_py_render_png", _C.c_int, _C.c_char_p, _i32, _C.POINTER(_D), _I, _C.POINTER(_I), _I,
               _C.POINTER(_D), _C.POINTER(_C.c_char_p), _i32, _i32, _i32, _C.c_double, _C.c_double,
               _C.c_char_p, _C.c_int)

_OK, _NOT_CONVERGED = 0, 11  # wr_status values (core.h's list order)


def _err():
    return _C.create_string_buffer(1024)


def _fail(buf, what):
    raise Error("%s: %s" % (what, buf.value.decode("utf-8", "replace")))


def _dptr(a):
    return a.ctypes.data_as(_D)


def _iptr(a):
    return a.ctypes.data_as(_I)


def _f64(x, shape_tail, name):
    a = _np.ascontiguousarray(x, dtype=_np.float64)
    if a.ndim != 1 + len(shape_tail) or tuple(a.shape[1:]) != tuple(shape_tail):
        raise Error("%s: expected shape (n, %s), got %s" % (name, ", ".join(map(str, shape_tail)), a.shape))
    if not _np.all(_np.isfinite(a)):
        raise Error("%s: contains a non-finite value" % name)
    return a


def _i32a(x, shape_tail, name):
    a = _np.ascontiguousarray(x, dtype=_np.int32)
    if a.ndim != 1 + len(shape_tail) or tuple(a.shape[1:]) != tuple(shape_tail):
        raise Error("%s: expected shape (n, %s), got %s" % (name, ", ".join(map(str, shape_tail)), a.shape))
    return a


def resolution(bending, young):
    """Optimal cloth mesh resolution r [m] from bending stiffness B [N·m] and Young's modulus E [N/m²]
    (Style3D Eq. 4 with the paper's constants): c1 r^6 + c2 r^4 = B/E."""
    r = _C.c_double(0.0)
    e = _err()
    if _resolution(float(bending), float(young), _C.byref(r), e, len(e)) != _OK:
        _fail(e, "resolution")
    return r.value


class PatternMesh:
    """A mesher result. pos (nv, 3) [m]; rest (nv, 2) pattern coordinates [m]; faces (nf, 3);
    face_panel (nf,); sizing (nv,) target edge length at each vertex [m]; panel_resolution
    (n_panels,) base resolution r of each panel [m]; sizing_at(panel, xy) evaluates the sizing map."""

    def __init__(self, handle):
        self._h = handle
        nv, nf, npn = _i32(), _i32(), _i32()
        _mesher_sizes(handle, _C.byref(nv), _C.byref(nf), _C.byref(npn))
        self.pos = _np.zeros((nv.value, 3))
        self.rest = _np.zeros((nv.value, 2))
        self.faces = _np.zeros((nf.value, 3), dtype=_np.int32)
        self.face_panel = _np.zeros(nf.value, dtype=_np.int32)
        self.sizing = _np.zeros(nv.value)
        self.panel_resolution = _np.zeros(npn.value)
        _mesher_get(handle, _dptr(self.pos), _dptr(self.rest), _iptr(self.faces), _iptr(self.face_panel),
                    _dptr(self.sizing), _dptr(self.panel_resolution))

    def sizing_at(self, panel, xy):
        """The panel's sizing map [m] at pattern points xy (n, 2) [m] (NaN outside its domain)."""
        p = _f64(_np.atleast_2d(xy), (2,), "xy")
        out = _np.zeros(len(p))
        _mesher_sizing(self._h, int(panel), _dptr(p), len(p), _dptr(out))
        return out

    def __del__(self):
        if getattr(self, "_h", None):
            _mesher_free(self._h)
            self._h = None


def mesh_pattern(pattern):
    """Sizing map and mesh of a garment pattern (Style3D Sec. 4). `pattern` is a dict (or JSON text)
    in the docs/pattern-format.md layout — coordinates in MILLIMETRES there, as in the files; the
    result is in metres."""
    text = pattern if isinstance(pattern, str) else _json.dumps(pattern)
    e = _err()
    h = _mesher_run(text.encode("utf-8"), e, len(e))
    if not h:
        _fail(e, "mesh_pattern")
    return PatternMesh(h)


def triangulate(points, segments=None, holes=None, min_angle=None, max_area=None):
    """Constrained Delaunay triangulation (exact predicates; Ruppert refinement when min_angle [deg]
    or max_area is given). points (n, 2); segments (s, 2) indices; holes (k, 2) seed points.
    Returns (points (m, 2), triangles (t, 3), counter-clockwise)."""
    p = _f64(points, (2,), "points")
    s = _i32a(segments if segments is not None else _np.zeros((0, 2)), (2,), "segments")
    h = _f64(holes if holes is not None else _np.zeros((0, 2)), (2,), "holes")
    e = _err()
    r = _triangulate(_dptr(p), len(p), _iptr(s), len(s), _dptr(h), len(h), float(min_angle or 0.0),
                     float(max_area or 0.0), e, len(e))
    if not r:
        _fail(e, "triangulate")
    try:
        n, t = _i32(), _i32()
        _cdt_sizes(r, _C.byref(n), _C.byref(t))
        pts = _np.zeros((n.value, 2))
        tri = _np.zeros((t.value, 3), dtype=_np.int32)
        _cdt_get(r, _dptr(pts), _iptr(tri))
    finally:
        _cdt_free(r)
    return pts, tri


class Statics:
    """A static equilibrium. rest_pos (nv, 3) and rest (nv, 2) [m]; pos (nv, 3) the solved positions
    [m]; faces (nf, 3); newton_iterations; converged (False: the best iterate is kept)."""


def statics(scene, base_dir="."):
    """Static equilibrium of a scene (dict or JSON text, docs/scene-format.md: mesh, material,
    boundary motions, gravity, load steps, solver) with statics.h."""
    text = scene if isinstance(scene, str) else _json.dumps(scene)
    e = _err()
    h = _statics(text.encode("utf-8"), str(base_dir).encode("utf-8"), e, len(e))
    if not h:
        _fail(e, "statics")
    try:
        nv, nf, it, st = _i32(), _i32(), _i32(), _i32()
        _statics_sizes(h, _C.byref(nv), _C.byref(nf), _C.byref(it), _C.byref(st))
        out = Statics()
        out.rest_pos = _np.zeros((nv.value, 3))
        out.rest = _np.zeros((nv.value, 2))
        out.pos = _np.zeros((nv.value, 3))
        out.faces = _np.zeros((nf.value, 3), dtype=_np.int32)
        _statics_get(h, _dptr(out.rest_pos), _dptr(out.rest), _dptr(out.pos), _iptr(out.faces))
        out.newton_iterations = it.value
        out.converged = st.value == _OK
    finally:
        _statics_free(h)
    return out


class TFW:
    """TFW wrinkle fields on a base surface. a (nv,) amplitude [m]; edges (ne, 2) and omega (ne,)
    the frequency one-form [rad, phase change from edges[:, 0] to edges[:, 1]]; phi (nf, 3) per-corner
    phase [rad]; wrinkle_free (nf,) bool; wrinkled_pos (n, 3), wrinkled_faces (m, 3) the Loop-upsampled
    wrinkled surface (Eq. 19) with, per vertex, wrinkled_a (n,) the amplitude [m], wrinkled_phase (n,)
    the phase [rad, wrapped to (-pi, pi]] and wrinkled_wrinkle_free (n,) bool (vertex touches only
    wrinkle-free faces): its height over the base is wrinkled_a * cos(wrinkled_phase); sqp_iterations;
    converged."""


def tfw(rest_pos, faces, base_pos, young, poisson, thickness, levels=2, rest=None):
    """TFW (Chen et al. 2021) on a base surface: wrinkle-free set, App. E.2 start, App. E.3 SQP, phase,
    App. E.5 upsampling (`levels` Loop levels; 0 = fields only). rest_pos (nv, 3) the rest shape [m]
    (flat: z = 0), faces (nf, 3) counter-clockwise in the rest domain, base_pos (nv, 3) the base
    surface (a TFT statics solution, see statics()), material E [Pa], ν, h [m]."""
    rp = _f64(rest_pos, (3,), "rest_pos")
    f = _i32a(faces, (3,), "faces")
    bp = _f64(base_pos, (3,), "base_pos")
    if len(bp) != len(rp):
        raise Error("base_pos has %d vertices, rest_pos %d" % (len(bp), len(rp)))
    r2 = _f64(rest, (2,), "rest") if rest is not None else None
    e = _err()
    h = _tfw(len(rp), _dptr(rp), _dptr(r2) if r2 is not None else None, len(f), _iptr(f), _dptr(bp),
             float(young), float(poisson), float(thickness), int(levels), e, len(e))
    if not h:
        _fail(e, "tfw")
    try:
        ne, fnv, fnf, it, st = _i32(), _i32(), _i32(), _i32(), _i32()
        _tfw_sizes(h, _C.byref(ne), _C.byref(fnv), _C.byref(fnf), _C.byref(it), _C.byref(st))
        out = TFW()
        out.a = _np.zeros(len(rp))
        out.edges = _np.zeros((ne.value, 2), dtype=_np.int32)
        out.omega = _np.zeros(ne.value)
        out.phi = _np.zeros((len(f), 3))
        wf = _np.zeros(len(f), dtype=_np.uint8)
        out.wrinkled_pos = _np.zeros((fnv.value, 3))
        out.wrinkled_faces = _np.zeros((fnf.value, 3), dtype=_np.int32)
        out.wrinkled_a = _np.zeros(fnv.value)
        out.wrinkled_phase = _np.zeros(fnv.value)
        fw = _np.zeros(fnv.value, dtype=_np.uint8)
        _tfw_edges(h, _iptr(out.edges))
        _tfw_get(h, _dptr(out.a), _dptr(out.omega), _dptr(out.phi), wf.ctypes.data_as(_U8),
                 _dptr(out.wrinkled_pos), _iptr(out.wrinkled_faces), _dptr(out.wrinkled_a))
        _tfw_fine(h, _dptr(out.wrinkled_phase), fw.ctypes.data_as(_U8))
        out.wrinkled_wrinkle_free = fw.astype(bool)
        out.wrinkle_free = wf.astype(bool)
        out.sqp_iterations = it.value
        out.converged = st.value == _OK
    finally:
        _tfw_free(h)
    return out


def render_png(path, views, columns=None, size=(900, 500), view=None):
    """Draw meshes side by side into a PNG with the kit's renderer (render.h). views: a list of
    (pos (n, 3), faces (m, 3), scalar (n,) or None, title). A scalar with both signs gets the
    diverging blue-white-red map, else the sequential one; the first view shows its edges.
    size: pixels of each view; view: (azimuth, elevation) in degrees, e.g. (-90, 90) looks straight
    down on a flat pattern (default: a three-quarter view from the front left)."""
    n = len(views)
    keep = []
    pos = (_D * n)()
    faces = (_I * n)()
    scal = (_D * n)()
    nv = (_C.c_int32 * n)()
    nf = (_C.c_int32 * n)()
    titles = (_C.c_char_p * n)()
    for i, v in enumerate(views):
        p = _f64(v[0], (3,), "views[%d].pos" % i)
        f = _i32a(v[1], (3,), "views[%d].faces" % i)
        if f.size and (f.min() < 0 or f.max() >= len(p)):
            raise Error("views[%d].faces: index outside 0..%d" % (i, len(p) - 1))
        keep += [p, f]
        pos[i], faces[i], nv[i], nf[i] = _dptr(p), _iptr(f), len(p), len(f)
        if len(v) > 2 and v[2] is not None:
            s = _np.ascontiguousarray(v[2], dtype=_np.float64)
            if s.shape != (len(p),):
                raise Error("views[%d].scalar: expected %d values" % (i, len(p)))
            keep.append(s)
            scal[i] = _dptr(s)
        t = (v[3] if len(v) > 3 and v[3] else "").encode("utf-8")
        keep.append(t)
        titles[i] = t
    e = _err()
    az, el = view if view is not None else (float("nan"), float("nan"))
    if _render(str(path).encode("utf-8"), n, pos, nv, faces, nf, scal, titles, int(columns or n), int(size[0]),
               int(size[1]), float(az), float(el), e, len(e)) != _OK:
        _fail(e, "render_png")
