/* raster/: exact coverage of the triangle rasterizer. Every covered sample is compared with an
 * exact rational reference of the top-left rule on the snapped vertices (tests/raster_ref.h),
 * on >= 1e5 random triangle fans (shared edges and vertices, both windings, all sub-pixel
 * positions, tiny to huge, partly off-screen) and on the tessellated teapot: 0 gaps, 0 double
 * hits. Both paths are checked: the forward mode (every fragment) and the visibility pass. Then the
 * frame is bit-identical for threads 1, 2, 3 and tile sizes 8, 16, 64, 100, and the visibility
 * buffer is the nearest fragment (earliest on ties) of the forward mode.
 *
 * CJ_RASTER_EXACT_SCALE (default 1, and 0.1 in AddressSanitizer builds) scales the fan count;
 * below 1 the teapots are also tessellated more coarsely (fewer triangles, same checks). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "casteljau/scene.h"
#include "casteljau/tessellate.h"
#include "raster_ref.h"
#include "rng.h"

#include <stdio.h>

static uint64_t g_seed;

/* GCC names AddressSanitizer builds __SANITIZE_ADDRESS__, clang through __has_feature. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CJ_TEST_CLANG_ASAN 1
#endif
#endif
#ifndef CJ_TEST_CLANG_ASAN
#define CJ_TEST_CLANG_ASAN 0
#endif

static double scale_factor(void) {
    const char *s = getenv("CJ_RASTER_EXACT_SCALE");
    double f = s ? atof(s) : 1.0;
#if defined(__SANITIZE_ADDRESS__) || CJ_TEST_CLANG_ASAN
    if (!s) f = 0.1;
#endif
    return f > 0 ? f : 1.0;
}

static uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Per-sample fragment counts and a hash of the triangles that hit the sample. */
typedef struct acc {
    int W, H, spp;
    uint16_t *cnt;
    uint64_t *hash;
    int *sign; /* optional: per source triangle ±1 (orientation), signed sum in ssum */
    int32_t *ssum;
} acc;

static void acc_frag(void *u, int x, int y, int s, uint32_t tri, float z, float b1, float b2) {
    (void)z;
    (void)b1;
    (void)b2;
    acc *a = u;
    const size_t i = ((size_t)y * a->W + x) * a->spp + s;
    a->cnt[i]++;
    a->hash[i] += mix(tri);
    if (a->sign) a->ssum[i] += a->sign[tri];
}

/* Exact coverage of one triangle (snapped by the specified rule) added into acc. */
static void ref_tri(acc *a, const int64_t X[3], const int64_t Y[3], uint32_t tri,
                    const int64_t ox[16], const int64_t oy[16]) {
    int64_t lx = X[0], hx = X[0], ly = Y[0], hy = Y[0];
    for (int k = 1; k < 3; ++k) {
        lx = X[k] < lx ? X[k] : lx;
        hx = X[k] > hx ? X[k] : hx;
        ly = Y[k] < ly ? Y[k] : ly;
        hy = Y[k] > hy ? Y[k] : hy;
    }
    int64_t x0 = lx / 256 - 1, x1 = hx / 256 + 1, y0 = ly / 256 - 1, y1 = hy / 256 + 1;
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 >= a->W ? a->W - 1 : x1;
    y1 = y1 >= a->H ? a->H - 1 : y1;
    for (int64_t y = y0; y <= y1; ++y)
        for (int64_t x = x0; x <= x1; ++x)
            for (int s = 0; s < a->spp; ++s) {
                const int64_t sx = 256 * x + ox[s], sy = 256 * y + oy[s];
                if (sx < lx || sx > hx || sy < ly || sy > hy) continue;
                if (!ref_covers(X, Y, sx, sy)) continue;
                const size_t i = ((size_t)y * a->W + x) * a->spp + s;
                a->cnt[i]++;
                a->hash[i] += mix(tri);
                if (a->sign) a->ssum[i] += a->sign[tri];
            }
}

static void acc_init(acc *a, int W, int H, int spp) {
    memset(a, 0, sizeof *a);
    a->W = W;
    a->H = H;
    a->spp = spp;
    const size_t n = (size_t)W * H * spp;
    a->cnt = calloc(n, sizeof *a->cnt);
    a->hash = calloc(n, sizeof *a->hash);
    assert_non_null(a->cnt);
    assert_non_null(a->hash);
}

