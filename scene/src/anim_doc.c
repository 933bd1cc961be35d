/* Animation documents at run time: the cloth shown as a mesh node, frames advanced in fixed
 * simulation steps, checkpoints of the exact state. */
#include "casteljau/anim_json.h"

#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Area-weighted vertex normals of the cloth grid into n (3 per vertex). */
static void grid_normals(const double *x, int nu, int nv, double *n) {
    memset(n, 0, sizeof(double) * 3 * (size_t)nu * (size_t)nv);
    for (int j = 0; j + 1 < nv; ++j)
        for (int i = 0; i + 1 < nu; ++i) {
            const int q[4] = {j * nu + i, j * nu + i + 1, (j + 1) * nu + i + 1, (j + 1) * nu + i};
            const int tri[2][3] = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
            for (int t = 0; t < 2; ++t) {
                const double *a = x + 3 * tri[t][0], *b = x + 3 * tri[t][1], *c = x + 3 * tri[t][2];
                const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                const double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                      u[0] * v[1] - u[1] * v[0]};
                for (int k = 0; k < 3; ++k)
                    for (int m = 0; m < 3; ++m) n[3 * tri[t][k] + m] += cr[m];
            }
        }
    for (int i = 0; i < nu * nv; ++i) {
        double *p = n + 3 * i;
        const double l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (l > 0.0)
            for (int m = 0; m < 3; ++m) p[m] /= l;
        else
            p[1] = 1.0;
    }
}

/* A patch collider from the scene object named `name` (its patches at their world placement). */
static cj_status collider_for(const cj_scene *scene, const char *what, int k, const char *name,
                              cj_patch_collider **out) {
    int node = -1;
    for (size_t i = 0; i < cj_scene_node_count(scene); ++i) {
        const char *nm = cj_scene_node(scene, (int)i)->name;
        if (nm && !strcmp(nm, name)) node = (int)i;
    }
    if (node < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "%s.collide_with[%d]: no object named '%s'", what, k, name);
    const cj_node *n = cj_scene_node(scene, node);
    const cj_geometry *g = n->geometry >= 0 ? cj_scene_geometry(scene, n->geometry) : NULL;
    if (!g || g->kind != CJ_GEOM_PATCHES)
        return cj_fail(CJ_ERR_ARGUMENT, "%s.collide_with[%d]: '%s' is not made of Bezier patches",
                       what, k, name);
    cj_xform3 world;
    cj_status st = cj_scene_node_world(scene, node, &world);
    if (st) return st;
    return cj_patch_collider_create(g->u.patches.patches, g->u.patches.count, &world, 1e-6, 0.3,
                                    NULL, out);
}

