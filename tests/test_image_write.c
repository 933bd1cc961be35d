/* cj_image_write / cj_image_write_float: the format follows the extension (checked by the file's
 * magic bytes and by reading it back), formats without alpha are composited over black, unknown
 * extensions and 8-bit formats for float pixels are refused without creating a file, and a
 * write that fails half-way (a full disk: a 40 KB tmpfs when this test may mount one, and a
 * file-size limit, which is what a full disk looks like to write(2), always) returns CJ_ERR_IO,
 * leaves no file behind and keeps the previous image intact. Also: OpenImageIO is mapped into
 * the process only by the first call that needs it (PNG goes through libpng), and a missing
 * plug-in is a clear error for the formats that need it. */
#define _GNU_SOURCE
#include "casteljau/image_io.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "rng.h"

static char root[64];
static char dir[128]; /* a fresh empty folder per test */

static void fresh_dir(const char *name) {
    snprintf(dir, sizeof dir, "%s/%s", root, name);
    assert_int_equal(mkdir(dir, 0777), 0);
}

static int maps_contain(const char *needle) {
    FILE *f = fopen("/proc/self/maps", "r");
    assert_non_null(f);
    char line[4096];
    int found = 0;
    while (fgets(line, sizeof line, f))
        if (strstr(line, needle)) found = 1;
    fclose(f);
    return found;
}

static int entries(const char *d) {
    DIR *h = opendir(d);
    assert_non_null(h);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(h)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) ++n;
    closedir(h);
    return n;
}

static void path_in(char *out, size_t n, const char *d, const char *name) {
    snprintf(out, n, "%s/%s", d, name);
}

static size_t file_bytes(const char *p, unsigned char *head, size_t head_n) {
    FILE *f = fopen(p, "rb");
    if (!f) return 0;
    size_t got = fread(head, 1, head_n, f);
    (void)got;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fclose(f);
    return (size_t)len;
}

/* A 2 x 2 test image (bottom-up): opaque red, opaque green / half-transparent white, clear. */
static const uint8_t quad[16] = {255, 0, 0, 255, 0, 255, 0, 255, 255, 255, 255, 128, 9, 9, 9, 0};

/* The same four colours as 16 x 16 blocks, so that JPEG's 8 x 8 blocks and chroma subsampling
 * keep each colour: a 32 x 32 image. */
static uint8_t big_quad[32 * 32 * 4];

static void make_big_quad(void) {
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            memcpy(big_quad + 4 * (32 * y + x), quad + 4 * (2 * (y / 16) + x / 16), 4);
}

