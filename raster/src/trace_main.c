/* The ray tracer as a back end of the renderer (trace.h, renderer.h): tiles on the renderer's
 * worker pool, primary rays from the scene camera, the signature and depth planes, the stage
 * report. */
#include "trace_shade.h"

#include "pixel_filter.h"

#include "error_internal.h"
#include "render_internal.h"
#include "render_progress.h"
#include "renderer_internal.h"

#include <math.h>
#include <string.h>

typedef struct tr_job {
    const tr_scene *s;
    const tr_lights *lights;
    const cj_camera *cam;
    cj_xform3 clip;
    cj_render_image *img;
    int w, h, spp, strata, max_depth, tile, tiles_x, ntiles, random, indirect, integrator;
    int motion;             /* some object moves over the shutter: each sample draws a time */
    int emit_nee;           /* path tracer: emissive triangles sampled as lights */
    cj_pixel_filter filter; /* not box only when spp > 1 */
    double filter_r;
    uint64_t seed;
    cj_rgb bg;
    tr_shade *shade; /* per worker */
} tr_job;

static float pseudodepth(const cj_xform3 *m, cj_vec3 p) {
    double z = m->m[2][0] * p.x + m->m[2][1] * p.y + m->m[2][2] * p.z + m->m[2][3];
    double w = m->m[3][0] * p.x + m->m[3][1] * p.y + m->m[3][2] * p.z + m->m[3][3];
    double d = z / w;
    return (float)(d < -1.0 ? -1.0 : (d > 1.0 ? 1.0 : d));
}

static void render_pixel(tr_job *j, tr_shade *sh, int x, int y) {
    size_t pix = (size_t)y * (size_t)j->w + (size_t)x;
    double acc[3] = {0, 0, 0}, wsum = 0.0, wcov = 0.0;
    int covered = 0;
    uint64_t pkey = cj_trace_mix(j->seed ^ cj_trace_mix((uint64_t)pix));
    sh->perm = (uint32_t)(pkey >> 40);
    sh->perm_key = cj_trace_mix(pkey ^ 0x5851f42d4c957f2dull);
    for (int s = 0; s < j->spp; s++) {
        sh->sample = (uint32_t)s;
        sh->rng.key = cj_trace_mix(pkey + (uint64_t)s);
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
        double fw = 1.0;
        if (j->filter != CJ_FILTER_BOX) { /* the pixel's samples spread over the support */
            const double dx = (2.0 * (px - x) - 1.0) * j->filter_r,
                         dy = (2.0 * (py - y) - 1.0) * j->filter_r;
            px = x + 0.5 + dx;
            py = y + 0.5 + dy;
            fw = cj_pixel_filter_eval(j->filter, j->filter_r, dx) *
                 cj_pixel_filter_eval(j->filter, j->filter_r, dy);
        }
        sh->time = 0.5;
        if (j->motion) { /* a shutter time per sample, stratified like the lens */
            double tu = tr_rand(&sh->rng);
            if (j->spp > 1 && !j->random) {
                uint32_t ns = (uint32_t)j->spp;
                uint32_t si =
                    (cj_trace_permute((uint32_t)s, ns, sh->perm_key ^ 0x9e3779b97f4a7c15ull) +
                     sh->perm) %
                    ns;
                tu = (si + tu) / ns;
            }
            sh->time = tu;
        }
        cj_ray ray;
        if (j->cam->aperture > 0.0) { /* thin lens: a lens point per sample, stratified */
            double lu = tr_rand(&sh->rng), lv = tr_rand(&sh->rng);
            if (j->spp > 1 && !j->random) {
                uint32_t ns = (uint32_t)j->spp, k = (uint32_t)j->strata;
                uint32_t si =
                    (cj_trace_permute((uint32_t)s, ns, sh->perm_key ^ 0x2545f4914f6cdd1dull) +
                     sh->perm) %
                    ns;
                if (k * k == ns) {
                    lu = ((si % k) + lu) / k;
                    lv = ((si / k) + lv) / k;
                } else {
                    lu = (si + lu) / ns;
                }
            }
            if (cj_camera_lens_ray(j->cam, j->w, j->h, px, py, lu, lv, &ray.org, &ray.dir) != CJ_OK)
                continue;
        } else if (cj_camera_ray(j->cam, j->w, j->h, px, py, &ray.org, &ray.dir) != CJ_OK) {
            continue;
        }
        ray.tmin = 0.0;
        ray.tmax = INFINITY;
        tr_medium med;
        med.ior[0] = 1.0;
        med.top = 0;
        int hit = 0;
        cj_rgb c = sh->integrator == CJ_INTEGRATOR_PATH
                       ? tr_path(sh, &ray, &hit)
                       : tr_trace(sh, &ray, TR_PRIMARY, 0, med, &hit);
        if (j->filter != CJ_FILTER_BOX) {
            acc[0] += fw * c.r;
            acc[1] += fw * c.g;
            acc[2] += fw * c.b;
            wsum += fw;
            wcov += fw * hit;
            continue;
        }
        acc[0] += c.r;
        acc[1] += c.g;
        acc[2] += c.b;
        covered += hit;
    }
    float *o = j->img->rgba + 4 * pix;
    if (j->filter != CJ_FILTER_BOX) { /* the weighted mean Σ f L / Σ f */
        const double inv = wsum != 0.0 ? 1.0 / wsum : 0.0;
        for (int k = 0; k < 3; k++) o[k] = (float)(acc[k] * inv);
        double a = wcov * inv;
        o[3] = (float)(a < 0.0 ? 0.0 : (a > 1.0 ? 1.0 : a));
    } else {
        for (int k = 0; k < 3; k++) o[k] = (float)(acc[k] / j->spp);
        o[3] = (float)covered / (float)j->spp;
    }
    if (j->img->ids || j->img->depth) {
        cj_ray ray;
        cj_hit h;
        if (cj_camera_ray(j->cam, j->w, j->h, x + 0.5, y + 0.5, &ray.org, &ray.dir) == CJ_OK) {
            ray.tmin = 0.0;
            ray.tmax = INFINITY;
            if (tr_closest(j->s, &ray, 0.5, &h, NULL)) { /* mid-shutter */
                if (j->img->ids) j->img->ids[pix] = j->s->objs[h.obj].id;
                if (j->img->depth) j->img->depth[pix] = pseudodepth(&j->clip, h.p);
            }
        }
    }
}