static void acc_free(acc *a) {
    free(a->cnt);
    free(a->hash);
    free(a->ssum);
}

/* ---- fans ----------------------------------------------------------------------------- */

#define FAN_MAX 9 /* centre + up to 8 ring vertices */

typedef struct fan {
    int n; /* ring vertices */
    int64_t X[FAN_MAX], Y[FAN_MAX];
} fan;

/* A fan around (cx, cy) pixels with ring radii in [r0, r1] pixels: clip coordinates into clip
 * (random w, so snapping goes through the division), snapped positions into f. Returns 0 when
 * snapping made a triangle non-positive (the caller draws another fan). */
static int make_fan(cj_rng *r, double cx, double cy, double r0, double r1, int W, int H,
                    double *clip, fan *f) {
    const int n = cj_rng_int(r, 3, FAN_MAX - 1);
    /* Vertices on the 1/256 grid, or on coarse grids (1/16, 1/2 pixel, possibly through pixel
     * centres) so that many samples fall exactly on edges and vertices. */
    static const double grids[3] = {256.0, 16.0, 2.0};
    const double q = r1 <= 2.0 ? grids[cj_rng_int(r, 0, 1)] : grids[cj_rng_int(r, 0, 2)];
    const double centre_off = cj_rng_int(r, 0, 1) ? 0.5 : 0.0;
    double gaps[FAN_MAX], sum = 0;
    for (int i = 0; i < n; ++i) sum += gaps[i] = cj_rng_range(r, 0.5, 1.5);
    double ang = cj_rng_range(r, 0, 6.283185307179586);
    for (int i = 0; i < n; ++i)
        if (gaps[i] / sum * 6.283185307179586 > 0.9 * 3.141592653589793) return 0;
    for (int v = 0; v <= n; ++v) {
        double px, py;
        if (v == 0) {
            px = cx + floor(cj_rng_int(r, 0, 255) / 256.0 * q) / q + centre_off;
            py = cy + floor(cj_rng_int(r, 0, 255) / 256.0 * q) / q + centre_off;
        } else {
            const double rad = cj_rng_range(r, r0, r1);
            px = cx + rad * cos(ang);
            py = cy + rad * sin(ang);
            ang += gaps[v - 1] / sum * 6.283185307179586;
            px = floor(px * q) / q + centre_off;
            py = floor(py * q) / q + centre_off;
        }
        const double w = cj_rng_range(r, 0.25, 4.0);
        double *c = clip + 4 * v;
        c[0] = (2.0 * px / W - 1.0) * w;
        c[1] = (2.0 * py / H - 1.0) * w;
        c[2] = cj_rng_range(r, -0.5, 0.5) * w;
        c[3] = w;
        f->X[v] = ref_snap(c[0], c[3], W);
        f->Y[v] = ref_snap(c[1], c[3], H);
    }
    f->n = n;
    for (int i = 0; i < n; ++i) {
        const int a = 1 + i, b = 1 + (i + 1) % n;
        const int64_t X[3] = {f->X[0], f->X[a], f->X[b]}, Y[3] = {f->Y[0], f->Y[a], f->Y[b]};
        if (ref_area2(X, Y) <= 0) return 0;
    }
    return 1;
}

/* The winding number of the closed polyline (X[i], Y[i]) → (X[i+1], Y[i+1]) around the sample
 * moved by (+ε, −ε²): a ray to the right at height sy − ε² crosses edge a→b iff exactly one
 * end has Y >= sy, and the crossing lies right of the sample iff its exact abscissa at sy is
 * > sx, i.e. orient(a, b, s) > 0 for an upward edge, < 0 for a downward one. The moved sample
 * is never on an edge, so this is the exact number of times a partition must cover it. */
static int edge_crossing(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t sx, int64_t sy) {
    const int up = ay < sy && by >= sy, down = ay >= sy && by < sy;
    if (!up && !down) return 0;
    const int o = ref_orient(ax, ay, bx, by, sx, sy);
    if (up) return o > 0;
    return -(o < 0);
}