static void test_formats_by_extension(void **state) {
    (void)state;
    /* Must run first: nothing has loaded OpenImageIO yet. */
    assert_false(maps_contain("libOpenImageIO"));
    fresh_dir("formats");
    struct {
        const char *name;
        const unsigned char magic[4];
        size_t magic_n;
        int lossless, alpha;
    } cases[] = {
        {"a.png", {0x89, 'P', 'N', 'G'}, 4, 1, 1},    {"b.JPG", {0xff, 0xd8, 0xff}, 3, 0, 0},
        {"c.jpeg", {0xff, 0xd8, 0xff}, 3, 0, 0},      {"d.tif", {'I', 'I', 42, 0}, 4, 1, 1},
        {"e.exr", {0x76, 0x2f, 0x31, 0x01}, 4, 1, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char p[512];
        path_in(p, sizeof p, dir, cases[i].name);
        assert_int_equal(cj_image_write(p, 32, 32, big_quad, 0), CJ_OK);
        unsigned char head[4] = {0};
        assert_true(file_bytes(p, head, 4) > 0);
        assert_memory_equal(head, cases[i].magic, cases[i].magic_n);
        int w, h;
        uint8_t *back = NULL;
        assert_int_equal(cj_image_read(p, &w, &h, &back), CJ_OK);
        assert_int_equal(w, 32);
        assert_int_equal(h, 32);
        for (int k = 0; k < 32 * 32; ++k) {
            const uint8_t *src = big_quad + 4 * k, *got = back + 4 * k;
            const int bx = (k % 32) % 16, by = (k / 32) % 16;
            if (!cases[i].lossless && (bx < 4 || bx > 11 || by < 4 || by > 11))
                continue; /* JPEG rings across colour edges; judge the blocks' insides */
            for (int c = 0; c < 3; ++c) {
                /* Without alpha the colour is composited over black. */
                int want = cases[i].alpha ? src[c] : (int)lround(src[c] * src[3] / 255.0);
                int tol = cases[i].lossless ? 0 : 8;
                if (abs(got[c] - want) > tol)
                    fail_msg("%s pixel %d channel %d: %d, want %d", cases[i].name, k, c, got[c],
                             want);
            }
            assert_int_equal(got[3], cases[i].alpha ? src[3] : 255);
        }
        cj_image_free(back);
        unlink(p);
        /* The PNG (first) went through libpng: OpenImageIO is still not mapped. */
        if (i == 0) assert_false(maps_contain("libOpenImageIO"));
    }
    assert_true(maps_contain("libOpenImageIO"));
    printf("test_image_write: .png .JPG .jpeg .tif .exr written by extension (magic bytes and "
           "read-back checked; JPEG composited over black); a PNG written and read maps no "
           "OpenImageIO, the JPEG does\n");
}

static void test_float_exr(void **state) {
    (void)state;
    fresh_dir("float");
    char p[512];
    path_in(p, sizeof p, dir, "f.exr");
    float px[3 * 2 * 4];
    for (int i = 0; i < 6; ++i) {
        px[4 * i + 0] = 0.125f * (float)i; /* exact in half precision */
        px[4 * i + 1] = 1.0f - 0.125f * (float)i;
        px[4 * i + 2] = 0.5f;
        px[4 * i + 3] = 1.0f;
    }
    assert_int_equal(cj_image_write_float(p, 3, 2, px, 0), CJ_OK);
    int w, h;
    uint8_t *back = NULL;
    assert_int_equal(cj_image_read(p, &w, &h, &back), CJ_OK);
    assert_int_equal(w, 3);
    assert_int_equal(h, 2);
    for (int i = 0; i < 6; ++i) { /* bottom-up on both sides; values scaled by 255 on read */
        assert_true(abs(back[4 * i] - (int)lround(px[4 * i] * 255.0)) <= 1);
        assert_true(abs(back[4 * i + 1] - (int)lround(px[4 * i + 1] * 255.0)) <= 1);
    }
    cj_image_free(back);
    /* A stride with padding is honoured. */
    float padded[2 * 8];
    memset(padded, 0, sizeof padded);
    padded[0] = padded[3] = 1.0f;         /* row 0: red */
    padded[8 + 1] = padded[8 + 3] = 1.0f; /* row 1: green */
    assert_int_equal(cj_image_write_float(p, 1, 2, padded, 8 * sizeof(float)), CJ_OK);
    assert_int_equal(cj_image_read(p, &w, &h, &back), CJ_OK);
    assert_int_equal(back[0], 255);
    assert_int_equal(back[5], 255);
    cj_image_free(back);
    unlink(p);
    printf("test_image_write: float RGBA to OpenEXR round-trips (bottom-up rows, padded stride)\n");
}

static void test_refusals(void **state) {
    (void)state;
    fresh_dir("refusals");
    const char *bad[] = {"x.nosuchformat", "noext", "dir/.hidden", ""};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char p[512];
        if (*bad[i])
            path_in(p, sizeof p, dir, bad[i]);
        else
            p[0] = '\0';
        if (i == 2) {
            char sub[512];
            path_in(sub, sizeof sub, dir, "dir");
            mkdir(sub, 0777);
        }
        assert_int_equal(cj_image_write(p, 2, 2, quad, 0), CJ_ERR_ARGUMENT);
        assert_int_equal(cj_image_check_destination(p, 0), CJ_ERR_ARGUMENT);
    }
    char sub[512];
    path_in(sub, sizeof sub, dir, "dir");
    assert_int_equal(entries(sub), 0);
    rmdir(sub);
    assert_int_equal(entries(dir), 0);
    char p[512];
    path_in(p, sizeof p, dir, "f.png");
    float one[4] = {1, 1, 1, 1};
    assert_int_equal(cj_image_write_float(p, 1, 1, one, 0), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_image_check_destination(p, 1), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_image_check_destination(p, 0), CJ_OK);
    path_in(p, sizeof p, dir, "missing/f.png");
    assert_int_equal(cj_image_check_destination(p, 0), CJ_ERR_IO);
    assert_int_equal(entries(dir), 0);
    printf("test_image_write: unknown/absent extensions, 8-bit formats for float pixels, empty "
           "names refused (CJ_ERR_ARGUMENT) without creating a file\n");
}

