/* The renderer object (casteljau/renderer.h): what it owns across frames, the draw that runs
 * the scene pass and hands the frame to a back end, and the one-shot calls as renderers used
 * once. Its services to the back ends are in renderer_services.c. */
#include "renderer_internal.h"

#include "casteljau/mesh.h"
#include "error_internal.h"
#include "render_pipe.h"
#include "trace_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

cj_renderer_options cj_renderer_options_defaults(void) {
    cj_renderer_options o;
    memset(&o, 0, sizeof o);
    o.render = cj_render_options_defaults();
    return o;
}

/* The checks that need no scene; each back end checks the rest against the scene's settings. */
static cj_status check_options(const cj_renderer_options *o) {
    const cj_render_options *ro = &o->render;
    if (ro->threads < 0) return cj_fail(CJ_ERR_RANGE, "thread count %d must be >= 0", ro->threads);
    if (ro->tile_size != 0 && ro->tile_size < 8)
        return cj_fail(CJ_ERR_RANGE, "tile size %d must be 0 or >= 8", ro->tile_size);
    if (ro->spp < 0) return cj_fail(CJ_ERR_RANGE, "samples per pixel %d must be >= 0", ro->spp);
    if (ro->width < 0 || ro->height < 0)
        return cj_fail(CJ_ERR_RANGE, "image size %d x %d must be >= 0", ro->width, ro->height);
    if (!(ro->tol_px >= 0.0) || !isfinite(ro->tol_px))
        return cj_fail(CJ_ERR_RANGE, "tessellation tolerance %g px must be >= 0 and finite",
                       ro->tol_px);
    if (ro->max_depth < 0 || ro->max_depth > 64)
        return cj_fail(CJ_ERR_RANGE, "max depth %d outside 0..64", ro->max_depth);
    double pt = o->trace.patch_tolerance;
    if (!(pt == 0.0 || (pt > 0.0 && pt <= 1.0)))
        return cj_fail(CJ_ERR_RANGE, "patch tolerance %g outside (0, 1]", pt);
    if (o->trace.indirect_samples < 0 || o->trace.indirect_samples > 4096)
        return cj_fail(CJ_ERR_RANGE, "indirect samples %d outside 0..4096",
                       o->trace.indirect_samples);
    if (o->trace.integrator != CJ_INTEGRATOR_WHITTED && o->trace.integrator != CJ_INTEGRATOR_PATH)
        return cj_fail(CJ_ERR_RANGE, "integrator %d is neither whitted (0) nor path (1)",
                       o->trace.integrator);
    if (o->trace.emission_by_chance != 0 && o->trace.emission_by_chance != 1)
        return cj_fail(CJ_ERR_RANGE, "emission_by_chance %d is neither 0 nor 1",
                       o->trace.emission_by_chance);
    return CJ_OK;
}

static cj_status create(const cj_renderer_options *opt, const cj_allocator *alloc, int caching,
                        cj_renderer **out) {
    assert(out);
    cj_renderer_options o = opt ? *opt : cj_renderer_options_defaults();
    cj_status st = check_options(&o);
    if (st) return st;
    cj_allocator a = cj_render_alloc(alloc);
    cj_renderer *r = cj_ralloc(&a, sizeof *r);
    if (!r) return cj_fail(CJ_ERR_NOMEM, "renderer");
    memset(r, 0, sizeof *r);
    r->alloc = a;
    r->opt = o;
    r->caching = caching;
    st = cj_raster_workspace_create(&a, &r->ws);
    if (!st) st = cj_rscratch_create(&a, &r->scratch);
    if (!st && caching) st = cj_render_cache_create(&a, &r->cache);
    if (!st && caching) st = tr_bvh_cache_create(&a, &r->bvh);
    if (st) {
        cj_renderer_destroy(r);
        return st;
    }
    *out = r;
    return CJ_OK;
}

cj_status cj_renderer_create(const cj_renderer_options *opt, const cj_allocator *alloc,
                             cj_renderer **out) {
    return create(opt, alloc, 1, out);
}

cj_status cj_renderer_create_once(const cj_renderer_options *opt, const cj_allocator *alloc,
                                  cj_renderer **out) {
    return create(opt, alloc, 0, out);
}

