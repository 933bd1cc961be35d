/* The rasterizer's frame steps that read the scene's lights, materials and textures: each
 * records in the stage report the stages its findings decide (render_frame.h). */
#include "render_frame.h"

#include "reflect_model.h"

#include "error_internal.h"

#include <math.h>
#include <string.h>

const char *const cj_rmodel_name[CJ_RM_COUNT] = {"unlit", "flat", "gouraud", "phong"};

static void prepare_lights(const cj_scene *scene, cj_rctx *c, float Ia[3], cj_rfeatures *f) {
    size_t n = cj_scene_light_count(scene);
    const int radiometric = cj_scene_get_settings(scene)->light_model == CJ_LIGHT_RADIOMETRIC;
    c->radiometric = radiometric;
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
        if (radiometric &&
            (L->kind == CJ_LIGHT_AREA || L->kind == CJ_LIGHT_DISC || L->kind == CJ_LIGHT_SPHERE))
            c->emitters[c->nemitters++] = L;
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
        } else if (radiometric && L->kind == CJ_LIGHT_AREA) {
            cj_vec3 nrm = cj_v3_cross(L->edge_u, L->edge_v);
            const cj_vec3 q[4] = {L->position, cj_v3_add(L->position, L->edge_u),
                                  cj_v3_add(cj_v3_add(L->position, L->edge_u), L->edge_v),
                                  cj_v3_add(L->position, L->edge_v)};
            r->area = 1;
            r->ncorner = 4;
            r->size = cj_v3_norm(nrm);
            nrm = cj_v3_normalize(nrm);
            r->normal[0] = nrm.x;
            r->normal[1] = nrm.y;
            r->normal[2] = nrm.z;
            for (int j = 0; j < 4; ++j) {
                r->corner[j][0] = q[j].x;
                r->corner[j][1] = q[j].y;
                r->corner[j][2] = q[j].z;
            }
        } else if (radiometric && L->kind == CJ_LIGHT_DISC) {
            /* the disc's irradiance by the polygon path (cj_reflect_disc_polygon); the specular
             * term its centre as a point of intensity L_e π R² cos θ′, as before */
            const cj_vec3 nrm = cj_v3_normalize(L->direction);
            r->area = 1;
            r->ncorner = CJ_REFLECT_DISC_SIDES;
            r->size = 3.14159265358979323846 * L->radius * L->radius;
            r->normal[0] = nrm.x;
            r->normal[1] = nrm.y;
            r->normal[2] = nrm.z;
            cj_reflect_disc_polygon(r->pos, r->normal, L->radius, r->corner);
        } else if (L->kind == CJ_LIGHT_SPOT) {
            cj_vec3 a = cj_v3_normalize(L->direction);
            r->spot = 1;
            r->axis[0] = (float)a.x;
            r->axis[1] = (float)a.y;
            r->axis[2] = (float)a.z;
            r->cos_cut = (float)cos(L->spot_angle);
            r->spot_exp = (float)L->spot_exponent;
        }
        r->falloff = radiometric && (L->kind == CJ_LIGHT_POINT || L->kind == CJ_LIGHT_SPOT);
        if (L->kind == CJ_LIGHT_SPHERE || (L->kind == CJ_LIGHT_DISC && !radiometric)) {
            /* the far-field point at the centre (scene.h): legacy, a point of strength I;
             * radiometric, a sphere of intensity π R² L_e (exact wherever the sphere is wholly
             * above the receiver's horizon) */
            r->falloff = radiometric;
            r->sphere = radiometric && L->kind == CJ_LIGHT_SPHERE;
            r->radius = L->radius;
            if (radiometric) {
                const float proj = (float)(3.14159265358979323846 * L->radius * L->radius);
                for (int k = 0; k < 3; ++k) r->I[k] *= proj;
            }
        }
    }
    f->lit = c->nlights > 0;
}

/* What the materials of the drawn surfaces ask for (the scene pass lists them in order of first
 * use, so each reason names the same material as a walk over the nodes would). */
