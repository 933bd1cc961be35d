"""B-splines, NURBS and the plane queries through Python: values and derivatives against exact
de Boor in rational arithmetic (fractions) within the proven bounds, a NURBS circle on the
circle, two lines' crossing, the nearest point of a parabola against the cubic's root found
exactly, the offset of a circle, and agreement with the library's own Bézier pieces."""
from decimal import Decimal, getcontext
from fractions import Fraction

import numpy as np
import pytest

import casteljau as cj


def exact_deboor(points, degree, knots, t):
    """c(t) of a polynomial B-spline by de Boor in exact rational arithmetic (the oracle)."""
    t = Fraction(t)
    kn = [Fraction(k) for k in knots]
    n = len(points) - 1
    s = max(i for i in range(degree, n + 1) if kn[i] <= t) if t < kn[n + 1] else n
    while kn[s] == kn[s + 1] and s > degree:
        s -= 1
    d = [[Fraction(x) for x in points[j]] for j in range(s - degree, s + 1)]
    for r in range(1, degree + 1):
        for j in range(degree, r - 1, -1):
            i = s - degree + j
            a = (t - kn[i]) / (kn[i + degree - r + 1] - kn[i])
            d[j] = [(1 - a) * x + a * y for x, y in zip(d[j - 1], d[j])]
    return d[degree]


def random_knots(rng, npts, degree):
    inner = np.sort(rng.uniform(0, 1, size=npts - degree - 1))
    return np.concatenate([np.zeros(degree + 1), inner, np.ones(degree + 1)])


def test_bspline_eval_and_derivative_within_bounds(rng):
    checked = 0
    for _ in range(30):
        p = int(rng.integers(1, 6))
        npts = int(rng.integers(p + 1, p + 8))
        pts = rng.uniform(-1, 1, size=(npts, 2))
        knots = random_knots(rng, npts, p)
        c = cj.BSpline(pts, p, knots)
        ts = rng.uniform(0, 1, size=6)
        vals, bounds = c.eval(ts), c.error_bound(ts)
        ders, dbounds = c.derivatives(ts, 1), c.error_bound(ts, kmax=1)
        # The derivative is the degree p-1 B-spline of p (d_{i+1} - d_i) / (t_{i+p+1} - t_{i+1}).
        fk = [Fraction(k) for k in knots]
        dpts = [[p * (Fraction(pts[i + 1][k]) - Fraction(pts[i][k])) / (fk[i + p + 1] - fk[i + 1])
                 for k in range(2)] for i in range(npts - 1)]
        for j, t in enumerate(ts):
            exact = exact_deboor(pts, p, knots, t)
            exact_d = exact_deboor(dpts, p - 1, knots[1:-1], t)
            for k in range(2):
                assert abs(Fraction(vals[j, k]) - exact[k]) <= Fraction(bounds[j, k])
                assert ders[j, 0, k] == vals[j, k]
                assert abs(Fraction(ders[j, 1, k]) - exact_d[k]) <= Fraction(dbounds[j, 1, k])
                checked += 1
    print(f"{checked} coordinates and first derivatives within their proven bounds (exact de Boor)")


def test_default_knots_are_clamped_uniform():
    c = cj.BSpline([[0, 0], [1, 1], [2, 0], [3, 1], [4, 0]], degree=2)
    assert list(c.knots) == [0, 0, 0, 1 / 3, 2 / 3, 1, 1, 1]
    assert c.domain == (0.0, 1.0)
    assert np.array_equal(c.eval([0.0, 1.0]), [[0, 0], [4, 0]])
    print("clamped uniform default knots; the curve interpolates its end points")


def test_insert_knot_and_bezier_pieces_keep_the_curve(rng):
    pts = rng.uniform(-1, 1, size=(7, 3))
    w = rng.uniform(0.5, 2, size=7)
    for weights in (None, w):
        c = cj.BSpline(pts, 3, random_knots(rng, 7, 3), weights)
        refined = c.insert_knot(0.4, 2)
        assert refined.points.shape == (9, 3)
        ts = np.linspace(0, 1, 41)
        assert np.max(np.abs(refined.eval(ts) - c.eval(ts))) < 1e-13
        pieces, breaks = c.bezier_pieces()
        assert len(pieces) == 4 and breaks[0] == 0 and breaks[-1] == 1
        for j, piece in enumerate(pieces):
            assert isinstance(piece, cj.Bezier if weights is None else cj.RationalBezier)
            local = np.linspace(0, 1, 9)
            on_curve = c.eval(breaks[j] + (breaks[j + 1] - breaks[j]) * local)
            assert np.max(np.abs(piece.eval(local) - on_curve)) < 1e-13
    print("knot insertion and Bezier pieces reproduce the curve (polynomial and NURBS)")