void cj_renderer_destroy(cj_renderer *r) {
    if (!r) return;
    cj_rpool_destroy(r->pool);
    cj_raster_workspace_destroy(r->ws);
    cj_rscratch_destroy(r->scratch);
    cj_render_cache_destroy(r->cache);
    tr_bvh_cache_destroy(r->bvh);
    cj_renderer_free_shade_buffers(r);
    cj_rfree(&r->alloc, r->motion);
    cj_allocator a = r->alloc;
    cj_rfree(&a, r);
}

cj_status cj_renderer_set_options(cj_renderer *r, const cj_renderer_options *opt) {
    assert(r && opt);
    cj_status st = check_options(opt);
    if (!st) r->opt = *opt;
    return st;
}

cj_status cj_renderer_set_motion(cj_renderer *r, const cj_motion *m) {
    assert(r);
    cj_rfree(&r->alloc, r->motion);
    r->motion = NULL;
    r->motion_poses = 0;
    r->motion_nodes = 0;
    if (!m) return CJ_OK;
    assert(m->world);
    if (m->poses < 2 || m->poses > 1024)
        return cj_fail(CJ_ERR_RANGE, "motion: %d poses outside 2..1024", m->poses);
    if (m->node_count == 0 || m->node_count > ((size_t)1 << 40) / (size_t)m->poses)
        return cj_fail(CJ_ERR_RANGE, "motion: %zu nodes", m->node_count);
    const size_t n = (size_t)m->poses * m->node_count;
    for (size_t i = 0; i < n; ++i) {
        const cj_xform3 *x = &m->world[i];
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
                if (!isfinite(x->m[a][b]))
                    return cj_fail(CJ_ERR_NONFINITE,
                                   "motion: pose %zu, node %zu: entry (%d, %d) is %g",
                                   i / m->node_count, i % m->node_count, a, b, x->m[a][b]);
        if (x->m[3][0] != 0.0 || x->m[3][1] != 0.0 || x->m[3][2] != 0.0 || x->m[3][3] != 1.0)
            return cj_fail(CJ_ERR_UNSUPPORTED, "motion: pose %zu, node %zu: projective transform",
                           i / m->node_count, i % m->node_count);
    }
    r->motion = cj_ralloc(&r->alloc, n * sizeof *r->motion);
    if (!r->motion) return cj_fail(CJ_ERR_NOMEM, "motion: %zu transforms", n);
    memcpy(r->motion, m->world, n * sizeof *r->motion);
    r->motion_poses = m->poses;
    r->motion_nodes = m->node_count;
    return CJ_OK;
}

const cj_renderer_options *cj_renderer_get_options(const cj_renderer *r) {
    assert(r);
    return &r->opt;
}

cj_status cj_renderer_draw(cj_renderer *r, const cj_scene *scene, cj_backend backend,
                           unsigned planes, cj_render_image **image, cj_stage_report *report) {
    assert(r && scene && image);
    double t0 = cj_render_now();
    cj_stage_report *R = &r->report;
    cj_stage_report_init(R, backend == CJ_BACKEND_TRACE ? "trace" : "raster");
    cj_status st = cj_scene_check(scene);
    if (st) return st;
    ++r->frame;
    cj_rscene rs;
    st = cj_rscene_prepare(scene, &r->alloc, &rs);
    if (st) return st;
    if (backend == CJ_BACKEND_TRACE)
        st = cj_rtrace_frame(r, &rs, planes, image, R);
    else
        st = cj_rraster_frame(r, &rs, planes, image, R);
    cj_rscene_free(&rs);
    if (!st) R->total_seconds = cj_render_now() - t0;
    if (report) *report = *R;
    return st;
}

const cj_stage_report *cj_renderer_report(const cj_renderer *r) {
    assert(r);
    return &r->report;
}

/* ---- the one-shot calls: a renderer used once ---------------------------------------------- */