static cj_status attach(cj_anim_doc *doc, cj_scene *scene, int *binding) {
    cj_status st = CJ_OK;
    if (doc->cloth && doc->cloth_collide_count && !doc->cloth_colliders[0]) {
        for (int k = 0; k < doc->cloth_collide_count; ++k) {
            st = collider_for(scene, "cloth", k, doc->cloth_collide_with[k],
                              &doc->cloth_colliders[k]);
            if (st) return st;
            /* a cloth drapes over solids closed from above (the teapot's lid): against gravity */
            const double up[3] = {-doc->pdesc.gravity[0], -doc->pdesc.gravity[1],
                                  -doc->pdesc.gravity[2]};
            cj_patch_collider_set_solid(doc->cloth_colliders[k], up);
        }
        /* rebuild the cloth with the same description plus the colliders */
        cj_springs *old = doc->cloth;
        cj_springs_desc extra;
        memset(&extra, 0, sizeof extra);
        extra.dim = 3;
        memcpy(extra.gravity, doc->pdesc.gravity, sizeof extra.gravity);
        extra.drag = doc->pdesc.drag;
        extra.spheres = doc->spheres;
        extra.sphere_count = doc->pdesc.sphere_count;
        extra.planes = doc->planes;
        extra.plane_count = doc->pdesc.plane_count;
        extra.patch_collider_count = (size_t)doc->cloth_collide_count;
        extra.patch_colliders = (const cj_patch_collider *const *)doc->cloth_colliders;
        st = cj_springs_create_cloth(
            doc->cloth_grid[0], doc->cloth_grid[1], doc->cloth_corner, doc->cloth_eu, doc->cloth_ev,
            doc->cloth_mass, doc->cloth_k[0], doc->cloth_k[1], doc->cloth_k[2], doc->cloth_damping,
            doc->cloth_pins, doc->cloth_pin_count, &extra, NULL, &doc->cloth);
        if (st) return st;
        cj_springs_destroy(old);
    }
    if (doc->cloth && doc->cloth_node < 0) {
        const int nu = doc->cloth_nu, nv = doc->cloth_nv;
        const double *x = cj_springs_positions(doc->cloth);
        double *nrm = malloc(sizeof(double) * 3 * (size_t)nu * (size_t)nv);
        cj_mesh *mesh = NULL;
        if (!nrm) return cj_fail(CJ_ERR_NOMEM, "no memory for the cloth mesh");
        grid_normals(x, nu, nv, nrm);
        st = cj_mesh_create(NULL, &mesh);
        for (int j = 0; !st && j < nv; ++j)
            for (int i = 0; !st && i < nu; ++i) {
                const double uv[2] = {(double)i / (nu - 1), (double)j / (nv - 1)};
                const size_t id = (size_t)j * (size_t)nu + (size_t)i;
                st = cj_mesh_add_vertex(mesh, x + 3 * id, nrm + 3 * id, uv, NULL);
            }
        for (int j = 0; !st && j + 1 < nv; ++j)
            for (int i = 0; !st && i + 1 < nu; ++i) {
                const uint32_t a = (uint32_t)(j * nu + i), b = a + 1, c = a + 1 + (uint32_t)nu,
                               d = a + (uint32_t)nu;
                st = cj_mesh_add_triangle(mesh, a, b, c, 0);
                if (!st) st = cj_mesh_add_triangle(mesh, a, c, d, 0);
            }
        free(nrm);
        int mat = -1, geo = -1, node = -1;
        if (!st) {
            cj_material m = cj_material_defaults();
            m.color = doc->cloth_color;
            m.two_sided = 1;
            m.ks = 0.1;
            st = cj_scene_add_material(scene, &m, &mat);
        }
        if (!st) {
            cj_geometry g;
            memset(&g, 0, sizeof g);
            g.kind = CJ_GEOM_MESH;
            g.u.mesh = mesh;
            st = cj_scene_add_geometry(scene, &g, &geo);
        }
        cj_mesh_destroy(mesh);
        if (!st) {
            cj_node n = cj_node_defaults(geo, mat);
            n.name = doc->cloth_name;
            st = cj_scene_add_node(scene, &n, &node);
        }
        if (st) return st;
        doc->cloth_node = node;
        doc->cloth_geometry = geo;
    }
    if (doc->has_particles && !doc->particles) {
        for (int k = 0; k < doc->collide_count; ++k) {
            st =
                collider_for(scene, "particles", k, doc->collide_with[k], &doc->patch_colliders[k]);
            if (st) return st;
        }
        doc->pdesc.patch_collider_count = (size_t)doc->collide_count;
        doc->pdesc.patch_colliders = (const cj_patch_collider *const *)doc->patch_colliders;
        st = cj_particles_create(&doc->pdesc, NULL, &doc->particles);
        if (st) return st;
        int mat = -1, geo = -1;
        cj_material m = cj_material_defaults();
        m.color = doc->particle_color;
        m.shading = CJ_SHADE_GOURAUD;
        st = cj_scene_add_material(scene, &m, &mat);
        if (!st) {
            cj_geometry g;
            memset(&g, 0, sizeof g);
            g.kind = CJ_GEOM_SPHERE;
            g.u.sphere.radius = doc->particle_radius > 0 ? doc->particle_radius : 0.04;
            st = cj_scene_add_geometry(scene, &g, &geo);
        }
        for (size_t i = 0; !st && i < doc->pdesc.capacity; ++i) {
            cj_node n = cj_node_defaults(geo, mat);
            n.visible = 0;
            int idx;
            st = cj_scene_add_node(scene, &n, &idx);
            if (!st && i == 0) doc->particle_node0 = idx;
        }
        if (st) return st;
    }
    *binding = 1;
    return cj_anim_bind(doc->anim, scene);
}

cj_status cj_anim_doc_attach(cj_anim_doc *doc, cj_scene *scene) {
    assert(doc && scene);
    int binding = 0;
    cj_status st = attach(doc, scene, &binding);
    if (!st) return CJ_OK;
    /* What names nothing in the scene is found only now: name the document, and for a channel
     * its line, as the reader does for everything else. */
    char msg[512];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    size_t i = binding ? cj_anim_bind_failed(doc->anim) : (size_t)-1;
    if (i < doc->channel_line_count && doc->channel_lines[i] > 0)
        return cj_fail(st, "%s:%d: %s", doc->source, doc->channel_lines[i], msg);
    return cj_fail(st, "%s: %s", doc->source, msg);
}