/* Every sample in the fan's box is hit exactly as often as the ring winds around it (0 or
 * 1): no gaps, no double hits, on shared edges and vertices too. Returns the violations. */
static size_t check_fan(const acc *a, const fan *f, const int64_t ox[16], const int64_t oy[16],
                        size_t *inside_samples) {
    int64_t lx = f->X[0], hx = lx, ly = f->Y[0], hy = ly;
    for (int v = 1; v <= f->n; ++v) {
        lx = f->X[v] < lx ? f->X[v] : lx;
        hx = f->X[v] > hx ? f->X[v] : hx;
        ly = f->Y[v] < ly ? f->Y[v] : ly;
        hy = f->Y[v] > hy ? f->Y[v] : hy;
    }
    size_t bad = 0;
    const int64_t x0 = lx / 256 - 1 < 0 ? 0 : lx / 256 - 1,
                  y0 = ly / 256 - 1 < 0 ? 0 : ly / 256 - 1;
    for (int64_t y = y0; y <= hy / 256 + 1 && y < a->H; ++y)
        for (int64_t x = x0; x <= hx / 256 + 1 && x < a->W; ++x)
            for (int s = 0; s < a->spp; ++s) {
                const int64_t sx = 256 * x + ox[s], sy = 256 * y + oy[s];
                int w = 0;
                for (int i = 0; i < f->n; ++i) {
                    const int p = 1 + i, q = 1 + (i + 1) % f->n;
                    w += edge_crossing(f->X[p], f->Y[p], f->X[q], f->Y[q], sx, sy);
                }
                const int c = a->cnt[((size_t)y * a->W + x) * a->spp + s];
                if (c != w && bad == 0) {
                    printf("test_raster_exact: fan of %d: sample (%lld, %lld)/256 hit %d times, "
                           "winding %d; vertices",
                           f->n, (long long)sx, (long long)sy, c, w);
                    for (int v = 0; v <= f->n; ++v)
                        printf(" (%lld, %lld)", (long long)f->X[v], (long long)f->Y[v]);
                    printf("\n");
                }
                bad += c != w;
                *inside_samples += w == 1;
            }
    return bad;
}

typedef struct fan_totals {
    size_t fans, tris, inside, frags, mismatched, violations;
} fan_totals;

/* One image of fans: `cells` × `cells` cells of `cell` pixels with one fan each (radius in
 * [r0, r1]), or `huge` fans alone in a small image. */
