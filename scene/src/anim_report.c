/* The animation's entries in the stage report: each simulation stage run or left out, and the
 * scene feature that decided it. */
#include "casteljau/anim_scene.h"

#include "particle_internal.h"
#include "spring_internal.h"

#include <string.h>

void cj_anim_report_stages(cj_stage_report *r, const cj_anim *anim, const cj_anim_pose_info *pose,
                           const cj_springs *sp, const cj_springs_stats *sst,
                           const cj_particles *pa, const cj_particles_stats *pst) {
    cj_stage *s;
    const size_t nch = anim ? cj_anim_channel_count(anim) : 0;
    if (nch) {
        s = cj_stage_report_set(r, "keyframes", 1, "%zu animation channel%s", nch,
                                nch == 1 ? "" : "s");
        if (s && pose) {
            s->seconds = pose->seconds;
            s->in = pose->channels;
            snprintf(s->unit_in, sizeof s->unit_in, "channels");
        }
    } else {
        cj_stage_report_set(r, "keyframes", 0, "no animation channels");
    }
    if (sp && sp->nsprings) {
        s = cj_stage_report_set(r, "spring_forces", 1, "%zu springs on %zu particles", sp->nsprings,
                                sp->count);
        if (s && sst) {
            s->seconds = sst->seconds_forces + sst->seconds_solve;
            s->in = sp->nsprings;
            snprintf(s->unit_in, sizeof s->unit_in, "springs");
            if (sst->cg_iterations) cj_stage_add_value(s, "cg_iterations", sst->cg_iterations);
        }
    } else {
        cj_stage_report_set(r, "spring_forces", 0,
                            sp ? "the spring system has no springs" : "no spring system");
    }
    if (pa) {
        s = cj_stage_report_set(r, "particle_pass", 1, "%zu emitters, capacity %zu",
                                pa->d.emitter_count, pa->d.capacity);
        if (s && pst) {
            s->seconds = pst->seconds_emit + pst->seconds_forces;
            s->out = pa->count;
            snprintf(s->unit_out, sizeof s->unit_out, "particles");
            cj_stage_add_value(s, "emitted", (double)pst->emitted);
            cj_stage_add_value(s, "died", (double)pst->died);
        }
        const cj_flocking *f = &pa->d.flocking;
        if (f->radius > 0.0 &&
            (f->separation != 0.0 || f->alignment != 0.0 || f->cohesion != 0.0)) {
            s = cj_stage_report_set(r, "flocking", 1, "flocking radius %g", f->radius);
            if (s && pst) cj_stage_add_value(s, "neighbour_pairs", (double)pst->neighbour_pairs);
        } else {
            cj_stage_report_set(r, "flocking", 0, "flocking weights or radius are 0");
        }
    } else {
        cj_stage_report_set(r, "particle_pass", 0, "no particle system");
        cj_stage_report_set(r, "flocking", 0, "no particle system");
    }
    const size_t sc = sp ? sp->nspheres + sp->nplanes : 0;
    const size_t pc = pa ? pa->d.sphere_count + pa->d.plane_count + pa->d.patch_collider_count : 0;
    if (sc + pc) {
        s = cj_stage_report_set(r, "collisions", 1, "%zu cloth/spring and %zu particle colliders",
                                sc, pc);
        if (s) {
            s->seconds =
                (sst && sc ? sst->seconds_collide : 0.0) + (pst && pc ? pst->seconds_collide : 0.0);
            s->out = (sst && sc ? sst->collisions : 0) + (pst && pc ? pst->collisions : 0);
            snprintf(s->unit_out, sizeof s->unit_out, "contacts");
        }
    } else {
        cj_stage_report_set(r, "collisions", 0, "no colliders");
    }
    if (anim && cj_anim_animates_control_points(anim)) {
        const char *why = "control points are animated";
        for (size_t i = 0; i < nch; ++i)
            if (strstr(cj_anim_channel_path(anim, i), ".points[")) {
                why = cj_anim_channel_path(anim, i);
                break;
            }
        cj_stage_report_set(r, "retessellate", pose ? pose->control_points : 1, "channel on %s",
                            why);
    } else {
        cj_stage_report_set(r, "retessellate", 0, "no animated control points");
    }
}
