/* Atomic, checked output files for the tool: a temporary file beside the destination, every
 * write checked, fsync before close, rename only when all of it reached the disk. */
#define _POSIX_C_SOURCE 200809L
#include "cli_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_file_open(cli_file *f, const char *path, char *why, size_t why_size) {
    memset(f, 0, sizeof *f);
    const char *slash = strrchr(path, '/');
    const size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    const size_t need = strlen(path) + 32;
    f->tmp = malloc(need);
    if (!f->tmp) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    snprintf(f->tmp, need, "%.*s.%s.tmp-XXXXXX", (int)dir_len, path, path + dir_len);
    int fd = mkstemp(f->tmp);
    if (fd < 0) {
        snprintf(why, why_size, "cannot create a file beside '%s': %s", path, strerror(errno));
        free(f->tmp);
        f->tmp = NULL;
        return -1;
    }
    /* mkstemp makes the file 0600; give it the mode fopen would (0666 minus the umask). */
    const mode_t mask = umask(0);
    umask(mask);
    (void)fchmod(fd, 0666 & ~mask);
    f->fp = fdopen(fd, "wb");
    if (!f->fp) {
        snprintf(why, why_size, "cannot write beside '%s': %s", path, strerror(errno));
        close(fd);
        unlink(f->tmp);
        free(f->tmp);
        f->tmp = NULL;
        return -1;
    }
    f->path = path;
    return 0;
}

int cli_file_commit(cli_file *f, char *why, size_t why_size) {
    int ok = !ferror(f->fp);
    int err = ok ? 0 : EIO;
    if (ok && fflush(f->fp) != 0) ok = 0, err = errno;
    if (ok && fsync(fileno(f->fp)) != 0) ok = 0, err = errno;
    if (fclose(f->fp) != 0 && ok) ok = 0, err = errno;
    f->fp = NULL;
    if (ok && rename(f->tmp, f->path) != 0) ok = 0, err = errno;
    if (!ok) {
        snprintf(why, why_size, "cannot write '%s': %s", f->path, strerror(err));
        unlink(f->tmp);
    }
    free(f->tmp);
    f->tmp = NULL;
    return ok ? 0 : -1;
}

void cli_file_abandon(cli_file *f) {
    if (f->fp) fclose(f->fp);
    if (f->tmp) {
        unlink(f->tmp);
        free(f->tmp);
    }
    f->fp = NULL;
    f->tmp = NULL;
}
