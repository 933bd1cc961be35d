/* casteljau: keyframe channels applied to a scene (DESIGN.md: "animation evaluates the scene at
 * a time t into a posed scene"), and the stage report of the simulation.
 *
 * An animation is a list of channels (casteljau/anim.h), each on a TARGET PATH:
 *   nodes[N].translate  nodes[N].scale                  vector channels of dimension 3
 *   nodes[N].rotation                                   quaternion or Euler channel
 *   nodes[N].patches[P].points[J]                       control point J (x, y, z) of patch P of
 *   nodes[N].curve.points[J]                            the node's geometry / of its curve
 *   camera.eye  camera.gaze  camera.up  camera.look_at  dimension 3 (look_at sets the gaze to
 *                                                       look_at − eye after eye is applied)
 *   camera.fov_y                                        dimension 1, radians
 *   lights[L].position  lights[L].direction  lights[L].color            dimension 3
 *   lights[L].intensity                                                 dimension 1
 *   materials[M].color  materials[M].specular                           dimension 3
 *   materials[M].ka  .kd  .ks  .alpha  .opacity  .mirror  .transmission dimension 1
 * where N, L, M, P, J are indices, and N may also be a node's name in double quotes
 * (nodes["pot"].rotation).
 *
 * cj_anim_bind() resolves every path ONCE into pointers through the scene's *_mut accessors and
 * checks the channel's kind and dimension against the field. CONTROL POINTS belong to the
 * node's geometry, so an animated point moves in every node sharing that geometry; they are
 * written through the scene's own (owned, heap-allocated) point arrays.
 *
 * cj_anim_pose() WRITES INTO THE BOUND SCENE IN PLACE: every animated field is overwritten by
 * its channel's value at t (channels are absolute, not offsets), so the posed scene depends on t
 * alone, never on earlier poses; fields without a channel keep their values. To keep the rest
 * pose, pose a copy (load the scene twice) — the scene model has no clone today. Renderers
 * call cj_scene_check() as usual: a channel that drives a field out of its range (a negative
 * intensity from an overshooting spline) is caught there, naming the field.
 * info->control_points tells whether any control point changed, so that a renderer
 * re-tessellates only then.
 *
 * Bind again after adding parts to the scene (the accessors' pointers move on add).
 *
 * Errors: a path that does not parse or names no field: CJ_ERR_ARGUMENT with the channel number
 * and the path ("channel 2: nodes[7].translate: node 7 does not exist (3 nodes)"); a channel
 * whose kind or dimension does not fit the field: CJ_ERR_DIMENSION naming both; a NaN time:
 * CJ_ERR_NONFINITE; posing before binding: CJ_ERR_ARGUMENT; a camera made invalid by its
 * channels (up parallel to gaze): the scene's CJ_ERR_DEGENERATE naming the time, the camera
 * left as it was.
 */
#ifndef CASTELJAU_ANIM_SCENE_H
#define CASTELJAU_ANIM_SCENE_H

#include "casteljau/alloc.h"
#include "casteljau/anim.h"
#include "casteljau/motion.h"
#include "casteljau/particles.h"
#include "casteljau/scene.h"
#include "casteljau/springs.h"
#include "casteljau/stage_report.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_anim cj_anim;

cj_status cj_anim_create(const cj_allocator *alloc, cj_anim **out);
void cj_anim_destroy(cj_anim *anim);

/* Adds a channel (the keys are copied, the channel built and validated now) on `path` (copied;
 * syntax checked at bind). Errors of the channel come back as from cj_channel_create, prefixed
 * with the path. */
cj_status cj_anim_add(cj_anim *anim, const char *path, const cj_channel_desc *desc);

/* Adds MOTION ALONG A PATH at controlled speed (casteljau/motion.h) on a target of dimension 3:
 * the value at time t is the path point at length fraction σ((t − start)/duration) of the ease
 * profile (held before start and after start + duration). The animation takes ownership of
 * `motion` on success (destroyed with the animation); on failure the caller keeps it.
 * start < 0, duration <= 0, a bad ease parameter: CJ_ERR_RANGE; NaN: CJ_ERR_NONFINITE. */
cj_status cj_anim_add_path(cj_anim *anim, const char *path, cj_path *motion, double start,
                           double duration, cj_ease ease, double ease_param);

size_t cj_anim_channel_count(const cj_anim *anim);
const char *cj_anim_channel_path(const cj_anim *anim, size_t i);
/* The keyframe channel of entry i (NULL for motion along a path). */
const cj_channel *cj_anim_channel(const cj_anim *anim, size_t i);
/* The first and last key time over all channels (0, 0 when there are none). */
void cj_anim_range(const cj_anim *anim, double *t0, double *t1);
/* 1 if any channel targets control points. */
int cj_anim_animates_control_points(const cj_anim *anim);

cj_status cj_anim_bind(cj_anim *anim, cj_scene *scene);
/* After cj_anim_bind failed: the index of the channel it stopped at (so that a file reader can
 * name the channel's line). */
size_t cj_anim_bind_failed(const cj_anim *anim);

typedef struct cj_anim_pose_info {
    size_t channels;    /* channels evaluated */
    int control_points; /* 1 if control points were written (re-tessellate) */
    int camera;         /* 1 if the camera changed */
    double seconds;
} cj_anim_pose_info;

/* Poses the bound scene at time t (see above); info may be NULL. */
cj_status cj_anim_pose(cj_scene *scene, const cj_anim *anim, double t, cj_anim_pose_info *info);

/* MOTION BLUR: the world transform (cj_scene_node_world) of every node of the scene at `poses`
 * times evenly spaced over [t_open, t_close], pose k at t_open + k (t_close − t_open)/(poses − 1),
 * written pose-major into world[k * node_count + node] (the caller's array of poses ×
 * cj_scene_node_count(scene) transforms); the renderer's cj_renderer_set_motion takes it as is.
 * The scene is posed at each time in turn and left posed at t_close: pose it again at the
 * frame's time afterwards. Only node transforms are recorded (the camera, lights, materials and
 * control points stay whatever the caller poses last). poses < 2, t_close <= t_open:
 * CJ_ERR_RANGE; other errors as cj_anim_pose and cj_scene_node_world. */
cj_status cj_anim_sample_motion(cj_scene *scene, const cj_anim *anim, double t_open, double t_close,
                                int poses, cj_xform3 *world);

/* Records the animation stages of one frame in a stage report, run or left out and why:
 * "keyframes" (channels), "spring_forces" (a spring system with springs), "particle_pass" (a
 * particle system), "flocking" (non-zero flocking weights), "collisions" (colliders of either
 * system), "retessellate" (animated control points). Any argument but r may be NULL (absent);
 * the stats give the stage's time and counts. */
void cj_anim_report_stages(cj_stage_report *r, const cj_anim *anim, const cj_anim_pose_info *pose,
                           const cj_springs *springs, const cj_springs_stats *spring_stats,
                           const cj_particles *particles, const cj_particles_stats *particle_stats);

#ifdef __cplusplus
}
#endif
#endif
