/* cj_render_trace: tiles over threads, primary rays from the scene camera, the signature and
 * depth planes, the stage report (trace.h). */
#define _POSIX_C_SOURCE 200809L
#include "trace_shade.h"

#include "error_internal.h"
#include "render_internal.h"
#include "render_progress.h"

#include <math.h>
#include <pthread.h>
#include <string.h>
#include <unistd.h>

typedef struct tr_job {
    const tr_scene *s;
    const tr_lights *lights;
    const cj_camera *cam;
    cj_xform3 clip;
    cj_render_image *img;
    int w, h, spp, strata, max_depth, tile, tiles_x, ntiles, random, indirect;
    uint64_t seed;
    cj_rgb bg;
    pthread_mutex_t lock;
    cj_rprogress *progress;
    int next;
    tr_counts *counts;
} tr_job;

static float pseudodepth(const cj_xform3 *m, cj_vec3 p) {
    double z = m->m[2][0] * p.x + m->m[2][1] * p.y + m->m[2][2] * p.z + m->m[2][3];
    double w = m->m[3][0] * p.x + m->m[3][1] * p.y + m->m[3][2] * p.z + m->m[3][3];
    double d = z / w;
    return (float)(d < -1.0 ? -1.0 : (d > 1.0 ? 1.0 : d));
}

static void render_pixel(tr_job *j, tr_shade *sh, int x, int y) {
    size_t pix = (size_t)y * (size_t)j->w + (size_t)x;
    double acc[3] = {0, 0, 0};
    int covered = 0;
    uint64_t pkey = tr_mix(j->seed ^ tr_mix((uint64_t)pix));
    sh->perm = (uint32_t)(pkey >> 40);
    sh->perm_key = tr_mix(pkey ^ 0x5851f42d4c957f2dull);
    for (int s = 0; s < j->spp; s++) {
        sh->sample = (uint32_t)s;
        sh->rng.key = tr_mix(pkey + (uint64_t)s);
        sh->rng.n = 0;
        double px = x + 0.5, py = y + 0.5;
        if (j->spp > 1 && j->random) {
            px = x + tr_rand(&sh->rng);
            py = y + tr_rand(&sh->rng);
        } else if (j->spp > 1) {
            int k = j->strata;
            if (k * k == j->spp) {
                px = x + ((s % k) + tr_rand(&sh->rng)) / k;
                py = y + ((s / k) + tr_rand(&sh->rng)) / k;
            } else {
                px = x + (s + tr_rand(&sh->rng)) / j->spp;
                py = y + tr_rand(&sh->rng);
            }
        }
        cj_ray ray;
        if (cj_camera_ray(j->cam, j->w, j->h, px, py, &ray.org, &ray.dir) != CJ_OK) continue;
        ray.tmin = 0.0;
        ray.tmax = INFINITY;
        tr_medium med;
        med.ior[0] = 1.0;
        med.top = 0;
        int hit = 0;
        cj_rgb c = tr_trace(sh, &ray, TR_PRIMARY, 0, med, &hit);
        acc[0] += c.r;
        acc[1] += c.g;
        acc[2] += c.b;
        covered += hit;
    }
    float *o = j->img->rgba + 4 * pix;
    for (int k = 0; k < 3; k++) o[k] = (float)(acc[k] / j->spp);
    o[3] = (float)covered / (float)j->spp;
    if (j->img->ids || j->img->depth) {
        cj_ray ray;
        cj_hit h;
        if (cj_camera_ray(j->cam, j->w, j->h, x + 0.5, y + 0.5, &ray.org, &ray.dir) == CJ_OK) {
            ray.tmin = 0.0;
            ray.tmax = INFINITY;
            if (tr_closest(j->s, &ray, &h, NULL)) {
                if (j->img->ids) j->img->ids[pix] = j->s->objs[h.obj].id;
                if (j->img->depth) j->img->depth[pix] = pseudodepth(&j->clip, h.p);
            }
        }
    }
}