static void shade_init(const tr_job *j, tr_counts *c, tr_shade *sh) {
    memset(sh, 0, sizeof *sh);
    sh->s = j->s;
    sh->lights = j->lights;
    sh->c = c;
    sh->background = j->bg;
    sh->max_depth = j->max_depth;
    sh->spp = j->spp;
    sh->strata = j->strata;
    sh->random = j->random;
    sh->indirect = j->indirect;
    sh->integrator = j->integrator;
    sh->time = 0.5;
    sh->emit_nee = j->emit_nee;
}

/* One tile: a task of the renderer's scheduler (render_pool.h). */
static void tile_task(void *user, int t, int worker) {
    tr_job *j = user;
    tr_shade *sh = &j->shade[worker];
    int x0 = (t % j->tiles_x) * j->tile, y0 = (t / j->tiles_x) * j->tile;
    for (int y = y0; y < y0 + j->tile && y < j->h; y++)
        for (int x = x0; x < x0 + j->tile && x < j->w; x++) render_pixel(j, sh, x, y);
}

static const char *const ray_stage[TR_KINDS] = {"primary_rays",      "shadow_rays",
                                                "reflection_rays",   "refraction_rays",
                                                "transparency_rays", "indirect_rays"};

/* The stages the scene's lights and materials decide, recorded with their reasons before any
 * ray is cast (a ray stage is marked as run afterwards, when rays of its kind were cast). */
