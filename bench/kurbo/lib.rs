//! bench_flatten's kurbo peer: kurbo::flatten on one quadratic or cubic, its points written
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
