/* Private to the intersection search (intersect*.c): its tables, and the parts shared by the
 * pair search (intersect_search.c), self-intersections (intersect_self.c), joints, overlaps and
 * output (intersect_output.c), and the entry points (intersect.c). */
#ifndef CASTELJAU_INTERSECT_INTERNAL_H
#define CASTELJAU_INTERSECT_INTERNAL_H

#include "query_internal.h"

#define MAX_ROOTS    512
#define MAX_LEAVES   4096
#define MAX_OVERLAPS 4
#define MIN_WIDTH    0x1p-52
/* Krawczyk is tried once both pieces are this small against their curves */
#define KRAWCZYK_SIZE 0.03125
/* clipping stops for a Krawczyk try once both pieces are this narrow (measured 2^-8..2^-32:
 * from 2^-24 boxes K lands at the rounding limit without refinement) */
#define EARLY_WIDTH 0x1p-24

typedef struct root {
    cj_ivl K[2]; /* enclosure */
    cj_ivl U[2]; /* uniqueness box */
    int at_end;
} root;

typedef struct leaf {
    cj_ivl B[2];
    double size;
    int exact;   /* a joint: bitwise equal end points */
    int dropped; /* set by cj_isect_finish: inside a crossing's uniqueness box or an overlap */
} leaf;

typedef struct run {
    const cj_qctx *qa, *qb;
    double tol;
    double ext_a, ext_b; /* extents of the whole curves */
    long max_boxes;
    const cj_bezier2 *ca; /* the first curve, for exact end points */
    int self;             /* qa == qb, s < t */
    int line;             /* qb is a line: no domain clipping on t */
    long boxes;
    int capped;
    int table_full; /* capped because roots or leaves ran out of room */
    int in_flat;    /* searching inside a flat pair (intersect_search.c): no flat contacts */
    root *roots;    /* the tables: max_roots and max_leaves entries (small ones on the stack
                       first, MAX_ROOTS and MAX_LEAVES on the heap when they fill) */
    int nroots, max_roots;
    leaf *leaves;
    int nleaves, max_leaves;
    cj_ivl overlap[MAX_OVERLAPS][2];
    double overlap_dev[MAX_OVERLAPS];
    int noverlaps;
} run;

/* The full-size tables, allocated when the small ones fill. */
typedef struct run_tables {
    root roots[MAX_ROOTS];
    leaf leaves[MAX_LEAVES];
} run_tables;

static inline int inside(const cj_ivl a[2], const cj_ivl b[2]) {
    return a[0].lo >= b[0].lo && a[0].hi <= b[0].hi && a[1].lo >= b[1].lo && a[1].hi <= b[1].hi;
}

static inline int meets(const cj_ivl a[2], const cj_ivl b[2]) {
    return a[0].lo <= b[0].hi && b[0].lo <= a[0].hi && a[1].lo <= b[1].hi && b[1].lo <= a[1].hi;
}

/* Empties the tables (keeping their storage). */
void cj_isect_run_reset(run *R);
/* -1: no zero of a(s) - b(t) in X; 1: exactly one, inside K; 0: undecided. */
int cj_isect_krawczyk(const cj_qctx *qa, const cj_qctx *qb, const cj_ivl X[2], cj_ivl K[2]);
int cj_isect_record(run *R, cj_ivl K[2], const cj_ivl U[2]);
void cj_isect_add_leaf(run *R, cj_ivl S, cj_ivl T, double size, int exact);
double cj_isect_extent(const cj_qpiece *p);
void cj_isect_pair(run *R, const cj_qpiece *pa, const cj_qpiece *pb);
void cj_isect_self_piece(run *R, const cj_qpiece *p);
void cj_isect_joints(run *R, const cj_bezier2 *a, const cj_bezier2 *b);
void cj_isect_overlaps(run *R, const cj_bezier2 *a, const cj_bezier2 *b);
cj_status cj_isect_finish(run *R, double line_scale, cj_isect *out, int cap, int *count);
cj_status cj_isect_check_tol(double tol, double scale);

#endif
