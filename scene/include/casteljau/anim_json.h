/* casteljau: animation documents (JSON) — keyframe channels, motion along paths, and a cloth
 * simulation for a scene, read by `casteljau animate`.
 *
 * The scene file format (casteljau/scene_json.h) checks every key, so an animation lives in its
 * own document that names its scene:
 *
 * {
 *   "scene": "teapot.json",        the scene file, relative to this document's folder
 *   "fps": 24,                     frames per second (in [0.001, 10000]; default 24)
 *   "frames": [0, 95],             the default frame range (first <= last, >= 0)
 *   "shutter": [-0.25, 0.25],      MOTION BLUR (the ray tracer): the shutter is open from
 *                                  frame + open to frame + close, in frames (−1 <= open <
 *                                  close <= 1); absent: an instantaneous shutter
 *   "shutter_poses": 16,           node transforms posed at this many times evenly spaced over
 *                                  the shutter (2..1024, default 16), interpolated between them
 *   "channels": [
 *     {"target": "nodes[\"pot\"].rotation", "type": "quaternion",      vector | quaternion | euler
 *      "interpolation": "squad",   step | linear | catmull_rom | centripetal | kochanek_bartels |
 *                                  hermite | bezier_auto | gltf_cubic | squad
 *      "times": [0, 1, 2],         seconds, strictly increasing, >= 0
 *      "values": [[1,0,0,0], ...], one array per key (a number per key for dimension 1)
 *      "tangents": [...],          hermite: one array per key; gltf_cubic: [in, out] per key
 *      "tension": 0.5, "continuity": 0, "bias": 0,
 *      "euler_order": "xyz", "degrees": true},      Euler channels: angles in degrees if true
 *     {"target": "camera.eye",
 *      "path": {"points": [[6,2,0], [0,2,6], [-6,2,0], [0,2,-6]], "closed": true,
 *               "spline": "catmull_rom", "tension": 0.5},   or "centripetal"
 *      "start": 0, "duration": 4, "ease": "linear", "accel": 0.25}
 *                                  motion at controlled speed (casteljau/motion.h): linear |
 *                                  smoothstep | sine | trapezoid (accel = its fraction)
 *   ],
 *   "gravity": [0, -9.81, 0], "drag": 0.1,
 *   "colliders": {"spheres": [{"center": [0,0,0], "radius": 1, "friction": 0.3}],
 *                 "planes": [{"normal": [0,1,0], "offset": 0, "friction": 0.5}]},
 *   "cloth": {"grid": [24, 24], "corner": [-1.5, 2, -1.5], "edge_u": [3, 0, 0],
 *             "edge_v": [0, 0, 3], "mass": 1, "stiffness": [2000, 500, 50], "damping": 0.5,
 *             "pinned": [0, 23], "integrator": "implicit_euler", "steps_per_frame": 4,
 *             "color": [0.8, 0.2, 0.2], "name": "cloth",
 *             "collide_with": ["teapot"]},  scene objects made of Bézier patches it drapes over
 *   "particles": {"capacity": 300, "seed": 1, "restitution": 0.6, "wind": [0, 0, 0],
 *                 "steps_per_frame": 2, "radius": 0.04, "color": [1, 0.8, 0.2],
 *                 "collide_with": ["teapot"],   scene objects whose Bézier patches (placed by
 *                                               their world transform) the particles bounce off
 *                 "flocking": {"radius": 0, "separation": 0, "alignment": 0, "cohesion": 0,
 *                              "max_speed": 0},
 *                 "emitters": [{"position": [0, 4, 0], "direction": [0, -1, 0], "spread": 0.3,
 *                               "speed": 2, "speed_jitter": 0.2, "rate": 60, "lifetime": 3,
 *                               "lifetime_jitter": 0.2, "jitter_radius": 0.3, "start": 0,
 *                               "stop": 0}]}
 * }
 * Particles share "gravity", "drag" and "colliders" with the cloth; they are drawn as small
 * spheres (one scene node per pool slot, hidden while the slot is empty).
 *
 * Errors name the file, the line and the JSON path ("flyby.json:12: channels[1].times[2] ...");
 * unknown or repeated keys are errors; a channel on a field that does not exist is reported when
 * the document is attached to its scene (cj_anim_doc_attach), with the file, the channel's line
 * and its path ("flyby.json:7: channel 0: nodes[3].translate: index 3 does not exist").
 *
 * SIMULATION: the cloth (and its colliders, gravity, drag) is a spring system (springs.h)
 * advanced in fixed steps of 1/(fps · steps_per_frame) seconds from t = 0; the scene shows it as
 * a triangle mesh whose vertices and normals are rewritten every frame. cj_anim_doc_advance()
 * steps it up to a frame; checkpoints (cj_anim_doc_save_state / load_state) store the exact
 * state, so frames A..B rendered after loading the checkpoint of frame A are bit-identical to
 * those of one long run.
 */
#ifndef CASTELJAU_ANIM_JSON_H
#define CASTELJAU_ANIM_JSON_H

