/* casteljau: the ray tracer (seed 11-13): the same scenes, camera and image type as the
 * rasterizer (casteljau/render.h), surfaces intersected exactly (casteljau/ray.h).
 *
 * GEOMETRY. Every visible object with a surface is traced: spheres, quadrics, tori, cylinders,
 * planar and bilinear patches exactly; Bézier patch sets (and surfaces of revolution / general
 * cylinders, as their exact rational patches) DIRECTLY by subdivision + Newton with the
 * tolerance 1e-7 × the object's box diagonal (object space; the largest distance to the ray
 * reached is reported in the stage "patch_rays"); meshes through a per-mesh BVH of watertight
 * triangles with normals and (u, v) interpolated from the mesh's vertices. Objects are
 * intersected in object space through the inverse of their world transform (normals by the
 * inverse transpose), under a top-level SAH BVH of their world boxes. Curves are not traced.
 *
 * SHADING (Whitted). At a hit, with n the surface normal turned to the side the ray comes from:
 *   local = c_r (r_a I_a + r_d Σ_visible I max(0, n·l)) + c_p r_s Σ_visible I s + emission
 * (the rasterizer's model, evaluated by the same code: s is the material's specular lobe,
 * Blinn's max(0, n·h)^α or Phong's max(0, m·v)^α, and 0 where n·l <= 0; c_r the colour times
 * the texture; docs/light.md), where a
 * light is "visible" unless a shadow ray finds an occluder: an occluded light (or one behind
 * the surface, n·l <= 0) contributes only its ambient part. Then
 *   L = (1 − r_t) [o local + (1 − o) L_through] + r_m L_reflected + r_t L_refracted
 * with o the material's opacity (a straight-through ray for o < 1), r_m = mirror, r_t =
 * transmission. Refraction follows Snell's law with the index of refraction of the current
 * medium tracked along the ray (a stack: entering a transmissive object pushes its ior, leaving
 * pops it); total internal reflection sends the refracted weight along the reflected ray.
 * Recursion stops at max_depth (the primary ray is depth 0); a ray that leaves the scene
 * returns the background.
 *
 * ONLY THE EFFECTS THE SCENE CALLS FOR: a shadow ray is cast only for lights with
 * casts_shadows from hits on materials with receives_shadows; a reflection ray only from
 * materials with mirror > 0; a refracted ray only into materials with transmission > 0; a
 * straight-through ray only for opacity < 1; area lights and glossy materials draw samples
 * only when spp > 1 (at spp = 1 an area light is its centre and glossy reflection a mirror).
 * The stage report counts each kind of ray (in = cast, out = hit something) and the time spent
 * tracing it, summed over threads.
 *
 * SECONDARY RAYS start at cj_ray_offset_origin(hit, direction) with tmin = 0: no fixed
 * epsilon; the offset follows the hit's floating-point error bound.
 *
 * SAMPLING. spp = 1: one ray through each pixel centre. spp > 1: stratified jittered samples
 * (a k × k grid when spp = k², else spp strata along x) with a box filter; area-light points
 * (stratified the same way) and Phong-lobe glossy directions (exponent `glossiness`) come from
 * a counter-based generator hashed from (seed, pixel, sample, bounce, use), so the image is
 * BIT-IDENTICAL for any thread count and tile size. Opt-in one-bounce diffuse interreflection
 * (cj_trace_options.indirect_samples) draws cosine-weighted directions from the same generator.
 *
 * PLANES. CJ_IMAGE_IDS: the scene signature image (seed 11.4), the id of the first object hit
 * by the ray through the pixel centre (0 = background); CJ_IMAGE_DEPTH: its pseudodepth.
 */
#ifndef CASTELJAU_TRACE_H
#define CASTELJAU_TRACE_H

