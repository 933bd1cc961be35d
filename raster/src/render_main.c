/* cj_render_raster: the pipeline assembled from what the scene uses, with a stage report entry
 * for every stage, run or left out, and the feature that decided it. */
#include "render_pipe.h"

#include "casteljau/framebuffer.h"
#include "error_internal.h"
#include "render_progress.h"

#include <math.h>
#include <string.h>

static const char *model_name[CJ_RM_COUNT] = {"unlit", "flat", "gouraud", "phong"};

typedef struct features {
    int lit, any_ambient;
    int model_used[CJ_RM_COUNT];
    int model_mat[CJ_RM_COUNT]; /* a material using it (for the report) */
    int textured, tex_mat, trilinear;
    int transparent, transp_mat;
    int one_sided;
    int overlays, overlay_node;
    int patches, surfaces, meshes;
} features;

static void prepare_lights(const cj_scene *scene, cj_rctx *c, float Ia[3], features *f) {
    size_t n = cj_scene_light_count(scene);
    Ia[0] = Ia[1] = Ia[2] = 0.0f;
    for (size_t i = 0; i < n; ++i) {
        const cj_light *L = cj_scene_light(scene, (int)i);
        float I[3] = {(float)(L->color.r * L->intensity), (float)(L->color.g * L->intensity),
                      (float)(L->color.b * L->intensity)};
        /* a light that gives nothing is left out: the image is the same without it */
        if (!(I[0] > 0.0f || I[1] > 0.0f || I[2] > 0.0f)) continue;
        if (L->kind == CJ_LIGHT_AMBIENT) {
            for (int k = 0; k < 3; ++k) Ia[k] += I[k];
            f->any_ambient = 1;
            continue;
        }
        cj_rlight *r = &c->lights[c->nlights++];
        memset(r, 0, sizeof *r);
        memcpy(r->I, I, sizeof I);
        cj_vec3 pos = L->position;
        if (L->kind == CJ_LIGHT_AREA) /* the rasterizer sees an area light as its centre */
            pos = cj_v3_add(pos, cj_v3_scale(cj_v3_add(L->edge_u, L->edge_v), 0.5));
        r->pos[0] = pos.x;
        r->pos[1] = pos.y;
        r->pos[2] = pos.z;
        if (L->kind == CJ_LIGHT_DIRECTIONAL) {
            cj_vec3 l = cj_v3_normalize(cj_v3_scale(L->direction, -1.0));
            r->directional = 1;
            r->l[0] = (float)l.x;
            r->l[1] = (float)l.y;
            r->l[2] = (float)l.z;
        } else if (L->kind == CJ_LIGHT_SPOT) {
            cj_vec3 a = cj_v3_normalize(L->direction);
            r->spot = 1;
            r->axis[0] = (float)a.x;
            r->axis[1] = (float)a.y;
            r->axis[2] = (float)a.z;
            r->cos_cut = (float)cos(L->spot_angle);
            r->spot_exp = (float)L->spot_exponent;
        }
    }
    f->lit = c->nlights > 0;
}

/* Which materials visible objects use, and what they ask for. */
static void scan_scene(const cj_scene *scene, cj_rctx *c, features *f) {
    size_t nn = cj_scene_node_count(scene);
    f->tex_mat = f->transp_mat = f->overlay_node = -1;
    for (int m = 0; m < CJ_RM_COUNT; ++m) f->model_mat[m] = -1;
    for (size_t i = 0; i < nn; ++i) {
        const cj_node *nd = cj_scene_node(scene, (int)i);
        if (nd->geometry < 0) continue;
        int vis = 1;
        for (int p = (int)i; p >= 0; p = cj_scene_node(scene, p)->parent)
            if (!cj_scene_node(scene, p)->visible) vis = 0;
        if (!vis) continue;
        const cj_geometry *g = cj_scene_geometry(scene, nd->geometry);
        if (g->kind == CJ_GEOM_CURVE || nd->overlay.flags) {
            if (!f->overlays) f->overlay_node = (int)i;
            f->overlays = 1;
        }
        if (g->kind == CJ_GEOM_CURVE) continue;
        if (g->kind == CJ_GEOM_PATCHES || g->kind == CJ_GEOM_REVOLUTION ||
            g->kind == CJ_GEOM_GEN_CYLINDER)
            f->patches = 1;
        else if (g->kind == CJ_GEOM_MESH)
            f->meshes = 1;
        else
            f->surfaces = 1;
        int mi = nd->material >= 0 ? nd->material : c->nmat;
        cj_rmat *m = &c->mats[mi];
        m->used = 1;
        if (f->model_mat[m->model] < 0) f->model_mat[m->model] = mi;
        f->model_used[m->model] = 1;
        if (m->tex >= 0) {
            if (!f->textured) f->tex_mat = mi;
            f->textured = 1;
        }
        if (m->opacity < 1.0f) {
            if (!f->transparent) f->transp_mat = mi;
            f->transparent = 1;
        }
        if (!m->two_sided) f->one_sided = 1;
    }
}

