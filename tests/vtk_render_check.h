/* Oracles and comparisons for test_vtk_render: exact classification of pixel centres against
 * a sphere's projected conic (MPFR), the exact depth interval of an inscribed sphere mesh, and
 * mask/depth/colour comparisons of two renderings with a one-pixel silhouette band. */
#ifndef CJ_TEST_VTK_RENDER_CHECK_H
#define CJ_TEST_VTK_RENDER_CHECK_H

#include "casteljau/scene.h"
#include <mpfr.h>
#include <stddef.h>
#include <stdint.h>

/* Depth agreement (pseudodepth units) where nothing but arithmetic separates two depths of the
 * same plane: llvmpipe stores depth in a 24-bit (or 32-bit float) buffer and both renderers
 * interpolate in float from vertices snapped to 1/256 px; see the measured margins printed. */
#define CJ_DEPTH_TOL 2e-6

/* Colour agreement per channel, in 8-bit linear units, of diffuse + ambient shading (the same
 * formula in both renderers, per fragment with interpolated, renormalised normals): each image
 * is rounded to 8 bits (0.5 each) and both compute in float; 2 leaves one unit for the float
 * arithmetic and the normals' interpolation in different frames (world vs eye). */
#define CJ_COLOUR_TOL 2
/* vtkImageDifference with the same per-channel threshold: its thresholded error is 0 only if
 * every pixel finds a match within the threshold in the other picture (exact pixel, 3 x 3
 * shift or 3 x 3 average, VTK's defaults), background and silhouettes included. */
#define CJ_IMAGEDIFF_THRESHOLD CJ_COLOUR_TOL
#define CJ_IMAGEDIFF_MAX       0.0

typedef struct cj_check_planes {
    int w, h;
    float *rgba;
    uint32_t *ids;
    float *depth;
} cj_check_planes;

void cj_check_planes_alloc(cj_check_planes *p, int w, int h);
void cj_check_planes_free(cj_check_planes *p);

/* A sphere seen by a camera on a w × h image. */
typedef struct cj_sphere_oracle {
    cj_camera cam;
    int w, h;
    double r;
    double C[3];        /* the centre in camera coordinates */
    double tx, ty;      /* NDC -> camera-plane scale: perspective a·tan(fov/2), tan(fov/2);
                           orthographic a·h/2, h/2 */
    double px_per_unit; /* image pixels per world unit at the centre's distance */
    /* the conic in pixel coordinates relative to the image centre, for distances */
    double ec[2], axis[2][2], semi[2];
    /* 256-bit copies for the exact classification */
    mpfr_t mC[3], mk, mtx, mty, mr2, s[6];
} cj_sphere_oracle;

void cj_sphere_oracle_init(cj_sphere_oracle *o, const cj_camera *cam, int w, int h, cj_vec3 c,
                           double r);
void cj_sphere_oracle_clear(cj_sphere_oracle *o);
/* 1 if the centre of pixel (x, y) sees the sphere (exact), else 0. */
int cj_sphere_inside(cj_sphere_oracle *o, int x, int y);
/* Distance in pixels from the centre of pixel (x, y) to the projected conic. */
double cj_sphere_conic_distance(const cj_sphere_oracle *o, int x, int y);

/* The first point where the ray through the centre of pixel (x, y) meets the ball of radius
 * rho about the sphere's centre, in camera coordinates; 0 if it misses. */
int cj_sphere_hit(const cj_sphere_oracle *o, int x, int y, double rho, double hit[3]);

typedef struct cj_silhouette_stats {
    size_t differ;   /* pixels whose mask disagrees with the exact classification */
    size_t beyond;   /* ... of them farther than 1 px from the conic */
    double max_dist; /* the largest distance of a disagreeing pixel */
} cj_silhouette_stats;

/* Compares the mask (ids != 0) with the exact classification of every pixel centre. */
void cj_silhouette_check(cj_sphere_oracle *o, const uint32_t *ids, cj_silhouette_stats *out);

typedef struct cj_depth_interval_stats {
    size_t checked, beyond;
    double max_excess; /* largest distance of a depth outside its exact interval */
    double max_width;  /* widest interval */
} cj_depth_interval_stats;

/* Where the pixel's ray meets the ball of radius `inner` (inside the mesh), the depth of a
 * covered pixel must lie between the sphere's exact pseudodepth and the inner ball's, up to
 * CJ_DEPTH_TOL. */
void cj_sphere_depth_check(const cj_sphere_oracle *o, double inner, const uint32_t *ids,
                           const float *depth, cj_depth_interval_stats *out);

#endif
