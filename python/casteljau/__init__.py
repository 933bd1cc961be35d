"""casteljau for Python: Bézier, rational and B-spline/NURBS curves, patches and B-spline
surfaces, certified plane-curve queries, scenes and renderers.

A thin layer over the C library's public API (compiled through cffi into the extension
module casteljau._casteljau_cffi). NumPy arrays go in and come out; every failure of the
library raises CasteljauError carrying the library's own message (cj_last_error).

    import casteljau as cj
    c = cj.Bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
    c.eval([0.0, 0.5, 1.0])            # (3, 2) array of points
    c.eval_bound(0.5)                  # compensated value and a proven error bound
    pts, bound = c.flatten(1e-3)       # polyline within 1e-3 of the curve (bound proven)

See docs/python.md for the whole interface.
"""

import math

import numpy as np

from casteljau._casteljau_cffi import ffi, lib

try:  # written by CMake: where the build (or install) keeps the shipped data
    from casteljau import _paths
except ImportError:  # pragma: no cover - a copy of the sources without the build's file
    _paths = None

__all__ = [
    "CasteljauError",
    "Bezier",
    "RationalBezier",
    "Patch",
    "Mesh",
    "tessellate",
    "load_bpt",
    "teapot",
    "Scene",
    "Image",
    "BSpline",
    "BSplineSurface",
    "Intersection",
    "Nearest",
    "intersect",
    "nearest",
    "offset",
]

_METHODS = {
    "decasteljau": lib.CJ_EVAL_DECASTELJAU,
    "bernstein": lib.CJ_EVAL_BERNSTEIN,
    "horner": lib.CJ_EVAL_HORNER,
    "compensated": lib.CJ_EVAL_COMPENSATED,
}
_FLATTEN = {
    "uniform": lib.CJ_FLATTEN_UNIFORM,
    "subdivide": lib.CJ_FLATTEN_SUBDIVIDE,
    "near_optimal": lib.CJ_FLATTEN_NEAR_OPTIMAL,
}
_LIGHTS = {
    "ambient": lib.CJ_LIGHT_AMBIENT,
    "point": lib.CJ_LIGHT_POINT,
    "directional": lib.CJ_LIGHT_DIRECTIONAL,
    "spot": lib.CJ_LIGHT_SPOT,
}


class CasteljauError(Exception):
    """A status other than CJ_OK from the library.

    str(error) is the library's message naming the offending input; `status` is the numeric
    cj_status and `status_name` its short description (cj_status_str)."""

    def __init__(self, status, message, what=None):
        self.status = int(status)
        self.status_name = ffi.string(lib.cj_status_str(status)).decode()
        self.function = what
        super().__init__(message or self.status_name)


def _check(status, what):
    if status != lib.CJ_OK:
        message = ffi.string(lib.cj_last_error()).decode("utf-8", "replace")
        raise CasteljauError(status, message, what)


def _doubles(values, name):
    """A C-contiguous float64 copy-or-view of `values` and its cffi pointer."""
    arr = np.ascontiguousarray(values, dtype=np.float64)
    return arr, ffi.cast("double *", ffi.from_buffer(arr))


def _out(shape, dtype=np.float64):
    arr = np.empty(shape, dtype=dtype)
    ctype = {np.float64: "double *", np.float32: "float *", np.uint8: "uint8_t *"}[dtype]
    return arr, ffi.cast(ctype, ffi.from_buffer(arr))


def _method(name):
    try:
        return _METHODS[name]
    except KeyError:
        raise ValueError(f"unknown method {name!r}: one of {', '.join(_METHODS)}") from None


def _params(t):
    """(array of parameters, True if the caller gave a scalar)."""
    arr = np.asarray(t, dtype=np.float64)
    return np.atleast_1d(arr).ravel(), arr.ndim == 0


# ---- curves ----------------------------------------------------------------------------