static void set_material(cj_rmat *r, const cj_material *m, int lit, int any_ambient,
                         const float Ia[3]) {
    memset(r, 0, sizeof *r);
    r->cr[0] = (float)m->color.r;
    r->cr[1] = (float)m->color.g;
    r->cr[2] = (float)m->color.b;
    for (int k = 0; k < 3; ++k) r->amb[k] = (lit || any_ambient) ? (float)m->ka * Ia[k] : 1.0f;
    r->spec[0] = (float)(m->specular.r * m->ks);
    r->spec[1] = (float)(m->specular.g * m->ks);
    r->spec[2] = (float)(m->specular.b * m->ks);
    r->kd = (float)m->kd;
    r->alpha = (float)m->alpha;
    r->opacity = (float)m->opacity;
    r->model = lit ? 1 + (int)m->shading : CJ_RM_UNLIT;
    r->two_sided = m->two_sided != 0;
    r->tex = m->texture;
}

static void clear_ctx(cj_rctx *c, const cj_allocator *a) {
    cj_rlist *lists[2] = {&c->opaque, &c->transp};
    for (int i = 0; i < 2; ++i) {
        cj_rfree(a, lists[i]->tris);
        cj_rfree(a, lists[i]->obj);
        cj_rfree(a, lists[i]->kernel);
        cj_rfree(a, lists[i]->flat);
        cj_rfree(a, lists[i]->uvplane);
        cj_rfree(a, lists[i]->back);
        cj_raster_prep_destroy(lists[i]->prep);
    }
    cj_rfree(a, c->clip);
    cj_rfree(a, c->gouraud);
    cj_rfree(a, c->mats);
    cj_rfree(a, c->obj_mat);
    cj_rfree(a, c->lights);
    for (int i = 0; i < c->nsamplers; ++i) cj_tex_sampler_free(&c->samplers[i]);
    cj_rfree(a, c->samplers);
    cj_rlines_free(&c->lines, a);
    for (int i = 0; i < c->threads; ++i) {
        if (c->color) cj_rfree(a, c->color[i]);
        if (c->order) cj_rfree(a, c->order[i]);
    }
    cj_rfree(a, c->color);
    cj_rfree(a, c->order);
    cj_rfree(a, c->count);
}

