/* The per-tile work of the rasterizer pipeline, run on the workers after the tile's visibility
 * buffer is complete: samples sorted by shading kernel and shaded one loop per kernel,
 * overlay lines, transparent surfaces blended back to front, resolve and output. Everything
 * here is a function of the sample alone (its position, triangle and barycentrics), never of
 * the tile or thread, so the image is the same for any tiling and thread count. */
#include "render_pipe.h"

#include <string.h>

typedef struct frag_ctx {
    const cj_rctx *c;
    const cj_tile *t;
    float *col;
    uint64_t n;
} frag_ctx;

/* A transparent fragment in front of the opaque surface: shaded, then blended over what the
 * sample holds (fragments arrive back to front: the triangles are in BSP order). */
static void frag(void *user, int x, int y, int s, uint32_t tri, float depth, float b1, float b2) {
    (void)depth;
    frag_ctx *f = user;
    const cj_rctx *c = f->c;
    const cj_tile *t = f->t;
    float o[4];
    cj_rshade_one(c, &c->transp, tri, b1, b2, x + c->pattern[s][0], y + c->pattern[s][1], o);
    size_t i =
        ((size_t)(y - t->y0) * (size_t)(t->x1 - t->x0) + (size_t)(x - t->x0)) * (size_t)t->spp +
        (size_t)s;
    float *cc = f->col + 4 * i, a = o[3];
    cc[0] += a * (o[0] - cc[0]);
    cc[1] += a * (o[1] - cc[1]);
    cc[2] += a * (o[2] - cc[2]);
    cc[3] += a * (1.0f - cc[3]);
    ++f->n;
}

void cj_rtile_run(void *user, const cj_tile *t) {
    const cj_rctx *c = user;
    cj_rcount *cnt = &c->count[t->thread];
    const int tw = t->x1 - t->x0, th = t->y1 - t->y0, spp = t->spp;
    const size_t n = (size_t)tw * (size_t)th * (size_t)spp;
    float *col = c->color[t->thread];
    uint32_t *ord = c->order[t->thread];
    double t0 = cj_render_now();

    /* counting sort of the samples by kernel; bucket CJ_RK_COUNT is the background */
    size_t start[CJ_RK_COUNT + 2], fill[CJ_RK_COUNT + 1];
    memset(start, 0, sizeof start);
    /* each sample's bucket is looked up once and kept, one byte per sample, in the colour
     * buffer (written only after the sort), for the second pass */
    const uint8_t *kern = c->opaque.kernel;
    uint8_t *bucket = (uint8_t *)col;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t tri = t->samples[i].tri;
        const uint8_t k = tri == CJ_RASTER_NO_TRI ? (uint8_t)CJ_RK_COUNT : kern[tri];
        bucket[i] = k;
        ++start[k + 1];
    }
    for (int k = 0; k <= CJ_RK_COUNT; ++k) start[k + 1] += start[k];
    memcpy(fill, start, sizeof fill);
    for (size_t i = 0; i < n; ++i) ord[fill[bucket[i]]++] = (uint32_t)i;
    for (size_t j = start[CJ_RK_COUNT]; j < start[CJ_RK_COUNT + 1]; ++j) {
        float *cc = col + 4 * (size_t)ord[j];
        cc[0] = c->bg[0];
        cc[1] = c->bg[1];
        cc[2] = c->bg[2];
        cc[3] = 0.0f;
    }
    double t1 = cj_render_now();
    cnt->sec[CJ_RS_BACKGROUND] += t1 - t0;
    cnt->n[CJ_RS_BACKGROUND] += start[CJ_RK_COUNT + 1] - start[CJ_RK_COUNT];

    /* id and depth planes: sample 0 of each pixel, before lines lower the depths */
    cj_render_image *img = c->img;
    if (img->ids || img->depth)
        for (int y = t->y0; y < t->y1; ++y)
            for (int x = t->x0; x < t->x1; ++x) {
                const cj_vis_sample *s =
                    &t->samples[((size_t)(y - t->y0) * (size_t)tw + (size_t)(x - t->x0)) *
                                (size_t)spp];
                size_t p = (size_t)y * (size_t)c->width + (size_t)x;
                if (img->ids)
                    img->ids[p] =
                        s->tri == CJ_RASTER_NO_TRI ? 0u : c->b->objects[c->opaque.obj[s->tri]].id;
                if (img->depth) img->depth[p] = s->depth;
            }

    for (int k = 0; k < CJ_RK_COUNT; ++k) {
        size_t m = start[k + 1] - start[k];
        if (!m) continue;
        double a = cj_render_now(), ac = cj_render_thread_cpu();
        cj_rshade_kernel(c, k, t, ord + start[k], m, col);
        cnt->sec[CJ_RS_SHADE0 + k] += cj_render_now() - a;
        cnt->cpu[CJ_RS_SHADE0 + k] += cj_render_thread_cpu() - ac;
        cnt->n[CJ_RS_SHADE0 + k] += m;
    }

    if (c->nemitters) cj_remitters_tile(c, t, col);

    if (c->has_lines) {
        double a = cj_render_now();
        cj_rlines_tile(c, t, col, &cnt->n[CJ_RS_LINES]);
        cnt->sec[CJ_RS_LINES] += cj_render_now() - a;
    }
    if (c->has_transp) {
        double a = cj_render_now(), ac = cj_render_thread_cpu();
        frag_ctx f = {c, t, col, 0};
        cj_raster_tile_forward(c->transp.prep, t, frag, &f);
        cnt->n[CJ_RS_TRANSPARENT] += f.n;
        cnt->sec[CJ_RS_TRANSPARENT] += cj_render_now() - a;
        cnt->cpu[CJ_RS_TRANSPARENT] += cj_render_thread_cpu() - ac;
    }

    double a = cj_render_now();
    if (spp == 1) {
        for (int y = t->y0; y < t->y1; ++y)
            memcpy(img->rgba + 4 * ((size_t)y * (size_t)c->width + (size_t)t->x0),
                   col + 4 * (size_t)(y - t->y0) * (size_t)tw, 4 * sizeof(float) * (size_t)tw);
        cnt->sec[CJ_RS_OUTPUT] += cj_render_now() - a;
        cnt->n[CJ_RS_OUTPUT] += (uint64_t)tw * (uint64_t)th;
        return;
    }
    /* box filter: the mean of the pixel's samples (1/spp is a power of two: exact scaling) */
    const float inv = 1.0f / (float)spp;
    for (int y = t->y0; y < t->y1; ++y)
        for (int x = t->x0; x < t->x1; ++x) {
            const float *s =
                col + 4 * ((size_t)(y - t->y0) * (size_t)tw + (size_t)(x - t->x0)) * (size_t)spp;
            float acc[4] = {0, 0, 0, 0};
            for (int k = 0; k < spp; ++k)
                for (int ch = 0; ch < 4; ++ch) acc[ch] += s[4 * k + ch];
            float *d = img->rgba + 4 * ((size_t)y * (size_t)c->width + (size_t)x);
            for (int ch = 0; ch < 4; ++ch) d[ch] = acc[ch] * inv;
        }
    cnt->sec[CJ_RS_RESOLVE] += cj_render_now() - a;
    cnt->n[CJ_RS_RESOLVE] += (uint64_t)tw * (uint64_t)th;
}
