/* The rasterizer as a back end of the renderer (render.h, renderer.h): the pipeline assembled
 * from what the scene uses. Every stage's entry in the report (run or left out, and the
 * feature that decided it) is written where the decision is made; the figures follow when the
 * stage has run. cj_rraster_frame at the bottom is the table of contents. */
#include "render_frame.h"

#include "casteljau/framebuffer.h"
#include "error_internal.h"
#include "render_progress.h"
#include "renderer_internal.h"

#include <math.h>
#include <string.h>

static void clear_ctx(cj_rctx *c, const cj_allocator *a) {
    cj_rlist *lists[2] = {&c->opaque, &c->transp};
    for (int i = 0; i < 2; ++i) {
        cj_rfree(a, lists[i]->tris);
        cj_rfree(a, lists[i]->obj);
        cj_rfree(a, lists[i]->kernel);
        cj_rfree(a, lists[i]->flat);
        cj_rfree(a, lists[i]->uvplane);
        cj_rfree(a, (void *)lists[i]->plane_state);
        cj_rfree(a, lists[i]->back);
        cj_raster_prep_destroy(lists[i]->prep);
    }
    cj_rfree(a, c->clip);
    cj_rfree(a, c->vrec);
    cj_rfree(a, c->gouraud);
    cj_rfree(a, c->mats);
    cj_rfree(a, c->obj_mat);
    cj_rfree(a, c->lights);
    cj_rfree(a, c->emitters);
    for (int i = 0; i < c->nsamplers; ++i) cj_tex_sampler_free(&c->samplers[i]);
    cj_rfree(a, c->samplers);
    cj_rlines_free(&c->lines, a);
}

static cj_status split_lists(cj_rctx *c, const cj_rbuild *b, const cj_allocator *a) {
    size_t nt = 0, no = 0;
    for (size_t t = 0; t < b->tri_count; ++t)
        if (c->mats[c->obj_mat[b->tobj[t]]].opacity < 1.0f)
            ++nt;
        else
            ++no;
    c->opaque.tris = cj_ralloc(a, sizeof(uint32_t) * 3 * (no ? no : 1));
    c->opaque.obj = cj_ralloc(a, sizeof(uint32_t) * (no ? no : 1));
    c->transp.tris = cj_ralloc(a, sizeof(uint32_t) * 3 * (nt ? nt : 1));
    c->transp.obj = cj_ralloc(a, sizeof(uint32_t) * (nt ? nt : 1));
    if (!c->opaque.tris || !c->opaque.obj || !c->transp.tris || !c->transp.obj)
        return cj_fail(CJ_ERR_NOMEM, "triangle lists of %zu triangles", b->tri_count);
    for (size_t t = 0; t < b->tri_count; ++t) {
        cj_rlist *L = c->mats[c->obj_mat[b->tobj[t]]].opacity < 1.0f ? &c->transp : &c->opaque;
        memcpy(L->tris + 3 * L->count, b->tris + 3 * t, 3 * sizeof(uint32_t));
        L->obj[L->count++] = b->tobj[t];
    }
    return CJ_OK;
}

static cj_status project(cj_rctx *c, const cj_rbuild *b, const cj_allocator *a) {
    c->clip = cj_ralloc(a, sizeof(double) * 4 * (b->vertex_count ? b->vertex_count : 1));
    if (!c->clip) return cj_fail(CJ_ERR_NOMEM, "clip coordinates of %zu vertices", b->vertex_count);
    const cj_xform3 *M = &c->view->world_to_clip;
    for (size_t v = 0; v < b->vertex_count; ++v) {
        const double *p = b->pos + 3 * v;
        for (int r = 0; r < 4; ++r)
            c->clip[4 * v + r] =
                M->m[r][0] * p[0] + M->m[r][1] * p[1] + M->m[r][2] * p[2] + M->m[r][3];
    }
    return CJ_OK;
}

static cj_status prep_list(cj_rctx *c, cj_rlist *L, const cj_allocator *alloc,
                           cj_raster_stats *st) {
    cj_raster_input in;
    memset(&in, 0, sizeof in);
    in.vertex_count = c->b->vertex_count;
    in.clip = c->clip;
    in.tri_count = L->count;
    in.tris = L->tris;
    in.width = c->width;
    in.height = c->height;
    in.spp = c->spp;
    return cj_raster_prepare(&in, c->tile_size, alloc, &L->prep, st);
}