class Bezier:
    """A polynomial Bézier curve c(t) = Σ b_i B_i^n(t), t in [0, 1].

    points: (n+1, d) array of control points, d in 1..8 (a 1-D array is a curve in 1-D).
    The curve keeps its own float64 copy; validation happens in the C library, so bad data
    (NaN, a degree beyond the limit) raises CasteljauError naming the point."""

    def __init__(self, points):
        pts = np.array(points, dtype=np.float64)
        if pts.ndim == 1:
            pts = pts.reshape(-1, 1)
        if pts.ndim != 2 or pts.shape[0] == 0:
            raise ValueError("points must be an (n+1, d) array with n+1 >= 1")
        self.points = np.ascontiguousarray(pts)
        self.points.setflags(write=False)
        self._c = ffi.new("cj_bezier *")
        self._c.degree = self.points.shape[0] - 1
        self._c.dim = self.points.shape[1]
        self._c.pts = ffi.cast("double *", ffi.from_buffer(self.points))

    @property
    def degree(self):
        return self._c.degree

    @property
    def dim(self):
        return self._c.dim

    def __repr__(self):
        return f"Bezier(degree={self.degree}, dim={self.dim})"

    def eval(self, t, method="decasteljau"):
        """c(t): a (d,) array for a scalar t, else an (len(t), d) array (cj_bezier_eval_batch)."""
        ts, scalar = _params(t)
        tsa, tsp = _doubles(ts, "t")
        out, outp = _out((ts.size, self.dim))
        _check(lib.cj_bezier_eval_batch(self._c, _method(method), tsp, ts.size, outp),
               "cj_bezier_eval_batch")
        return out[0] if scalar else out

    __call__ = eval

    def eval_bound(self, t):
        """Compensated value and its a-posteriori error bound per coordinate:
        (value, bound), each shaped as eval's result; |value - c(t)| <= bound."""
        ts, scalar = _params(t)
        vals, vp = _out((ts.size, self.dim))
        bounds, bp = _out((ts.size, self.dim))
        for j, tj in enumerate(ts):
            _check(lib.cj_bezier_eval_compensated(self._c, float(tj), vp + j * self.dim,
                                                  bp + j * self.dim),
                   "cj_bezier_eval_compensated")
        return (vals[0], bounds[0]) if scalar else (vals, bounds)

    def error_bound(self, t, method="decasteljau"):
        """A-priori absolute error bound of `method` at t, per coordinate (cj_bezier_error_bound)."""
        ts, scalar = _params(t)
        out, op = _out((ts.size, self.dim))
        m = _method(method)
        for j, tj in enumerate(ts):
            _check(lib.cj_bezier_error_bound(self._c, m, float(tj), op + j * self.dim),
                   "cj_bezier_error_bound")
        return out[0] if scalar else out

    def derivatives(self, t, kmax=1):
        """Point and derivatives 0..kmax at t: a (kmax+1, d) array, row j = c^(j)(t)."""
        if kmax < 0:
            raise ValueError("kmax must be >= 0")
        out, op = _out((kmax + 1, self.dim))
        _check(lib.cj_bezier_eval_derivs(self._c, float(t), int(kmax), op),
               "cj_bezier_eval_derivs")
        return out

    def hodograph(self, k=1):
        """The k-th derivative as a Bézier curve of degree max(n-k, 0)."""
        n = max(self.degree - k, 0)
        out, op = _out((n + 1, self.dim))
        _check(lib.cj_bezier_hodograph(self._c, int(k), op), "cj_bezier_hodograph")
        return Bezier(out)

    def split(self, t):
        """(left, right): the curve on [0, t] and on [t, 1], each reparametrised to [0, 1]."""
        left, lp = _out(self.points.shape)
        right, rp = _out(self.points.shape)
        _check(lib.cj_bezier_split(self._c, float(t), lp, rp), "cj_bezier_split")
        return Bezier(left), Bezier(right)

    def bbox(self):
        """Tight axis-aligned box of c([0, 1]): (lo, hi), each a (d,) array."""
        lo, lp = _out(self.dim)
        hi, hp = _out(self.dim)
        _check(lib.cj_bezier_bbox(self._c, lp, hp), "cj_bezier_bbox")
        return lo, hi

    def arclength(self, tol=1e-10, a=0.0, b=1.0):
        """Arc length on [a, b] to absolute tolerance tol: (length, error estimate)."""
        length = ffi.new("double *")
        err = ffi.new("double *")
        _check(lib.cj_bezier_arclength(self._c, float(a), float(b), float(tol), length, err),
               "cj_bezier_arclength")
        return length[0], err[0]

    def curvature(self, t):
        """Curvature at t (signed in 2-D, >= 0 in 3-D)."""
        kappa = ffi.new("double *")
        _check(lib.cj_bezier_curvature(self._c, float(t), kappa), "cj_bezier_curvature")
        return kappa[0]

    def flatten(self, tol, method="near_optimal", max_segments=0):
        """A polyline within tol of the curve: (points (m, d), proven bound <= tol)."""
        return _flatten(lib.cj_flatten_bezier, self._c, self.dim, tol, method, max_segments)