static void scan_scene(const cj_rscene *rs, cj_rctx *c, cj_rfeatures *f) {
    f->tex_mat = f->transp_mat = -1;
    f->overlay_node = rs->overlay_node;
    f->overlays = (rs->features & CJ_RF_OVERLAYS) != 0;
    f->patches = (rs->features & CJ_RF_PATCHES) != 0;
    f->surfaces = (rs->features & CJ_RF_SURFACES) != 0;
    f->meshes = (rs->features & CJ_RF_MESHES) != 0;
    for (int m = 0; m < CJ_RM_COUNT; ++m) f->model_mat[m] = -1;
    for (int k = 0; k < rs->material_order_count; ++k) {
        const int mi = rs->material_order[k];
        cj_rmat *m = &c->mats[mi];
        m->used = 1;
        if (f->model_mat[m->model] < 0) f->model_mat[m->model] = mi;
        f->model_used[m->model] = 1;
        if (m->tex >= 0 && !f->textured) {
            f->tex_mat = mi;
            f->textured = 1;
        }
        if (m->opacity < 1.0f && !f->transparent) {
            f->transp_mat = mi;
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
    r->emit[0] = (float)m->emission.r;
    r->emit[1] = (float)m->emission.g;
    r->emit[2] = (float)m->emission.b;
    r->kd = (float)m->kd;
    r->alpha = (float)m->alpha;
    r->spec_model = (int)m->specular_model;
    r->opacity = (float)m->opacity;
    r->model = lit ? 1 + (int)m->shading : CJ_RM_UNLIT;
    r->two_sided = m->two_sided != 0;
    r->tex = m->texture;
}

cj_status cj_rframe_materials(cj_rframe *F) {
    cj_rctx *c = &F->c;
    cj_rfeatures *f = &F->f;
    const cj_scene *scene = F->scene;
    c->nmat = (int)cj_scene_material_count(scene);
    c->mats = cj_ralloc(&F->A, sizeof(cj_rmat) * (size_t)(c->nmat + 1));
    c->lights = cj_ralloc(&F->A, sizeof(cj_rlight) * (cj_scene_light_count(scene) + 1));
    c->emitters = cj_ralloc(&F->A, sizeof(cj_light *) * (cj_scene_light_count(scene) + 1));
    c->nsamplers = (int)cj_scene_texture_count(scene);
    c->samplers = cj_ralloc(&F->A, sizeof(cj_tex_sampler) * (size_t)(c->nsamplers + 1));
    F->need = cj_ralloc(&F->A, sizeof(unsigned) * (size_t)(c->nmat + 1));
    if (!c->mats || !c->lights || !c->emitters || !c->samplers || !F->need)
        return cj_fail(CJ_ERR_NOMEM, "render tables");
    memset(c->samplers, 0, sizeof(cj_tex_sampler) * (size_t)(c->nsamplers + 1));
    prepare_lights(scene, c, F->Ia, f);
    for (int m = 0; m <= c->nmat; ++m) {
        cj_material def = cj_material_defaults();
        set_material(&c->mats[m], m < c->nmat ? cj_scene_material(scene, m) : &def, f->lit,
                     f->any_ambient, F->Ia);
    }
    scan_scene(F->rs, c, f);
    const int normals_overlay = (F->rs->features & CJ_RF_NORMALS_OVERLAY) != 0;
    F->flags = 0;
    for (int m = 0; m <= c->nmat; ++m) {
        const cj_rmat *r = &c->mats[m];
        F->need[m] = 0;
        if (r->model == CJ_RM_GOURAUD || r->model == CJ_RM_PHONG || normals_overlay)
            F->need[m] |= CJ_RB_NORMALS;
        if (r->tex >= 0) F->need[m] |= CJ_RB_UVS;
        if (r->used) F->flags |= F->need[m];
    }
    cj_stage_report *R = F->R;
    cj_stage_report_set(R, "vertex_normals", (F->flags & CJ_RB_NORMALS) != 0, "%s",
                        (F->flags & CJ_RB_NORMALS)
                            ? (normals_overlay ? "a normals overlay or Gouraud/Phong shading"
                                               : "lit Gouraud/Phong materials")
                            : (f->lit ? "flat shading only: face normals" : "no lights"));
    cj_stage_report_set(R, "texture_coords", (F->flags & CJ_RB_UVS) != 0, "%s",
                        (F->flags & CJ_RB_UVS) ? "a material has a texture" : "no textures");
    cj_stage_report_set(R, "cull_backfaces", f->one_sided, "%s",
                        f->one_sided ? "one-sided materials" : "every material is two-sided");
    cj_stage_report_set(R, "sort_transparent", f->transparent, "%s",
                        f->transparent ? "a material has opacity < 1" : "no transparent material");
    int any_setup = f->model_used[CJ_RM_FLAT] || f->model_used[CJ_RM_GOURAUD];
    cj_stage_report_set(R, "shade_setup", any_setup, "%s",
                        any_setup ? "flat/Gouraud materials: per-triangle/vertex lighting"
                                  : "no flat or Gouraud material");
    for (int m = 0; m < CJ_RM_COUNT; ++m) {
        char name[CJ_STAGE_NAME_MAX];
        snprintf(name, sizeof name, "shade_%s", cj_rmodel_name[m]);
        if (f->model_used[m])
            cj_stage_report_set(
                R, name, 1, "material %d is %s%s", f->model_mat[m], cj_rmodel_name[m],
                m == CJ_RM_UNLIT ? (f->any_ambient ? " (ambient light only)" : " (no lights)")
                                 : "");
        else if (m == CJ_RM_UNLIT)
            cj_stage_report_set(R, name, 0, "the scene has lights");
        else if (f->lit)
            cj_stage_report_set(R, name, 0, "no %s material", cj_rmodel_name[m]);
        else
            cj_stage_report_set(R, name, 0, "no lights");
    }
    if (f->textured)
        cj_stage_report_set(R, "texture", 1, "material %d has a texture", f->tex_mat);
    else
        cj_stage_report_set(R, "texture", 0, "no textures");
    if (f->overlays)
        cj_stage_report_set(R, "overlay_lines", 1, "node %d has overlays or is a curve",
                            f->overlay_node);
    else
        cj_stage_report_set(R, "overlay_lines", 0, "no overlays or curves");
    if (f->transparent)
        cj_stage_report_set(R, "transparency", 1, "material %d has opacity < 1", f->transp_mat);
    else
        cj_stage_report_set(R, "transparency", 0, "no transparent material");
    cj_stage_report_set(R, "resolve", F->spp > 1, "spp = %d", F->spp);
    return CJ_OK;
}

/* Samplers of the textures the drawn materials use (mipmaps for trilinear images). */
cj_status cj_rframe_textures(cj_rframe *F) {
    cj_rctx *c = &F->c;
    double ts = cj_render_now();
    cj_status st = CJ_OK;
    for (int m = 0; m <= c->nmat && !st; ++m) {
        const cj_rmat *r = &c->mats[m];
        if (!r->used || r->tex < 0 || c->samplers[r->tex].alloc.alloc) continue;
        const cj_texture *tx = cj_scene_texture(F->scene, r->tex);
        st = cj_tex_sampler_init(tx, r->tex, &F->A, &c->samplers[r->tex]);
        if (tx->kind == CJ_TEX_IMAGE && tx->filter == CJ_TEX_TRILINEAR) F->f.trilinear = 1;
    }
    F->sec_mip = cj_render_now() - ts;
    cj_stage_report_set(F->R, "mipmaps", F->f.trilinear, "%s",
                        F->f.trilinear ? "a trilinear image texture"
                                       : "no trilinear image texture");
    cj_stage_report_figures(F->R, "mipmaps", "textures", (uint64_t)c->nsamplers, "textures",
                            (uint64_t)c->nsamplers, F->sec_mip);
    return st;
}

/* Scene -> world triangles: tessellation for the view (through the renderer's cache),
 * transforms, culling. */