/* ---- one frame --------------------------------------------------------------------------- */

/* The stages in the order the report lists them (each is filled where it is decided). */
static const char *const stage_order[] = {"scene_check",
                                          "tessellate_patches",
                                          "tessellate_surfaces",
                                          "meshes",
                                          "transform",
                                          "vertex_normals",
                                          "texture_coords",
                                          "cull_backfaces",
                                          "sort_transparent",
                                          "project",
                                          "shade_setup",
                                          "mipmaps",
                                          "raster_setup",
                                          "rasterize",
                                          "shade_unlit",
                                          "shade_flat",
                                          "shade_gouraud",
                                          "shade_phong",
                                          "texture",
                                          "overlay_lines",
                                          "transparency",
                                          "resolve",
                                          "output",
                                          "frame"};

/* Image size, samples, tolerance and tiles: the renderer's options over the scene's. */
static cj_status resolve_settings(cj_rframe *F) {
    const cj_render_options *o = &F->r->opt.render;
    const cj_scene_settings *ss = cj_scene_get_settings(F->scene);
    F->W = o->width ? o->width : ss->width;
    F->H = o->height ? o->height : ss->height;
    F->spp = o->spp ? o->spp : ss->spp;
    F->tol_px = o->tol_px != 0.0 ? o->tol_px : ss->tol_px;
    F->tile = o->tile_size ? o->tile_size : 64;
    if (F->W < 1 || F->H < 1 || F->W > CJ_FRAMEBUFFER_MAX_SIDE || F->H > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "image size %d x %d outside 1..%d", F->W, F->H,
                       CJ_FRAMEBUFFER_MAX_SIDE);
    if (F->spp != 1 && F->spp != 4 && F->spp != 16)
        return cj_fail(CJ_ERR_RANGE, "samples per pixel %d: the rasterizer takes 1, 4 or 16",
                       F->spp);
    if (!isfinite(F->tol_px) || !(F->tol_px > 0.0))
        return cj_fail(CJ_ERR_RANGE, "tessellation tolerance %g px must be > 0 and finite",
                       F->tol_px);
    if (F->tile < 8 || F->tile > 4096)
        return cj_fail(CJ_ERR_RANGE, "tile size %d outside 8..4096", F->tile);
    for (size_t i = 0; i < sizeof stage_order / sizeof stage_order[0]; ++i)
        cj_stage_report_stage(F->R, stage_order[i]);
    cj_stage_report_set(F->R, "scene_check", 1, "always");
    return CJ_OK;
}

/* The camera and the frame's constants the tiles read. */
static cj_status setup_view(cj_rframe *F) {
    cj_status st = cj_rview_init(cj_scene_get_camera(F->scene), F->W, F->H, &F->view);
    if (st) return st;
    cj_rctx *c = &F->c;
    const cj_scene_settings *ss = cj_scene_get_settings(F->scene);
    c->view = &F->view;
    c->width = F->W;
    c->height = F->H;
    c->spp = F->spp;
    c->tile_size = F->tile;
    c->tiles_x = (F->W + F->tile - 1) / F->tile;
    c->pattern = cj_raster_sample_pattern(F->spp);
    c->bg[0] = (float)ss->background.r;
    c->bg[1] = (float)ss->background.g;
    c->bg[2] = (float)ss->background.b;
    c->b = &F->b;
    return CJ_OK;
}