#include "casteljau/anim_scene.h"
#include "casteljau/particles.h"
#include "casteljau/springs.h"
#include "casteljau/status.h"
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bounds on the simulation parameters of a document, checked when it is read (each refusal
 * names the file, line and JSON path), so that no document implies unbounded work or a number
 * that overflows: steps per frame (cloth and particles), the length of "gravity" (m/s^2), an
 * emitter's "rate" (particles per second), "speed", "lifetime" and "jitter_radius", lengths of
 * positions and edges, and the particles emitted by one emitter in one step
 * (rate / (fps * steps_per_frame)), which also bounds an --fps given later
 * (cj_anim_doc_set_fps). A blow-up of the simulation itself (an explicit-Euler cloth whose
 * springs are too stiff for its step) can only be found by simulating: cj_anim_doc_frame then
 * fails with CJ_ERR_NONFINITE naming the part, the field to change and the frame. */
#define CJ_ANIM_MAX_STEPS_PER_FRAME 1000
#define CJ_ANIM_MAX_GRAVITY         1e4
#define CJ_ANIM_MAX_EMIT_RATE       1e6
#define CJ_ANIM_MAX_SPEED           1e6
#define CJ_ANIM_MAX_LIFETIME        1e6
#define CJ_ANIM_MAX_COORD           1e9
#define CJ_ANIM_MAX_EMIT_PER_STEP   1e4
#define CJ_ANIM_MIN_FPS             1e-3
#define CJ_ANIM_MAX_FPS             1e4
#define CJ_ANIM_MAX_SHUTTER_POSES   1024

typedef struct cj_anim_doc {
    char scene_path[1024]; /* resolved; "" if the document names none */
    char source[256];      /* the document's name in messages (its path) */
    int *channel_lines;    /* owned: the line of each channel, in the order they were added */
    size_t channel_line_count, channel_line_cap;
    double fps;
    int frame_first, frame_last;
    cj_anim *anim;     /* owned */
    cj_springs *cloth; /* owned, or NULL */
    int cloth_nu, cloth_nv;
    cj_integrator cloth_integrator;
    int steps_per_frame;
    cj_rgb cloth_color;
    char cloth_name[64];
    long sim_frame;     /* the frame the simulation state belongs to */
    int cloth_node;     /* scene node showing the cloth after attach, or −1 */
    int cloth_geometry; /* its mesh geometry */
    /* particles: the description is kept until attach builds the system (its patch colliders
     * come from the scene) */
    int has_particles;
    cj_particles_desc pdesc; /* emitters, spheres, planes point into the arrays below */
    cj_emitter emitters[16];
    cj_sphere_collider spheres[8];
    cj_plane_collider planes[8];
    char collide_with[8][64];
    int collide_count;
    cj_patch_collider *patch_colliders[8]; /* owned, built at attach */
    cj_particles *particles;               /* owned, built at attach */
    int particle_steps;
    double particle_radius;
    cj_rgb particle_color;
    int particle_node0; /* first of pdesc.capacity sphere nodes, or −1 */
    /* cloth on patch objects: rebuilt at attach with the colliders */
    char cloth_collide_with[4][64];
    int cloth_collide_count;
    cj_patch_collider *cloth_colliders[4];
    int cloth_grid[2];
    double cloth_corner[3], cloth_eu[3], cloth_ev[3], cloth_mass, cloth_k[3], cloth_damping;
    int cloth_pins[64];
    size_t cloth_pin_count;
    int emitter_lines[16]; /* the line of each emitter (for messages after reading) */
    int fps_line;          /* the line of "fps", 0 if absent */
    /* motion blur: has_shutter 0 = instantaneous; shutter[0] < shutter[1] in frames relative to
     * the frame's time; shutter_poses >= 2 (cj_anim_sample_motion) */
    int has_shutter;
    double shutter[2];
    int shutter_poses;
} cj_anim_doc;

cj_status cj_anim_doc_load(const char *path, cj_anim_doc **out);
cj_status cj_anim_doc_parse(const char *text, const char *name, const char *base_dir,
                            cj_anim_doc **out);
void cj_anim_doc_destroy(cj_anim_doc *doc);

/* Sets the frame rate after checking it and the work it implies: fps in [CJ_ANIM_MIN_FPS,
 * CJ_ANIM_MAX_FPS], and for every emitter rate / (fps * particles.steps_per_frame) at most
 * CJ_ANIM_MAX_EMIT_PER_STEP. `origin` names where fps comes from in messages ("--fps"); NULL
 * for the document's own. CJ_ERR_RANGE naming the emitter's path and line; doc unchanged. */
cj_status cj_anim_doc_set_fps(cj_anim_doc *doc, double fps, const char *origin);

/* Adds the cloth's mesh node (if any) to the scene and binds the channels (errors name the
 * document, and for a channel its line and path). Call once, before posing. */
cj_status cj_anim_doc_attach(cj_anim_doc *doc, cj_scene *scene);

/* Advances the simulation to frame `frame` (>= the current one; frames before it need a
 * checkpoint: CJ_ERR_RANGE) and poses the scene at t = frame / fps: channels, then the cloth
 * mesh. report (may be NULL) receives the frame's animation stages. */
cj_status cj_anim_doc_frame(cj_anim_doc *doc, cj_scene *scene, long frame, cj_stage_report *report);

/* The simulation state (frame number, cloth positions and velocities, bit-exact) to/from a
 * checkpoint file. Loading a state of another document (particle counts differ): CJ_ERR_PARSE. */
cj_status cj_anim_doc_save_state(const cj_anim_doc *doc, FILE *f);
cj_status cj_anim_doc_load_state(cj_anim_doc *doc, FILE *f);

#ifdef __cplusplus
}
#endif
#endif
