/* Private, shared by every layer and the tool: the one whole-file reader, the one atomic writer
 * (with the registry that removes its temporary files on SIGINT/SIGTERM) and the one "is this
 * output one of my inputs" check. */
#ifndef CASTELJAU_FILE_INTERNAL_H
#define CASTELJAU_FILE_INTERNAL_H

#include "casteljau/status.h"

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The size cap of every document the library reads whole (scene and animation JSON, .bpt, OBJ,
 * PLY, checkpoints, fonts): 256 MiB. Image files have their own caps (image_io.h). */
#define CJ_FILE_MAX_BYTES ((size_t)256 << 20)

/* Checks that `path` names a regular file of at most max_bytes bytes, without reading it (for
 * readers that open the file themselves, such as the image library). `what` names the kind of
 * file in messages ("texture"). Errors: CJ_ERR_IO (cannot open or stat: the message carries
 * strerror), CJ_ERR_ARGUMENT (a directory, device, pipe or socket: "/dev/zero is not a regular
 * file"), CJ_ERR_RANGE (larger than the cap; the message gives both sizes). */
cj_status cj_file_check_input(const char *path, size_t max_bytes, const char *what);

/* Reads the whole regular file `path` (at most max_bytes bytes) into a malloc'd buffer with a
 * NUL byte after the last one; *size excludes that NUL. The file is opened without blocking
 * (a FIFO does not hang) and checked with fstat before any byte is read, and reading stops at
 * max_bytes + 1 even if the file grows meanwhile. The caller frees *data. Errors: those of
 * cj_file_check_input, and CJ_ERR_NOMEM. */
cj_status cj_file_read_all(const char *path, size_t max_bytes, const char *what, char **data,
                           size_t *size);

/* Reads standard input to its end the same way (at most max_bytes bytes, a NUL after them; the
 * stream is named '-' in messages). Errors: CJ_ERR_IO, CJ_ERR_RANGE (over the cap),
 * CJ_ERR_NOMEM. */
cj_status cj_file_read_stdin(size_t max_bytes, const char *what, char **data, size_t *size);

/* A command's input: standard input when path is "-", else cj_file_read_all(path). */
cj_status cj_file_read_input(const char *path, size_t max_bytes, const char *what, char **data,
                             size_t *size);

/* The log of inputs: every file cj_file_read_all read and cj_file_check_input admitted in this
 * process (device and inode, and the name it was given; the first 256). Returns the name under
 * which `path`'s file was read, or NULL if it was not: an output that must not overwrite an
 * input asks this before any work. */
const char *cj_file_input_named(const char *path);
size_t cj_file_input_count(void);
const char *cj_file_input_path(size_t i); /* NULL past the end */

/* 1 when a and b name the same existing file (same device and inode, so hard links, symbolic
 * links and "./x" versus "x" are caught), else 0. */
int cj_file_same(const char *a, const char *b);

/* ---- the atomic writer ----
 * Bytes go to a temporary file ".<name>.tmp-<pid>-<n>" in the destination's folder; commit
 * checks every write (the stream's error flag), fflush, fsync and close, and only then renames
 * the temporary onto the destination (and syncs the folder). On any failure the destination
 * keeps its old content and the temporary is removed. While it exists the temporary is in the
 * registry below, so that a SIGINT or SIGTERM removes it too. */
typedef struct cj_atomic_file {
    FILE *fp;  /* write here */
    char *tmp; /* the temporary's name (malloc'd) */
    char *path;
    int slot; /* registry slot, or -1 */
} cj_atomic_file;

/* Creates the temporary beside path. Errors: CJ_ERR_IO naming the folder, CJ_ERR_NOMEM. */
cj_status cj_atomic_open(cj_atomic_file *f, const char *path);

/* Checks, syncs, closes and renames (see above). Error: CJ_ERR_IO naming the path and the
 * system's reason ("No space left on device"). f is closed either way. */
cj_status cj_atomic_commit(cj_atomic_file *f);

/* Closes and removes the temporary (after an error of the caller's own). Safe on a closed f. */
void cj_atomic_abandon(cj_atomic_file *f);

/* Creates an empty temporary beside path (opened O_EXCL, mode 0666 minus the umask) and
 * registers it; returns its descriptor, its malloc'd name in *tmp and its registry slot in
 * *slot; -1 with errno set on failure. For writers that fill the file through a descriptor or
 * a library; they call cj_temp_release after the rename or unlink. */
int cj_temp_create_beside(const char *path, char **tmp, int *slot);

/* Forgets a registered temporary (after it was renamed or removed). slot < 0 is a no-op. */
void cj_temp_release(int slot);

/* Installs handlers for SIGINT and SIGTERM (where their disposition is the default) that
 * remove every registered temporary and then die of the same signal. For programs (the
 * casteljau tool), not called by the library itself. */
void cj_temp_install_signal_cleanup(void);

/* Checks that the folder of `path` exists and accepts new files (by creating and removing a
 * temporary there) and that path is not a folder. `what` names the output ("GIF").
 * Errors: CJ_ERR_ARGUMENT (path names a folder), CJ_ERR_IO (folder missing or not writable). */
cj_status cj_file_check_output(const char *path, const char *what);

#ifdef __cplusplus
}
#endif
#endif