static void *worker(void *arg) {
    void **a = arg;
    tr_job *j = a[0];
    tr_counts *c = a[1];
    tr_shade sh;
    memset(&sh, 0, sizeof sh);
    sh.s = j->s;
    sh.lights = j->lights;
    sh.c = c;
    sh.background = j->bg;
    sh.max_depth = j->max_depth;
    sh.spp = j->spp;
    sh.strata = j->strata;
    sh.random = j->random;
    sh.indirect = j->indirect;
    for (;;) {
        if (cj_rprogress_stopped(j->progress)) break;
        pthread_mutex_lock(&j->lock);
        int t = j->next++;
        pthread_mutex_unlock(&j->lock);
        if (t >= j->ntiles) break;
        int x0 = (t % j->tiles_x) * j->tile, y0 = (t / j->tiles_x) * j->tile;
        for (int y = y0; y < y0 + j->tile && y < j->h; y++)
            for (int x = x0; x < x0 + j->tile && x < j->w; x++) render_pixel(j, &sh, x, y);
        cj_rprogress_tile_done(j->progress);
    }
    return NULL;
}

static void report_stages(cj_stage_report *r, const cj_scene *scene, const tr_scene *ts,
                          const tr_counts *c, int spp, int indirect, double build_s, int planes) {
    int shadow_lights = 0, receivers = 0, mirrors = -1, refr = -1, through = -1, tex = -1;
    int area = -1, glossy = -1, diffuse = -1;
    for (size_t i = 0; i < cj_scene_light_count(scene); i++) {
        const cj_light *l = cj_scene_light(scene, (int)i);
        if (l->kind != CJ_LIGHT_AMBIENT && l->casts_shadows && l->intensity > 0) shadow_lights++;
        if (l->kind == CJ_LIGHT_AREA && area < 0) area = (int)i;
    }
    for (size_t i = 0; i < cj_scene_material_count(scene); i++) {
        const cj_material *m = cj_scene_material(scene, (int)i);
        if (m->receives_shadows) receivers++;
        if (m->mirror > 0 && mirrors < 0) mirrors = (int)i;
        if (m->transmission > 0 && refr < 0) refr = (int)i;
        if (m->opacity < 1 && through < 0) through = (int)i;
        if (m->texture >= 0 && tex < 0) tex = (int)i;
        if (m->glossiness > 0 && glossy < 0) glossy = (int)i;
        if (m->kd > 0 && m->transmission < 1 && diffuse < 0) diffuse = (int)i;
    }
    cj_stage *s = cj_stage_report_set(r, "build_bvh", 1, "%zu objects traced", ts->nobj);
    if (s) {
        s->in = ts->nobj;
        s->out = ts->top ? ts->top->node_count : 0;
        strcpy(s->unit_in, "objects");
        strcpy(s->unit_out, "nodes");
        s->seconds = build_s;
    }
    static const char *names[TR_KINDS] = {"primary_rays",    "shadow_rays",       "reflection_rays",
                                          "refraction_rays", "transparency_rays", "indirect_rays"};
    for (int k = 0; k < TR_KINDS; k++) {
        int ran = c->cast[k] > 0;
        char why[CJ_STAGE_WHY_MAX];
        switch (k) {
        case TR_PRIMARY:
            snprintf(why, sizeof why, "%d sample(s) per pixel", spp);
            break;
        case TR_SHADOW:
            if (shadow_lights && receivers)
                snprintf(why, sizeof why, "%d light(s) cast shadows, %d material(s) receive them",
                         shadow_lights, receivers);
            else
                snprintf(why, sizeof why, "%s",
                         shadow_lights ? "no material receives shadows" : "no light casts shadows");
            break;
        case TR_REFLECT:
            if (mirrors >= 0)
                snprintf(why, sizeof why, "material %d has mirror > 0", mirrors);
            else if (refr >= 0)
                snprintf(why, sizeof why, "total internal reflection in material %d", refr);
            else
                snprintf(why, sizeof why, "no material has mirror > 0");
            break;
        case TR_REFRACT:
            if (refr >= 0)
                snprintf(why, sizeof why, "material %d has transmission > 0", refr);
            else
                snprintf(why, sizeof why, "no material has transmission > 0");
            break;
        case TR_INDIRECT:
            if (indirect == 0)
                snprintf(why, sizeof why, "indirect_samples 0: no diffuse interreflection");
            else if (diffuse < 0)
                snprintf(why, sizeof why, "no material has kd > 0");
            else
                snprintf(why, sizeof why, "%d cosine-weighted ray(s) per diffuse hit (material %d)",
                         indirect, diffuse);
            break;
        default:
            if (through >= 0)
                snprintf(why, sizeof why, "material %d has opacity < 1", through);
            else
                snprintf(why, sizeof why, "every material is opaque");
            break;
        }
        s = cj_stage_report_set(r, names[k], ran, "%s", why);
        if (!s) continue;
        s->in = c->cast[k];
        s->out = c->hit[k];
        strcpy(s->unit_in, "rays");
        strcpy(s->unit_out, "hits");
        s->seconds = c->seconds[k];
    }
    s = cj_stage_report_set(r, "patch_rays", c->patch_rays > 0, "%s",
                            c->patch_rays ? "patches intersected directly" : "no patch was hit");
    if (s) {
        s->in = c->patch_rays;
        strcpy(s->unit_in, "hits");
        cj_stage_add_value(s, "max_err", c->patch_max_err);
    }
    if (tex >= 0)
        cj_stage_report_set(r, "textures", 1, "material %d has a texture", tex);
    else
        cj_stage_report_set(r, "textures", 0, "no material has a texture");
    cj_stage_report_set(r, "area_light_samples", area >= 0 && spp > 1, "%s",
                        area < 0 ? "no area light"
                                 : (spp > 1 ? "area light sampled per sample"
                                            : "spp = 1: area light at its centre"));
    cj_stage_report_set(r, "glossy_samples", glossy >= 0 && spp > 1, "%s",
                        glossy < 0
                            ? "no glossy material"
                            : (spp > 1 ? "glossy lobe sampled" : "spp = 1: glossy as mirror"));
    cj_stage_report_set(r, "signature", (planes & CJ_IMAGE_IDS) != 0, "%s",
                        (planes & CJ_IMAGE_IDS) ? "ids plane asked for" : "no ids plane asked for");
}

