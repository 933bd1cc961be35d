/* The rasterizer's emitters (radiometric area, disc and sphere lights): not triangles of the
 * scene but analytic shapes, so each sample's camera ray is intersected with them exactly
 * (the tracer's tr_emitter_hit) and the nearer of the emitter and the drawn surface wins, by
 * the same pseudodepth the visibility buffer holds. The ray tracer sees the same shapes. */
#include "render_pipe.h"

#include "trace_shade.h"

#include <math.h>

void cj_remitters_tile(const cj_rctx *c, const cj_tile *t, float *col) {
    const cj_rview *v = c->view;
    const cj_xform3 *m = &v->world_to_clip;
    const int tw = t->x1 - t->x0, spp = t->spp;
    for (int y = t->y0; y < t->y1; ++y)
        for (int x = t->x0; x < t->x1; ++x)
            for (int s = 0; s < spp; ++s) {
                const size_t i =
                    ((size_t)(y - t->y0) * (size_t)tw + (size_t)(x - t->x0)) * (size_t)spp +
                    (size_t)s;
                cj_ray ray;
                if (cj_camera_ray(&v->cam, c->width, c->height, x + c->pattern[s][0],
                                  y + c->pattern[s][1], &ray.org, &ray.dir) != CJ_OK)
                    continue;
                ray.tmin = 0.0;
                ray.tmax = INFINITY;
                double best = t->samples[i].depth;
                const cj_light *hit = NULL;
                for (int k = 0; k < c->nemitters; ++k) {
                    double th, pdf;
                    if (!tr_emitter_hit(c->emitters[k], &ray, INFINITY, &th, &pdf)) continue;
                    const cj_vec3 p = cj_v3_add(ray.org, cj_v3_scale(ray.dir, th));
                    const double z = m->m[2][0] * p.x + m->m[2][1] * p.y + m->m[2][2] * p.z +
                                     m->m[2][3],
                                 w = m->m[3][0] * p.x + m->m[3][1] * p.y + m->m[3][2] * p.z +
                                     m->m[3][3];
                    const double d = z / w;
                    if (d >= -1.0 && d < best) { /* inside the view volume, in front */
                        best = d;
                        hit = c->emitters[k];
                    }
                }
                if (!hit) continue;
                float *o = col + 4 * i;
                o[0] = (float)(hit->color.r * hit->intensity);
                o[1] = (float)(hit->color.g * hit->intensity);
                o[2] = (float)(hit->color.b * hit->intensity);
                o[3] = 1.0f;
            }
}