/* Random bytes do not compress: an image of `w` x `w` needs about 4 w^2 bytes in any format. */
static uint8_t *noise(int w, uint64_t seed) {
    cj_rng r;
    cj_rng_init(&r, seed);
    uint8_t *px = malloc((size_t)w * w * 4);
    assert_non_null(px);
    for (size_t i = 0; i < (size_t)w * w * 4; ++i) px[i] = (uint8_t)cj_rng_next(&r);
    return px;
}

/* Writes a small image, then a large one over it in `d` (which holds about 40 KB): the large
 * write fails, the small image is intact and nothing else is in `d`. */
static void full_disk_case(const char *d, const char *ext, const char *how) {
    char p[512];
    snprintf(p, sizeof p, "%s/g.%s", d, ext);
    uint8_t *small = noise(8, 1);
    const int is_float = !strcmp(ext, "exr");
    float smallf[8 * 8 * 4], *bigf = NULL;
    for (int i = 0; i < 8 * 8 * 4; ++i) smallf[i] = small[i] / 255.0f;
    cj_status st =
        is_float ? cj_image_write_float(p, 8, 8, smallf, 0) : cj_image_write(p, 8, 8, small, 0);
    assert_int_equal(st, CJ_OK);
    unsigned char before[64];
    size_t before_len = file_bytes(p, before, sizeof before);
    assert_true(before_len > 0);
    uint8_t *big = noise(256, 2);
    if (is_float) {
        bigf = malloc(sizeof(float) * 256 * 256 * 4);
        assert_non_null(bigf);
        for (int i = 0; i < 256 * 256 * 4; ++i) bigf[i] = big[i] / 255.0f;
        st = cj_image_write_float(p, 256, 256, bigf, 0);
    } else {
        st = cj_image_write(p, 256, 256, big, 0);
    }
    if (st != CJ_ERR_IO) fail_msg("%s (%s): writing 256 KB returned %d", ext, how, (int)st);
    unsigned char after[64];
    assert_int_equal(file_bytes(p, after, sizeof after), before_len);
    assert_memory_equal(before, after, sizeof before < before_len ? sizeof before : before_len);
    int w, h;
    uint8_t *back = NULL;
    assert_int_equal(cj_image_read(p, &w, &h, &back), CJ_OK);
    assert_int_equal(w, 8);
    cj_image_free(back);
    assert_int_equal(entries(d), 1); /* no temporary file left */
    unlink(p);
    free(small);
    free(big);
    free(bigf);
}