class RationalBezier:
    """A rational Bézier curve c(t) = Σ w_i b_i B_i^n(t) / Σ w_i B_i^n(t).

    points: (n+1, d) control points, d in 1..7; weights: n+1 finite weights > 0."""

    def __init__(self, points, weights):
        pts = np.array(points, dtype=np.float64)
        if pts.ndim == 1:
            pts = pts.reshape(-1, 1)
        w = np.array(weights, dtype=np.float64).ravel()
        if pts.ndim != 2 or pts.shape[0] == 0 or w.size != pts.shape[0]:
            raise ValueError("points must be (n+1, d) and weights n+1 values")
        self.points = np.ascontiguousarray(pts)
        self.weights = np.ascontiguousarray(w)
        self.points.setflags(write=False)
        self.weights.setflags(write=False)
        self._c = ffi.new("cj_rbezier *")
        self._c.degree = self.points.shape[0] - 1
        self._c.dim = self.points.shape[1]
        self._c.pts = ffi.cast("double *", ffi.from_buffer(self.points))
        self._c.weights = ffi.cast("double *", ffi.from_buffer(self.weights))

    @classmethod
    def ellipse_arcs(cls, center, rx, ry, a0, a1, rotation=0.0):
        """The exact conic arcs of the ellipse arc from angle a0 to a1 (radians), as a list of
        quadratic RationalBezier pieces (cj_rbezier_ellipse_arcs)."""
        pieces = lib.cj_rbezier_arc_pieces(float(a0), float(a1))
        if pieces <= 0:
            raise CasteljauError(lib.CJ_ERR_RANGE, f"sweep from {a0} to {a1} is not in [-2pi, 2pi]")
        pts, pp = _out((pieces, 3, 2))
        w, wp = _out((pieces, 3))
        count = ffi.new("int *")
        _check(lib.cj_rbezier_ellipse_arcs(float(center[0]), float(center[1]), float(rx),
                                           float(ry), float(rotation), float(a0), float(a1),
                                           pp, wp, pieces, count),
               "cj_rbezier_ellipse_arcs")
        return [cls(pts[i], w[i]) for i in range(count[0])]

    @property
    def degree(self):
        return self._c.degree

    @property
    def dim(self):
        return self._c.dim

    def __repr__(self):
        return f"RationalBezier(degree={self.degree}, dim={self.dim})"

    def eval(self, t):
        """c(t): a (d,) array for a scalar t, else (len(t), d)."""
        ts, scalar = _params(t)
        out, op = _out((ts.size, self.dim))
        for j, tj in enumerate(ts):
            _check(lib.cj_rbezier_eval(self._c, float(tj), op + j * self.dim), "cj_rbezier_eval")
        return out[0] if scalar else out

    __call__ = eval

    def derivatives(self, t, kmax=1):
        """Point and derivatives 0..kmax at t: a (kmax+1, d) array."""
        if kmax < 0:
            raise ValueError("kmax must be >= 0")
        out, op = _out((kmax + 1, self.dim))
        _check(lib.cj_rbezier_eval_derivs(self._c, float(t), int(kmax), op),
               "cj_rbezier_eval_derivs")
        return out

    def flatten(self, tol, method="near_optimal", max_segments=0):
        """A polyline within tol of the curve: (points (m, d), proven bound <= tol)."""
        return _flatten(lib.cj_flatten_rbezier, self._c, self.dim, tol, method, max_segments)


def _flatten(fn, curve, dim, tol, method, max_segments):
    if method not in _FLATTEN:
        raise ValueError(f"unknown method {method!r}: one of {', '.join(_FLATTEN)}")
    opts = ffi.new("cj_flatten_opts *")
    opts.method = _FLATTEN[method]
    opts.tol = float(tol)
    opts.max_segments = int(max_segments)
    npoints = ffi.new("size_t *")
    _check(fn(curve, opts, ffi.NULL, 0, npoints, ffi.NULL), "flatten (count)")
    out, op = _out((npoints[0], dim))
    stats = ffi.new("cj_flatten_stats *")
    _check(fn(curve, opts, op, npoints[0], npoints, stats), "flatten")
    return out, stats.bound