static int finite_state(const cj_springs *cloth) {
    const size_t n = 3 * cj_springs_count(cloth);
    const double *x = cj_springs_positions(cloth), *v = cj_springs_velocities(cloth);
    for (size_t i = 0; i < n; ++i)
        if (!(fabs(x[i]) <= CJ_SCENE_MAX_COORD) || !isfinite(v[i])) return 0;
    return 1;
}

cj_status cj_anim_doc_frame(cj_anim_doc *doc, cj_scene *scene, long frame,
                            cj_stage_report *report) {
    assert(doc && scene);
    if (frame < 0) return cj_fail(CJ_ERR_RANGE, "frame %ld is negative", frame);
    cj_springs_stats sum;
    memset(&sum, 0, sizeof sum);
    cj_particles_stats psum;
    memset(&psum, 0, sizeof psum);
    const int simulated = doc->cloth || doc->particles;
    if (simulated && frame < doc->sim_frame)
        return cj_fail(CJ_ERR_RANGE,
                       "frame %ld is before the simulation state (frame %ld): start from a "
                       "checkpoint at or before it",
                       frame, doc->sim_frame);
    while (simulated && doc->sim_frame < frame) {
        if (doc->cloth) {
            const double h = 1.0 / (doc->fps * doc->steps_per_frame);
            for (int s = 0; s < doc->steps_per_frame; ++s) {
                cj_springs_stats st1;
                cj_status st = cj_springs_step(doc->cloth, doc->cloth_integrator, h, &st1);
                if (st != CJ_OK && st != CJ_ERR_CAP) return st;
                if (!finite_state(doc->cloth))
                    return cj_fail(
                        CJ_ERR_NONFINITE,
                        "%s: the cloth blew up (positions beyond +-1e9 or not finite) in frame "
                        "%ld: its step 1/(fps * cloth.steps_per_frame) = %g s is too "
                        "long for cloth.stiffness; raise cloth.steps_per_frame or use "
                        "\"integrator\": \"implicit_euler\"",
                        doc->source, doc->sim_frame + 1, h);
                sum.seconds_forces += st1.seconds_forces;
                sum.seconds_solve += st1.seconds_solve;
                sum.seconds_collide += st1.seconds_collide;
                sum.collisions = st1.collisions;
                sum.cg_iterations =
                    st1.cg_iterations > sum.cg_iterations ? st1.cg_iterations : sum.cg_iterations;
            }
        }
        if (doc->particles) {
            const double h = 1.0 / (doc->fps * doc->particle_steps);
            for (int s = 0; s < doc->particle_steps; ++s) {
                cj_particles_stats p1;
                cj_status st = cj_particles_step(doc->particles, h, &p1);
                if (st != CJ_OK) {
                    char msg[400];
                    snprintf(msg, sizeof msg, "%s", cj_last_error());
                    return cj_fail(st, "%s: particles, frame %ld: %s", doc->source,
                                   doc->sim_frame + 1, msg);
                }
                psum.emitted += p1.emitted;
                psum.dropped += p1.dropped;
                psum.died += p1.died;
                psum.collisions += p1.collisions;
                psum.neighbour_pairs += p1.neighbour_pairs;
                psum.seconds_emit += p1.seconds_emit;
                psum.seconds_forces += p1.seconds_forces;
                psum.seconds_collide += p1.seconds_collide;
            }
        }
        ++doc->sim_frame;
    }
    cj_anim_pose_info info;
    cj_status st = cj_anim_pose(scene, doc->anim, (double)frame / doc->fps, &info);
    if (st != CJ_OK) return st;
    if (doc->cloth && doc->cloth_geometry >= 0) {
        cj_geometry *g = cj_scene_geometry_mut(scene, doc->cloth_geometry);
        if (!g || g->kind != CJ_GEOM_MESH)
            return cj_fail(CJ_ERR_ARGUMENT, "the cloth's mesh geometry is gone from the scene");
        cj_mesh *m = g->u.mesh;
        const size_t nv = (size_t)doc->cloth_nu * (size_t)doc->cloth_nv;
        memcpy(m->positions, cj_springs_positions(doc->cloth), sizeof(double) * 3 * nv);
        grid_normals(m->positions, doc->cloth_nu, doc->cloth_nv, m->normals);
    }
    if (doc->particles && doc->particle_node0 >= 0) {
        const size_t n = cj_particles_count(doc->particles);
        const double *x = cj_particles_positions(doc->particles);
        for (size_t i = 0; i < doc->pdesc.capacity; ++i) {
            cj_node *nd = cj_scene_node_mut(scene, doc->particle_node0 + (int)i);
            if (!nd)
                return cj_fail(CJ_ERR_ARGUMENT, "the particles' nodes are gone from the scene");
            nd->visible = i < n;
            if (i < n) nd->local.translate = cj_v3(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        }
    }
    if (report)
        cj_anim_report_stages(report, doc->anim, &info, doc->cloth, doc->cloth ? &sum : NULL,
                              doc->particles, doc->particles ? &psum : NULL);
    return CJ_OK;
}

static const char STATE_MAGIC[8] = {'C', 'J', 'A', 'N', 'I', 'M', '0', '1'};

static int put_u64(FILE *f, uint64_t v) {
    unsigned char b[8];
    for (int k = 0; k < 8; ++k) b[k] = (unsigned char)(v >> (8 * k));
    return fwrite(b, 1, 8, f) == 8;
}
static int get_u64(FILE *f, uint64_t *v) {
    unsigned char b[8];
    if (fread(b, 1, 8, f) != 8) return 0;
    *v = 0;
    for (int k = 0; k < 8; ++k) *v |= (uint64_t)b[k] << (8 * k);
    return 1;
}

cj_status cj_anim_doc_save_state(const cj_anim_doc *doc, FILE *f) {
    const size_t n = doc->cloth ? cj_springs_count(doc->cloth) * 3 : 0;
    int ok =
        fwrite(STATE_MAGIC, 1, 8, f) == 8 && put_u64(f, (uint64_t)doc->sim_frame) && put_u64(f, n);
    for (int pass = 0; pass < 2 && n; ++pass) {
        const double *a =
            pass ? cj_springs_velocities(doc->cloth) : cj_springs_positions(doc->cloth);
        for (size_t i = 0; i < n && ok; ++i) {
            uint64_t u;
            memcpy(&u, &a[i], sizeof u);
            ok = put_u64(f, u);
        }
    }
    ok = ok && put_u64(f, doc->particles ? 1u : 0u);
    if (!ok || fflush(f) != 0) return cj_fail(CJ_ERR_IO, "writing the animation checkpoint failed");
    return doc->particles ? cj_particles_save(doc->particles, f) : CJ_OK;
}

cj_status cj_anim_doc_load_state(cj_anim_doc *doc, FILE *f) {
    char magic[8];
    uint64_t frame, n;
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, STATE_MAGIC, 8) || !get_u64(f, &frame) ||
        !get_u64(f, &n))
        return cj_fail(CJ_ERR_PARSE, "not an animation checkpoint (magic CJANIM01)");
    const size_t want = doc->cloth ? cj_springs_count(doc->cloth) * 3 : 0;
    if (frame > 10000000)
        return cj_fail(CJ_ERR_PARSE,
                       "checkpoint of frame %llu, beyond the last frame an animation can have "
                       "(10000000): a damaged or foreign file",
                       (unsigned long long)frame);
    if (n != want)
        return cj_fail(CJ_ERR_PARSE,
                       "checkpoint of another animation (%llu cloth coordinates, "
                       "this one has %zu)",
                       (unsigned long long)n, want);
    double *buf = malloc(sizeof(double) * (2 * want + 1));
    if (!buf) return cj_fail(CJ_ERR_NOMEM, "no memory for the checkpoint");
    for (size_t i = 0; i < 2 * want; ++i) {
        uint64_t u;
        if (!get_u64(f, &u)) {
            free(buf);
            return cj_fail(CJ_ERR_PARSE, "animation checkpoint truncated");
        }
        memcpy(&buf[i], &u, sizeof u);
    }
    for (size_t i = 0; i < 2 * want; ++i)
        if (!isfinite(buf[i])) {
            const char *what = isnan(buf[i]) ? "NaN" : "infinite";
            free(buf);
            return cj_fail(CJ_ERR_PARSE, "cloth vertex %zu: %s coordinate %zu is %s",
                           (i % want) / 3, i < want ? "position" : "velocity", i % 3, what);
        }
    uint64_t has_p = 0;
    if (!get_u64(f, &has_p) || has_p != (doc->particles ? 1u : 0u)) {
        free(buf);
        return cj_fail(CJ_ERR_PARSE, "checkpoint of another animation (particles %s)",
                       doc->particles ? "missing" : "unexpected");
    }
    /* particles first: their loader changes nothing when it fails */
    cj_status st = doc->particles ? cj_particles_load(doc->particles, f) : CJ_OK;
    if (st == CJ_OK && want) st = cj_springs_set_state(doc->cloth, buf, buf + want);
    free(buf);
    if (st == CJ_OK) doc->sim_frame = (long)frame;
    return st;
}