static void decide_stages(cj_stage_report *r, const cj_scene *scene, int spp, int indirect,
                          unsigned planes, int integrator) {
    cj_stage_report_stage(r, "build_bvh"); /* the report's order */
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
    cj_stage_report_set(r, ray_stage[TR_PRIMARY], 0, "%d sample(s) per pixel", spp);
    if (shadow_lights && receivers)
        cj_stage_report_set(r, ray_stage[TR_SHADOW], 0,
                            "%d light(s) cast shadows, %d material(s) receive them", shadow_lights,
                            receivers);
    else
        cj_stage_report_set(r, ray_stage[TR_SHADOW], 0, "%s",
                            shadow_lights ? "no material receives shadows"
                                          : "no light casts shadows");
    if (mirrors >= 0)
        cj_stage_report_set(r, ray_stage[TR_REFLECT], 0, "material %d has mirror > 0", mirrors);
    else if (refr >= 0)
        cj_stage_report_set(r, ray_stage[TR_REFLECT], 0, "total internal reflection in material %d",
                            refr);
    else
        cj_stage_report_set(r, ray_stage[TR_REFLECT], 0, "no material has mirror > 0");
    if (refr >= 0)
        cj_stage_report_set(r, ray_stage[TR_REFRACT], 0, "material %d has transmission > 0", refr);
    else
        cj_stage_report_set(r, ray_stage[TR_REFRACT], 0, "no material has transmission > 0");
    if (through >= 0)
        cj_stage_report_set(r, ray_stage[TR_THROUGH], 0, "material %d has opacity < 1", through);
    else
        cj_stage_report_set(r, ray_stage[TR_THROUGH], 0, "every material is opaque");
    if (integrator == CJ_INTEGRATOR_PATH)
        cj_stage_report_set(r, ray_stage[TR_INDIRECT], 0,
                            "path tracer: BRDF-sampled bounces, Russian roulette, max depth");
    else if (indirect == 0)
        cj_stage_report_set(r, ray_stage[TR_INDIRECT], 0,
                            "indirect_samples 0: no diffuse interreflection");
    else if (diffuse < 0)
        cj_stage_report_set(r, ray_stage[TR_INDIRECT], 0, "no material has kd > 0");
    else
        cj_stage_report_set(r, ray_stage[TR_INDIRECT], 0,
                            "%d cosine-weighted ray(s) per diffuse hit (material %d)", indirect,
                            diffuse);
    cj_stage_report_stage(r, "patch_rays");
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

/* The traced scene's stage, recorded when it is built. */
static void report_build(cj_stage_report *r, const tr_scene *ts, double build_s, size_t bvh_reused,
                         size_t bvh_built) {
    cj_stage *s = cj_stage_report_set(r, "build_bvh", 1, "%zu objects traced", ts->nobj);
    if (!s) return;
    s->in = ts->nobj;
    s->out = ts->top ? ts->top->node_count : 0;
    strcpy(s->unit_in, "objects");
    strcpy(s->unit_out, "nodes");
    s->seconds = build_s;
    cj_stage_add_value(s, "bvh_reused", (double)bvh_reused);
    cj_stage_add_value(s, "bvh_built", (double)bvh_built);
}

/* The rays cast, summed over the workers: a ray stage ran when rays of its kind were cast. */
static void report_rays(cj_stage_report *r, const tr_counts *c) {
    for (int k = 0; k < TR_KINDS; k++) {
        cj_stage *s = cj_stage_report_stage(r, ray_stage[k]);
        if (!s) continue;
        s->ran = c->cast[k] > 0;
        s->in = c->cast[k];
        s->out = c->hit[k];
        strcpy(s->unit_in, "rays");
        strcpy(s->unit_out, "hits");
        s->seconds = c->seconds[k];
    }
    cj_stage *s =
        cj_stage_report_set(r, "patch_rays", c->patch_rays > 0, "%s",
                            c->patch_rays ? "patches intersected directly" : "no patch was hit");
    if (s) {
        s->in = c->patch_rays;
        strcpy(s->unit_in, "hits");
        cj_stage_add_value(s, "max_err", c->patch_max_err);
    }
}

/* The frame's settings: the options over the scene's. */
typedef struct trace_settings {
    int w, h, spp, max_depth, indirect, tile, threads;
    double ptol;
} trace_settings;

static cj_status resolve(const cj_renderer *r, const cj_scene *scene, trace_settings *t) {
    const cj_render_options *o = &r->opt.render;
    const cj_scene_settings *ss = cj_scene_get_settings(scene);
    t->w = o->width ? o->width : ss->width;
    t->h = o->height ? o->height : ss->height;
    t->spp = o->spp ? o->spp : ss->spp;
    if (t->spp < 1 || t->spp > 65536)
        return cj_fail(CJ_ERR_RANGE, "samples per pixel %d outside 1..65536", t->spp);
    t->max_depth = o->max_depth ? o->max_depth : ss->max_depth;
    if (t->max_depth < 0 || t->max_depth > 64)
        return cj_fail(CJ_ERR_RANGE, "max depth %d outside 0..64", t->max_depth);
    t->ptol = r->opt.trace.patch_tolerance;
    t->indirect = r->opt.trace.indirect_samples;
    t->tile = o->tile_size ? o->tile_size : 32;
    t->threads = o->threads;
    return CJ_OK;
}

/* Ambient light summed; the other lights with intensity > 0 (at most TR_MAX_LIGHTS). */
static cj_status gather_lights(const cj_scene *scene, tr_lights *lights) {
    memset(lights, 0, sizeof *lights);
    lights->unlit = cj_scene_light_count(scene) == 0;
    lights->radiometric = cj_scene_get_settings(scene)->light_model == CJ_LIGHT_RADIOMETRIC;
    for (size_t i = 0; i < cj_scene_light_count(scene); i++) {
        const cj_light *l = cj_scene_light(scene, (int)i);
        if (l->kind == CJ_LIGHT_AMBIENT) {
            lights->ia.r += l->color.r * l->intensity;
            lights->ia.g += l->color.g * l->intensity;
            lights->ia.b += l->color.b * l->intensity;
        } else if (l->intensity > 0) {
            if (lights->count == TR_MAX_LIGHTS)
                return cj_fail(CJ_ERR_CAP, "ray tracer: more than %d lights with intensity > 0",
                               TR_MAX_LIGHTS);
            lights->light[lights->count++] = l;
        }
    }
    return CJ_OK;
}

static void sum_counts(const tr_counts *per, int n, tr_counts *sum) {
    memset(sum, 0, sizeof *sum);
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < TR_KINDS; k++) {
            sum->cast[k] += per[i].cast[k];
            sum->hit[k] += per[i].hit[k];
            sum->seconds[k] += per[i].seconds[k];
        }
        sum->patch_rays += per[i].patch_rays;
        if (per[i].patch_max_err > sum->patch_max_err) sum->patch_max_err = per[i].patch_max_err;
    }
}