cj_status cj_render_trace(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                          const cj_allocator *alloc, cj_render_image **out,
                          cj_stage_report *report) {
    return cj_render_trace_ex(scene, opt, NULL, planes, alloc, out, report);
}

cj_status cj_render_trace_ex(const cj_scene *scene, const cj_render_options *opt,
                             const cj_trace_options *topt, unsigned planes,
                             const cj_allocator *alloc, cj_render_image **out,
                             cj_stage_report *report) {
    double t_start = cj_render_now();
    cj_status st = cj_scene_check(scene);
    if (st) return st;
    cj_render_options o = opt ? *opt : cj_render_options_default();
    const cj_scene_settings *ss = cj_scene_settings_get(scene);
    int w = o.width ? o.width : ss->width, h = o.height ? o.height : ss->height;
    int spp = o.spp ? o.spp : ss->spp;
    if (spp < 1 || spp > 65536)
        return cj_fail(CJ_ERR_RANGE, "samples per pixel %d outside 1..65536", spp);
    if (o.threads < 0) return cj_fail(CJ_ERR_RANGE, "thread count %d must be >= 0", o.threads);
    if (o.tile_size != 0 && o.tile_size < 8)
        return cj_fail(CJ_ERR_RANGE, "tile size %d must be 0 or >= 8", o.tile_size);
    int max_depth = o.max_depth ? o.max_depth : ss->max_depth;
    if (max_depth < 0 || max_depth > 64)
        return cj_fail(CJ_ERR_RANGE, "max depth %d outside 0..64", max_depth);
    double ptol = topt ? topt->patch_tolerance : 0.0;
    if (!(ptol == 0.0 || (ptol > 0.0 && ptol <= 1.0)))
        return cj_fail(CJ_ERR_RANGE, "patch tolerance %g outside (0, 1]", ptol);
    int indirect = topt ? topt->indirect_samples : 0;
    if (indirect < 0 || indirect > 4096)
        return cj_fail(CJ_ERR_RANGE, "indirect samples %d outside 0..4096", indirect);
    cj_render_image *img = NULL;
    st = cj_render_image_create(w, h, planes, alloc, &img);
    if (st) return st;
    tr_scene ts;
    double t0 = cj_render_now();
    st = tr_scene_build(scene, alloc, &ts);
    double build_s = cj_render_now() - t0;
    if (st) {
        cj_render_image_destroy(img);
        return st;
    }
    if (ptol > 0.0)
        for (size_t i = 0; i < ts.nobj; i++) ts.objs[i].tol *= ptol / 1e-7;
    tr_lights lights;
    memset(&lights, 0, sizeof lights);
    lights.unlit = cj_scene_light_count(scene) == 0;
    for (size_t i = 0; i < cj_scene_light_count(scene); i++) {
        const cj_light *l = cj_scene_light(scene, (int)i);
        if (l->kind == CJ_LIGHT_AMBIENT) {
            lights.ia.r += l->color.r * l->intensity;
            lights.ia.g += l->color.g * l->intensity;
            lights.ia.b += l->color.b * l->intensity;
        } else if (l->intensity > 0) {
            if (lights.count == TR_MAX_LIGHTS) {
                tr_scene_free(&ts);
                cj_render_image_destroy(img);
                return cj_fail(CJ_ERR_CAP, "ray tracer: more than %d lights with intensity > 0",
                               TR_MAX_LIGHTS);
            }
            lights.light[lights.count++] = l;
        }
    }
    tr_job j;
    memset(&j, 0, sizeof j);
    j.s = &ts;
    j.lights = &lights;
    j.cam = cj_scene_camera(scene);
    cj_camera_world_to_clip(j.cam, (double)w / h, &j.clip);
    j.img = img;
    j.w = w;
    j.h = h;
    j.spp = spp;
    j.strata = (int)floor(sqrt((double)spp) + 0.5);
    j.random = topt ? topt->random_sampling != 0 : 0;
    j.max_depth = max_depth;
    j.indirect = indirect;
    j.seed = o.use_seed ? o.seed : ss->seed;
    j.bg = ss->background;
    j.tile = o.tile_size ? o.tile_size : 32;
    j.tiles_x = (w + j.tile - 1) / j.tile;
    j.ntiles = j.tiles_x * ((h + j.tile - 1) / j.tile);
    int nth = o.threads;
    if (nth == 0) {
        long nc = sysconf(_SC_NPROCESSORS_ONLN);
        nth = nc > 0 ? (int)nc : 1;
    }
    if (nth > j.ntiles) nth = j.ntiles;
    if (nth > 256) nth = 256;
    tr_counts *counts = cj_ralloc(&ts.alloc, sizeof *counts * (size_t)nth);
    pthread_t *th = cj_ralloc(&ts.alloc, sizeof *th * (size_t)nth);
    void **args = cj_ralloc(&ts.alloc, sizeof *args * 2 * (size_t)nth);
    if (!counts || !th || !args) {
        cj_rfree(&ts.alloc, counts);
        cj_rfree(&ts.alloc, th);
        cj_rfree(&ts.alloc, args);
        tr_scene_free(&ts);
        cj_render_image_destroy(img);
        return cj_fail(CJ_ERR_NOMEM, "ray tracer: out of memory");
    }
    memset(counts, 0, sizeof *counts * (size_t)nth);
    pthread_mutex_init(&j.lock, NULL);
    cj_rprogress pg;
    cj_rprogress_init(&pg, &o, (uint64_t)j.ntiles);
    j.progress = &pg;
    int started = 0;
    for (int i = 0; i < nth; i++) {
        args[2 * i] = &j;
        args[2 * i + 1] = &counts[i];
        if (i == 0) continue;
        if (pthread_create(&th[i], NULL, worker, &args[2 * i]) == 0)
            started++;
        else
            break;
    }
    worker(&args[0]);
    for (int i = 1; i <= started; i++) pthread_join(th[i], NULL);
    pthread_mutex_destroy(&j.lock);
    int cancelled = cj_rprogress_stopped(&pg);
    cj_rprogress_destroy(&pg);
    if (cancelled) {
        cj_rfree(&ts.alloc, counts);
        cj_rfree(&ts.alloc, th);
        cj_rfree(&ts.alloc, args);
        tr_scene_free(&ts);
        cj_render_image_destroy(img);
        return cj_fail(CJ_ERR_CANCELLED, "ray tracer: cancelled by the progress callback");
    }
    tr_counts sum;
    memset(&sum, 0, sizeof sum);
    for (int i = 0; i < nth; i++)
        for (int k = 0; k < TR_KINDS; k++) {
            sum.cast[k] += counts[i].cast[k];
            sum.hit[k] += counts[i].hit[k];
            sum.seconds[k] += counts[i].seconds[k];
        }
    for (int i = 0; i < nth; i++) {
        sum.patch_rays += counts[i].patch_rays;
        if (counts[i].patch_max_err > sum.patch_max_err)
            sum.patch_max_err = counts[i].patch_max_err;
    }
    if (report) {
        cj_stage_report_init(report, "trace");
        report_stages(report, scene, &ts, &sum, spp, indirect, build_s, (int)planes);
        report->total_seconds = cj_render_now() - t_start;
    }
    cj_rfree(&ts.alloc, counts);
    cj_rfree(&ts.alloc, th);
    cj_rfree(&ts.alloc, args);
    tr_scene_free(&ts);
    *out = img;
    return CJ_OK;
}