static void fan_batch(cj_rng *r, int spp, int cells, int cell, double r0, double r1, int huge,
                      fan_totals *tot) {
    const int W = huge ? cj_rng_int(r, 60, 200) : cells * cell;
    const int H = huge ? cj_rng_int(r, 60, 200) : cells * cell;
    const int nf = huge ? 1 : cells * cells;
    double *clip = malloc(sizeof(double) * 4 * FAN_MAX * nf);
    uint32_t *tris = malloc(sizeof(uint32_t) * 3 * (FAN_MAX - 1) * nf);
    fan *fans = malloc(sizeof(fan) * nf);
    size_t nv = 0, nt = 0;
    for (int i = 0; i < nf; ++i) {
        double cx, cy;
        if (huge) {
            cx = cj_rng_range(r, -0.5 * W, 1.5 * W);
            cy = cj_rng_range(r, -0.5 * H, 1.5 * H);
        } else {
            /* fans stay >= 2 pixels apart: centre within 2 px of the cell's, radius <= 9.5 */
            cx = (i % cells) * cell + 0.5 * cell + cj_rng_range(r, -2, 2);
            cy = (i / cells) * cell + 0.5 * cell + cj_rng_range(r, -2, 2);
        }
        while (!make_fan(r, floor(cx), floor(cy), r0, r1, W, H, clip + 4 * nv, &fans[i])) {
        }
        const int n = fans[i].n;
        for (int k = 0; k < n; ++k) {
            uint32_t v[3] = {(uint32_t)nv, (uint32_t)(nv + 1 + k),
                             (uint32_t)(nv + 1 + (k + 1) % n)};
            /* both windings and every rotation of the index triple */
            const int perm = cj_rng_int(r, 0, 5);
            static const int P[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                        {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
            for (int j = 0; j < 3; ++j) tris[3 * nt + j] = v[P[perm][j]];
            nt++;
        }
        nv += 1 + n;
    }
    cj_raster_input in = {nv, clip, nt, tris, W, H, spp};
    acc ras, ref;
    acc_init(&ras, W, H, spp);
    acc_init(&ref, W, H, spp);
    int64_t ox[16], oy[16];
    assert_true(ref_pattern(spp, ox, oy));
    cj_raster_stats st;
    cj_vis_sample *vis = malloc(sizeof *vis * W * H * spp);
    assert_int_equal(rh_render(&in, 64, 1, vis, acc_frag, &ras, &st), CJ_OK);
    for (size_t t = 0; t < nt; ++t) {
        int64_t X[3], Y[3];
        for (int k = 0; k < 3; ++k) {
            const double *c = clip + 4 * tris[3 * t + k];
            X[k] = ref_snap(c[0], c[3], W);
            Y[k] = ref_snap(c[1], c[3], H);
        }
        ref_tri(&ref, X, Y, (uint32_t)t, ox, oy);
    }
    const size_t n = (size_t)W * H * spp;
    size_t mism = 0;
    for (size_t i = 0; i < n; ++i) {
        mism += ras.cnt[i] != ref.cnt[i] || ras.hash[i] != ref.hash[i];
        tot->frags += ras.cnt[i];
        /* The fans do not overlap: the visibility pass keeps the one covering triangle. */
        if (ref.cnt[i] == 1)
            mism += vis[i].tri == CJ_RASTER_NO_TRI || mix(vis[i].tri) != ref.hash[i];
        else
            mism += ref.cnt[i] == 0 && vis[i].tri != CJ_RASTER_NO_TRI;
    }
    free(vis);
    if (mism && !tot->mismatched)
        printf("test_raster_exact: first mismatch batch spp %d W %d H %d\n", spp, W, H);
    tot->mismatched += mism;
    for (int i = 0; i < nf; ++i) tot->violations += check_fan(&ras, &fans[i], ox, oy, &tot->inside);
    tot->fans += nf;
    tot->tris += nt;
    acc_free(&ras);
    acc_free(&ref);
    free(clip);
    free(tris);
    free(fans);
}

static void test_fans(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed);
    const double f = scale_factor();
    fan_totals tot;
    memset(&tot, 0, sizeof tot);
    /* spp 1: 32 × 32 cells of 28 px; spp 4: 16 × 16; spp 16: 8 × 8; radii tiny to 10 px. */
    const int b1 = (int)ceil(92 * f), b4 = (int)ceil(20 * f), b16 = (int)ceil(40 * f);
    for (int b = 0; b < b1 + b4 + b16; ++b) {
        const int spp = b < b1 ? 1 : b < b1 + b4 ? 4 : 16;
        const int cells = spp == 1 ? 32 : spp == 4 ? 16 : 8;
        const int kind = b % 3; /* tiny, small, mixed */
        const double r0 = kind == 0 ? 0.3 : kind == 1 ? 2.0 : 0.3;
        const double r1 = kind == 0 ? 2.0 : kind == 1 ? 9.0 : 9.0;
        fan_batch(&r, spp, cells, 28, r0, r1, 0, &tot);
    }
    const size_t small_fans = tot.fans;
    /* Huge fans, partly off-screen, one per image: radii up to 1e5 px. */
    const int nh = (int)ceil(60 * f);
    for (int b = 0; b < nh; ++b) {
        const int spp = b % 3 == 0 ? 1 : b % 3 == 1 ? 4 : 16;
        const double rmax = b % 2 ? 1e5 : 400;
        fan_batch(&r, spp, 1, 0, 30, rmax, 1, &tot);
    }
    printf("test_raster_exact: %zu fans (%zu small, %zu huge), %zu triangles, %zu fragments: "
           "%zu samples differ from the exact reference; %zu samples inside a fan, %zu where the "
           "hit count differs from the fan's winding number (gaps or double hits)\n",
           tot.fans, small_fans, tot.fans - small_fans, tot.tris, tot.frags, tot.mismatched,
           tot.inside, tot.violations);
    assert_true(tot.fans >= (size_t)(1e5 * f));
    assert_int_equal(tot.mismatched, 0);
    assert_int_equal(tot.violations, 0);
    assert_true(tot.inside > tot.fans);
}

/* ---- the small-triangle kernel ---------------------------------------------------------- */

/* Triangles the 32-bit kernel takes (columns in a tile <= 8, sides <= 64 px) and their
 * neighbours just past its limits: thin and tall (1–10 × 50–70 px), flat and wide
 * (50–70 × 1–10 px, whose columns a small tile cuts to <= 8), and 3–9 px ones, one per cell,
 * straddling tile borders, at tile sizes 8, 16 and 64. Every fragment of the forward mode and
 * every visibility sample must equal the exact reference. */
static void test_small_kernel(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed ^ 0x5a5au);
    const int cells = 10, cell = 80, W = cells * cell, H = cells * cell;
    const int nt = cells * cells;
    double *clip = malloc(sizeof(double) * 4 * 3 * nt);
    uint32_t *tris = malloc(sizeof(uint32_t) * 3 * nt);
    size_t mism = 0, frags = 0, runs = 0, small_sized = 0;
    static const int tiles[3] = {8, 16, 64};
    const int rounds = scale_factor() < 1 ? 3 : 6; /* spp 1, 4, 16 (twice) */
    for (int round = 0; round < rounds; ++round) {
        const int spp = round % 3 == 0 ? 1 : round % 3 == 1 ? 4 : 16;
        for (int t = 0; t < nt; ++t) {
            const int kind = cj_rng_int(&r, 0, 2);
            double sw = cj_rng_range(&r, 1, 10), sh = cj_rng_range(&r, 50, 70);
            if (kind == 1) {
                const double tmp = sw;
                sw = sh;
                sh = tmp;
            } else if (kind == 2) {
                sw = cj_rng_range(&r, 3, 9);
                sh = cj_rng_range(&r, 3, 9);
            }
            small_sized += sw <= 64 && sh <= 64;
            const double ox = (t % cells) * cell + cj_rng_range(&r, 2, cell - 2 - sw);
            const double oy = (t / cells) * cell + cj_rng_range(&r, 2, cell - 2 - sh);
            /* one vertex on each of three sides of the box, so the box is the triangle's */
            const double px[3] = {ox, ox + sw, ox + cj_rng_range(&r, 0, sw)};
            const double py[3] = {oy + cj_rng_range(&r, 0, sh), oy, oy + sh};
            const int flip = cj_rng_int(&r, 0, 1); /* both windings */
            for (int k = 0; k < 3; ++k) {
                const double w = cj_rng_range(&r, 0.5, 2.0);
                double *c = clip + 4 * (3 * t + k);
                c[0] = (2.0 * (floor(px[k] * 256) / 256) / W - 1.0) * w;
                c[1] = (2.0 * (floor(py[k] * 256) / 256) / H - 1.0) * w;
                c[2] = cj_rng_range(&r, -0.5, 0.5) * w;
                c[3] = w;
                tris[3 * t + k] = (uint32_t)(3 * t + (flip ? 2 - k : k));
            }
        }
        acc ref;
        acc_init(&ref, W, H, spp);
        int64_t ox[16], oy[16];
        assert_true(ref_pattern(spp, ox, oy));
        for (int t = 0; t < nt; ++t) {
            int64_t X[3], Y[3];
            for (int k = 0; k < 3; ++k) {
                const double *c = clip + 4 * tris[3 * t + k];
                X[k] = ref_snap(c[0], c[3], W);
                Y[k] = ref_snap(c[1], c[3], H);
            }
            ref_tri(&ref, X, Y, (uint32_t)t, ox, oy);
        }
        const size_t n = (size_t)W * H * spp;
        cj_vis_sample *vis = malloc(sizeof *vis * n);
        for (int k = 0; k < 3; ++k) {
            cj_raster_input in = {(size_t)3 * nt, clip, (size_t)nt, tris, W, H, spp};
            acc ras;
            acc_init(&ras, W, H, spp);
            assert_int_equal(rh_render(&in, tiles[k], 1, vis, acc_frag, &ras, NULL), CJ_OK);
            for (size_t i = 0; i < n; ++i) {
                mism += ras.cnt[i] != ref.cnt[i] || ras.hash[i] != ref.hash[i];
                frags += ras.cnt[i];
                if (ref.cnt[i] == 1) /* the cells do not overlap */
                    mism += vis[i].tri == CJ_RASTER_NO_TRI || mix(vis[i].tri) != ref.hash[i];
                else
                    mism += vis[i].tri != CJ_RASTER_NO_TRI;
            }
            acc_free(&ras);
            runs++;
        }
        free(vis);
        acc_free(&ref);
    }
    printf("test_raster_exact: small-triangle kernel: %zu runs (spp 1/4/16 x tiles 8/16/64) of "
           "%d triangles (%zu of %zu within 64 px each way), %zu fragments: %zu samples differ "
           "from the exact reference\n",
           runs, nt, small_sized, (size_t)rounds * nt, frags, mism);
    assert_int_equal(mism, 0);
    assert_true(frags > 0);
    free(clip);
    free(tris);
}