/* Lights, materials and the feature mask; the per-material attributes the build must make. */
static cj_status build_triangles(cj_rframe *F) {
    cj_render_cache *cache = cj_renderer_cache(F->r);
    const cj_render_options *ro = &F->r->opt.render;
    if (cache) cj_rcache_set_progress(cache, ro->progress, ro->progress_user);
    cj_status st =
        cj_rbuild_scene(F->rs, &F->view, F->tol_px, F->flags, F->need, 1, cache, &F->A, &F->b);
    if (cache) cj_rcache_set_progress(cache, NULL, NULL);
    if (st) return st;
    const cj_rbuild *b = &F->b;
    const cj_rfeatures *f = &F->f;
    cj_stage_report *R = F->R;
    cj_stage *s =
        cj_stage_report_set(R, "tessellate_patches", f->patches, "%s",
                            f->patches ? "the scene has Bezier patch objects" : "no patch objects");
    cj_stage_report_figures(R, "tessellate_patches", "patches", b->patches_in, "triangles",
                            b->patch_tris, b->sec_patches);
    cj_stage_add_value(s, "tol_px", F->tol_px);
    cj_stage_add_value(s, "bound_px", b->patch_bound_px);
    cj_stage_add_value(s, "patches_culled", (double)b->patches_culled);
    if (cache) {
        cj_stage_add_value(s, "patches_planned", (double)b->patches_planned);
        cj_stage_add_value(s, "patches_built", (double)b->patches_built);
        cj_stage_add_value(s, "patches_reused", (double)b->patches_reused);
        cj_stage_add_value(s, "cache_misses", (double)b->cache_misses);
        cj_stage_add_value(s, "cache_hits", (double)b->cache_hits);
    }
    s = cj_stage_report_set(R, "tessellate_surfaces", f->surfaces, "%s",
                            f->surfaces ? "the scene has analytic surfaces"
                                        : "no analytic surfaces");
    cj_stage_report_figures(R, "tessellate_surfaces", "objects", 0, "triangles", b->surface_tris,
                            b->sec_surfaces);
    cj_stage_add_value(s, "bound_px", b->surface_bound_px);
    cj_stage_report_set(R, "meshes", f->meshes, "%s",
                        f->meshes ? "the scene has triangle meshes" : "no mesh objects");
    cj_stage_report_figures(R, "meshes", "triangles", b->mesh_tris, "triangles", b->mesh_tris,
                            b->sec_meshes);
    cj_stage_report_set(R, "transform", 1, "always");
    cj_stage_report_figures(R, "transform", "vertices", b->vertex_count, "vertices",
                            b->vertex_count, b->sec_transform);
    const uint64_t vn = (F->flags & CJ_RB_NORMALS) ? b->vertex_count : 0;
    const uint64_t vt = (F->flags & CJ_RB_UVS) ? b->vertex_count : 0;
    cj_stage_report_figures(R, "vertex_normals", "vertices", vn, "vertices", vn, 0.0);
    cj_stage_report_figures(R, "texture_coords", "vertices", vt, "vertices", vt, 0.0);
    size_t built = b->patch_tris + b->surface_tris + b->mesh_tris;
    cj_stage_report_figures(R, "cull_backfaces", "triangles", built + b->culled_back, "triangles",
                            built, b->sec_cull);
    cj_rctx *c = &F->c;
    c->obj_mat = cj_ralloc(&F->A, sizeof(int) * (b->object_count ? b->object_count : 1));
    if (!c->obj_mat) return cj_fail(CJ_ERR_NOMEM, "object table");
    for (size_t i = 0; i < b->object_count; ++i)
        c->obj_mat[i] = b->objects[i].material >= 0 ? b->objects[i].material : c->nmat;
    return CJ_OK;
}

/* Opaque and transparent lists; the transparent one back to front (BSP). */
static cj_status order_triangles(cj_rframe *F) {
    cj_rctx *c = &F->c;
    cj_status st = split_lists(c, &F->b, &F->A);
    if (st) return st;
    F->transp_in = c->transp.count;
    if (F->f.transparent) {
        double ts = cj_render_now();
        st = cj_rbsp_order(&F->b, &F->view, &c->transp.tris, &c->transp.obj, &c->transp.count,
                           &F->splits, &F->fallback, &F->A);
        F->sec_sort = cj_render_now() - ts;
        if (st) return st;
    }
    cj_stage *s = cj_stage_report_figures(F->R, "sort_transparent", "triangles", F->transp_in,
                                          "triangles", c->transp.count, F->sec_sort);
    if (F->f.transparent) {
        cj_stage_add_value(s, "bsp_splits", (double)F->splits);
        cj_stage_add_value(s, "painter_fallback", F->fallback);
    }
    return CJ_OK;
}