#include "casteljau/render.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Traces the scene into *out (created here with `planes`): a renderer used once
 * (casteljau/renderer.h keeps one across frames, with its BVHs). Options as cj_render_raster's
 * (spp: any >= 1; 0 = the scene's); report may be NULL. Status: whatever cj_scene_check
 * reports; CJ_ERR_RANGE (a size or spp out of range), CJ_ERR_ARGUMENT (an image texture
 * without pixels), CJ_ERR_DEGREE (a patch above CJ_RAY_PATCH_MAX_DEGREE), CJ_ERR_SINGULAR (a
 * singular object transform), CJ_ERR_CAP (more than 64 non-ambient lights), CJ_ERR_NOMEM.
 * *out is set only on success. */
cj_status cj_render_trace(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                          const cj_allocator *alloc, cj_render_image **out,
                          cj_stage_report *report);

/* Sampling choices beyond cj_render_options (all zero: the defaults). */
typedef struct cj_trace_options {
    int random_sampling;    /* 1: plain uniform random pixel positions and area-light points instead
                               of stratified ones (to measure what stratification gains); the
                               path tracer: also its first hit's light and BRDF samples */
    double patch_tolerance; /* 0: the default 1e-7; else the tolerance of the direct Bézier
                               patch intersection, relative to each patch object's box diagonal
                               (to measure what accuracy costs); must be finite, in (0, 1] */
    int indirect_samples;   /* 0: off (Whitted). N in 1..4096: ONE-BOUNCE DIFFUSE INTERREFLECTION:
                               at each hit on a material with kd > 0 (lit scene, depth < max_depth,
                               not itself reached by an indirect ray) N cosine-weighted hemisphere
                               rays about the shading normal (cj_trace_cosine_sample, u1
                               stratified over the N) each add kd c_r L_in / N to the local term,
                               L_in traced with depth + 1 but casting no further indirect rays.
                               Counted in the stage "indirect_rays". */
    int integrator;         /* CJ_INTEGRATOR_WHITTED (0, the default) or CJ_INTEGRATOR_PATH */
    int emission_by_chance; /* path tracer, 1: emissive surfaces are found only by BRDF samples,
                               not sampled as lights (to measure what sampling them gains) */
} cj_trace_options;

/* CJ_INTEGRATOR_WHITTED: the shading described above. CJ_INTEGRATOR_PATH: a path tracer
 * (docs/light.md): the rendering equation by random walks with next-event estimation to every
 * light, multiple importance sampling (power heuristic) between area-light and BRDF samples,
 * Russian roulette from the fourth bounce (survival q = the largest throughput channel, capped
 * at 0.95, weight 1/q) and max_depth as a hard cap. Lights are read radiometrically (scene.h)
 * and materials as the BSDF mixture r_t dielectric + r_m mirror + (1 − r_t − r_m) (r_d c_r/π +
 * r_s c_p f_s); area lights are seen by camera rays and emission is added where a path meets
 * it; ambient light is the radiance of the environment (added to the background). Diffuse
 * and glossy bounces are counted as indirect_rays, mirror and Fresnel reflections as
 * reflection_rays, refractions as refraction_rays, next-event rays as shadow_rays;
 * indirect_samples is ignored. At the camera ray's first hit the light samples and the BRDF
 * sample are stratified over the pixel's samples (keyed random permutations, as the Whitted
 * tracer's light strata); deeper bounces draw uniformly.
 * Bit-identical for any thread count, like the Whitted tracer. */
typedef enum cj_trace_integrator {
    CJ_INTEGRATOR_WHITTED = 0,
    CJ_INTEGRATOR_PATH
} cj_trace_integrator;

/* cj_render_trace with trace options (NULL: defaults); same status codes, and CJ_ERR_RANGE
 * for a patch_tolerance that is not 0 and not in (0, 1], indirect_samples outside 0..4096 or
 * an integrator that is not a cj_trace_integrator. */
cj_status cj_render_trace_with_options(const cj_scene *scene, const cj_render_options *opt,
                                       const cj_trace_options *topt, unsigned planes,
                                       const cj_allocator *alloc, cj_render_image **out,
                                       cj_stage_report *report);

/* Refraction of the unit direction d at a surface with unit normal n facing against d
 * (d·n <= 0), from index n1 into n2 (Snell: n1 sin θ1 = n2 sin θ2): 1 and the unit refracted
 * direction in *t, or 0 on total internal reflection (n1 sin θ1 > n2). */
int cj_trace_refract(cj_vec3 d, cj_vec3 n, double n1, double n2, cj_vec3 *t);

/* Cosine-weighted direction about the unit normal n (pdf cos θ / π) from (u1, u2) in [0, 1)²
 * by Malley's method: the point (sqrt(u1) cos 2πu2, sqrt(u1) sin 2πu2) of the unit disk lifted
 * to the hemisphere (height sqrt(1 − u1) = cos θ). A unit vector with n·d >= 0. */
cj_vec3 cj_trace_cosine_sample(cj_vec3 n, double u1, double u2);

/* The built-in demo of `casteljau trace --demo`: the lit Utah teapot (patches, traced
 * directly) on a checkered floor, a mirror sphere and a glass sphere (ior 1.5): the scene
 * scenes/demo_trace.json, embedded at build time (as cj_render_demo_scene; same statuses). */
cj_status cj_trace_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out);

#ifdef __cplusplus
}
#endif
#endif