/* ---- the tessellated teapot ------------------------------------------------------------ */

typedef struct teapot {
    cj_mesh *mesh;
    double *clip;
} teapot;

static void teapot_make(teapot *tp, double tol, const cj_camera *cam, double aspect) {
    cj_patchset *ps = NULL;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &ps), CJ_OK);
    assert_int_equal(cj_mesh_create(NULL, &tp->mesh), CJ_OK);
    cj_tess_options o;
    memset(&o, 0, sizeof o);
    o.tol = tol;
    cj_tess_report rep;
    assert_int_equal(cj_tessellate_patches(ps->patches, ps->count, &o, tp->mesh, &rep), CJ_OK);
    cj_patchset_destroy(ps);
    cj_xform3 M;
    assert_int_equal(cj_camera_world_to_clip(cam, aspect, &M), CJ_OK);
    const size_t nv = tp->mesh->vertex_count;
    tp->clip = malloc(sizeof(double) * 4 * nv);
    for (size_t i = 0; i < nv; ++i) {
        const double *p = tp->mesh->positions + 3 * i;
        for (int r = 0; r < 4; ++r)
            tp->clip[4 * i + r] =
                M.m[r][0] * p[0] + M.m[r][1] * p[1] + M.m[r][2] * p[2] + M.m[r][3];
    }
}