QUARTER = dict(points=[[1, 0], [1, 1], [0, 1]], degree=2, weights=[1, np.sqrt(0.5), 1])


def test_nurbs_circle_lies_on_the_circle():
    quarter = cj.BSpline(**QUARTER)
    ts = np.linspace(0, 1, 101)
    r = np.hypot(*quarter.eval(ts).T)
    assert np.max(np.abs(r - 1)) < 4e-16
    # The full circle: nine points, double knots at the quarters.
    pts = [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]]
    w = [1, np.sqrt(0.5)] * 4 + [1]
    knots = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
    circle = cj.BSpline(pts, 2, knots, w)
    r = np.hypot(*circle.eval(ts).T)
    assert np.max(np.abs(r - 1)) < 4e-16
    assert len(circle.bezier_pieces()[0]) == 4
    print(f"NURBS circle: max |r - 1| = {np.max(np.abs(r - 1)):.2e} over {ts.size} points")


def test_two_lines_cross_where_the_closed_form_says():
    a = cj.Bezier([[0, 0], [2, 2]])
    b = cj.Bezier([[0, 2], [2, 0]])
    hits = cj.intersect(a, b)
    assert len(hits) == 1 and hits[0].kind == "crossing"
    h = hits[0]
    assert h.s_interval[0] <= 0.5 <= h.s_interval[1]
    assert h.t_interval[0] <= 0.5 <= h.t_interval[1]
    assert np.allclose(h.point, [1, 1], atol=1e-15)
    # The same lines as degree-1 B-splines of three pieces each, on [0, 1]: s = t = 1/2 again.
    a3 = cj.BSpline([[0, 0], [0.5, 0.5], [1.5, 1.5], [2, 2]], 1)
    b3 = cj.BSpline([[0, 2], [0.2, 1.8], [1, 1], [2, 0]], 1, [0, 0, 0.1, 0.5, 1, 1])
    hits = cj.intersect(a3, b3)
    assert len(hits) == 1, hits
    h = hits[0]
    s_exact = Fraction(1, 3) + Fraction(1, 3) * Fraction(1, 2)  # middle piece, (1,1) at its half
    assert Fraction(h.s_interval[0]) <= s_exact <= Fraction(h.s_interval[1])
    assert h.t_interval[0] <= 0.5 <= h.t_interval[1]
    print(f"lines cross at s={hits[0].s!r}, t={hits[0].t!r}, enclosures {h.s_interval}, "
          f"{h.t_interval}; the joint crossing is reported once")


def test_nearest_on_a_parabola_against_the_cubic_root():
    getcontext().prec = 60
    parabola = cj.Bezier([[-1, 1], [0, -1], [1, 1]])  # x = 2t - 1, y = x^2
    as_bspline = cj.BSpline([[-1, 1], [0, -1], [1, 1]], 2).insert_knot(0.3)
    for q in ([0.7, 0.3], [-0.4, 0.1], [0.25, -2.0]):
        qx, qy = Fraction(q[0]), Fraction(q[1])

        def g(x):  # half the derivative of |(x, x^2) - q|^2: one real root when qy < 1/2
            return 2 * x ** 3 + (1 - 2 * qy) * x - qx

        lo, hi = Fraction(-2), Fraction(2)
        for _ in range(110):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if g(mid) < 0 else (lo, mid)
        x = Decimal(lo.numerator) / Decimal(lo.denominator)
        exact = ((x - Decimal(q[0])) ** 2 + (x * x - Decimal(q[1])) ** 2).sqrt()
        for curve in (parabola, as_bspline):
            res = cj.nearest(curve, q, tol=1e-11)
            assert Decimal(res.lower) <= exact + Decimal("1e-30")
            assert exact <= Decimal(res.distance) + Decimal("1e-30")
            assert res.distance - res.lower <= 1e-11
            assert abs(res.t - float((Decimal(1) + x) / 2)) < 1e-6
        print(f"q={q}: exact distance {float(exact)!r} in [{res.lower!r}, {res.distance!r}]")


def test_offset_of_a_circle_is_a_circle():
    quarter = cj.BSpline(**QUARTER)
    for d in (0.25, -0.5):
        pieces, breaks, deviation, cusps = cj.offset(quarter, d, tol=1e-6)
        assert deviation <= 1e-6 and cusps == 0
        assert breaks[0] == 0 and breaks[-1] == 1 and len(breaks) == len(pieces) + 1
        assert np.allclose(pieces[0, 0], [1 - d, 0]) and np.allclose(pieces[-1, 3], [0, 1 - d])
        worst = 0.0
        for piece in pieces:
            r = np.hypot(*cj.Bezier(piece).eval(np.linspace(0, 1, 17)).T)
            worst = max(worst, np.max(np.abs(r - (1 - d))))
        assert worst <= deviation + 1e-12
        print(f"offset d={d}: {len(pieces)} cubics, radius error {worst:.2e} <= {deviation:.2e}")


