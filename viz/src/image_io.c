/* Image files: the loader side of the OpenImageIO plug-in (see image_plugin.h), the choice
 * between it and libpng (image_png.c, for every PNG), and the one place where image bytes
 * reach the disk. OpenImageIO is opened with dlopen on the first call that needs it, so a
 * program linking casteljau_viz pays for it only when it reads or writes a non-PNG image. Every
 * write goes to a temporary file beside the destination; each write(2), fsync(2) and close(2) is
 * checked, and only a complete, synced file is renamed onto the destination. */
#define _GNU_SOURCE /* dladdr */
#include "casteljau/image_io.h"

#include "error_internal.h"
#include "file_internal.h"
#include "image_plugin.h"
#include "image_png_internal.h"

#include <assert.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef CJ_IMAGE_PLUGIN_FILE
#define CJ_IMAGE_PLUGIN_FILE "libcasteljau_image_oiio.so"
#endif

/* ---- finding and opening the plug-in --------------------------------------------------- */

static pthread_once_t plugin_once = PTHREAD_ONCE_INIT;
static const cj_image_plugin *plugin;
static char plugin_error[1024];
static char plugin_path[PATH_MAX];

static int try_plugin(const char *path) {
    if (!path || !*path) return 0;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *e = dlerror();
        /* Keep the first real failure (a library that exists but cannot load): it is the
         * interesting one; "no such file" for later candidates is not. */
        if (access(path, F_OK) == 0 && !plugin_error[0])
            snprintf(plugin_error, sizeof plugin_error, "%s", e ? e : path);
        return 0;
    }
    cj_image_plugin_entry entry =
        (cj_image_plugin_entry)(uintptr_t)dlsym(h, CJ_IMAGE_PLUGIN_SYMBOL);
    const cj_image_plugin *table = entry ? entry() : NULL;
    if (!table || table->abi != CJ_IMAGE_PLUGIN_ABI) {
        if (!plugin_error[0])
            snprintf(plugin_error, sizeof plugin_error,
                     "'%s' is not a casteljau image plug-in "
                     "of this version",
                     path);
        dlclose(h);
        return 0;
    }
    plugin = table;
    snprintf(plugin_path, sizeof plugin_path, "%s", path);
    return 1;
}

/* Tries <dir>/<rel><file> for the directory holding `object` (a file path). */
static int try_beside(const char *object, const char *rel) {
    char buf[PATH_MAX];
    if (!object || !realpath(object, buf)) return 0;
    char *slash = strrchr(buf, '/');
    if (!slash) return 0;
    slash[1] = '\0';
    char cand[PATH_MAX + 64];
    if (snprintf(cand, sizeof cand, "%s%s%s", buf, rel, CJ_IMAGE_PLUGIN_FILE) >= (int)sizeof cand)
        return 0;
    return try_plugin(cand);
}

static void load_plugin(void) {
    const char *env = getenv("CJ_IMAGE_PLUGIN");
    if (env && *env) {
        if (!try_plugin(env) && !plugin_error[0])
            snprintf(plugin_error, sizeof plugin_error, "CJ_IMAGE_PLUGIN='%s' cannot be opened",
                     env);
        return; /* an explicit choice is not second-guessed */
    }
    /* Relative to the object that holds this code (the executable when linked statically,
     * libcasteljau_viz.so otherwise) and to the running executable: an installed copy finds
     * the plug-in wherever the prefix was moved to. */
    const char *rels[] = {"", "casteljau/", CJ_IMAGE_PLUGIN_RELDIR};
    Dl_info info;
    const char *holder = dladdr((void *)(uintptr_t)&load_plugin, &info) ? info.dli_fname : NULL;
    for (size_t i = 0; i < sizeof rels / sizeof rels[0]; ++i)
        if (try_beside(holder, rels[i]) || try_beside("/proc/self/exe", rels[i])) return;
#ifdef CJ_IMAGE_PLUGIN_BUILD
    if (try_plugin(CJ_IMAGE_PLUGIN_BUILD)) return;
#endif
#ifdef CJ_IMAGE_PLUGIN_INSTALL
    if (try_plugin(CJ_IMAGE_PLUGIN_INSTALL)) return;
#endif
    if (!plugin_error[0])
        snprintf(plugin_error, sizeof plugin_error,
                 "the OpenImageIO plug-in " CJ_IMAGE_PLUGIN_FILE " was not found next to the "
                 "program or library, in its ../lib/casteljau, or where it was built or "
                 "installed (set CJ_IMAGE_PLUGIN to its path)");
}