# ---- patches and meshes ------------------------------------------------------------------


class Patch:
    """A tensor-product Bézier patch in 3-D, polynomial or rational.

    points: (m+1, n+1, 3) array, points[i, j] = b_ij (i along u, j along v);
    weights: None or an (m+1, n+1) array of weights > 0."""

    def __init__(self, points, weights=None):
        pts = np.array(points, dtype=np.float64)
        if pts.ndim != 3 or pts.shape[2] != 3 or pts.shape[0] == 0 or pts.shape[1] == 0:
            raise ValueError("points must be an (m+1, n+1, 3) array")
        # The library stores point j*(m+1)+i: v-major.
        self._pts = np.ascontiguousarray(pts.transpose(1, 0, 2))
        self._w = None
        if weights is not None:
            w = np.array(weights, dtype=np.float64)
            if w.shape != pts.shape[:2]:
                raise ValueError("weights must be an (m+1, n+1) array")
            self._w = np.ascontiguousarray(w.T)
        self._p = ffi.new("cj_patch *")
        self._fill(self._p)

    def _fill(self, p):
        p.deg_u = self._pts.shape[1] - 1
        p.deg_v = self._pts.shape[0] - 1
        p.pts = ffi.cast("double *", ffi.from_buffer(self._pts))
        p.weights = ffi.NULL if self._w is None else ffi.cast("double *", ffi.from_buffer(self._w))

    @property
    def points(self):
        """(m+1, n+1, 3) control points, points[i, j] = b_ij."""
        return self._pts.transpose(1, 0, 2).copy()

    @property
    def degree(self):
        return (self._p.deg_u, self._p.deg_v)

    def __repr__(self):
        kind = "rational " if self._w is not None else ""
        return f"Patch({kind}degree={self.degree})"

    def eval(self, u, v, method="decasteljau"):
        """The point S(u, v): a (3,) array."""
        out, op = _out(3)
        _check(lib.cj_patch_eval(self._p, _method(method), float(u), float(v), op),
               "cj_patch_eval")
        return out

    def normal(self, u, v):
        """The unit normal at (u, v) (limit direction at degenerate corners)."""
        out, op = _out(3)
        _check(lib.cj_patch_normal(self._p, float(u), float(v), op, ffi.NULL), "cj_patch_normal")
        return out


class Mesh:
    """A triangle mesh as arrays: positions (V, 3), normals (V, 3), uvs (V, 2), triangles
    (T, 3) uint32 counter-clockwise from outside, patch (T,) int32 (index of the patch each
    triangle came from), and `bound`, the proven max distance from the patches to the mesh."""

    def __init__(self, positions, normals, uvs, triangles, patch, bound, measured):
        self.positions = positions
        self.normals = normals
        self.uvs = uvs
        self.triangles = triangles
        self.patch = patch
        self.bound = bound
        self.measured = measured

    def __repr__(self):
        return (f"Mesh(vertices={len(self.positions)}, triangles={len(self.triangles)}, "
                f"bound={self.bound:.3g})")