static cj_stage *stage(cj_stage_report *R, const char *name, int ran, const char *why,
                       const char *uin, uint64_t in, const char *uout, uint64_t out, double sec) {
    cj_stage *s = cj_stage_report_set(R, name, ran, "%s", why);
    if (!s) return NULL;
    snprintf(s->unit_in, sizeof s->unit_in, "%s", uin);
    snprintf(s->unit_out, sizeof s->unit_out, "%s", uout);
    s->in = in;
    s->out = out;
    s->seconds = sec;
    return s;
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

cj_status cj_render_raster(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                           const cj_allocator *alloc, cj_render_image **out,
                           cj_stage_report *report) {
    cj_stage_report local;
    cj_stage_report *R = report ? report : &local;
    cj_stage_report_init(R, "raster");
    double T0 = cj_render_now();
    cj_status st = cj_scene_check(scene);
    if (st) return st;
    const cj_scene_settings *ss = cj_scene_settings_get(scene);
    cj_render_options o = opt ? *opt : cj_render_options_default();
    int W = o.width ? o.width : ss->width, H = o.height ? o.height : ss->height;
    int spp = o.spp ? o.spp : ss->spp;
    double tol_px = o.tol_px != 0.0 ? o.tol_px : ss->tol_px;
    int tile = o.tile_size ? o.tile_size : 64;
    if (W < 1 || H < 1 || W > CJ_FRAMEBUFFER_MAX_SIDE || H > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "image size %d x %d outside 1..%d", W, H,
                       CJ_FRAMEBUFFER_MAX_SIDE);
    if (spp != 1 && spp != 4 && spp != 16)
        return cj_fail(CJ_ERR_RANGE, "samples per pixel %d: the rasterizer takes 1, 4 or 16", spp);
    if (!isfinite(tol_px) || !(tol_px > 0.0))
        return cj_fail(CJ_ERR_RANGE, "tessellation tolerance %g px must be > 0 and finite", tol_px);
    if (tile < 8 || tile > 4096) return cj_fail(CJ_ERR_RANGE, "tile size %d outside 8..4096", tile);
    if (o.threads < 0) return cj_fail(CJ_ERR_RANGE, "thread count %d must be >= 0", o.threads);
    cj_allocator A = cj_render_alloc(alloc);
    cj_stage_report_set(R, "scene_check", 1, "always");

    cj_rview view;
    st = cj_rview_init(cj_scene_camera(scene), W, H, &view);
    if (st) return st;
    cj_rctx c;
    memset(&c, 0, sizeof c);
    c.view = &view;
    c.width = W;
    c.height = H;
    c.spp = spp;
    c.tile_size = tile;
    c.tiles_x = (W + tile - 1) / tile;
    c.pattern = cj_raster_sample_pattern(spp);
    c.bg[0] = (float)ss->background.r;
    c.bg[1] = (float)ss->background.g;
    c.bg[2] = (float)ss->background.b;

    /* ---- features: lights, materials, textures ---- */
    features f;
    memset(&f, 0, sizeof f);
    c.nmat = (int)cj_scene_material_count(scene);
    c.mats = cj_ralloc(&A, sizeof(cj_rmat) * (size_t)(c.nmat + 1));
    c.lights = cj_ralloc(&A, sizeof(cj_rlight) * (cj_scene_light_count(scene) + 1));
    c.nsamplers = (int)cj_scene_texture_count(scene);
    c.samplers = cj_ralloc(&A, sizeof(cj_tex_sampler) * (size_t)(c.nsamplers + 1));
    unsigned *need = cj_ralloc(&A, sizeof(unsigned) * (size_t)(c.nmat + 1));
    cj_rbuild b;
    memset(&b, 0, sizeof b);
    c.b = &b;
    cj_render_image *img = NULL;
    if (!c.mats || !c.lights || !c.samplers || !need) {
        st = cj_fail(CJ_ERR_NOMEM, "render tables");
        goto fail;
    }
    memset(c.samplers, 0, sizeof(cj_tex_sampler) * (size_t)(c.nsamplers + 1));
    float Ia[3];
    prepare_lights(scene, &c, Ia, &f);
    for (int m = 0; m <= c.nmat; ++m) {
        cj_material def = cj_material_default();
        set_material(&c.mats[m], m < c.nmat ? cj_scene_material(scene, m) : &def, f.lit,
                     f.any_ambient, Ia);
    }
    scan_scene(scene, &c, &f);
    int normals_overlay = 0;
    for (size_t i = 0; i < cj_scene_node_count(scene); ++i)
        if (cj_scene_node(scene, (int)i)->overlay.flags & CJ_OVERLAY_NORMALS) normals_overlay = 1;
    unsigned flags = 0;
    for (int m = 0; m <= c.nmat; ++m) {
        const cj_rmat *r = &c.mats[m];
        need[m] = 0;
        if (r->model == CJ_RM_GOURAUD || r->model == CJ_RM_PHONG || normals_overlay)
            need[m] |= CJ_RB_NORMALS;
        if (r->tex >= 0) need[m] |= CJ_RB_UVS;
        if (r->used) flags |= need[m];
    }
    /* samplers of the textures used */
    double ts = cj_render_now();
    for (int m = 0; m <= c.nmat && !st; ++m) {
        const cj_rmat *r = &c.mats[m];
        if (!r->used || r->tex < 0 || c.samplers[r->tex].alloc.alloc) continue;
        const cj_texture *tx = cj_scene_texture(scene, r->tex);
        st = cj_tex_sampler_init(tx, r->tex, &A, &c.samplers[r->tex]);
        if (tx->kind == CJ_TEX_IMAGE && tx->filter == CJ_TEX_TRILINEAR) f.trilinear = 1;
    }
    if (st) goto fail;
    double sec_mip = cj_render_now() - ts;

    /* ---- scene -> world triangles ---- */
    st = cj_rbuild_scene(scene, &view, tol_px, flags, need, 1, o.cache, &A, &b);
    if (st) goto fail;
    c.obj_mat = cj_ralloc(&A, sizeof(int) * (b.object_count ? b.object_count : 1));
    if (!c.obj_mat) {
        st = cj_fail(CJ_ERR_NOMEM, "object table");
        goto fail;
    }
    for (size_t i = 0; i < b.object_count; ++i)
        c.obj_mat[i] = b.objects[i].material >= 0 ? b.objects[i].material : c.nmat;
    st = split_lists(&c, &b, &A);
    if (st) goto fail;
    size_t transp_in = c.transp.count, splits = 0;
    int fallback = 0;
    double sec_sort = 0.0;
    if (f.transparent) {
        ts = cj_render_now();
        st = cj_rbsp_order(&b, &view, &c.transp.tris, &c.transp.obj, &c.transp.count, &splits,
                           &fallback, &A);
        sec_sort = cj_render_now() - ts;
        if (st) goto fail;
    }
    ts = cj_render_now();
    st = project(&c, &b, &A);
    double sec_project = cj_render_now() - ts;
    if (st) goto fail;
    ts = cj_render_now();
    size_t gouraud_vertices = 0;
    st = cj_rshade_prepare_list(&c, &c.opaque, &A);
    if (!st) st = cj_rshade_prepare_list(&c, &c.transp, &A);
    if (!st) st = cj_rshade_prepare_gouraud(&c, &A, &gouraud_vertices);
    double sec_shade_setup = cj_render_now() - ts;
    if (st) goto fail;
    ts = cj_render_now();
    if (f.overlays) st = cj_rlines_build(&c, scene, &A);
    double sec_lines_setup = cj_render_now() - ts;
    if (st) goto fail;
    c.has_lines = f.overlays && c.lines.count > 0;

    /* ---- rasterize (visibility), shade per tile ---- */
    cj_raster_stats rs_o, rs_t, run;
    memset(&rs_o, 0, sizeof rs_o);
    memset(&rs_t, 0, sizeof rs_t);
    memset(&run, 0, sizeof run);
    ts = cj_render_now();
    st = prep_list(&c, &c.opaque, &A, &rs_o);
    if (!st && f.transparent) st = prep_list(&c, &c.transp, &A, &rs_t);
    double sec_setup = cj_render_now() - ts;
    if (st) goto fail;
    c.has_transp = f.transparent && c.transp.count > 0;
    st = cj_render_image_create(W, H, planes, &A, &img);
    if (st) goto fail;
    c.img = img;
    c.threads = cj_raster_thread_count(c.opaque.prep, o.threads);
    size_t samples = (size_t)tile * (size_t)tile * (size_t)spp;
    c.color = cj_ralloc(&A, sizeof(float *) * (size_t)c.threads);
    c.order = cj_ralloc(&A, sizeof(uint32_t *) * (size_t)c.threads);
    c.count = cj_ralloc(&A, sizeof(cj_rcount) * (size_t)c.threads);
    if (!c.color || !c.order || !c.count) {
        st = cj_fail(CJ_ERR_NOMEM, "per-thread tables");
        goto fail;
    }
    memset(c.color, 0, sizeof(float *) * (size_t)c.threads);
    memset(c.order, 0, sizeof(uint32_t *) * (size_t)c.threads);
    memset(c.count, 0, sizeof(cj_rcount) * (size_t)c.threads);
    for (int i = 0; i < c.threads; ++i) {
        c.color[i] = cj_ralloc(&A, sizeof(float) * 4 * samples);
        c.order[i] = cj_ralloc(&A, sizeof(uint32_t) * samples);
        if (!c.color[i] || !c.order[i]) {
            st = cj_fail(CJ_ERR_NOMEM, "tile buffers of %zu samples", samples);
            goto fail;
        }
    }
    ts = cj_render_now();
    cj_rprogress pg;
    cj_rprogress_init(&pg, &o, (uint64_t)c.tiles_x * (uint64_t)((H + tile - 1) / tile));
    st = cj_raster_run(c.opaque.prep, c.threads, cj_rtile_run, &c, &pg, &run);
    cj_rprogress_destroy(&pg);
    double sec_run = cj_render_now() - ts;
    if (st) goto fail;

    /* ---- the report ---- */
    cj_rcount sum;
    memset(&sum, 0, sizeof sum);
    for (int i = 0; i < c.threads; ++i)
        for (int k = 0; k < CJ_RS_COUNT; ++k) {
            sum.sec[k] += c.count[i].sec[k];
            sum.cpu[k] += c.count[i].cpu[k];
            sum.n[k] += c.count[i].n[k];
        }
    size_t tris_built = b.patch_tris + b.surface_tris + b.mesh_tris;
    cj_stage *s;
    s = stage(R, "tessellate_patches", f.patches,
              f.patches ? "the scene has Bezier patch objects" : "no patch objects", "patches",
              b.patches_in, "triangles", b.patch_tris, b.sec_patches);
    cj_stage_add_value(s, "tol_px", tol_px);
    cj_stage_add_value(s, "bound_px", b.patch_bound_px);
    cj_stage_add_value(s, "patches_culled", (double)b.patches_culled);
    if (o.cache) {
        cj_stage_add_value(s, "patches_planned", (double)b.patches_planned);
        cj_stage_add_value(s, "patches_built", (double)b.patches_built);
        cj_stage_add_value(s, "patches_reused", (double)b.patches_reused);
        cj_stage_add_value(s, "cache_hits", (double)b.cache_hits);
    }
    s = stage(R, "tessellate_surfaces", f.surfaces,
              f.surfaces ? "the scene has analytic surfaces" : "no analytic surfaces", "objects", 0,
              "triangles", b.surface_tris, b.sec_surfaces);
    cj_stage_add_value(s, "bound_px", b.surface_bound_px);
    stage(R, "meshes", f.meshes, f.meshes ? "the scene has triangle meshes" : "no mesh objects",
          "triangles", b.mesh_tris, "triangles", b.mesh_tris, b.sec_meshes);
    stage(R, "transform", 1, "always", "vertices", b.vertex_count, "vertices", b.vertex_count,
          b.sec_transform);
    stage(R, "vertex_normals", (flags & CJ_RB_NORMALS) != 0,
          (flags & CJ_RB_NORMALS) ? (normals_overlay ? "a normals overlay or Gouraud/Phong shading"
                                                     : "lit Gouraud/Phong materials")
                                  : (f.lit ? "flat shading only: face normals" : "no lights"),
          "vertices", (flags & CJ_RB_NORMALS) ? b.vertex_count : 0, "vertices",
          (flags & CJ_RB_NORMALS) ? b.vertex_count : 0, 0.0);
    stage(R, "texture_coords", (flags & CJ_RB_UVS) != 0,
          (flags & CJ_RB_UVS) ? "a material has a texture" : "no textures", "vertices",
          (flags & CJ_RB_UVS) ? b.vertex_count : 0, "vertices",
          (flags & CJ_RB_UVS) ? b.vertex_count : 0, 0.0);
    stage(R, "cull_backfaces", f.one_sided,
          f.one_sided ? "one-sided materials" : "every material is two-sided", "triangles",
          tris_built + b.culled_back, "triangles", tris_built, b.sec_cull);
    s = stage(R, "sort_transparent", f.transparent,
              f.transparent ? "a material has opacity < 1" : "no transparent material", "triangles",
              transp_in, "triangles", c.transp.count, sec_sort);
    if (f.transparent) {
        cj_stage_add_value(s, "bsp_splits", (double)splits);
        cj_stage_add_value(s, "painter_fallback", fallback);
    }
    stage(R, "project", 1, "always", "vertices", b.vertex_count, "vertices", b.vertex_count,
          sec_project);
    int any_setup = f.model_used[CJ_RM_FLAT] || f.model_used[CJ_RM_GOURAUD];
    stage(R, "shade_setup", any_setup,
          any_setup ? "flat/Gouraud materials: per-triangle/vertex lighting"
                    : "no flat or Gouraud material",
          "triangles", c.opaque.count + c.transp.count, "vertices", gouraud_vertices,
          sec_shade_setup);
    stage(R, "mipmaps", f.trilinear,
          f.trilinear ? "a trilinear image texture" : "no trilinear image texture", "textures",
          (uint64_t)c.nsamplers, "textures", (uint64_t)c.nsamplers, sec_mip);
    stage(R, "raster_setup", 1, "always", "triangles", rs_o.tris_in + rs_t.tris_in, "triangles",
          rs_o.tris_setup + rs_t.tris_setup, sec_setup);
    /* the workers' time outside the pipeline's tile callback: the visibility pass */
    double cb = 0.0;
    for (int k = 0; k < CJ_RS_COUNT; ++k) cb += sum.sec[k];
    double vis = run.seconds_raster * c.threads - cb;
    s = stage(R, "rasterize", 1, "always", "samples", run.samples_tested, "samples",
              run.samples_written, vis > 0.0 ? vis : 0.0);
    cj_stage_add_value(s, "tris_clipped", (double)(rs_o.tris_clipped + rs_t.tris_clipped));
    cj_stage_add_value(s, "tris_rejected", (double)(rs_o.tris_rejected + rs_t.tris_rejected));
    cj_stage_add_value(s, "run_wall_seconds", sec_run);
    char why[CJ_STAGE_WHY_MAX];
    uint64_t textured = 0;
    double tex_sec = 0.0;
    for (int m = 0; m < CJ_RM_COUNT; ++m) {
        char name[CJ_STAGE_NAME_MAX];
        snprintf(name, sizeof name, "shade_%s", model_name[m]);
        if (f.model_used[m])
            snprintf(why, sizeof why, "material %d is %s%s", f.model_mat[m], model_name[m],
                     m == CJ_RM_UNLIT ? (f.any_ambient ? " (ambient light only)" : " (no lights)")
                                      : "");
        else
            snprintf(why, sizeof why,
                     m == CJ_RM_UNLIT ? "the scene has lights"
                     : f.lit          ? "no %s material"
                                      : "no lights",
                     model_name[m]);
        uint64_t n = sum.n[2 * m] + sum.n[2 * m + 1];
        textured += sum.n[2 * m + 1];
        tex_sec += sum.sec[2 * m + 1];
        cj_stage *sh = stage(R, name, f.model_used[m], why, "samples", n, "samples", n,
                             sum.sec[2 * m] + sum.sec[2 * m + 1]);
        if (f.model_used[m])
            cj_stage_add_value(sh, "cpu_seconds", sum.cpu[2 * m] + sum.cpu[2 * m + 1]);
    }
    if (f.textured) snprintf(why, sizeof why, "material %d has a texture", f.tex_mat);
    s = stage(R, "texture", f.textured, f.textured ? why : "no textures", "samples", textured,
              "samples", textured, tex_sec);
    if (f.textured) cj_stage_add_value(s, "seconds_include_shading", 1.0);
    if (f.overlays) snprintf(why, sizeof why, "node %d has overlays or is a curve", f.overlay_node);
    s = stage(R, "overlay_lines", f.overlays, f.overlays ? why : "no overlays or curves",
              "segments", c.lines.world_segments, "pixels", sum.n[CJ_RS_LINES],
              sum.sec[CJ_RS_LINES] + sec_lines_setup);
    if (f.transparent) snprintf(why, sizeof why, "material %d has opacity < 1", f.transp_mat);
    s = stage(R, "transparency", f.transparent, f.transparent ? why : "no transparent material",
              "triangles", c.transp.count, "fragments", sum.n[CJ_RS_TRANSPARENT],
              sum.sec[CJ_RS_TRANSPARENT]);
    if (f.transparent) cj_stage_add_value(s, "cpu_seconds", sum.cpu[CJ_RS_TRANSPARENT]);
    snprintf(why, sizeof why, "spp = %d", spp);
    stage(R, "resolve", spp > 1, why, "samples", spp > 1 ? sum.n[CJ_RS_RESOLVE] * (uint64_t)spp : 0,
          "pixels", sum.n[CJ_RS_RESOLVE], sum.sec[CJ_RS_RESOLVE]);
    stage(R, "output", 1, "always", "pixels", (uint64_t)W * (uint64_t)H, "pixels",
          (uint64_t)W * (uint64_t)H, sum.sec[CJ_RS_OUTPUT] + sum.sec[CJ_RS_BACKGROUND]);
    R->total_seconds = cj_render_now() - T0;
    *out = img;
    img = NULL;
fail:
    cj_render_image_destroy(img);
    clear_ctx(&c, &A);
    cj_rfree(&A, need);
    cj_rbuild_free(&b);
    return st;
}