/* Clip coordinates, per-triangle / per-vertex lighting, overlay segments. */
static cj_status project_and_light(cj_rframe *F) {
    cj_rctx *c = &F->c;
    double ts = cj_render_now();
    cj_status st = project(c, &F->b, &F->A);
    F->sec_project = cj_render_now() - ts;
    if (st) return st;
    cj_stage_report_set(F->R, "project", 1, "always");
    cj_stage_report_figures(F->R, "project", "vertices", F->b.vertex_count, "vertices",
                            F->b.vertex_count, F->sec_project);
    ts = cj_render_now();
    st = cj_rshade_prepare_eye(c, &F->A);
    /* the opaque list's per-triangle values are made beside its raster set-up (setup_raster) */
    if (!st) st = cj_rshade_prepare_begin(c, &c->opaque, &F->A);
    if (!st) st = cj_rshade_prepare_list(c, &c->transp, &F->A, NULL, 1);
    if (!st) st = cj_rshade_prepare_gouraud(c, &F->A, &F->gouraud_vertices);
    F->sec_shade_setup = cj_render_now() - ts;
    if (st) return st;
    ts = cj_render_now();
    if (F->f.overlays) st = cj_rlines_build(c, F->scene, &F->A);
    F->sec_lines_setup = cj_render_now() - ts;
    c->has_lines = F->f.overlays && c->lines.count > 0;
    return st;
}

/* The opaque list's raster set-up (task 0) beside its shading set-up in ranges (tasks 1..):
 * on a warm frame's pool the two run at once, on two workers, instead of one after the other.
 * Each task writes arrays of its own; the values never depend on the worker. */
typedef struct setup_job {
    cj_rframe *F;
    size_t chunk;
    cj_status st;              /* task 0's status */
    char msg[512];             /* and its message, to be raised again on the calling thread */
    double sec_raster;         /* task 0's seconds */
    double sec_shade[256 + 1]; /* per worker: the shading ranges' seconds */
} setup_job;

static void setup_task(void *user, int task, int worker) {
    setup_job *j = user;
    cj_rframe *F = j->F;
    cj_rctx *c = &F->c;
    const double ts = cj_render_now();
    if (task == 0) {
        j->st = prep_list(c, &c->opaque, &F->A, &F->rs_o);
        if (j->st) snprintf(j->msg, sizeof j->msg, "%s", cj_last_error());
        j->sec_raster = cj_render_now() - ts;
        return;
    }
    const size_t t0 = (size_t)(task - 1) * j->chunk, t1 = t0 + j->chunk;
    cj_rshade_prepare_range(c, &c->opaque, t0, t1 < c->opaque.count ? t1 : c->opaque.count);
    j->sec_shade[worker] += cj_render_now() - ts;
}

/* Clipping, snapping, edge set-up and binning of both lists (and the opaque list's shading
 * set-up beside it). */
static cj_status setup_raster(cj_rframe *F) {
    cj_rctx *c = &F->c;
    setup_job *j = cj_ralloc(&F->A, sizeof *j);
    if (!j) return cj_fail(CJ_ERR_NOMEM, "set-up job");
    memset(j, 0, sizeof *j);
    j->F = F;
    j->chunk = 4096;
    const size_t n = c->opaque.count, ranges = (n + j->chunk - 1) / j->chunk;
    /* the pool of the last frame, if any (the first frame starts it in run_tiles) */
    cj_rpool *pool = F->r->pool;
    const int workers = pool ? cj_rpool_plan(F->r->opt.render.threads, cj_rpool_threads(pool)) : 1;
    double ts = cj_render_now();
    if (workers > 1 && ranges < 1000000) {
        cj_rpool_run(pool, (int)ranges + 1, workers, setup_task, j, NULL);
    } else {
        for (size_t k = 0; k <= ranges; ++k) setup_task(j, (int)k, 0);
    }
    const double wall = cj_render_now() - ts;
    cj_status st = j->st;
    if (st) cj_fail(st, "%s", j->msg);
    double shade = 0.0;
    for (int w = 0; w <= 256; ++w) shade += j->sec_shade[w];
    F->sec_setup = j->sec_raster;
    cj_rfree(&F->A, j);
    ts = cj_render_now();
    if (!st && F->f.transparent) st = prep_list(c, &c->transp, &F->A, &F->rs_t);
    F->sec_setup += cj_render_now() - ts;
    if (st) return st;
    /* shade_setup: its serial part and its ranges, summed over the workers (as the per-tile
     * stages are); with both sets of tasks on one thread, their wall time is this step's */
    F->sec_shade_setup += shade;
    cj_stage *s =
        cj_stage_report_figures(F->R, "shade_setup", "triangles", c->opaque.count + c->transp.count,
                                "vertices", F->gouraud_vertices, F->sec_shade_setup);
    cj_stage_add_value(s, "wall_with_raster_setup", wall);
    c->has_transp = F->f.transparent && c->transp.count > 0;
    cj_stage_report_set(F->R, "raster_setup", 1, "always");
    cj_stage_report_figures(F->R, "raster_setup", "triangles", F->rs_o.tris_in + F->rs_t.tris_in,
                            "triangles", F->rs_o.tris_setup + F->rs_t.tris_setup, F->sec_setup);
    return CJ_OK;
}

