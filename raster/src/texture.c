/* Texture sampling: nearest, bilinear, trilinear mip-mapped, and the box-filtered procedural
 * checker (see texture_internal.h). */
#include "texture_internal.h"

#include "render_internal.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>

cj_status cj_tex_sampler_init(const cj_texture *tex, int index, const cj_allocator *alloc,
                              cj_tex_sampler *out) {
    memset(out, 0, sizeof *out);
    out->alloc = cj_render_alloc(alloc);
    out->kind = tex->kind;
    out->filter = tex->filter;
    out->wrap = tex->wrap;
    out->su = tex->scale_u;
    out->sv = tex->scale_v;
    out->ou = tex->offset_u;
    out->ov = tex->offset_v;
    if (tex->kind == CJ_TEX_CHECKER) {
        out->checks_u = tex->checks_u > 0 ? tex->checks_u : 1;
        out->checks_v = tex->checks_v > 0 ? tex->checks_v : 1;
        out->a[0] = (float)tex->checker_a.r;
        out->a[1] = (float)tex->checker_a.g;
        out->a[2] = (float)tex->checker_a.b;
        out->b[0] = (float)tex->checker_b.r;
        out->b[1] = (float)tex->checker_b.g;
        out->b[2] = (float)tex->checker_b.b;
        out->needs_deriv = tex->filter != CJ_TEX_NEAREST;
        return CJ_OK;
    }
    if (!tex->texels || tex->width < 1 || tex->height < 1)
        return cj_fail(CJ_ERR_ARGUMENT, "textures[%d]: image texture '%s' has no pixels loaded",
                       index, tex->path ? tex->path : "");
    out->levels = 1;
    out->level[0].w = tex->width;
    out->level[0].h = tex->height;
    out->level[0].rgba = tex->texels;
    if (tex->filter != CJ_TEX_TRILINEAR) return CJ_OK;
    out->needs_deriv = 1;
    size_t total = 0;
    int w = tex->width, h = tex->height, n = 1;
    while ((w > 1 || h > 1) && n < CJ_TEX_MAX_LEVELS) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        total += (size_t)w * (size_t)h * 4;
        ++n;
    }
    out->owned = cj_ralloc(&out->alloc, total * sizeof(float));
    if (!out->owned) return cj_fail(CJ_ERR_NOMEM, "textures[%d]: mip levels", index);
    float *dst = out->owned;
    for (int l = 1; l < n; ++l) {
        const cj_tex_level *s = &out->level[l - 1];
        cj_tex_level *d = &out->level[l];
        d->w = s->w > 1 ? s->w / 2 : 1;
        d->h = s->h > 1 ? s->h / 2 : 1;
        for (int y = 0; y < d->h; ++y)
            for (int x = 0; x < d->w; ++x) {
                float acc[4] = {0, 0, 0, 0};
                int cnt = 0;
                /* the texels of the level below that this one covers (3 on an odd last row) */
                int x1 = (x == d->w - 1) ? s->w : 2 * x + 2,
                    y1 = (y == d->h - 1) ? s->h : 2 * y + 2;
                for (int yy = 2 * y; yy < y1; ++yy)
                    for (int xx = 2 * x; xx < x1; ++xx, ++cnt)
                        for (int c = 0; c < 4; ++c)
                            acc[c] += s->rgba[((size_t)yy * (size_t)s->w + (size_t)xx) * 4 + c];
                for (int c = 0; c < 4; ++c)
                    dst[((size_t)y * (size_t)d->w + (size_t)x) * 4 + c] = acc[c] / (float)cnt;
            }
        d->rgba = dst;
        dst += (size_t)d->w * (size_t)d->h * 4;
    }
    out->levels = n;
    return CJ_OK;
}

void cj_tex_sampler_free(cj_tex_sampler *s) {
    cj_rfree(&s->alloc, s->owned);
    s->owned = NULL;
}

static inline int wrap_index(int i, int n, cj_tex_wrap wrap) {
    if (wrap == CJ_TEX_CLAMP) return i < 0 ? 0 : i >= n ? n - 1 : i;
    int m = i % n;
    return m < 0 ? m + n : m;
}

/* Keeps huge coordinates in int range (repeat: only the fraction matters). */
static inline double reduce(double t, cj_tex_wrap wrap) {
    if (wrap == CJ_TEX_REPEAT) return t - floor(t);
    return t < -1.0 ? -1.0 : t > 2.0 ? 2.0 : t;
}

static inline float lerpf(float a, float b, float f) {
    return a + f * (b - a);
}

static void texel(const cj_tex_level *l, int x, int y, float out[3]) {
    const float *p = l->rgba + ((size_t)y * (size_t)l->w + (size_t)x) * 4;
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
}