def test_interpolate_and_fit():
    xs = np.linspace(0, 3, 40)
    data = np.c_[xs, np.sin(xs)]
    through = cj.BSpline.interpolate(data[::5], degree=3)
    assert through.residual < 1e-14
    fitted = cj.BSpline.fit(data, tol=1e-4)
    assert fitted.deviation <= 1e-4 and fitted.points.shape[0] < len(data)
    assert np.array_equal(fitted.eval([0.0, 1.0]), data[[0, -1]])
    with_ends = cj.BSpline.interpolate(data[::5], d_start=[3, 3], d_end=[3, -3])
    assert np.allclose(with_ends.derivatives(0.0)[1], [3, 3])
    print(f"interpolation residual {through.residual:.1e}; fit with "
          f"{fitted.points.shape[0]} points, deviation {fitted.deviation:.2e}")


def test_surface_patches_agree_with_the_surface(rng):
    nu, nv = 6, 5
    grid = np.dstack(np.meshgrid(np.arange(nu, dtype=float), np.arange(nv, dtype=float),
                                 indexing="ij") + [rng.uniform(-1, 1, size=(nu, nv))])
    for weights in (None, rng.uniform(0.5, 2, size=(nu, nv))):
        s = cj.BSplineSurface(grid, 3, 2, weights=weights)
        patches, ub, vb = s.to_patches()
        assert len(patches) == (len(ub) - 1) * (len(vb) - 1) == 3 * 3
        u, v = rng.uniform(0, 1, size=(2, 12))
        vals, bounds = s.eval(u, v), s.error_bound(u, v)
        assert vals.shape == bounds.shape == (12, 3) and np.all(bounds < 1e-13)
        for k in range(12):
            a = min(np.searchsorted(ub, u[k], side="right") - 1, len(ub) - 2)
            b = min(np.searchsorted(vb, v[k], side="right") - 1, len(vb) - 2)
            patch = patches[b * (len(ub) - 1) + a]
            lu = (u[k] - ub[a]) / (ub[a + 1] - ub[a])
            lv = (v[k] - vb[b]) / (vb[b + 1] - vb[b])
            assert np.max(np.abs(patch.eval(lu, lv) - vals[k])) < 1e-12
        mesh = cj.tessellate(patches, tol=1e-2)
        assert mesh.triangles.shape[0] > 0
    print("surface values match its Bezier patches (polynomial and NURBS); patches tessellate")


def test_errors_carry_the_library_message():
    with pytest.raises(cj.CasteljauError, match="NaN"):
        cj.BSpline([[0, 0], [1, np.nan], [2, 0]], degree=2)
    c = cj.BSpline([[0, 0], [1, 1], [2, 0]], degree=2)
    with pytest.raises(cj.CasteljauError, match="outside the domain"):
        c.eval(1.5)
    with pytest.raises(cj.CasteljauError) as err:
        cj.BSpline([[0, 0], [1, 1], [2, 0]], degree=1, knots=[0, 0.5, 0.2, 1, 1])
    assert err.value.status_name and str(err.value)
    with pytest.raises(cj.CasteljauError):
        cj.BSpline(**QUARTER).insert_knot(0.5, 3)
    with pytest.raises(ValueError):
        cj.intersect(cj.Bezier([[0, 0, 0], [1, 1, 1]]), c)
    with pytest.raises(cj.CasteljauError, match="tol"):
        cj.nearest(c, [0, 1], tol=0)
    print(f"errors raised with the library's messages, e.g. {str(err.value)!r}")


def test_cdef_struct_layouts_match_the_headers():
    """The structs build_cffi.py declares in full are checked by cffi against the compiler's
    layout only when their fields are first looked at: look at every one, so a declaration
    that drifted from its header ("wrong offset for field ...") fails here, not in a call."""
    from casteljau._casteljau_cffi import ffi

    names = ["cj_bezier", "cj_rbezier", "cj_patch", "cj_bspline", "cj_bspline_surface",
             "cj_bezier2", "cj_isect", "cj_nearest", "cj_vec3", "cj_rgb"]
    fields = 0
    for name in names:
        for field, _ in ffi.typeof(name).fields:
            assert ffi.offsetof(name, field) < ffi.sizeof(name)
            fields += 1
    print(f"{fields} fields of {len(names)} structs laid out as the compiler lays them out")