/* The image, the pool and the per-worker buffers (all kept by the renderer), then the tiles:
 * visibility, shading, overlays, transparency, resolve, output. */
static cj_status run_tiles(cj_rframe *F, unsigned planes, cj_render_image *const *image) {
    cj_rctx *c = &F->c;
    /* every tile writes all its pixels' colours, ids and depths (cj_rtile_run) */
    cj_status st = cj_rtarget_acquire_overwritten(F->r, F->W, F->H, planes, image, &F->target);
    if (st) return st;
    c->img = F->target.img;
    F->pool_workers = cj_raster_thread_count(c->opaque.prep, F->r->opt.render.threads);
    st = cj_renderer_pool(F->r, F->pool_workers, &F->pool_reused);
    if (st) return st;
    if (F->pool_workers > cj_rpool_threads(F->r->pool))
        F->pool_workers = cj_rpool_threads(F->r->pool);
    c->threads = F->pool_workers;
    size_t samples = (size_t)F->tile * (size_t)F->tile * (size_t)F->spp;
    st = cj_renderer_shade_buffers(F->r, c->threads, samples, &F->buffers_reused);
    if (st) return st;
    c->color = F->r->color;
    c->order = F->r->order;
    c->count = F->r->count;
    double ts = cj_render_now();
    cj_rprogress pg;
    cj_rprogress_init(&pg, &F->r->opt.render,
                      (uint64_t)c->tiles_x * (uint64_t)((F->H + F->tile - 1) / F->tile));
    int ws_reused = 0;
    st = cj_raster_run_on(c->opaque.prep, F->r->pool, c->threads, F->r->ws, cj_rtile_run, c, &pg,
                          &F->run, &ws_reused);
    cj_rprogress_destroy(&pg);
    F->sec_run = cj_render_now() - ts;
    F->buffers_reused = F->buffers_reused && ws_reused;
    return st;
}

