/* A program outside the casteljau tree: uses only the installed headers and libraries. */
#include <casteljau/bezier.h>
#include <casteljau/transform.h>

#include <stdio.h>

int main(void) {
    /* c(t) = (2t, 4t(1-t)): c(1/2) = (1, 1), bounding box [0,2] x [0,1]. */
    const double pts[] = {0, 0, 1, 2, 2, 0};
    cj_bezier c = cj_bezier_view(2, 2, pts);
    double p[2], lo[2], hi[2];
    if (cj_bezier_eval(&c, CJ_EVAL_DECASTELJAU, 0.5, p) != CJ_OK) return 1;
    if (cj_bezier_bbox(&c, lo, hi) != CJ_OK) return 1;
    cj_xform2 m = cj_xform2_translate(10, 20);
    cj_vec2 q;
    if (cj_xform2_apply_point(&m, cj_v2(p[0], p[1]), &q) != CJ_OK) return 1;
    printf("casteljau consumer: c(0.5) = %g %g, bbox %g %g %g %g, moved %g %g, status: %s\n", p[0],
           p[1], lo[0], lo[1], hi[0], hi[1], q.x, q.y, cj_status_str(CJ_ERR_RANGE));
    return 0;
}
