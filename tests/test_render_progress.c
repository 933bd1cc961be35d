/* Progress and cancellation (cj_render_options.progress, casteljau/render.h) in both back ends:
 * every tile is reported once, in order, with the same total; a callback that never cancels
 * leaves the image bit-identical; one that cancels makes the render return CJ_ERR_CANCELLED
 * with no image, after at most one tile per worker more. */
#include "render_scenes.h"

#include "casteljau/trace.h"

#include <stdatomic.h>
#include <stdint.h>

typedef struct counter {
    uint64_t calls, last_done, total;
    int in_order;
    uint64_t cancel_at; /* 0: never */
} counter;

static int on_tile(void *user, uint64_t done, uint64_t total) {
    counter *c = user;
    if (done != c->last_done + 1) c->in_order = 0;
    if (c->total && total != c->total) c->in_order = 0;
    c->total = total;
    c->last_done = done;
    ++c->calls;
    return c->cancel_at && done >= c->cancel_at;
}

typedef cj_status (*render_fn)(const cj_scene *, const cj_render_options *, unsigned,
                               const cj_allocator *, cj_render_image **, cj_stage_report *);

static int same_image(const cj_render_image *a, const cj_render_image *b) {
    return a->width == b->width && a->height == b->height &&
           memcmp(a->rgba, b->rgba, sizeof(float) * 4 * (size_t)a->width * (size_t)a->height) == 0;
}

static int check_backend(const char *name, render_fn fn, const cj_scene *s, int threads) {
    cj_render_options o = cj_render_options_defaults();
    o.width = 96;
    o.height = 64;
    o.tile_size = 16;
    o.threads = threads;
    o.spp = 1;
    cj_render_image *plain = NULL, *watched = NULL, *cancelled = NULL;
    if (fn(s, &o, 0, NULL, &plain, NULL)) {
        fprintf(stderr, "%s: plain render failed: %s\n", name, cj_last_error());
        return 1;
    }
    counter c = {0, 0, 0, 1, 0};
    o.progress = on_tile;
    o.progress_user = &c;
    int fails = 0;
    if (fn(s, &o, 0, NULL, &watched, NULL)) {
        fprintf(stderr, "%s: watched render failed: %s\n", name, cj_last_error());
        fails++;
    } else {
        const uint64_t tiles = 6 * 4;
        if (c.calls != tiles || c.total != tiles || c.last_done != tiles || !c.in_order) {
            fprintf(stderr, "%s (%d threads): %llu calls, done %llu of %llu, in order %d\n", name,
                    threads, (unsigned long long)c.calls, (unsigned long long)c.last_done,
                    (unsigned long long)c.total, c.in_order);
            fails++;
        }
        if (!same_image(plain, watched)) {
            fprintf(stderr, "%s: a progress callback changed the image\n", name);
            fails++;
        }
    }
    counter k = {0, 0, 0, 1, 3};
    o.progress_user = &k;
    cj_status st = fn(s, &o, 0, NULL, &cancelled, NULL);
    if (st != CJ_ERR_CANCELLED || cancelled) {
        fprintf(stderr, "%s: cancelling gave status %d (%s), image %p\n", name, (int)st,
                cj_status_str(st), (void *)cancelled);
        fails++;
    }
    /* after the cancelling call no worker takes a new tile; those already running finish */
    if (k.calls < 3 || k.calls > 3 + (uint64_t)(threads > 0 ? threads : 64) - 1) {
        fprintf(stderr, "%s: %llu tiles reported after cancelling at 3\n", name,
                (unsigned long long)k.calls);
        fails++;
    }
    printf("%s, %d thread(s): 24 tiles reported in order, same image; cancel at tile 3 -> "
           "CJ_ERR_CANCELLED after %llu tiles\n",
           name, threads, (unsigned long long)k.calls);
    cj_render_image_destroy(plain);
    cj_render_image_destroy(watched);
    return fails;
}

int main(void) {
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    int fails = 0;
    for (int threads = 1; threads <= 3; threads += 2) {
        fails += check_backend("raster", cj_render_raster, sc.s, threads);
        fails += check_backend("trace", cj_render_trace, sc.s, threads);
    }
    cj_scene_destroy(sc.s);
    printf("test_render_progress: %s\n", fails ? "FAILED" : "all checks passed");
    return fails != 0;
}
