"""B-spline and NURBS curves and surfaces, and the certified plane-curve queries.

Part of `import casteljau` (re-exported there): BSpline, BSplineSurface, intersect, nearest,
offset. Thin wrappers over bspline.h, bspline_fit.h, bspline_surface.h, intersect.h, nearest.h
and offset.h; every failure raises CasteljauError with the library's message.
"""

import numpy as np

from casteljau import Bezier, Patch, RationalBezier, _check, _doubles, _out, _params
from casteljau._casteljau_cffi import ffi, lib

_FIT = {
    "uniform": lib.CJ_FIT_UNIFORM,
    "chord": lib.CJ_FIT_CHORD,
    "centripetal": lib.CJ_FIT_CENTRIPETAL,
}


def _ptr(arr):
    return ffi.NULL if arr is None else ffi.cast("double *", ffi.from_buffer(arr))


def _frozen(values, shape_check, message):
    arr = np.ascontiguousarray(np.array(values, dtype=np.float64))
    if not shape_check(arr):
        raise ValueError(message)
    arr.setflags(write=False)
    return arr


def _clamped_knots(npts, degree):
    """The clamped uniform knot vector over [0, 1] (cj_bspline_uniform_knots)."""
    knots, kp = _out(npts + degree + 1)
    _check(lib.cj_bspline_uniform_knots(int(npts), int(degree), 0.0, 1.0, 1, kp),
           "cj_bspline_uniform_knots")
    return knots


def _fit_kind(param):
    try:
        return _FIT[param]
    except KeyError:
        raise ValueError(f"unknown parametrisation {param!r}: one of {', '.join(_FIT)}") from None


