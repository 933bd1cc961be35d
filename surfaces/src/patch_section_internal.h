/* Private: fitting the polylines of plane sections by cubic Bézier pieces (patch_section_fit.c),
 * used by the model section (patch_section_join.c). */
#ifndef CASTELJAU_PATCH_SECTION_INTERNAL_H
#define CASTELJAU_PATCH_SECTION_INTERNAL_H

/* Growing list of cubic pieces, 12 doubles each. */
typedef struct cj_sect_pieces {
    double *ctrl;
    int count, cap;
    double worst; /* largest fit error max(e_v, e_s + 3L/2S) of the pieces appended */
    int nomem;
} cj_sect_pieces;

/* Fits the run P[0..np-1] (np >= 2 points x y z, consecutive points distinct or not) with unit
 * forward tangents T[0..np-1] by cubic pieces appended to out, each within `target` of the
 * vertices of its range and of its polyline (see patch_section.h), halving the vertex range
 * where it is not; a range of one segment becomes the straight piece along it. The first piece
 * starts at P[0] and the last ends at P[np-1], bit for bit, and consecutive pieces share their
 * end points. `margin` (rounding of the distance evaluations) is added to every error. */
void cj_sect_fit_run(const double *P, const double *T, int np, double target, double margin,
                     cj_sect_pieces *out);

#endif