static void test_full_disk(void **state) {
    (void)state;
    fresh_dir("full");
    const char *exts[] = {"png", "jpg", "tif", "exr"};
    /* A real full disk, when this process may mount a small tmpfs (root). */
    char fs[512];
    snprintf(fs, sizeof fs, "%s/fs", dir);
    assert_int_equal(mkdir(fs, 0777), 0);
    if (mount("tmpfs", fs, "tmpfs", 0, "size=40k") == 0) {
        for (size_t i = 0; i < sizeof exts / sizeof exts[0]; ++i)
            full_disk_case(fs, exts[i], "40 KB tmpfs");
        assert_int_equal(umount(fs), 0);
        printf("test_image_write: on a full 40 KB tmpfs, .png .jpg .tif .exr writes fail with "
               "CJ_ERR_IO, leave no file and keep the previous image\n");
    } else {
        printf("test_image_write: cannot mount a tmpfs here (%s); the file-size limit below "
               "stands in for a full disk\n",
               strerror(errno));
    }
    rmdir(fs);
    /* A file-size limit fails write(2) with EFBIG just as a full disk fails it with ENOSPC. */
    struct rlimit old, lim;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
    lim = old;
    lim.rlim_cur = 40 * 1024;
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; ++i)
        full_disk_case(dir, exts[i], "40 KB file-size limit");
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
    signal(SIGXFSZ, prev);
    printf("test_image_write: under a 40 KB file-size limit, .png .jpg .tif .exr writes fail "
           "with CJ_ERR_IO, leave no file and keep the previous image\n");
}

static char self_exe[4096];

/* Runs in a fresh process (exec of this program): the plug-in is looked up once per process. */
static int missing_plugin_child(const char *d) {
    setenv("CJ_IMAGE_PLUGIN", "/nonexistent/libcasteljau_image_oiio.so", 1);
    char p[512];
    /* PNG goes through libpng and needs no plug-in: written and read back. */
    snprintf(p, sizeof p, "%s/x.png", d);
    int w = 0, h = 0;
    uint8_t *back = NULL;
    if (cj_image_write(p, 2, 2, quad, 0) != CJ_OK || cj_image_read(p, &w, &h, &back) != CJ_OK ||
        w != 2 || h != 2 || memcmp(back, quad, sizeof quad) != 0) {
        printf("child: PNG without the plug-in failed: %s\n", cj_last_error());
        return 1;
    }
    cj_image_free(back);
    unlink(p);
    snprintf(p, sizeof p, "%s/x.tif", d);
    cj_status st = cj_image_write(p, 2, 2, quad, 0);
    const char *msg = cj_last_error();
    printf("child: PNG written and read without the plug-in; TIFF: status %d, message: %s\n",
           (int)st, msg);
    return st == CJ_ERR_UNSUPPORTED && strstr(msg, "CJ_IMAGE_PLUGIN") && access(p, F_OK) != 0 ? 0
                                                                                              : 1;
}

static void test_missing_plugin(void **state) {
    (void)state;
    fresh_dir("plugin");
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        execl(self_exe, self_exe, "--missing-plugin-child", dir, (char *)NULL);
        _exit(127);
    }
    int ws = 0;
    assert_int_equal(waitpid(pid, &ws, 0), pid);
    assert_true(WIFEXITED(ws));
    assert_int_equal(WEXITSTATUS(ws), 0);
    assert_int_equal(entries(dir), 0);
    printf("test_image_write: with the plug-in missing, PNG still round-trips (libpng) and TIFF is "
           "CJ_ERR_UNSUPPORTED naming CJ_IMAGE_PLUGIN\n");
}

static void remove_tree(const char *d) {
    DIR *h = opendir(d);
    if (!h) return;
    struct dirent *e;
    while ((e = readdir(h))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char p[512];
        snprintf(p, sizeof p, "%s/%s", d, e->d_name);
        if (unlink(p) != 0) remove_tree(p);
    }
    closedir(h);
    rmdir(d);
}

int main(int argc, char **argv) {
    if (argc == 3 && !strcmp(argv[1], "--missing-plugin-child"))
        return missing_plugin_child(argv[2]);
    ssize_t n = readlink("/proc/self/exe", self_exe, sizeof self_exe - 1);
    assert_true(n > 0);
    self_exe[n] = '\0';
    make_big_quad();
    snprintf(root, sizeof root, "/tmp/cj_test_image_write_XXXXXX");
    assert_non_null(mkdtemp(root));
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_formats_by_extension),
        cmocka_unit_test(test_float_exr),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_full_disk),
        cmocka_unit_test(test_missing_plugin),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    remove_tree(root);
    return rc;
}