class BSpline:
    """A B-spline curve c(t) = Σ d_i N_{i,p}(t), or a NURBS when weights are given.

    points: (n+1, d) control points (d in 1..8, NURBS 1..7); degree p (n+1 >= p+1);
    knots: n+p+2 non-decreasing values, or None for the clamped uniform vector over [0, 1];
    weights: None (polynomial) or n+1 weights > 0. The curve is validated by the library
    (cj_bspline_check) when built: bad data raises CasteljauError naming the input."""

    def __init__(self, points, degree=3, knots=None, weights=None):
        pts = np.array(points, dtype=np.float64)
        if pts.ndim == 1:
            pts = pts.reshape(-1, 1)
        if pts.ndim != 2 or pts.shape[0] == 0:
            raise ValueError("points must be an (n+1, d) array with n+1 >= 1")
        npts = pts.shape[0]
        degree = int(degree)
        if degree < 0:
            raise ValueError("degree must be >= 0")
        if knots is None:
            if npts < degree + 1:
                raise ValueError(f"{npts} points are too few for degree {degree}")
            knots = _clamped_knots(npts, degree)
        self.points = _frozen(pts, lambda a: True, "")
        self.knots = _frozen(np.ravel(knots), lambda a: a.size == npts + degree + 1,
                             f"knots must hold npts + degree + 1 = {npts + degree + 1} values")
        self.weights = None
        if weights is not None:
            self.weights = _frozen(np.ravel(weights), lambda a: a.size == npts,
                                   f"weights must hold {npts} values")
        self._c = ffi.new("cj_bspline *")
        self._c.degree = degree
        self._c.dim = pts.shape[1]
        self._c.npts = npts
        self._c.pts = _ptr(self.points)
        self._c.weights = _ptr(self.weights)
        self._c.knots = _ptr(self.knots)
        _check(lib.cj_bspline_check(self._c), "cj_bspline_check")

    @property
    def degree(self):
        return self._c.degree

    @property
    def dim(self):
        return self._c.dim

    @property
    def rational(self):
        return self.weights is not None

    @property
    def domain(self):
        """(t0, t1): the parameter domain [t_p, t_{n+1}]."""
        t0 = ffi.new("double *")
        t1 = ffi.new("double *")
        _check(lib.cj_bspline_domain(self._c, t0, t1), "cj_bspline_domain")
        return t0[0], t1[0]

    def __repr__(self):
        kind = "NURBS" if self.rational else "BSpline"
        return f"{kind}(degree={self.degree}, dim={self.dim}, npts={self.points.shape[0]})"

    def eval(self, t):
        """c(t): a (d,) array for a scalar t, else (len(t), d) (cj_bspline_eval_batch).
        A t outside the domain raises CasteljauError."""
        ts, scalar = _params(t)
        tsa, tsp = _doubles(ts, "t")
        out, op = _out((ts.size, self.dim))
        _check(lib.cj_bspline_eval_batch(self._c, tsp, ts.size, op), "cj_bspline_eval_batch")
        return out[0] if scalar else out

    __call__ = eval

    def derivatives(self, t, kmax=1):
        """Point and derivatives 0..kmax: (kmax+1, d) for a scalar t (row j = c^(j)(t)),
        else (len(t), kmax+1, d) (cj_bspline_eval_derivs)."""
        if kmax < 0:
            raise ValueError("kmax must be >= 0")
        ts, scalar = _params(t)
        out, op = _out((ts.size, kmax + 1, self.dim))
        step = (kmax + 1) * self.dim
        for j, tj in enumerate(ts):
            _check(lib.cj_bspline_eval_derivs(self._c, float(tj), int(kmax), op + j * step),
                   "cj_bspline_eval_derivs")
        return out[0] if scalar else out

    def error_bound(self, t, kmax=None):
        """Proven a-priori absolute error bound per coordinate of eval (kmax None:
        cj_bspline_error_bound, shaped as eval's result) or of derivatives(t, kmax)
        (cj_bspline_derivs_error_bound, shaped as derivatives' result)."""
        ts, scalar = _params(t)
        if kmax is None:
            out, op = _out((ts.size, self.dim))
            for j, tj in enumerate(ts):
                _check(lib.cj_bspline_error_bound(self._c, float(tj), op + j * self.dim),
                       "cj_bspline_error_bound")
        else:
            if kmax < 0:
                raise ValueError("kmax must be >= 0")
            out, op = _out((ts.size, kmax + 1, self.dim))
            step = (kmax + 1) * self.dim
            for j, tj in enumerate(ts):
                _check(lib.cj_bspline_derivs_error_bound(self._c, float(tj), int(kmax),
                                                         op + j * step),
                       "cj_bspline_derivs_error_bound")
        return out[0] if scalar else out

    def insert_knot(self, x, r=1):
        """The same curve with the knot x inserted r times (Boehm; cj_bspline_insert_knot)."""
        n = self.points.shape[0] + int(r)
        pts, pp = _out((n, self.dim))
        knots, kp = _out(n + self.degree + 1)
        w, wp = (None, ffi.NULL) if self.weights is None else _out(n)
        _check(lib.cj_bspline_insert_knot(self._c, float(x), int(r), pp, wp, kp),
               "cj_bspline_insert_knot")
        return BSpline(pts, self.degree, knots, w)

    def bezier_pieces(self):
        """(pieces, breaks): the Bézier (RationalBezier for a NURBS) pieces, one per
        non-empty span, and the len(pieces)+1 break parameters; piece j maps [0, 1] onto
        [breaks[j], breaks[j+1]] (cj_bspline_to_bezier)."""
        count = ffi.new("int *")
        _check(lib.cj_bspline_bezier_count(self._c, count), "cj_bspline_bezier_count")
        m, p1 = count[0], self.degree + 1
        pts, pp = _out((m, p1, self.dim))
        w, wp = (None, ffi.NULL) if self.weights is None else _out((m, p1))
        breaks, bp = _out(m + 1)
        _check(lib.cj_bspline_to_bezier(self._c, pp, wp, bp, m, count), "cj_bspline_to_bezier")
        if w is None:
            return [Bezier(pts[j]) for j in range(m)], breaks
        return [RationalBezier(pts[j], w[j]) for j in range(m)], breaks

    @classmethod
    def interpolate(cls, points, degree=3, param="chord", d_start=None, d_end=None):
        """The B-spline of the given degree through the points (global interpolation,
        cj_bspline_interpolate), optionally with end derivatives; domain [0, 1]. The result's
        `residual` is the largest |c(ū_k) - Q_k| the library measured."""
        q = np.ascontiguousarray(np.array(points, dtype=np.float64))
        if q.ndim != 2:
            raise ValueError("points must be an (N, d) array")
        npts, dim = q.shape
        ds = None if d_start is None else np.ascontiguousarray(d_start, dtype=np.float64)
        de = None if d_end is None else np.ascontiguousarray(d_end, dtype=np.float64)
        for name, d in (("d_start", ds), ("d_end", de)):
            if d is not None and d.shape != (dim,):
                raise ValueError(f"{name} must hold {dim} values")
        m = npts + (ds is not None) + (de is not None)
        pts, pp = _out((m, dim))
        knots, kp = _out(m + int(degree) + 1)
        nout = ffi.new("int *")
        residual = ffi.new("double *")
        _check(lib.cj_bspline_interpolate(_ptr(q), npts, dim, int(degree), _fit_kind(param),
                                          _ptr(ds), _ptr(de), pp, kp, nout, residual),
               "cj_bspline_interpolate")
        curve = cls(pts[: nout[0]], degree, knots[: nout[0] + int(degree) + 1])
        curve.residual = residual[0]
        return curve

    @classmethod
    def fit(cls, points, tol, degree=3, param="chord", max_pts=None):
        """The clamped B-spline with the fewest control points found whose deviation at the
        data parameters is <= tol (least squares, end points kept; cj_bspline_approximate).
        The result's `deviation` is the deviation reached. No curve within tol up to max_pts
        points raises CasteljauError (CJ_ERR_CAP)."""
        q = np.ascontiguousarray(np.array(points, dtype=np.float64))
        if q.ndim != 2:
            raise ValueError("points must be an (N, d) array")
        npts, dim = q.shape
        cap = npts if max_pts is None else min(int(max_pts), npts)
        pts, pp = _out((max(cap, 1), dim))
        knots, kp = _out(max(cap, 1) + int(degree) + 1)
        nout = ffi.new("int *")
        dev = ffi.new("double *")
        _check(lib.cj_bspline_approximate(_ptr(q), npts, dim, int(degree), _fit_kind(param),
                                          float(tol), cap, pp, kp, nout, dev),
               "cj_bspline_approximate")
        curve = cls(pts[: nout[0]], degree, knots[: nout[0] + int(degree) + 1])
        curve.deviation = dev[0]
        return curve


