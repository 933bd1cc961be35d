/* The one whole-file reader, the one atomic writer and the registry of temporary files that a
 * SIGINT or SIGTERM removes (file_internal.h). */
#define _POSIX_C_SOURCE 200809L
#include "file_internal.h"

#include "error_internal.h"

#include <assert.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

/* ---- the log of inputs ------------------------------------------------------------------
 * Every file the reader opens (and every file cj_file_check_input admits) is noted with its
 * device and inode, so that a program can refuse an output that would overwrite any of them,
 * however it was named (the scene, a texture it names, a .bpt or OBJ, a checkpoint). */
enum { INPUT_LOG_MAX = 256, INPUT_NAME_MAX = 1024 };
typedef struct input_entry {
    dev_t dev;
    ino_t ino;
    char path[INPUT_NAME_MAX];
} input_entry;
static input_entry input_log[INPUT_LOG_MAX];
static size_t input_count;
static atomic_flag input_lock = ATOMIC_FLAG_INIT;

static void lock_inputs(void) {
    while (atomic_flag_test_and_set(&input_lock)) {
    }
}

static void note_input(const char *path, const struct stat *sb) {
    lock_inputs();
    int known = 0;
    for (size_t i = 0; i < input_count; ++i)
        known |= input_log[i].dev == sb->st_dev && input_log[i].ino == sb->st_ino;
    if (!known && input_count < INPUT_LOG_MAX) {
        input_entry *e = &input_log[input_count++];
        e->dev = sb->st_dev;
        e->ino = sb->st_ino;
        snprintf(e->path, sizeof e->path, "%s", path);
    }
    atomic_flag_clear(&input_lock);
}

const char *cj_file_input_named(const char *path) {
    assert(path);
    struct stat sb;
    if (stat(path, &sb) != 0) return NULL;
    const char *hit = NULL;
    lock_inputs();
    for (size_t i = 0; i < input_count && !hit; ++i)
        if (input_log[i].dev == sb.st_dev && input_log[i].ino == sb.st_ino) hit = input_log[i].path;
    atomic_flag_clear(&input_lock);
    return hit;
}

size_t cj_file_input_count(void) {
    lock_inputs();
    const size_t n = input_count;
    atomic_flag_clear(&input_lock);
    return n;
}

const char *cj_file_input_path(size_t i) {
    return i < cj_file_input_count() ? input_log[i].path : NULL;
}

/* ---- reading -------------------------------------------------------------------------- */

static const char *kind_of(mode_t m) {
    if (S_ISDIR(m)) return "a directory";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISFIFO(m)) return "a pipe";
    if (S_ISSOCK(m)) return "a socket";
    return "not a regular file";
}

static cj_status check_stat(const struct stat *sb, const char *path, size_t max_bytes,
                            const char *what) {
    if (!S_ISREG(sb->st_mode))
        return cj_fail(CJ_ERR_ARGUMENT, "%s '%s' is %s, not a regular file", what, path,
                       kind_of(sb->st_mode));
    if ((unsigned long long)sb->st_size > (unsigned long long)max_bytes)
        return cj_fail(CJ_ERR_RANGE, "%s '%s' is %lld bytes, over the limit of %zu MiB", what, path,
                       (long long)sb->st_size, max_bytes >> 20);
    return CJ_OK;
}

