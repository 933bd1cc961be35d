// kurbo (Debian librust-kurbo-dev 0.7, built with cargo --offline) on the seeded random cubics
// and query points of bench_query_occt (same xorshift sequence): nearest point per query,
// median of 5 repetitions. kurbo 0.7 has no curve-curve intersection and no offsets.
use kurbo::{CubicBez, ParamCurveNearest, Point};
use std::time::Instant;

fn main() {
    let mut state: u64 = 0x9e3779b97f4a7c15;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 * (1.0 / 9007199254740992.0)
    };
    const N: usize = 2000;
    let mut curves = Vec::with_capacity(N);
    for _ in 0..N {
        let mut c = [0.0f64; 8];
        for v in c.iter_mut() {
            *v = unit();
        }
        curves.push(CubicBez::new((c[0], c[1]), (c[2], c[3]), (c[4], c[5]), (c[6], c[7])));
    }
    let qs: Vec<Point> = (0..N).map(|_| Point::new(unit(), unit())).collect();
    let mut times = Vec::new();
    let mut sum = 0.0;
    for _ in 0..5 {
        let t0 = Instant::now();
        sum = 0.0;
        for i in 0..N {
            let (_t, d2) = curves[i].nearest(qs[i], 1e-10);
            sum += d2.sqrt();
        }
        times.push(t0.elapsed().as_secs_f64() / N as f64);
    }
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    println!(
        "nearest point, cubic:  kurbo 0.7 {:8.2} us (accuracy 1e-10, not certified); mean distance {:.12}",
        1e6 * times[2],
        sum / N as f64
    );
}