static void nearest(const cj_tex_level *l, cj_tex_wrap wrap, double u, double v, float out[3]) {
    int x = wrap_index((int)floor(u * l->w), l->w, wrap);
    int y = wrap_index((int)floor(v * l->h), l->h, wrap);
    texel(l, x, y, out);
}

static void bilinear(const cj_tex_level *l, cj_tex_wrap wrap, double u, double v, float out[3]) {
    double x = u * l->w - 0.5, y = v * l->h - 0.5;
    double fx0 = floor(x), fy0 = floor(y);
    float fx = (float)(x - fx0), fy = (float)(y - fy0);
    int x0 = wrap_index((int)fx0, l->w, wrap), x1 = wrap_index((int)fx0 + 1, l->w, wrap);
    int y0 = wrap_index((int)fy0, l->h, wrap), y1 = wrap_index((int)fy0 + 1, l->h, wrap);
    float a[3], b[3], c[3], d[3];
    texel(l, x0, y0, a);
    texel(l, x1, y0, b);
    texel(l, x0, y1, c);
    texel(l, x1, y1, d);
    for (int k = 0; k < 3; ++k) out[k] = lerpf(lerpf(a[k], b[k], fx), lerpf(c[k], d[k], fx), fy);
}

/* ∫_0^x (floor(t) mod 2) dt: the measure of odd cells in [0, x]. */
static double odd_measure(double x) {
    double h = floor(x / 2.0), r = x - 2.0 * h;
    return h + (r > 1.0 ? r - 1.0 : 0.0);
}

/* Fraction of [x − w/2, x + w/2] in odd cells (w > 0), or the point's parity. Inlined into
 * cj_tex_sample: it runs twice per textured sample. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline double
odd_fraction(double x, double w) {
    if (!(w > 1e-9)) return (double)((long long)floor(x) & 1);
    if (w > 1e6) return 0.5;
    return (odd_measure(x + 0.5 * w) - odd_measure(x - 0.5 * w)) / w;
}

void cj_tex_sample(const cj_tex_sampler *s, double u, double v, double dudx, double dvdx,
                   double dudy, double dvdy, float out[3]) {
    double tu = u * s->su + s->ou, tv = v * s->sv + s->ov;
    if (s->kind == CJ_TEX_CHECKER) {
        double cu = tu * s->checks_u, cv = tv * s->checks_v, fu, fv;
        cu -= 2.0 * floor(cu / 2.0); /* period 2: keeps the arguments small */
        cv -= 2.0 * floor(cv / 2.0);
        if (s->needs_deriv) {
            double wu = (fabs(dudx) + fabs(dudy)) * fabs(s->su) * s->checks_u;
            double wv = (fabs(dvdx) + fabs(dvdy)) * fabs(s->sv) * s->checks_v;
            fu = odd_fraction(cu, wu);
            fv = odd_fraction(cv, wv);
        } else {
            fu = cu >= 1.0 ? 1.0 : 0.0;
            fv = cv >= 1.0 ? 1.0 : 0.0;
        }
        /* odd parity of the sum: exactly one of the two is odd */
        float f = (float)(fu * (1.0 - fv) + fv * (1.0 - fu));
        for (int k = 0; k < 3; ++k) out[k] = lerpf(s->a[k], s->b[k], f);
        return;
    }
    tu = reduce(tu, s->wrap);
    tv = reduce(tv, s->wrap);
    if (s->filter == CJ_TEX_NEAREST) {
        nearest(&s->level[0], s->wrap, tu, tv, out);
        return;
    }
    if (s->filter == CJ_TEX_BILINEAR || s->levels == 1) {
        bilinear(&s->level[0], s->wrap, tu, tv, out);
        return;
    }
    double W = s->level[0].w, H = s->level[0].h;
    double rx = hypot(dudx * s->su * W, dvdx * s->sv * H);
    double ry = hypot(dudy * s->su * W, dvdy * s->sv * H);
    double rho = rx > ry ? rx : ry;
    double lambda = rho > 1.0 ? log2(rho) : 0.0;
    if (lambda <= 0.0) {
        bilinear(&s->level[0], s->wrap, tu, tv, out);
        return;
    }
    if (lambda >= s->levels - 1) {
        bilinear(&s->level[s->levels - 1], s->wrap, tu, tv, out);
        return;
    }
    int l0 = (int)lambda;
    float f = (float)(lambda - l0), a[3], b[3];
    bilinear(&s->level[l0], s->wrap, tu, tv, a);
    bilinear(&s->level[l0 + 1], s->wrap, tu, tv, b);
    for (int k = 0; k < 3; ++k) out[k] = lerpf(a[k], b[k], f);
}