static cj_status once(const cj_scene *scene, const cj_render_options *opt,
                      const cj_trace_options *topt, cj_backend backend, unsigned planes,
                      const cj_allocator *alloc, cj_render_image **out, cj_stage_report *report) {
    assert(scene && out);
    cj_renderer_options ro = cj_renderer_options_defaults();
    if (opt) ro.render = *opt;
    if (topt) ro.trace = *topt;
    cj_renderer *r = NULL;
    cj_status st = cj_renderer_create_once(&ro, alloc, &r);
    if (st) return st;
    cj_render_image *img = NULL;
    st = cj_renderer_draw(r, scene, backend, planes, &img, report);
    cj_renderer_destroy(r);
    if (!st) *out = img;
    return st;
}

cj_status cj_render_raster(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                           const cj_allocator *alloc, cj_render_image **out,
                           cj_stage_report *report) {
    return once(scene, opt, NULL, CJ_BACKEND_RASTER, planes, alloc, out, report);
}

cj_status cj_render_trace(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                          const cj_allocator *alloc, cj_render_image **out,
                          cj_stage_report *report) {
    return once(scene, opt, NULL, CJ_BACKEND_TRACE, planes, alloc, out, report);
}

cj_status cj_render_trace_with_options(const cj_scene *scene, const cj_render_options *opt,
                                       const cj_trace_options *topt, unsigned planes,
                                       const cj_allocator *alloc, cj_render_image **out,
                                       cj_stage_report *report) {
    return once(scene, opt, topt, CJ_BACKEND_TRACE, planes, alloc, out, report);
}

cj_status cj_renderer_scene_mesh(cj_renderer *r, const cj_scene *scene, cj_mesh **out) {
    assert(r && scene && out);
    cj_status st = cj_scene_check(scene);
    if (st) return st;
    const cj_scene_settings *ss = cj_scene_get_settings(scene);
    const cj_render_options *opt = &r->opt.render;
    int W = opt->width ? opt->width : ss->width;
    int H = opt->height ? opt->height : ss->height;
    double tol = opt->tol_px != 0.0 ? opt->tol_px : ss->tol_px;
    if (W < 1 || H < 1 || !isfinite(tol) || !(tol > 0.0))
        return cj_fail(CJ_ERR_RANGE, "image size %d x %d or tolerance %g px out of range", W, H,
                       tol);
    cj_rview view;
    st = cj_rview_init(cj_scene_get_camera(scene), W, H, &view);
    if (st) return st;
    cj_rscene rs;
    st = cj_rscene_prepare(scene, &r->alloc, &rs);
    if (st) return st;
    cj_rbuild b;
    st = cj_rbuild_scene(&rs, &view, tol, CJ_RB_NORMALS | CJ_RB_UVS, NULL, 1, cj_renderer_cache(r),
                         &r->alloc, &b);
    cj_rscene_free(&rs);
    if (st) return st;
    cj_mesh *m = NULL;
    st = cj_mesh_create(&r->alloc, &m);
    if (!st) st = cj_mesh_reserve(m, b.vertex_count, b.tri_count);
    for (size_t v = 0; v < b.vertex_count && !st; ++v) {
        double n[3] = {b.nrm[3 * v], b.nrm[3 * v + 1], b.nrm[3 * v + 2]};
        double uv[2] = {b.uv[2 * v], b.uv[2 * v + 1]};
        st = cj_mesh_add_vertex(m, b.pos + 3 * v, n, uv, NULL);
    }
    for (size_t t = 0; t < b.tri_count && !st; ++t)
        st = cj_mesh_add_triangle(m, b.tris[3 * t], b.tris[3 * t + 1], b.tris[3 * t + 2],
                                  (int32_t)b.objects[b.tobj[t]].id);
    cj_rbuild_free(&b);
    if (st) {
        cj_mesh_destroy(m);
        return st;
    }
    *out = m;
    return CJ_OK;
}

cj_status cj_render_scene_mesh(const cj_scene *scene, const cj_render_options *opt,
                               const cj_allocator *alloc, cj_mesh **out) {
    cj_renderer_options ro = cj_renderer_options_defaults();
    if (opt) ro.render = *opt;
    cj_renderer *r = NULL;
    cj_status st = cj_renderer_create_once(&ro, alloc, &r);
    if (st) return st;
    st = cj_renderer_scene_mesh(r, scene, out);
    cj_renderer_destroy(r);
    return st;
}
