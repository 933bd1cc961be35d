//! The kurbo peer of bench_flatten (kurbo::flatten) and bench_query_occt (nearest points, curve-line
//! intersections), linked into those programs. kurbo::flatten on one quadratic or cubic, its points written
//! into a caller buffer (the whole polyline, start point included). Used by the bench only.
use kurbo::{PathEl, Point};

/// Flattens the Bézier curve of degree `n` (2 or 3) with control points `p[0..2(n+1)]` at
/// tolerance `tol`; writes up to `cap` points (x, y) to `out` and returns how many kurbo emitted.
#[no_mangle]
pub unsafe extern "C" fn cj_bench_kurbo_flatten(
    n: i32,
    p: *const f64,
    tol: f64,
    out: *mut f64,
    cap: usize,
) -> usize {
    let c = std::slice::from_raw_parts(p, 2 * (n as usize + 1));
    let pt = |i: usize| Point::new(c[2 * i], c[2 * i + 1]);
    let path = if n == 3 {
        [PathEl::MoveTo(pt(0)), PathEl::CurveTo(pt(1), pt(2), pt(3))]
    } else {
        [PathEl::MoveTo(pt(0)), PathEl::QuadTo(pt(1), pt(2))]
    };
    let mut count = 0usize;
    kurbo::flatten(path.iter().cloned(), tol, |el| {
        let q = match el {
            PathEl::MoveTo(q) | PathEl::LineTo(q) => q,
            _ => return,
        };
        if count < cap {
            *out.add(2 * count) = q.x;
            *out.add(2 * count + 1) = q.y;
        }
        count += 1;
    });
    count
}

/// bench_query_occt's kurbo peer: `CubicBez::nearest` (kurbo 0.7: subdivision into quadratics
/// at `accuracy`, then each quadratic's cubic equation; not certified). Returns the distance
/// and writes the parameter to `t`.
#[no_mangle]
pub unsafe extern "C" fn cj_bench_kurbo_nearest(
    p: *const f64,
    qx: f64,
    qy: f64,
    accuracy: f64,
    t: *mut f64,
) -> f64 {
    use kurbo::{CubicBez, ParamCurveNearest};
    let c = std::slice::from_raw_parts(p, 8);
    let cubic = CubicBez::new((c[0], c[1]), (c[2], c[3]), (c[4], c[5]), (c[6], c[7]));
    let (best_t, d2) = cubic.nearest(Point::new(qx, qy), accuracy);
    *t = best_t;
    d2.sqrt()
}

/// kurbo 0.7's only curve intersection: `PathSeg::intersect_line` of a cubic with the line
/// through (x0, y0) and (x1, y1) (the line's parameter restricted to [0, 1] by kurbo). Writes
/// up to 3 cubic parameters to `ts` and returns how many.
#[no_mangle]
pub unsafe extern "C" fn cj_bench_kurbo_intersect_line(
    p: *const f64,
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    ts: *mut f64,
) -> usize {
    use kurbo::{CubicBez, Line, PathSeg};
    let c = std::slice::from_raw_parts(p, 8);
    let cubic = CubicBez::new((c[0], c[1]), (c[2], c[3]), (c[4], c[5]), (c[6], c[7]));
    let hits = PathSeg::Cubic(cubic).intersect_line(Line::new((x0, y0), (x1, y1)));
    for (k, hit) in hits.iter().enumerate() {
        *ts.add(k) = hit.segment_t;
    }
    hits.len()
}