class BSplineSurface:
    """A tensor-product B-spline (or NURBS) surface in 3-D.

    points: (nu, nv, 3), points[i, j] = d_ij (i along u); degrees (deg_u, deg_v); knots_u,
    knots_v: None for clamped uniform over [0, 1]; weights: None or (nu, nv) weights > 0."""

    def __init__(self, points, deg_u=3, deg_v=3, knots_u=None, knots_v=None, weights=None):
        pts = np.array(points, dtype=np.float64)
        if pts.ndim != 3 or pts.shape[2] != 3 or pts.shape[0] == 0 or pts.shape[1] == 0:
            raise ValueError("points must be an (nu, nv, 3) array")
        nu, nv = pts.shape[:2]
        if knots_u is None:
            knots_u = _clamped_knots(nu, deg_u) if nu > deg_u else np.zeros(nu + deg_u + 1)
        if knots_v is None:
            knots_v = _clamped_knots(nv, deg_v) if nv > deg_v else np.zeros(nv + deg_v + 1)
        # The library stores point (i, j) at j*nu + i: v-major.
        self._pts = _frozen(pts.transpose(1, 0, 2), lambda a: True, "")
        self.knots_u = _frozen(np.ravel(knots_u), lambda a: a.size == nu + deg_u + 1,
                               f"knots_u must hold {nu + deg_u + 1} values")
        self.knots_v = _frozen(np.ravel(knots_v), lambda a: a.size == nv + deg_v + 1,
                               f"knots_v must hold {nv + deg_v + 1} values")
        self._w = None
        if weights is not None:
            w = np.array(weights, dtype=np.float64)
            if w.shape != (nu, nv):
                raise ValueError("weights must be an (nu, nv) array")
            self._w = _frozen(w.T, lambda a: True, "")
        self._s = ffi.new("cj_bspline_surface *")
        self._s.deg_u, self._s.deg_v = int(deg_u), int(deg_v)
        self._s.npts_u, self._s.npts_v = nu, nv
        self._s.pts = _ptr(self._pts)
        self._s.weights = _ptr(self._w)
        self._s.knots_u = _ptr(self.knots_u)
        self._s.knots_v = _ptr(self.knots_v)
        _check(lib.cj_bspline_surface_check(self._s), "cj_bspline_surface_check")

    def __repr__(self):
        return (f"BSplineSurface(deg=({self._s.deg_u}, {self._s.deg_v}), "
                f"npts=({self._s.npts_u}, {self._s.npts_v}))")

    def _per_uv(self, fn, what, u, v):
        uu, vv = np.broadcast_arrays(np.asarray(u, dtype=np.float64),
                                     np.asarray(v, dtype=np.float64))
        flat_u, flat_v = uu.ravel(), vv.ravel()
        out, op = _out((flat_u.size, 3))
        for j in range(flat_u.size):
            _check(fn(self._s, float(flat_u[j]), float(flat_v[j]), op + 3 * j), what)
        return out.reshape(uu.shape + (3,))

    def eval(self, u, v):
        """S(u, v): u and v broadcast together; result shape broadcast + (3,)."""
        return self._per_uv(lib.cj_bspline_surface_eval, "cj_bspline_surface_eval", u, v)

    def error_bound(self, u, v):
        """Proven a-priori error bound of eval per coordinate (cj_bspline_surface_error_bound)."""
        return self._per_uv(lib.cj_bspline_surface_error_bound,
                            "cj_bspline_surface_error_bound", u, v)

    def to_patches(self):
        """(patches, ub, vb): the Bézier patches (rational for a NURBS; patch b*(len(ub)-1)+a
        covers [ub[a], ub[a+1]] x [vb[b], vb[b+1]]), ready for tessellate()."""
        count = ffi.new("int *")
        _check(lib.cj_bspline_surface_patch_count(self._s, count),
               "cj_bspline_surface_patch_count")
        k, p, q = count[0], self._s.deg_u, self._s.deg_v
        pts, pp = _out((k, q + 1, p + 1, 3))
        w, wp = (None, ffi.NULL) if self._w is None else _out((k, q + 1, p + 1))
        ub, ubp = _out(self._s.npts_u + p + 1)
        vb, vbp = _out(self._s.npts_v + q + 1)
        _check(lib.cj_bspline_surface_to_patches(self._s, pp, wp, ubp, vbp, k, count),
               "cj_bspline_surface_to_patches")
        # Only the breaks (distinct knots of each domain) are written; trim the buffers.
        nsu = np.unique(self.knots_u[p:self._s.npts_u + 1]).size - 1
        nsv = np.unique(self.knots_v[q:self._s.npts_v + 1]).size - 1
        ub, vb = ub[: nsu + 1], vb[: nsv + 1]
        patches = [Patch(pts[j].transpose(1, 0, 2), None if w is None else w[j].T)
                   for j in range(k)]
        return patches, ub, vb


