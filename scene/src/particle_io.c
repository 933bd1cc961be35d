/* Particle checkpoints: the whole state as little-endian 64-bit words (doubles as their IEEE
 * bit patterns), so a resumed run is bit-identical to the uninterrupted one. */
#include "casteljau/particles.h"

#include "error_internal.h"
#include "particle_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char MAGIC[8] = {'C', 'J', 'P', 'A', 'R', 'T', 'S', '1'};

static int put_u64(FILE *f, uint64_t v) {
    unsigned char b[8];
    for (int k = 0; k < 8; ++k) b[k] = (unsigned char)(v >> (8 * k));
    return fwrite(b, 1, 8, f) == 8;
}

static int put_f64(FILE *f, double d) {
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    return put_u64(f, v);
}

static int get_u64(FILE *f, uint64_t *v) {
    unsigned char b[8];
    if (fread(b, 1, 8, f) != 8) return 0;
    uint64_t r = 0;
    for (int k = 0; k < 8; ++k) r |= (uint64_t)b[k] << (8 * k);
    *v = r;
    return 1;
}

static int get_f64(FILE *f, double *d) {
    uint64_t v;
    if (!get_u64(f, &v)) return 0;
    memcpy(d, &v, sizeof v);
    return 1;
}

cj_status cj_particles_save(const cj_particles *p, FILE *f) {
    assert(p && f);
    int ok = fwrite(MAGIC, 1, 8, f) == 8;
    ok = ok && put_u64(f, p->d.capacity) && put_u64(f, p->d.emitter_count) &&
         put_u64(f, p->count) && put_u64(f, p->steps) && put_f64(f, p->t);
    for (int k = 0; k < 4 && ok; ++k) ok = put_u64(f, p->rng[k]);
    for (size_t j = 0; j < p->d.emitter_count && ok; ++j) ok = put_f64(f, p->emit_acc[j]);
    for (size_t i = 0; i < p->count && ok; ++i) {
        for (int k = 0; k < 3 && ok; ++k) ok = put_f64(f, p->x[3 * i + (size_t)k]);
        for (int k = 0; k < 3 && ok; ++k) ok = put_f64(f, p->v[3 * i + (size_t)k]);
        ok = ok && put_f64(f, p->age[i]) && put_f64(f, p->life[i]);
    }
    if (!ok || fflush(f) != 0) return cj_fail(CJ_ERR_IO, "writing the particle checkpoint failed");
    return CJ_OK;
}

cj_status cj_particles_load(cj_particles *p, FILE *f) {
    assert(p && f);
    char magic[8];
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, MAGIC, 8) != 0)
        return cj_fail(CJ_ERR_PARSE, "not a particle checkpoint (magic CJPARTS1 missing)");
    uint64_t cap, ne, count, steps, rng[4];
    double t;
    if (!get_u64(f, &cap) || !get_u64(f, &ne) || !get_u64(f, &count) || !get_u64(f, &steps) ||
        !get_f64(f, &t))
        return cj_fail(CJ_ERR_PARSE, "particle checkpoint truncated in its header");
    if (cap != p->d.capacity || ne != p->d.emitter_count)
        return cj_fail(CJ_ERR_PARSE,
                       "particle checkpoint of another system (capacity %llu, %llu emitters; "
                       "this one %zu, %zu)",
                       (unsigned long long)cap, (unsigned long long)ne, p->d.capacity,
                       p->d.emitter_count);
    if (count > cap)
        return cj_fail(CJ_ERR_PARSE, "particle checkpoint holds %llu particles, capacity %llu",
                       (unsigned long long)count, (unsigned long long)cap);
    for (int k = 0; k < 4; ++k)
        if (!get_u64(f, &rng[k])) return cj_fail(CJ_ERR_PARSE, "particle checkpoint truncated");
    /* xoshiro256's one fixed point: from it every draw is 0 and the emitter's rejection
     * sampling would never end (found by fuzz_checkpoint) */
    if (!(rng[0] | rng[1] | rng[2] | rng[3]))
        return cj_fail(CJ_ERR_PARSE, "particle checkpoint: the random generator's state is all "
                                     "zero, a state it never reaches");
    /* read everything into scratch first so a truncated file changes nothing */
    const size_t nd = (size_t)ne + 8 * (size_t)count;
    double *buf = malloc(sizeof(double) * (nd ? nd : 1));
    if (!buf) return cj_fail(CJ_ERR_NOMEM, "particle checkpoint: no memory");
    for (size_t i = 0; i < nd; ++i)
        if (!get_f64(f, &buf[i])) {
            free(buf);
            return cj_fail(CJ_ERR_PARSE, "particle checkpoint truncated at value %zu of %zu", i,
                           nd);
        }
    const char *bad = NULL;
    size_t which = 0;
    if (!(t >= 0.0 && t < HUGE_VAL)) bad = "time";
    for (size_t j = 0; !bad && j < ne; ++j)
        if (!(buf[j] >= 0.0 && buf[j] < 1.0)) bad = "emitter fraction (emit_acc)", which = j;
    for (size_t i = 0; !bad && i < count; ++i) {
        const double *r = buf + ne + 8 * i;
        which = i;
        if (!(isfinite(r[0]) && isfinite(r[1]) && isfinite(r[2])))
            bad = "position";
        else if (!(isfinite(r[3]) && isfinite(r[4]) && isfinite(r[5])))
            bad = "velocity";
        else if (!(r[6] >= 0.0 && r[6] < HUGE_VAL))
            bad = "age";
        else if (!(r[7] > 0.0 && r[7] < HUGE_VAL))
            bad = "life";
    }
    if (bad) {
        free(buf);
        if (!strcmp(bad, "time"))
            return cj_fail(CJ_ERR_PARSE, "particle checkpoint: time %g is not finite and >= 0", t);
        return cj_fail(CJ_ERR_PARSE,
                       "particle checkpoint: %s %zu: %s is NaN, infinite or out of its "
                       "range",
                       strchr(bad, '(') ? "emitter" : "particle", which, bad);
    }
    memcpy(p->emit_acc, buf, sizeof(double) * (size_t)ne);
    const double *q = buf + ne;
    for (size_t i = 0; i < count; ++i, q += 8) {
        memcpy(p->x + 3 * i, q, sizeof(double) * 3);
        memcpy(p->v + 3 * i, q + 3, sizeof(double) * 3);
        p->age[i] = q[6];
        p->life[i] = q[7];
    }
    free(buf);
    p->count = (size_t)count;
    p->steps = steps;
    p->t = t;
    memcpy(p->rng, rng, sizeof rng);
    return CJ_OK;
}
