// The analytic-surface headers compile as C++ and link (extern "C"): a tiny end-to-end use.
#include "casteljau/analytic.h"
#include "casteljau/deform.h"
#include "casteljau/quadric.h"
#include "casteljau/surface.h"

#include <cmath>
#include <cstdio>

int main() {
    cj_quadric q;
    if (cj_quadric_ellipsoid(&q, 1.0, 2.0, 3.0) != CJ_OK) return 1;
    cj_param_surface s;
    cj_quadric_surface(&q, &s);
    cj_vec3 p, n;
    if (cj_surface_eval(&s, 0.0, 0.0, &p, nullptr, nullptr) != CJ_OK) return 1;
    if (cj_surface_normal(&s, 0.0, 0.0, &n) != CJ_OK) return 1;
    cj_torus t;
    if (cj_torus_init(&t, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 2.0, 1.0) != CJ_OK) return 1;
    cj_deform d;
    if (cj_deform_twist(&d, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 1.0) != CJ_OK) return 1;
    // S(0,0) = (a, 0, 0) with outward normal +x.
    bool ok = p.x == 1.0 && p.y == 0.0 && std::fabs(n.x - 1.0) < 1e-15;
    std::printf("C++: surface.h, quadric.h, analytic.h, deform.h compile and link; ellipsoid "
                "S(0,0) = (%g, %g, %g), n = (%g, %g, %g): %s\n",
                p.x, p.y, p.z, n.x, n.y, n.z, ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