static cj_status get_plugin(const cj_image_plugin **out) {
    pthread_once(&plugin_once, load_plugin);
    if (!plugin) return cj_fail(CJ_ERR_UNSUPPORTED, "image files: %s", plugin_error);
    *out = plugin;
    return CJ_OK;
}

const char *cj_image_backend(void) {
    const cj_image_plugin *p = NULL;
    if (get_plugin(&p)) return NULL;
    return p->version();
}

/* ---- the atomic write ----------------------------------------------------------------- */

static int write_all(int fd, const unsigned char *p, size_t n) {
    while (n > 0) {
        ssize_t k = write(fd, p, n);
        if (k < 0) {
            if (errno == EINTR) continue;
            return -1;
        }
        if (k == 0) {
            errno = ENOSPC;
            return -1;
        }
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* Makes the rename itself durable; a directory that cannot be synced (some file systems
 * refuse) does not make the image any less complete, so that failure is not reported. */
static void sync_directory_of(const char *path) {
    const char *slash = strrchr(path, '/');
    char dir[PATH_MAX];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else if (snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path) >= (int)sizeof dir)
        return;
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
}

static cj_status check_size(int width, int height, size_t row_stride, size_t pixel_bytes,
                            size_t *stride_out) {
    if (width < 1 || height < 1 || width > 65535 || height > 65535)
        return cj_fail(CJ_ERR_ARGUMENT, "image size %d x %d is not between 1 and 65535", width,
                       height);
    const size_t row_bytes = (size_t)width * pixel_bytes;
    if (row_stride == 0) row_stride = row_bytes;
    if (row_stride < row_bytes)
        return cj_fail(CJ_ERR_ARGUMENT, "row stride %zu is smaller than %zu*width = %zu",
                       row_stride, pixel_bytes, row_bytes);
    *stride_out = row_stride;
    return CJ_OK;
}

static cj_status write_image(const char *path, const char *force_ext, const cj_image_pixels *px) {
    if (!*path) return cj_fail(CJ_ERR_ARGUMENT, "the image file name is empty");
    /* PNG through libpng, without the plug-in: the common case starts in milliseconds. */
    const int png = force_ext ? !strcmp(force_ext, "png") : cj_png_is_png_name(path);
    const cj_image_plugin *p = NULL;
    if (!png) {
        cj_status st = get_plugin(&p);
        if (st) return st;
    }
    char *tmp = NULL;
    int slot = -1;
    int fd = cj_temp_create_beside(path, &tmp, &slot);
    if (fd < 0)
        return cj_fail(CJ_ERR_IO, "cannot create a temporary file beside '%s': %s", path,
                       strerror(errno));
    char why[512] = "";
    unsigned char *bytes = NULL;
    size_t size = 0;
    /* The format is chosen from `name`: the destination's own extension, or a forced one. */
    char forced[32];
    const char *name = path;
    if (force_ext) {
        snprintf(forced, sizeof forced, "x.%s", force_ext);
        name = forced;
    }
    int code = png ? cj_png_encode(px, &bytes, &size, why, sizeof why)
                   : p->encode(name, tmp, px, &bytes, &size, why, sizeof why);
    const char *stage = "cannot write";
    const int in_memory = bytes != NULL;
    if (code == CJ_OK && in_memory) {
        if (write_all(fd, bytes, size) != 0) {
            code = CJ_ERR_IO;
            snprintf(why, sizeof why, "%s", strerror(errno));
        }
    }
    free(bytes);
    if (code == CJ_OK && fsync(fd) != 0) {
        code = CJ_ERR_IO;
        snprintf(why, sizeof why, "fsync: %s", strerror(errno));
    }
    if (close(fd) != 0 && code == CJ_OK) {
        code = CJ_ERR_IO;
        snprintf(why, sizeof why, "close: %s", strerror(errno));
    }
    if (code == CJ_OK && !in_memory) {
        /* OpenImageIO wrote the file itself (a format without in-memory encoding): make sure
         * what reached the disk decodes completely before it replaces anything. */
        int rfd = open(tmp, O_RDONLY | O_CLOEXEC);
        if (rfd < 0 || fsync(rfd) != 0) {
            code = CJ_ERR_IO;
            snprintf(why, sizeof why, "fsync: %s", strerror(errno));
        }
        if (rfd >= 0) close(rfd);
        if (code == CJ_OK) code = p->check_file(tmp, px->width, px->height, why, sizeof why);
    }
    if (code == CJ_OK && rename(tmp, path) != 0) {
        code = CJ_ERR_IO;
        snprintf(why, sizeof why, "rename failed: %s", strerror(errno));
    }
    if (code != CJ_OK) {
        unlink(tmp);
        cj_temp_release(slot);
        free(tmp);
        if (code == CJ_ERR_ARGUMENT) stage = "cannot choose a format for";
        return cj_fail((cj_status)code, "%s '%s': %s", stage, path, why);
    }
    cj_temp_release(slot);
    free(tmp);
    sync_directory_of(path);
    return CJ_OK;
}

cj_status cj_image_write(const char *path, int width, int height, const uint8_t *rgba,
                         size_t row_stride) {
    assert(path && rgba);
    cj_image_pixels px = {width, height, 0, rgba, 0};
    cj_status st = check_size(width, height, row_stride, 4, &px.row_stride);
    if (st) return st;
    return write_image(path, NULL, &px);
}

cj_status cj_image_write_float(const char *path, int width, int height, const float *rgba,
                               size_t row_stride) {
    return cj_image_write_float_with_flags(path, width, height, rgba, row_stride, 0);
}

cj_status cj_image_write_float_with_flags(const char *path, int width, int height,
                                          const float *rgba, size_t row_stride, unsigned flags) {
    assert(path && rgba);
    cj_image_pixels px = {width, height, (flags & CJ_IMAGE_FLOAT_HALF) ? 2 : 1, rgba, 0};
    cj_status st = check_size(width, height, row_stride, 4 * sizeof(float), &px.row_stride);
    if (st) return st;
    return write_image(path, NULL, &px);
}

cj_status cj_image_write_png(const char *path, int width, int height, const uint8_t *rgba,
                             size_t row_stride) {
    assert(path && rgba);
    cj_image_pixels px = {width, height, 0, rgba, 0};
    cj_status st = check_size(width, height, row_stride, 4, &px.row_stride);
    if (st) return st;
    return write_image(path, "png", &px);
}

cj_status cj_image_check_destination(const char *path, int is_float) {
    assert(path);
    if (!*path) return cj_fail(CJ_ERR_ARGUMENT, "the image file name is empty");
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (!*base) return cj_fail(CJ_ERR_ARGUMENT, "image file '%s' names a directory", path);
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return cj_fail(CJ_ERR_ARGUMENT, "image file '%s' is a directory", path);
    /* A 1 x 1 encode proves the extension names a format that can hold the pixels; creating
     * and removing the temporary file proves the directory is writable. */
    static const uint8_t px8[4] = {0, 0, 0, 255};
    static const float pxf[4] = {0, 0, 0, 1};
    const int png = cj_png_is_png_name(path);
    const cj_image_plugin *p = NULL;
    if (!png) {
        cj_status st = get_plugin(&p);
        if (st) return st;
    }
    char *tmp = NULL;
    int slot = -1;
    int fd = cj_temp_create_beside(path, &tmp, &slot);
    if (fd < 0)
        return cj_fail(CJ_ERR_IO, "cannot create files beside '%s': %s", path, strerror(errno));
    close(fd);
    cj_image_pixels px = {1, 1, is_float != 0, is_float ? (const void *)pxf : (const void *)px8,
                          is_float ? sizeof pxf : sizeof px8};
    char why[512] = "";
    unsigned char *bytes = NULL;
    size_t size = 0;
    int code = png ? cj_png_encode(&px, &bytes, &size, why, sizeof why)
                   : p->encode(path, tmp, &px, &bytes, &size, why, sizeof why);
    free(bytes);
    unlink(tmp);
    cj_temp_release(slot);
    free(tmp);
    if (code != CJ_OK) return cj_fail((cj_status)code, "image file '%s': %s", path, why);
    return CJ_OK;
}

cj_status cj_image_read(const char *path, int *width, int *height, uint8_t **rgba) {
    assert(path && width && height && rgba);
    cj_status st = cj_file_check_input(path, CJ_IMAGE_MAX_FILE_BYTES, "image");
    if (st) return st;
    /* A PNG (by its signature, whatever its name) is decoded by libpng, anything else by the
     * plug-in. */
    const int png = cj_png_file_is_png(path);
    const cj_image_plugin *p = NULL;
    if (!png) {
        st = get_plugin(&p);
        if (st) return st;
    }
    char why[512] = "";
    int w = 0, h = 0;
    uint8_t *buf = NULL;
    int code = png ? cj_png_read_rgba8(path, &w, &h, &buf, why, sizeof why)
                   : p->read_rgba8(path, &w, &h, &buf, why, sizeof why);
    if (code != CJ_OK) return cj_fail((cj_status)code, "cannot read image '%s': %s", path, why);
    *width = w;
    *height = h;
    *rgba = buf;
    return CJ_OK;
}

void cj_image_free(uint8_t *rgba) {
    free(rgba);
}
