/* casteljau: status codes shared by every module.
 *
 * Every fallible function returns a cj_status (CJ_OK == 0) and writes its results through
 * out-parameters. On failure, out-parameters are left untouched unless a function's docs say
 * otherwise, and cj_last_error() holds a one-line message naming the offending input
 * ("control point 3, coordinate 1 is NaN"). Programmer misuse (a NULL where none is allowed)
 * is an assertion, not a status.
 */
#ifndef CASTELJAU_STATUS_H
#define CASTELJAU_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_status {
    CJ_OK = 0,
    CJ_ERR_NONFINITE,   /* a NaN or infinite coordinate, parameter or tolerance */
    CJ_ERR_EMPTY,       /* no control points, no samples, empty input */
    CJ_ERR_DIMENSION,   /* dimension out of range, or points of different dimensions */
    CJ_ERR_DEGREE,      /* degree above the limit of the chosen method */
    CJ_ERR_RANGE,       /* a parameter outside the range the operation accepts */
    CJ_ERR_ARGUMENT,    /* an argument with a value the operation cannot accept */
    CJ_ERR_DEGENERATE,  /* degenerate geometry (zero-length axis, coincident points, ...) */
    CJ_ERR_SINGULAR,    /* singular or inconsistent system of constraints */
    CJ_ERR_CAP,         /* an internal cap (iterations, segments) was hit; result is partial */
    CJ_ERR_BUFFER,      /* a caller-provided buffer is too small */
    CJ_ERR_NOMEM,       /* an allocation failed */
    CJ_ERR_IO,          /* reading or writing a file failed */
    CJ_ERR_PARSE,       /* malformed text input */
    CJ_ERR_UNSUPPORTED, /* the build or the input asks for something not available */
    CJ_ERR_CANCELLED,   /* the caller's progress callback asked to stop; no result */
    CJ_STATUS_COUNT_
} cj_status;

/* A short, static English description of a status code ("NaN or infinite value"). */
const char *cj_status_str(cj_status status);

/* The message of the most recent failure on this thread, naming what was wrong; "" if none.
 * Valid until the next failing call on the same thread. */
const char *cj_last_error(void);

#ifdef __cplusplus
}
#endif
#endif
