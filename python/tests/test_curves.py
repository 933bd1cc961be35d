"""Curves through Python: values and bounds against exact rational arithmetic (fractions),
derivatives against the exact power form, flattening's proven bound against a dense check,
rational arcs against the circle, and errors carrying the library's message."""
from fractions import Fraction

import numpy as np
import pytest

import casteljau as cj


def exact_point(points, t):
    """c(t) by de Casteljau in exact rational arithmetic (the oracle)."""
    t = Fraction(t)
    row = [[Fraction(x) for x in p] for p in points]
    while len(row) > 1:
        row = [[(1 - t) * a + t * b for a, b in zip(p, q)] for p, q in zip(row, row[1:])]
    return row[0]


def test_eval_matches_exact_within_bounds(rng):
    checked = 0
    for _ in range(40):
        n = int(rng.integers(1, 12))
        d = int(rng.integers(1, 4))
        pts = rng.uniform(-1, 1, size=(n + 1, d))
        c = cj.Bezier(pts)
        ts = rng.uniform(0, 1, size=5)
        plain = c.eval(ts)
        bound_plain = c.error_bound(ts)
        value, bound = c.eval_bound(ts)
        for j, t in enumerate(ts):
            exact = exact_point(pts, t)
            for k in range(d):
                assert abs(Fraction(plain[j, k]) - exact[k]) <= Fraction(bound_plain[j, k])
                assert abs(Fraction(value[j, k]) - exact[k]) <= Fraction(bound[j, k])
                checked += 1
    print(f"{checked} coordinates within the plain and the compensated bound")


def test_compensated_beats_plain_near_a_root():
    # (1 - 2t)^n expanded in Bernstein form: huge condition number near t = 1/2.
    n = 12
    # control points of (1-2t)^n: b_i = (-1)^i
    pts = [[(-1.0) ** i] for i in range(n + 1)]
    t = 0.5013  # not a short binary fraction: the roundings are real
    exact = exact_point(pts, t)[0]
    plain = cj.Bezier(pts).eval(t)[0]
    comp, bound = cj.Bezier(pts).eval_bound(t)
    err_plain = abs(Fraction(plain) - exact)
    err_comp = abs(Fraction(comp[0]) - exact)
    print(f"plain error {float(err_plain):.3g}, compensated {float(err_comp):.3g}, "
          f"bound {bound[0]:.3g}")
    assert err_comp <= Fraction(bound[0])
    assert err_plain > 0 and err_comp < err_plain


def test_scalar_and_batch_shapes():
    c = cj.Bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
    assert c.eval(0.5).shape == (2,)
    assert c.eval([0, 0.5, 1]).shape == (3, 2)
    assert np.array_equal(c.eval(0.0), [0, 0]) and np.array_equal(c.eval(1.0), [4, 0])
    assert np.array_equal(c(0.25), c.eval([0.25])[0])
    for m in ("bernstein", "horner", "compensated"):
        assert np.allclose(c.eval(0.3, method=m), c.eval(0.3), rtol=0, atol=1e-14)


def test_derivatives_match_power_form(rng):
    # c(t) = a + b t + e t^2 + f t^3 in Bezier form; derivatives known exactly.
    a, b, e, f = rng.uniform(-2, 2, size=(4, 2))
    pts = np.array([a, a + b / 3, a + 2 * b / 3 + e / 3, a + b + e + f])
    c = cj.Bezier(pts)
    t = 0.37
    d = c.derivatives(t, 3)
    assert d.shape == (4, 2)
    assert np.allclose(d[0], a + b * t + e * t * t + f * t ** 3, atol=1e-13)
    assert np.allclose(d[1], b + 2 * e * t + 3 * f * t * t, atol=1e-12)
    assert np.allclose(d[2], 2 * e + 6 * f * t, atol=1e-12)
    assert np.allclose(d[3], 6 * f, atol=1e-12)
    h = c.hodograph(1)
    assert h.degree == 2
    assert np.allclose(h.eval(t), d[1], atol=1e-12)


def test_split_bbox_arclength_curvature():
    c = cj.Bezier([[0, 0], [0, 1], [1, 1]])
    left, right = c.split(0.5)
    assert np.array_equal(left.points[-1], right.points[0])
    assert np.allclose(left.eval(1.0), c.eval(0.5))
    lo, hi = c.bbox()
    assert np.allclose(lo, [0, 0]) and np.allclose(hi, [1, 1])
    line = cj.Bezier([[0, 0], [3, 4]])
    length, err = line.arclength(1e-12)
    assert abs(length - 5) <= 1e-12 and err <= 1e-12
    # a quarter circle approximated: curvature of a parabola y = x^2 at its vertex is 2
    parabola = cj.Bezier([[-1, 1], [0, -1], [1, 1]])
    assert abs(parabola.curvature(0.5) - 2.0) < 1e-12


@pytest.mark.parametrize("method", ["uniform", "subdivide", "near_optimal"])
def test_flatten_bound_holds(method, rng):
    pts = rng.uniform(-1, 1, size=(6, 2))
    c = cj.Bezier(pts)
    tol = 1e-3
    poly, bound = c.flatten(tol, method=method)
    assert bound <= tol
    assert np.array_equal(poly[0], pts[0]) and np.array_equal(poly[-1], pts[-1])
    # every dense curve sample lies within the bound of the polyline
    samples = c.eval(np.linspace(0, 1, 4001))
    a, b = poly[:-1], poly[1:]
    ab = b - a
    worst = 0.0
    for p in samples:
        s = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(
            np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        dist = np.min(np.linalg.norm(a + s[:, None] * ab - p, axis=1))
        worst = max(worst, dist)
    print(f"{method}: {len(poly)} points, bound {bound:.3g}, sampled distance {worst:.3g}")
    assert worst <= bound + 1e-12


def test_rational_circle():
    arcs = cj.RationalBezier.ellipse_arcs((1, 2), 3, 3, 0, 2 * np.pi)
    assert len(arcs) == 4
    for arc in arcs:
        p = arc.eval(np.linspace(0, 1, 33))
        r = np.linalg.norm(p - [1, 2], axis=1)
        assert np.max(np.abs(r - 3)) < 1e-14 * 8
    poly, bound = arcs[0].flatten(1e-4)
    r = np.linalg.norm(poly - [1, 2], axis=1)
    assert np.max(np.abs(r - 3)) < 1e-12  # vertices lie on the circle
    assert bound <= 1e-4
    d = arcs[0].derivatives(0.0, 1)
    assert abs(np.dot(d[1], d[0] - [1, 2])) < 1e-12  # tangent perpendicular to radius


def test_errors_carry_the_library_message():
    with pytest.raises(cj.CasteljauError) as e:
        cj.Bezier([[0, 0], [np.nan, 1], [2, 0]]).eval(0.5)
    print("message:", e.value)
    assert e.value.status == 1  # CJ_ERR_NONFINITE
    assert "1" in str(e.value) and "NaN" in str(e.value)
    with pytest.raises(cj.CasteljauError) as e:
        cj.RationalBezier([[0, 0], [1, 1], [2, 0]], [1, -1, 1]).eval(0.5)
    assert "weight" in str(e.value)
    with pytest.raises(cj.CasteljauError):
        cj.Bezier([[0, 0], [1, 1]]).flatten(-1.0)
    with pytest.raises(cj.CasteljauError) as e:
        cj.Bezier([[0, 0], [1, 1]]).split(1.5)
    assert e.value.status_name