# ---- certified plane-curve queries ----------------------------------------------------------


class _Plane:
    """A plane curve as Bézier pieces (cj_bezier2 views) and the parameter range of each."""

    def __init__(self, curve, name):
        if isinstance(curve, BSpline):
            pieces, breaks = curve.bezier_pieces()
        elif isinstance(curve, (Bezier, RationalBezier)):
            pieces, breaks = [curve], np.array([0.0, 1.0])
        else:
            raise TypeError(f"{name} must be a Bezier, RationalBezier or BSpline")
        if pieces[0].dim != 2:
            raise ValueError(f"{name} is a curve in {pieces[0].dim}-D: the queries are plane")
        self.pieces, self.breaks, self.views = pieces, breaks, []
        for piece in pieces:
            view = ffi.new("cj_bezier2 *")
            view.degree = piece.degree
            view.pts = ffi.cast("double *", ffi.from_buffer(piece.points))
            w = getattr(piece, "weights", None)
            view.weights = ffi.NULL if w is None else ffi.cast("double *", ffi.from_buffer(w))
            self.views.append(view)

    def param(self, j, x):
        a, b = self.breaks[j], self.breaks[j + 1]
        return a + (b - a) * x

    def enclose(self, j, lo, hi):
        """The piece's local interval mapped to the curve's parameter and widened by a bound of
        the rounding of that map (three roundings of a + (b - a) x: at most 4 u (|a| + |b - a| x)
        with room to spare, then one ulp outward), clipped to the piece's own parameter range,
        which holds it exactly. A single Bézier curve on [0, 1] is returned unchanged."""
        if len(self.pieces) == 1 and self.breaks[0] == 0.0 and self.breaks[1] == 1.0:
            return lo, hi
        a, b = self.breaks[j], self.breaks[j + 1]
        u = 2.0 ** -53

        def margin(x):
            return 4 * u * (abs(a) + abs(b - a) * abs(x)) + 2.0 ** -1074

        return (max(np.nextafter(self.param(j, lo) - margin(lo), -np.inf), a),
                min(np.nextafter(self.param(j, hi) + margin(hi), np.inf), b))


class Intersection:
    """One result of intersect(): kind ("crossing", "contact" or "overlap"), the estimates s, t,
    the proven enclosures s_interval, t_interval, the point a(s), deviation and at_end (see
    intersect.h for what each kind guarantees)."""

    def __init__(self, kind, s, t, s_interval, t_interval, point, deviation, at_end):
        self.kind, self.s, self.t = kind, s, t
        self.s_interval, self.t_interval = s_interval, t_interval
        self.point, self.deviation, self.at_end = point, deviation, at_end

    def __repr__(self):
        return f"Intersection({self.kind}, s={self.s!r}, t={self.t!r})"


def _overlaps(x, y):
    return x[0] <= y[1] and y[0] <= x[1]