def tessellate(patches, tol=None, uniform=0, weld=True, measure=0):
    """Tessellates patches into one Mesh (cj_tessellate_patches): adaptive to distance tol,
    or uniform K x K per patch when uniform=K > 0. weld=True merges the bit-identical vertices
    of shared edges (cj_mesh_weld), so a closed surface gives a watertight mesh. measure=N > 0
    also measures the deviation on an N-step lattice per triangle (Mesh.measured)."""
    if isinstance(patches, Patch):
        patches = [patches]
    patches = list(patches)
    if not patches:
        raise ValueError("no patches")
    if tol is None and uniform <= 0:
        raise ValueError("give tol (adaptive) or uniform=K")
    arr = ffi.new("cj_patch[]", len(patches))
    for i, p in enumerate(patches):
        p._fill(arr[i])
    opt = ffi.new("cj_tess_options *")
    opt.tol = float(tol) if tol is not None else 0.0
    opt.uniform = int(uniform)
    opt.measure = int(measure)
    rep = ffi.new("cj_tess_report *")
    meshp = ffi.new("cj_mesh **")
    _check(lib.cj_mesh_create(ffi.NULL, meshp), "cj_mesh_create")
    mesh = ffi.gc(meshp[0], lib.cj_mesh_destroy)
    _check(lib.cj_tessellate_patches(arr, len(patches), opt, mesh, rep), "cj_tessellate_patches")
    if weld:
        _check(lib.cj_mesh_weld(mesh, ffi.NULL), "cj_mesh_weld")
    nv, nt = mesh.vertex_count, mesh.triangle_count

    def grab(ptr, count, dtype, cols):
        if count == 0:
            return np.empty((0, cols) if cols > 1 else 0, dtype=dtype)
        buf = ffi.buffer(ptr, count * cols * np.dtype(dtype).itemsize)
        a = np.frombuffer(buf, dtype=dtype).copy()
        return a.reshape(count, cols) if cols > 1 else a

    return Mesh(grab(mesh.positions, nv, np.float64, 3), grab(mesh.normals, nv, np.float64, 3),
                grab(mesh.uvs, nv, np.float64, 2), grab(mesh.triangles, nt, np.uint32, 3),
                grab(mesh.triangle_patch, nt, np.int32, 1), rep.bound, rep.measured)


def load_bpt(path):
    """The bicubic patches of a .bpt file (the Utah teapot's format) as a list of Patch."""
    setp = ffi.new("cj_patchset **")
    _check(lib.cj_patchset_load_bpt(str(path).encode(), ffi.NULL, setp), "cj_patchset_load_bpt")
    s = ffi.gc(setp[0], lib.cj_patchset_destroy)
    out = []
    for k in range(s.count):
        p = s.patches[k]
        m, n = p.deg_u, p.deg_v
        flat = np.frombuffer(ffi.buffer(p.pts, 3 * (m + 1) * (n + 1) * 8), dtype=np.float64)
        out.append(Patch(flat.reshape(n + 1, m + 1, 3).transpose(1, 0, 2)))
    return out


def _teapot_path():
    if _paths is None or not _paths.TEAPOT:
        raise CasteljauError(lib.CJ_ERR_UNSUPPORTED, "this copy does not know where teapot.bpt is")
    return _paths.TEAPOT


def teapot():
    """The Utah teapot's 32 bicubic patches (data/teapot.bpt)."""
    return load_bpt(_teapot_path())


# ---- scenes and pictures -----------------------------------------------------------------


class Image:
    """A rendered picture as arrays, TOP row first (as image files and matplotlib expect):
    rgba (H, W, 4) float32 linear radiance with straight alpha, ids (H, W) uint32 object ids
    (0 = background) and depth (H, W) float32 pseudodepth (+1 = background)."""

    def __init__(self, rgba, ids, depth):
        self.rgba = rgba
        self.ids = ids
        self.depth = depth

    @property
    def shape(self):
        return self.rgba.shape[:2]

    def srgb8(self):
        """8-bit sRGB RGBA (H, W, 4) uint8, converted by the library (cj_render_image_to_srgb8)."""
        h, w = self.shape
        img = ffi.new("cj_render_image *")
        img.width, img.height = w, h
        linear = np.ascontiguousarray(self.rgba[::-1])  # back to bottom row first
        img.rgba = ffi.cast("float *", ffi.from_buffer(linear))
        out, op = _out((h, w, 4), np.uint8)
        _check(lib.cj_render_image_to_srgb8(img, op, 0), "cj_render_image_to_srgb8")
        return out[::-1].copy()


def _vec3(v, out):
    x, y, z = (float(c) for c in v)
    out.x, out.y, out.z = x, y, z


def _rgb(c, out):
    r, g, b = (float(x) for x in c)
    out.r, out.g, out.b = r, g, b