cj_status cj_file_check_input(const char *path, size_t max_bytes, const char *what) {
    assert(path && what);
    struct stat sb;
    if (stat(path, &sb) != 0)
        return cj_fail(CJ_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    cj_status st = check_stat(&sb, path, max_bytes, what);
    if (!st) note_input(path, &sb);
    return st;
}

/* Reads fd to its end into a malloc'd buffer (cap: the expected size + 1), at most max_bytes
 * bytes; `name` and `what` for messages. Closes nothing. */
static cj_status read_fd(int fd, size_t cap, size_t max_bytes, const char *what, const char *name,
                         char **data, size_t *size) {
    size_t len = 0;
    char *buf = malloc(cap + 1);
    if (!buf)
        return cj_fail(CJ_ERR_NOMEM, "out of memory reading %s '%s' (%zu bytes)", what, name,
                       cap - 1);
    for (;;) {
        if (len == cap) { /* the file grew since fstat, or a stream goes on */
            if (cap > max_bytes) break;
            size_t nc = cap * 2 > max_bytes + 1 ? max_bytes + 1 : cap * 2;
            char *b = realloc(buf, nc + 1);
            if (!b) {
                free(buf);
                return cj_fail(CJ_ERR_NOMEM, "out of memory reading %s '%s'", what, name);
            }
            buf = b;
            cap = nc;
        }
        ssize_t k = read(fd, buf + len, cap - len);
        if (k < 0 && errno == EINTR) continue;
        if (k < 0) {
            const int e = errno;
            free(buf);
            return cj_fail(CJ_ERR_IO, "cannot read %s '%s': %s", what, name, strerror(e));
        }
        if (k == 0) break;
        len += (size_t)k;
    }
    if (len > max_bytes) {
        free(buf);
        return cj_fail(CJ_ERR_RANGE, "%s '%s' is over the limit of %zu MiB", what, name,
                       max_bytes >> 20);
    }
    buf[len] = '\0';
    *data = buf;
    *size = len;
    return CJ_OK;
}

cj_status cj_file_read_all(const char *path, size_t max_bytes, const char *what, char **data,
                           size_t *size) {
    assert(path && what && data && size);
    /* O_NONBLOCK: opening a FIFO with no writer must not wait; fstat then refuses it. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return cj_fail(CJ_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        const int e = errno;
        close(fd);
        return cj_fail(CJ_ERR_IO, "cannot open '%s': %s", path, strerror(e));
    }
    cj_status st = check_stat(&sb, path, max_bytes, what);
    if (!st) {
        note_input(path, &sb);
        st = read_fd(fd, (size_t)sb.st_size + 1, max_bytes, what, path, data, size);
    }
    close(fd);
    return st;
}

cj_status cj_file_read_stdin(size_t max_bytes, const char *what, char **data, size_t *size) {
    assert(what && data && size);
    return read_fd(0, (size_t)1 << 16, max_bytes, what, "-", data, size);
}

cj_status cj_file_read_input(const char *path, size_t max_bytes, const char *what, char **data,
                             size_t *size) {
    return strcmp(path, "-") ? cj_file_read_all(path, max_bytes, what, data, size)
                             : cj_file_read_stdin(max_bytes, what, data, size);
}

int cj_file_same(const char *a, const char *b) {
    assert(a && b);
    struct stat sa, sb;
    if (stat(a, &sa) != 0 || stat(b, &sb) != 0) return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* ---- the registry of temporaries -------------------------------------------------------
 * Fixed storage, so that the signal handler reads only memory that is never freed: a slot is
 * free (0), being filled (1) or holds a name to remove (2). A temporary that finds no free
 * slot is still written atomically; it is only not removed on a signal. */
enum { TEMP_SLOTS = 64, TEMP_NAME_MAX = 4096 };
static atomic_int temp_state[TEMP_SLOTS];
static char temp_name[TEMP_SLOTS][TEMP_NAME_MAX];
static atomic_uint temp_counter;

static int temp_register(const char *name) {
    if (strlen(name) >= TEMP_NAME_MAX) return -1;
    for (int i = 0; i < TEMP_SLOTS; ++i) {
        int expected = 0;
        if (atomic_compare_exchange_strong(&temp_state[i], &expected, 1)) {
            memcpy(temp_name[i], name, strlen(name) + 1);
            atomic_store(&temp_state[i], 2);
            return i;
        }
    }
    return -1;
}

void cj_temp_release(int slot) {
    if (slot >= 0 && slot < TEMP_SLOTS) atomic_store(&temp_state[slot], 0);
}

static void on_fatal_signal(int sig) {
    for (int i = 0; i < TEMP_SLOTS; ++i)
        if (atomic_load(&temp_state[i]) == 2) (void)unlink(temp_name[i]);
    signal(sig, SIG_DFL);
    raise(sig);
}

void cj_temp_install_signal_cleanup(void) {
    const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; ++i) {
        struct sigaction old;
        if (sigaction(sigs[i], NULL, &old) != 0 || old.sa_handler != SIG_DFL) continue;
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_fatal_signal;
        sigemptyset(&sa.sa_mask);
        (void)sigaction(sigs[i], &sa, NULL);
    }
}

int cj_temp_create_beside(const char *path, char **tmp_out, int *slot) {
    const char *slash = strrchr(path, '/');
    const size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    const size_t need = strlen(path) + 64;
    char *tmp = malloc(need);
    if (!tmp) {
        errno = ENOMEM;
        return -1;
    }
    /* Block the signals between creating the file and registering it, so that no moment
     * exists where a temporary is on disk and unknown to the handler. */
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    for (int attempt = 0; attempt < 100; ++attempt) {
        const unsigned n = atomic_fetch_add(&temp_counter, 1u);
        snprintf(tmp, need, "%.*s.%s.tmp-%ld-%u", (int)dir_len, path, path + dir_len,
                 (long)getpid(), n);
        pthread_sigmask(SIG_BLOCK, &block, &old);
        int fd = open(tmp, O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0666);
        const int e = errno;
        *slot = fd >= 0 ? temp_register(tmp) : -1;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
        if (fd >= 0) {
            *tmp_out = tmp;
            return fd;
        }
        if (e != EEXIST) {
            free(tmp);
            errno = e;
            return -1;
        }
    }
    free(tmp);
    errno = EEXIST;
    return -1;
}

/* ---- the atomic writer ---------------------------------------------------------------- */

static void sync_folder_of(const char *path) {
    const char *slash = strrchr(path, '/');
    char dir[TEMP_NAME_MAX];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else if (snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path) >= (int)sizeof dir)
        return;
    int fd = open(dir, O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        (void)fsync(fd); /* a folder that cannot be synced leaves the file no less complete */
        close(fd);
    }
}