static void teapot_free(teapot *tp) {
    cj_mesh_destroy(tp->mesh);
    free(tp->clip);
}

static int cmp_pos(const void *a, const void *b, const double *pos) {
    return memcmp(pos + 3 * *(const uint32_t *)a, pos + 3 * *(const uint32_t *)b, 24);
}
static const double *g_sort_pos;
static int cmp_idx(const void *a, const void *b) {
    return cmp_pos(a, b, g_sort_pos);
}

/* Directed edge between welded vertices with its net multiplicity (a→b minus b→a). */
typedef struct dedge {
    uint32_t a, b;
    int net;
} dedge;
static int cmp_edge(const void *p, const void *q) {
    const dedge *e = p, *f = q;
    if (e->a != f->a) return e->a < f->a ? -1 : 1;
    if (e->b != f->b) return e->b < f->b ? -1 : 1;
    return 0;
}

/* The winding number of the net boundary edges around the moved sample (see edge_crossing). */
static int winding(const dedge *e, size_t ne, const int64_t *X, const int64_t *Y, int64_t sx,
                   int64_t sy) {
    int w = 0;
    for (size_t i = 0; i < ne; ++i)
        w += e[i].net * edge_crossing(X[e[i].a], Y[e[i].a], X[e[i].b], Y[e[i].b], sx, sy);
    return w;
}

