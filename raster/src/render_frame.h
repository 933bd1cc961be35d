/* Private to the rasterizer back end (render_main.c, render_prepare.c): one frame's state,
 * handed from step to step of cj_rraster_frame, and the steps that read the scene's lights,
 * materials and textures. */
#ifndef CJ_RENDER_FRAME_H
#define CJ_RENDER_FRAME_H

#include "render_pipe.h"
#include "renderer_internal.h"

extern const char *const cj_rmodel_name[CJ_RM_COUNT]; /* "unlit", "flat", "gouraud", "phong" */

/* What the drawn objects' materials and lights ask for. */
typedef struct cj_rfeatures {
    int lit, any_ambient;
    int model_used[CJ_RM_COUNT];
    int model_mat[CJ_RM_COUNT]; /* a material using it (for the report) */
    int textured, tex_mat, trilinear;
    int transparent, transp_mat;
    int one_sided;
    int overlays, overlay_node;
    int patches, surfaces, meshes;
} cj_rfeatures;

/* Everything one frame of the rasterizer holds, step to step. */
typedef struct cj_rframe {
    cj_renderer *r;
    const cj_rscene *rs;
    const cj_scene *scene;
    cj_stage_report *R;
    cj_allocator A;
    int W, H, spp, tile;
    double tol_px;
    cj_rview view;
    cj_rctx c;
    cj_rfeatures f;
    float Ia[3];
    unsigned *need, flags;
    cj_rbuild b;
    size_t transp_in, splits, gouraud_vertices;
    int fallback;
    cj_raster_stats rs_o, rs_t, run;
    cj_rtarget target;
    int pool_workers, pool_reused, buffers_reused;
    double sec_mip, sec_sort, sec_project, sec_shade_setup, sec_lines_setup, sec_setup, sec_run;
} cj_rframe;

/* render_prepare.c: lights, materials and the feature mask (recording the stages they
 * decide), then the samplers of the textures used. */
cj_status cj_rframe_materials(cj_rframe *F);
cj_status cj_rframe_textures(cj_rframe *F);

#endif