cj_status cj_rtrace_frame(cj_renderer *r, const cj_rscene *rs, unsigned planes,
                          cj_render_image **image, cj_stage_report *R) {
    const cj_scene *scene = rs->scene;
    trace_settings set;
    memset(&set, 0, sizeof set);
    cj_status st = resolve(r, scene, &set);
    if (st) return st;
    cj_rtarget target;
    st = cj_rtarget_acquire(r, set.w, set.h, planes, image, &target);
    if (st) return st;
    cj_render_image *img = target.img;
    if (!target.fresh) { /* the planes a traced pixel may leave untouched */
        size_t n = (size_t)set.w * (size_t)set.h;
        if (img->ids) memset(img->ids, 0, n * sizeof *img->ids);
        if (img->depth)
            for (size_t i = 0; i < n; i++) img->depth[i] = 1.0f;
    }
    decide_stages(R, scene, set.spp, set.indirect, planes, r->opt.trace.integrator);
    tr_scene ts;
    size_t bvh_reused = 0, bvh_built = 0, moving = 0;
    tr_motion motion = {r->motion, r->motion_poses, r->motion_nodes};
    if (r->motion && r->motion_nodes != rs->node_count) {
        st = cj_fail(CJ_ERR_DIMENSION, "motion blur: the motion has %zu nodes, the scene %zu",
                     r->motion_nodes, rs->node_count);
        cj_rtarget_finish(&target, image, st);
        return st;
    }
    double t0 = cj_render_now();
    st = tr_scene_build(rs, r->bvh, r->motion ? &motion : NULL, &r->alloc, &ts, &bvh_reused,
                        &bvh_built, &moving);
    double build_s = cj_render_now() - t0;
    if (r->bvh) tr_bvh_cache_sweep(r->bvh);
    if (st) {
        cj_rtarget_finish(&target, image, st);
        return st;
    }
    if (r->opt.trace.integrator == CJ_INTEGRATOR_PATH && !r->opt.trace.emission_by_chance)
        st = tr_scene_emitters(&ts);
    if (st) {
        tr_scene_free(&ts);
        cj_rtarget_finish(&target, image, st);
        return st;
    }
    report_build(R, &ts, build_s, bvh_reused, bvh_built);
    if (r->motion || moving)
        cj_stage_report_set(R, "motion_blur", moving > 0,
                            "%zu of %zu object(s) move over the shutter (%d poses)", moving,
                            ts.nobj, r->motion_poses);
    if (set.ptol > 0.0)
        for (size_t i = 0; i < ts.nobj; i++) ts.objs[i].tol *= set.ptol / 1e-7;
    tr_lights lights;
    st = gather_lights(scene, &lights);
    tr_job j;
    memset(&j, 0, sizeof j);
    j.s = &ts;
    j.lights = &lights;
    j.cam = cj_scene_get_camera(scene);
    cj_camera_world_to_clip(j.cam, (double)set.w / set.h, &j.clip);
    j.img = img;
    j.w = set.w;
    j.h = set.h;
    j.spp = set.spp;
    j.strata = (int)floor(sqrt((double)set.spp) + 0.5);
    j.random = r->opt.trace.random_sampling != 0;
    j.max_depth = set.max_depth;
    j.indirect = set.indirect;
    j.integrator = r->opt.trace.integrator;
    j.motion = moving > 0;
    j.emit_nee = ts.nemit > 0;
    j.filter = set.spp > 1 ? cj_scene_get_settings(scene)->filter : CJ_FILTER_BOX;
    j.filter_r = cj_pixel_filter_radius(j.filter, cj_scene_get_settings(scene)->filter_radius);
    j.seed = r->opt.render.use_seed ? r->opt.render.seed : cj_scene_get_settings(scene)->seed;
    j.bg = cj_scene_get_settings(scene)->background;
    j.tile = set.tile;
    j.tiles_x = (set.w + j.tile - 1) / j.tile;
    j.ntiles = j.tiles_x * ((set.h + j.tile - 1) / j.tile);
    int nth = cj_rpool_plan(set.threads, j.ntiles), pool_reused = 0;
    if (!st) st = cj_renderer_pool(r, nth, &pool_reused);
    if (!st && nth > cj_rpool_threads(r->pool)) nth = cj_rpool_threads(r->pool);
    tr_counts *counts = cj_ralloc(&r->alloc, sizeof *counts * (size_t)nth);
    j.shade = cj_ralloc(&r->alloc, sizeof *j.shade * (size_t)nth);
    if (!st && (!counts || !j.shade)) st = cj_fail(CJ_ERR_NOMEM, "ray tracer: out of memory");
    if (!st) {
        memset(counts, 0, sizeof *counts * (size_t)nth);
        for (int i = 0; i < nth; i++) shade_init(&j, &counts[i], &j.shade[i]);
        cj_rprogress pg;
        cj_rprogress_init(&pg, &r->opt.render, (uint64_t)j.ntiles);
        if (cj_rpool_run(r->pool, j.ntiles, nth, tile_task, &j, &pg))
            st = cj_fail(CJ_ERR_CANCELLED, "ray tracer: cancelled by the progress callback");
        cj_rprogress_destroy(&pg);
    }
    if (!st) {
        tr_counts sum;
        sum_counts(counts, nth, &sum);
        report_rays(R, &sum);
        cj_renderer_report_frame(r, R, nth, pool_reused, -1, !target.fresh);
    }
    cj_rfree(&r->alloc, counts);
    cj_rfree(&r->alloc, j.shade);
    tr_scene_free(&ts);
    cj_rtarget_finish(&target, image, st);
    return st;
}