static void test_teapot_coverage(void **state) {
    (void)state;
    const int W = 192, H = 144;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(5.5, 4.0, 6.5);
    cam.gaze = cj_v3(-5.5, -4.5, -6.5);
    cam.fov_y = 0.6;
    teapot tp;
    /* (coarser under the sanitizers, see scale_factor) */
    teapot_make(&tp, scale_factor() < 1 ? 8e-3 : 2e-3, &cam, (double)W / H);
    const cj_mesh *m = tp.mesh;
    const size_t nv = m->vertex_count, nt = m->triangle_count;
    /* Weld bit-identical positions (the tessellator's shared edges). */
    uint32_t *ord = malloc(nv * sizeof *ord), *weld = malloc(nv * sizeof *weld);
    for (size_t i = 0; i < nv; ++i) ord[i] = (uint32_t)i;
    g_sort_pos = m->positions;
    qsort(ord, nv, sizeof *ord, cmp_idx);
    for (size_t i = 0; i < nv; ++i)
        weld[ord[i]] =
            (i && !cmp_pos(&ord[i], &ord[i - 1], m->positions)) ? weld[ord[i - 1]] : ord[i];
    int64_t *X = malloc(nv * sizeof *X), *Y = malloc(nv * sizeof *Y);
    for (size_t i = 0; i < nv; ++i) {
        X[i] = ref_snap(tp.clip[4 * i], tp.clip[4 * i + 3], W);
        Y[i] = ref_snap(tp.clip[4 * i + 1], tp.clip[4 * i + 3], H);
    }
    dedge *e = malloc(3 * nt * sizeof *e);
    int *sign = malloc(nt * sizeof *sign);
    for (size_t t = 0; t < nt; ++t) {
        const uint32_t *v = m->triangles + 3 * t;
        const int64_t tx[3] = {X[v[0]], X[v[1]], X[v[2]]}, ty[3] = {Y[v[0]], Y[v[1]], Y[v[2]]};
        const int64_t a2 = ref_area2(tx, ty);
        sign[t] = a2 > 0 ? 1 : a2 < 0 ? -1 : 0;
        for (int k = 0; k < 3; ++k) {
            uint32_t a = weld[v[k]], b = weld[v[(k + 1) % 3]];
            e[3 * t + k].net = a < b ? 1 : -1;
            e[3 * t + k].a = a < b ? a : b;
            e[3 * t + k].b = a < b ? b : a;
        }
    }
    qsort(e, 3 * nt, sizeof *e, cmp_edge);
    size_t ne = 0;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i;
        int net = 0;
        while (j < 3 * nt && e[j].a == e[i].a && e[j].b == e[i].b) net += e[j++].net;
        if (net) e[ne++] = (dedge){e[i].a, e[i].b, net};
        i = j;
    }
    for (int spp = 1; spp <= 4; spp *= 4) {
        acc ras, ref;
        acc_init(&ras, W, H, spp);
        acc_init(&ref, W, H, spp);
        ras.sign = ref.sign = sign;
        ras.ssum = calloc((size_t)W * H * spp, sizeof *ras.ssum);
        ref.ssum = calloc((size_t)W * H * spp, sizeof *ref.ssum);
        int64_t ox[16], oy[16];
        assert_true(ref_pattern(spp, ox, oy));
        cj_raster_input in = {nv, tp.clip, nt, m->triangles, W, H, spp};
        assert_int_equal(rh_render(&in, 32, 2, NULL, acc_frag, &ras, NULL), CJ_OK);
        for (size_t t = 0; t < nt; ++t) {
            const uint32_t *v = m->triangles + 3 * t;
            const int64_t tx[3] = {X[v[0]], X[v[1]], X[v[2]]}, ty[3] = {Y[v[0]], Y[v[1]], Y[v[2]]};
            ref_tri(&ref, tx, ty, (uint32_t)t, ox, oy);
        }
        size_t mism = 0, topo = 0, foot = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                for (int s = 0; s < spp; ++s) {
                    const size_t i = ((size_t)y * W + x) * spp + s;
                    mism += ras.cnt[i] != ref.cnt[i] || ras.hash[i] != ref.hash[i];
                    const int w = winding(e, ne, X, Y, 256 * x + ox[s], 256 * y + oy[s]);
                    topo += ras.ssum[i] != w;
                    foot += ras.cnt[i] != 0;
                }
        printf("test_raster_exact: teapot %zu triangles, %zu net boundary edges, spp %d: %zu "
               "samples covered, %zu differ from the exact reference, %zu where the signed hit "
               "count differs from the winding number of the boundary (gaps/double hits)\n",
               nt, ne, spp, foot, mism, topo);
        assert_int_equal(mism, 0);
        assert_int_equal(topo, 0);
        assert_true(foot > (size_t)W * H * spp / 8);
        acc_free(&ras);
        acc_free(&ref);
    }
    free(ord);
    free(weld);
    free(X);
    free(Y);
    free(e);
    free(sign);
    teapot_free(&tp);
}