def intersect(curve_a, curve_b, tol=1e-9):
    """Certified intersections of two plane curves (Bezier, RationalBezier or BSpline in 2-D;
    B-splines piece by piece) by cj_intersect_curves: a list of Intersection sorted by s. A
    crossing at a joint of B-spline pieces, found on both pieces, is reported once."""
    a, b = _Plane(curve_a, "curve_a"), _Plane(curve_b, "curve_b")
    cap = 64
    results = []
    for i, va in enumerate(a.views):
        for j, vb in enumerate(b.views):
            count = ffi.new("int *")
            while True:
                buf = ffi.new("cj_isect[]", cap)
                status = lib.cj_intersect_curves(va, vb, float(tol), buf, cap, count)
                if status != lib.CJ_ERR_BUFFER:
                    break
                cap = count[0]
            _check(status, "cj_intersect_curves")
            for r in buf[0:count[0]]:
                hit = Intersection(
                    ffi.string(lib.cj_isect_kind_name(r.kind)).decode(), a.param(i, r.s),
                    b.param(j, r.t), a.enclose(i, r.s_lo, r.s_hi), b.enclose(j, r.t_lo, r.t_hi),
                    np.array([r.point[0], r.point[1]]), r.deviation, bool(r.at_end))
                same = [h for h in results if h.kind == hit.kind
                        and _overlaps(h.s_interval, hit.s_interval)
                        and _overlaps(h.t_interval, hit.t_interval)]
                if same:
                    h = same[0]
                    h.s_interval = (min(h.s_interval[0], hit.s_interval[0]),
                                    max(h.s_interval[1], hit.s_interval[1]))
                    h.t_interval = (min(h.t_interval[0], hit.t_interval[0]),
                                    max(h.t_interval[1], hit.t_interval[1]))
                else:
                    results.append(hit)
    results.sort(key=lambda h: (h.s, h.t))
    return results


class Nearest:
    """Result of nearest(): parameter t, point c(t), distance (proven upper bound of the
    minimum distance), lower (proven lower bound of it), pieces (work done)."""

    def __init__(self, t, point, distance, lower, pieces):
        self.t, self.point, self.distance, self.lower, self.pieces = (t, point, distance,
                                                                      lower, pieces)

    def __repr__(self):
        return f"Nearest(t={self.t!r}, distance={self.distance!r}, lower={self.lower!r})"


def nearest(curve, point, tol=1e-9):
    """The certified nearest point of a plane curve to `point` (cj_nearest_curve, per Bézier
    piece for a B-spline): lower <= min_t |c(t) - q| <= distance, distance - lower <= tol."""
    c = _Plane(curve, "curve")
    q = np.ascontiguousarray(np.array(point, dtype=np.float64).ravel())
    if q.size != 2:
        raise ValueError("point must hold 2 coordinates")
    best, lower, work = None, np.inf, 0
    res = ffi.new("cj_nearest *")
    for j, view in enumerate(c.views):
        _check(lib.cj_nearest_curve(view, _ptr(q), float(tol), res), "cj_nearest_curve")
        lower = min(lower, res.lower)
        work += res.pieces
        if best is None or res.distance < best[2]:
            best = (c.param(j, res.t), np.array([res.point[0], res.point[1]]), res.distance)
    return Nearest(best[0], best[1], best[2], lower, work)


def offset(curve, d, tol=1e-6):
    """The offset at signed distance d (left of the direction of travel) as cubic Bézier
    pieces within a proven deviation <= tol (cj_offset_curve, per piece for a B-spline).
    Returns (pieces, breaks, deviation, cusps): pieces an (m, 4, 2) array of control points,
    breaks the m+1 curve parameters they span, cusps the sign changes of 1 - d κ seen. The
    raw offset is returned: loops past cusps are not trimmed."""
    c = _Plane(curve, "curve")
    all_pts, all_breaks, deviation, cusps = [], [], 0.0, 0
    n = ffi.new("int *")
    dev = ffi.new("double *")
    ncusp = ffi.new("int *")
    for j, view in enumerate(c.views):
        status = lib.cj_offset_curve(view, float(d), float(tol), ffi.NULL, ffi.NULL, 0, n, dev,
                                     ncusp)
        if status != lib.CJ_ERR_BUFFER:
            _check(status, "cj_offset_curve")
        pts, pp = _out((n[0], 4, 2))
        br, bp = _out(n[0] + 1)
        _check(lib.cj_offset_curve(view, float(d), float(tol), pp, bp, n[0], n, dev, ncusp),
               "cj_offset_curve")
        all_pts.append(pts)
        all_breaks.append(c.param(j, br) if j == 0 else c.param(j, br[1:]))
        deviation = max(deviation, dev[0])
        cusps += ncusp[0]
    return np.concatenate(all_pts), np.concatenate(all_breaks), deviation, cusps