cj_status cj_atomic_open(cj_atomic_file *f, const char *path) {
    assert(f && path);
    memset(f, 0, sizeof *f);
    f->slot = -1;
    if (!*path) return cj_fail(CJ_ERR_ARGUMENT, "the output file name is empty");
    f->path = malloc(strlen(path) + 1);
    if (!f->path) return cj_fail(CJ_ERR_NOMEM, "out of memory opening '%s'", path);
    memcpy(f->path, path, strlen(path) + 1);
    int fd = cj_temp_create_beside(path, &f->tmp, &f->slot);
    if (fd < 0) {
        const int e = errno;
        free(f->path);
        f->path = NULL;
        return cj_fail(e == ENOMEM ? CJ_ERR_NOMEM : CJ_ERR_IO,
                       "cannot create a file beside '%s': %s", path, strerror(e));
    }
    f->fp = fdopen(fd, "wb");
    if (!f->fp) {
        const int e = errno;
        close(fd);
        cj_atomic_abandon(f);
        return cj_fail(CJ_ERR_IO, "cannot write beside '%s': %s", path, strerror(e));
    }
    return CJ_OK;
}

cj_status cj_atomic_commit(cj_atomic_file *f) {
    assert(f && f->fp);
    int ok = !ferror(f->fp);
    int err = ok ? 0 : EIO;
    if (ok && fflush(f->fp) != 0) ok = 0, err = errno;
    if (ok && fsync(fileno(f->fp)) != 0) ok = 0, err = errno;
    if (fclose(f->fp) != 0 && ok) ok = 0, err = errno;
    f->fp = NULL;
    if (ok && rename(f->tmp, f->path) != 0) ok = 0, err = errno;
    cj_status st = CJ_OK;
    if (!ok) {
        st = cj_fail(CJ_ERR_IO, "cannot write '%s': %s", f->path, strerror(err));
        unlink(f->tmp);
    } else {
        sync_folder_of(f->path);
    }
    cj_temp_release(f->slot);
    free(f->tmp);
    free(f->path);
    f->tmp = f->path = NULL;
    f->slot = -1;
    return st;
}

void cj_atomic_abandon(cj_atomic_file *f) {
    assert(f);
    if (f->fp) fclose(f->fp);
    if (f->tmp) unlink(f->tmp);
    cj_temp_release(f->slot);
    free(f->tmp);
    free(f->path);
    f->fp = NULL;
    f->tmp = f->path = NULL;
    f->slot = -1;
}

cj_status cj_file_check_output(const char *path, const char *what) {
    assert(path && what);
    if (!*path) return cj_fail(CJ_ERR_ARGUMENT, "the %s file name is empty", what);
    const size_t n = strlen(path);
    struct stat sb;
    if (path[n - 1] == '/' || (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)))
        return cj_fail(CJ_ERR_ARGUMENT, "%s '%s' names a folder, not a file", what, path);
    char *tmp = NULL;
    int slot = -1;
    int fd = cj_temp_create_beside(path, &tmp, &slot);
    if (fd < 0) return cj_fail(CJ_ERR_IO, "cannot write %s '%s': %s", what, path, strerror(errno));
    close(fd);
    unlink(tmp);
    cj_temp_release(slot);
    free(tmp);
    return CJ_OK;
}
