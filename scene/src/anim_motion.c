/* Motion blur's input: node transforms sampled over a shutter interval (anim_scene.h). */
#include "casteljau/anim_scene.h"

#include "error_internal.h"

#include <assert.h>
#include <math.h>

cj_status cj_anim_sample_motion(cj_scene *scene, const cj_anim *anim, double t_open, double t_close,
                                int poses, cj_xform3 *world) {
    assert(scene && anim && world);
    if (poses < 2) return cj_fail(CJ_ERR_RANGE, "motion: %d poses, at least 2 needed", poses);
    if (!isfinite(t_open) || !isfinite(t_close))
        return cj_fail(CJ_ERR_NONFINITE, "motion: shutter [%g, %g]", t_open, t_close);
    if (!(t_close > t_open))
        return cj_fail(CJ_ERR_RANGE, "motion: shutter closes at %g, not after it opens at %g",
                       t_close, t_open);
    const size_t n = cj_scene_node_count(scene);
    for (int k = 0; k < poses; ++k) {
        /* the last pose at t_close exactly, not t_open + (poses−1) × step rounded */
        const double t =
            k == poses - 1 ? t_close : t_open + (t_close - t_open) * k / (double)(poses - 1);
        cj_status st = cj_anim_pose(scene, anim, t, NULL);
        if (st) return st;
        for (size_t i = 0; i < n; ++i) {
            st = cj_scene_node_world(scene, (int)i, &world[(size_t)k * n + i]);
            if (st) return st;
        }
    }
    return CJ_OK;
}