/* ---- determinism and the depth test ----------------------------------------------------- */

typedef struct nearest {
    int W, spp;
    cj_vis_sample *best;
} nearest;

static void nearest_frag(void *u, int x, int y, int s, uint32_t tri, float z, float b1, float b2) {
    nearest *n = u;
    cj_vis_sample *b = &n->best[((size_t)y * n->W + x) * n->spp + s];
    /* fragments of one sample arrive in input order: strictly nearer wins */
    if (z < b->depth) {
        b->depth = z;
        b->tri = tri;
        b->b1 = b1;
        b->b2 = b2;
    }
}

static void test_determinism(void **state) {
    (void)state;
    const int W = 203, H = 157;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(2.5, 3.0, 4.0);
    cam.gaze = cj_v3(-2.5, -3.2, -4.0);
    cam.near = -3.0; /* cuts the teapot: near-plane clipping inside the frame */
    cam.fov_y = 0.9;
    teapot tp;
    teapot_make(&tp, scale_factor() < 1 ? 3e-2 : 5e-3, &cam, (double)W / H);
    /* A second teapot shifted by a few pixels in depth-order ties: draw the mesh twice. */
    const size_t nt = tp.mesh->triangle_count;
    uint32_t *tris = malloc(2 * 3 * nt * sizeof *tris);
    memcpy(tris, tp.mesh->triangles, 3 * nt * sizeof *tris);
    memcpy(tris + 3 * nt, tp.mesh->triangles, 3 * nt * sizeof *tris);
    static const int tiles[4] = {8, 16, 64, 100};
    size_t configs = 0;
    for (int spp = 1; spp <= 16; spp *= 4) {
        cj_raster_input in = {tp.mesh->vertex_count, tp.clip, 2 * nt, tris, W, H, spp};
        const size_t n = (size_t)W * H * spp;
        cj_vis_sample *first = malloc(n * sizeof *first), *vis = malloc(n * sizeof *vis);
        cj_raster_stats st0, st;
        assert_int_equal(rh_render(&in, 64, 1, first, NULL, NULL, &st0), CJ_OK);
        for (int th = 1; th <= 3; ++th)
            for (int k = 0; k < 4; ++k) {
                memset(vis, 0xab, n * sizeof *vis);
                assert_int_equal(rh_render(&in, tiles[k], th, vis, NULL, NULL, &st), CJ_OK);
                assert_memory_equal(first, vis, n * sizeof *vis);
                assert_true(st.samples_written == st0.samples_written);
                assert_true(st.tris_setup == st0.tris_setup);
                configs++;
            }
        /* The visibility buffer is the nearest of all fragments, the earliest on ties. */
        nearest nr = {W, spp, malloc(n * sizeof(cj_vis_sample))};
        for (size_t i = 0; i < n; ++i) {
            nr.best[i].depth = 1.0f;
            nr.best[i].tri = CJ_RASTER_NO_TRI;
            nr.best[i].b1 = nr.best[i].b2 = 0;
        }
        assert_int_equal(rh_render(&in, 16, 2, NULL, nearest_frag, &nr, NULL), CJ_OK);
        size_t covered = 0, second = 0;
        for (size_t i = 0; i < n; ++i) {
            covered += first[i].tri != CJ_RASTER_NO_TRI;
            second += first[i].tri != CJ_RASTER_NO_TRI && first[i].tri >= nt;
        }
        assert_memory_equal(first, nr.best, n * sizeof *vis);
        printf("test_raster_exact: spp %2d: visibility bit-identical over threads 1,2,3 x tiles "
               "8,16,64,100; %zu samples covered, %zu triangles clipped, all equal to the "
               "nearest forward fragment; %zu won by the duplicate mesh (must be 0)\n",
               spp, covered, (size_t)st0.tris_clipped, second);
        assert_int_equal(second, 0);
        assert_true(st0.tris_clipped > 0);
        free(first);
        free(vis);
        free(nr.best);
    }
    (void)configs;
    free(tris);
    teapot_free(&tp);
}

int main(void) {
    g_seed = cj_test_seed("test_raster_exact", 20261123);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fans),
        cmocka_unit_test(test_small_kernel),
        cmocka_unit_test(test_teapot_coverage),
        cmocka_unit_test(test_determinism),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