class Scene:
    """A scene: camera, lights, materials, objects (cj_scene). Load one from JSON
    (Scene.load, Scene.from_json) or build one: Scene(), then set_camera, add_light,
    add_material, add_sphere / add_patches. render() and trace() return an Image."""

    def __init__(self, _ptr=None):
        if _ptr is None:
            pp = ffi.new("cj_scene **")
            _check(lib.cj_scene_create(ffi.NULL, pp), "cj_scene_create")
            _ptr = pp[0]
        self._s = ffi.gc(_ptr, lib.cj_scene_destroy)

    @classmethod
    def load(cls, path):
        """Reads a scene file (the JSON format of docs/scenes.md). Image textures are not
        loaded (that needs the image layer): render such scenes with the command-line tool."""
        opts = ffi.new("cj_scene_json_options *")
        teapot_c = ffi.new("char[]", _teapot_path().encode()) if _paths else ffi.NULL
        opts.teapot_path = teapot_c
        pp = ffi.new("cj_scene **")
        _check(lib.cj_scene_load_json_with_options(str(path).encode(), opts, ffi.NULL, pp),
               "cj_scene_load_json_with_options")
        return cls(pp[0])

    @classmethod
    def from_json(cls, text, name="<string>", base_dir="."):
        """Parses a scene from JSON text; `name` is used in error messages, `base_dir`
        resolves relative file names in it."""
        opts = ffi.new("cj_scene_json_options *")
        teapot_c = ffi.new("char[]", _teapot_path().encode()) if _paths else ffi.NULL
        opts.teapot_path = teapot_c
        pp = ffi.new("cj_scene **")
        _check(lib.cj_scene_parse_json_with_options(text.encode(), name.encode(), str(base_dir).encode(),
                                          opts, ffi.NULL, pp),
               "cj_scene_parse_json_with_options")
        return cls(pp[0])

    def save(self, path):
        """Writes the scene as JSON (cj_scene_save_json)."""
        _check(lib.cj_scene_save_json(self._s, str(path).encode()), "cj_scene_save_json")

    @property
    def node_count(self):
        return lib.cj_scene_node_count(self._s)

    @property
    def light_count(self):
        return lib.cj_scene_light_count(self._s)

    def set_camera(self, eye=(0, 0, 5), look_at=(0, 0, 0), up=(0, 1, 0), fov_deg=45.0,
                   near=-0.1, far=-100.0):
        """A perspective camera at `eye` looking at `look_at` (near, far < 0 as in the seed)."""
        cam = ffi.new("cj_camera *", lib.cj_camera_defaults())
        _vec3(eye, cam.eye)
        _vec3(np.subtract(look_at, eye), cam.gaze)
        _vec3(up, cam.up)
        cam.fov_y = math.radians(float(fov_deg))
        cam.near, cam.far = float(near), float(far)
        _check(lib.cj_scene_set_camera(self._s, cam), "cj_scene_set_camera")

    def set_settings(self, width=None, height=None, spp=None, background=None, tol_px=None):
        """Changes the render settings stored with the scene (None keeps a value)."""
        s = ffi.new("cj_scene_settings *", lib.cj_scene_get_settings(self._s)[0])
        if width is not None:
            s.width = int(width)
        if height is not None:
            s.height = int(height)
        if spp is not None:
            s.spp = int(spp)
        if tol_px is not None:
            s.tol_px = float(tol_px)
        if background is not None:
            _rgb(background, s.background)
        _check(lib.cj_scene_set_settings(self._s, s), "cj_scene_set_settings")

    def add_light(self, kind="point", color=(1, 1, 1), intensity=1.0, position=None,
                  direction=None):
        """Adds an ambient, point, directional or spot light; returns its index."""
        if kind not in _LIGHTS:
            raise ValueError(f"unknown light {kind!r}: one of {', '.join(_LIGHTS)}")
        light = ffi.new("cj_light *", lib.cj_light_defaults(_LIGHTS[kind]))
        _rgb(color, light.color)
        light.intensity = float(intensity)
        if position is not None:
            _vec3(position, light.position)
        if direction is not None:
            _vec3(direction, light.direction)
        index = ffi.new("int *")
        _check(lib.cj_scene_add_light(self._s, light, index), "cj_scene_add_light")
        return index[0]

    def add_material(self, color=(0.8, 0.8, 0.8), ka=None, kd=None, ks=None, alpha=None,
                     two_sided=None, opacity=None, mirror=None, transmission=None, ior=None):
        """Adds a Phong material (defaults: cj_material_defaults); returns its index."""
        m = ffi.new("cj_material *", lib.cj_material_defaults())
        _rgb(color, m.color)
        for name, value in (("ka", ka), ("kd", kd), ("ks", ks), ("alpha", alpha),
                            ("opacity", opacity), ("mirror", mirror),
                            ("transmission", transmission), ("ior", ior)):
            if value is not None:
                setattr(m, name, float(value))
        if two_sided is not None:
            m.two_sided = 1 if two_sided else 0
        index = ffi.new("int *")
        _check(lib.cj_scene_add_material(self._s, m, index), "cj_scene_add_material")
        return index[0]

    def _add_object(self, geom, material, translate, scale):
        gi = ffi.new("int *")
        _check(lib.cj_scene_add_geometry(self._s, geom, gi), "cj_scene_add_geometry")
        node = ffi.new("cj_node *", lib.cj_node_defaults(gi[0], int(material)))
        if translate is not None:
            _vec3(translate, node.local.translate)
        if scale is not None:
            s = (scale, scale, scale) if np.isscalar(scale) else scale
            _vec3(s, node.local.scale)
        ni = ffi.new("int *")
        _check(lib.cj_scene_add_node(self._s, node, ni), "cj_scene_add_node")
        return ni[0]

    def add_sphere(self, center, radius, material, translate=None, scale=None):
        """Adds a sphere object; returns its node index (object id = node index + 1)."""
        geom = ffi.new("cj_geometry *", lib.cjpy_sphere(float(center[0]), float(center[1]),
                                                        float(center[2]), float(radius)))
        return self._add_object(geom, material, translate, scale)

    def add_patches(self, patches, material, translate=None, scale=None):
        """Adds one object made of Bézier patches (copied); returns its node index."""
        if isinstance(patches, Patch):
            patches = [patches]
        patches = list(patches)
        arr = ffi.new("cj_patch[]", len(patches))
        for i, p in enumerate(patches):
            p._fill(arr[i])
        geom = ffi.new("cj_geometry *", lib.cjpy_patches(arr, len(patches)))
        return self._add_object(geom, material, translate, scale)

    def check(self):
        """Validates the scene; raises CasteljauError naming the first bad part."""
        _check(lib.cj_scene_check(self._s), "cj_scene_check")

    def _image(self, fn, what, width, height, spp, threads, seed):
        opt = ffi.new("cj_render_options *", lib.cj_render_options_defaults())
        opt.width = int(width or 0)
        opt.height = int(height or 0)
        opt.spp = int(spp or 0)
        opt.threads = int(threads or 0)
        if seed is not None:
            opt.use_seed = 1
            opt.seed = int(seed)
        pp = ffi.new("cj_render_image **")
        _check(fn(self._s, opt, lib.CJ_IMAGE_IDS | lib.CJ_IMAGE_DEPTH, ffi.NULL, pp, ffi.NULL),
               what)
        img = ffi.gc(pp[0], lib.cj_render_image_destroy)
        w, h = img.width, img.height
        rgba = np.frombuffer(ffi.buffer(img.rgba, w * h * 16), dtype=np.float32)
        ids = np.frombuffer(ffi.buffer(img.ids, w * h * 4), dtype=np.uint32)
        depth = np.frombuffer(ffi.buffer(img.depth, w * h * 4), dtype=np.float32)
        # Bottom row first in the library; top row first here, copied out of the C image.
        return Image(rgba.reshape(h, w, 4)[::-1].copy(), ids.reshape(h, w)[::-1].copy(),
                     depth.reshape(h, w)[::-1].copy())

    def render(self, width=None, height=None, spp=None, threads=None):
        """Draws the scene with the exact triangle rasterizer (cj_render_raster); None takes
        the scene's settings; spp 1, 4 or 16."""
        return self._image(lib.cj_render_raster, "cj_render_raster", width, height, spp,
                           threads, None)

    def trace(self, width=None, height=None, spp=None, threads=None, seed=None):
        """Ray traces the scene (cj_render_trace): patches hit directly, shadows, mirrors,
        refraction; any spp >= 1; seed overrides the scene's sampling seed."""
        return self._image(lib.cj_render_trace, "cj_render_trace", width, height, spp,
                           threads, seed)


# B-splines, NURBS and the plane-curve queries live in splines.py (it uses the helpers above).
from casteljau.splines import (  # noqa: E402
    BSpline,
    BSplineSurface,
    Intersection,
    Nearest,
    intersect,
    nearest,
    offset,
)