/* The per-tile stages' figures, summed over the workers. */
static void report_tiles(cj_rframe *F) {
    cj_rctx *c = &F->c;
    cj_stage_report *R = F->R;
    cj_rcount sum;
    memset(&sum, 0, sizeof sum);
    for (int i = 0; i < c->threads; ++i)
        for (int k = 0; k < CJ_RS_COUNT; ++k) {
            sum.sec[k] += c->count[i].sec[k];
            sum.cpu[k] += c->count[i].cpu[k];
            sum.n[k] += c->count[i].n[k];
        }
    /* the workers' time outside the pipeline's tile callback: the visibility pass */
    double cb = 0.0;
    for (int k = 0; k < CJ_RS_COUNT; ++k) cb += sum.sec[k];
    double vis = F->run.seconds_raster * c->threads - cb;
    cj_stage_report_set(R, "rasterize", 1, "always");
    cj_stage *s = cj_stage_report_figures(R, "rasterize", "samples", F->run.samples_tested,
                                          "samples", F->run.samples_written, vis > 0.0 ? vis : 0.0);
    cj_stage_add_value(s, "tris_clipped", (double)(F->rs_o.tris_clipped + F->rs_t.tris_clipped));
    cj_stage_add_value(s, "tris_rejected", (double)(F->rs_o.tris_rejected + F->rs_t.tris_rejected));
    cj_stage_add_value(s, "run_wall_seconds", F->sec_run);
    uint64_t textured = 0;
    double tex_sec = 0.0;
    for (int m = 0; m < CJ_RM_COUNT; ++m) {
        char name[CJ_STAGE_NAME_MAX];
        snprintf(name, sizeof name, "shade_%s", cj_rmodel_name[m]);
        uint64_t n = sum.n[2 * m] + sum.n[2 * m + 1];
        textured += sum.n[2 * m + 1];
        tex_sec += sum.sec[2 * m + 1];
        cj_stage *sh = cj_stage_report_figures(R, name, "samples", n, "samples", n,
                                               sum.sec[2 * m] + sum.sec[2 * m + 1]);
        if (F->f.model_used[m])
            cj_stage_add_value(sh, "cpu_seconds", sum.cpu[2 * m] + sum.cpu[2 * m + 1]);
    }
    s = cj_stage_report_figures(R, "texture", "samples", textured, "samples", textured, tex_sec);
    if (F->f.textured) cj_stage_add_value(s, "seconds_include_shading", 1.0);
    if (c->opaque.plane_state || c->transp.plane_state)
        cj_stage_add_value(
            s, "planes_built",
            (double)(cj_rshade_planes_built(&c->opaque) + cj_rshade_planes_built(&c->transp)));
    cj_stage_report_figures(R, "overlay_lines", "segments", c->lines.world_segments, "pixels",
                            sum.n[CJ_RS_LINES], sum.sec[CJ_RS_LINES] + F->sec_lines_setup);
    s = cj_stage_report_figures(R, "transparency", "triangles", c->transp.count, "fragments",
                                sum.n[CJ_RS_TRANSPARENT], sum.sec[CJ_RS_TRANSPARENT]);
    if (F->f.transparent) cj_stage_add_value(s, "cpu_seconds", sum.cpu[CJ_RS_TRANSPARENT]);
    const uint64_t spp = (uint64_t)F->spp;
    cj_stage_report_figures(R, "resolve", "samples", spp > 1 ? sum.n[CJ_RS_RESOLVE] * spp : 0,
                            "pixels", sum.n[CJ_RS_RESOLVE], sum.sec[CJ_RS_RESOLVE]);
    const uint64_t px = (uint64_t)F->W * (uint64_t)F->H;
    cj_stage_report_set(R, "output", 1, "always");
    cj_stage_report_figures(R, "output", "pixels", px, "pixels", px,
                            sum.sec[CJ_RS_OUTPUT] + sum.sec[CJ_RS_BACKGROUND]);
    cj_renderer_report_frame(F->r, R, F->pool_workers, F->pool_reused, F->buffers_reused,
                             !F->target.fresh);
}

cj_status cj_rraster_frame(cj_renderer *r, const cj_rscene *rs, unsigned planes,
                           cj_render_image **image, cj_stage_report *R) {
    cj_rframe F;
    memset(&F, 0, sizeof F);
    F.r = r;
    F.rs = rs;
    F.scene = rs->scene;
    F.R = R;
    /* the frame's arrays come from the renderer's scratch blocks: a warm frame reuses the
     * memory of the last one instead of faulting in fresh pages (render_scratch.h) */
    F.A = cj_rscratch_allocator(r->scratch);
    F.target.fresh = 0;
    cj_status st = resolve_settings(&F);
    if (!st) st = setup_view(&F);
    if (!st) st = cj_rframe_materials(&F);
    if (!st) st = cj_rframe_textures(&F);
    if (!st) st = build_triangles(&F);
    if (!st) st = order_triangles(&F);
    if (!st) st = project_and_light(&F);
    if (!st) st = setup_raster(&F);
    if (!st) st = run_tiles(&F, planes, image);
    if (!st) report_tiles(&F);
    cj_rtarget_finish(&F.target, image, st);
    clear_ctx(&F.c, &F.A);
    cj_rfree(&F.A, F.need);
    cj_rbuild_free(&F.b);
    return st;
}
