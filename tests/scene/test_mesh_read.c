/* OBJ and PLY readers: what cj_mesh_write_obj/ply write reads back exactly (seeded random
 * meshes), polygons are fan-triangulated, negative OBJ indices, missing normals computed,
 * foreign PLY layouts (float, s/t, other elements), and bad input named by file and line (or
 * element and index). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh_read.h"
#include "rng.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[256];

static int setup(void **state) {
    (void)state;
    /* tmpfs when there is one: the writers fsync every file, which a busy disk makes slow. */
    snprintf(dir, sizeof dir, "/dev/shm/cj_test_mesh_read_XXXXXX");
    if (mkdtemp(dir)) return 0;
    snprintf(dir, sizeof dir, "/tmp/cj_test_mesh_read_XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    DIR *d = opendir(dir);
    if (!d) return 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char p[512];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    closedir(d);
    rmdir(dir);
    return 0;
}

static const char *file(const char *name) {
    static char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return p;
}

static void write_bytes(const char *name, const void *data, size_t n) {
    FILE *f = fopen(file(name), "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static void write_text(const char *name, const char *text) {
    write_bytes(name, text, strlen(text));
}

/* A random mesh: `nv` vertices (some sharing positions, as seams do), random triangles. */
static cj_mesh *random_mesh(cj_rng *r, size_t nv, size_t nt) {
    cj_mesh *m;
    assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
    for (size_t i = 0; i < nv; ++i) {
        double p[3], n[3], uv[2];
        for (int k = 0; k < 3; ++k) p[k] = cj_rng_range(r, -10, 10) / 3.0;
        if (i > 0 && cj_rng_unit(r) < 0.2) memcpy(p, m->positions + 3 * (i - 1), sizeof p);
        for (int k = 0; k < 3; ++k) n[k] = cj_rng_range(r, -1, 1);
        uv[0] = cj_rng_unit(r) / 7.0;
        uv[1] = cj_rng_unit(r);
        assert_int_equal(cj_mesh_add_vertex(m, p, n, uv, NULL), CJ_OK);
    }
    for (size_t t = 0; t < nt; ++t) {
        uint32_t a = (uint32_t)cj_rng_int(r, 0, (int)nv - 1), b, c;
        do b = (uint32_t)cj_rng_int(r, 0, (int)nv - 1);
        while (b == a);
        do c = (uint32_t)cj_rng_int(r, 0, (int)nv - 1);
        while (c == a || c == b);
        assert_int_equal(cj_mesh_add_triangle(m, a, b, c, cj_rng_int(r, -3, 40)), CJ_OK);
    }
    return m;
}

/* Same triangles corner by corner: position, normal, (u, v) bit-identical, same patch ids. */
static void same_corners(const cj_mesh *a, const cj_mesh *b, int patch_ids) {
    assert_int_equal(a->triangle_count, b->triangle_count);
    for (size_t t = 0; t < a->triangle_count; ++t) {
        for (int k = 0; k < 3; ++k) {
            size_t i = a->triangles[3 * t + (size_t)k], j = b->triangles[3 * t + (size_t)k];
            if (memcmp(a->positions + 3 * i, b->positions + 3 * j, 3 * sizeof(double)) ||
                memcmp(a->normals + 3 * i, b->normals + 3 * j, 3 * sizeof(double)) ||
                memcmp(a->uvs + 2 * i, b->uvs + 2 * j, 2 * sizeof(double)))
                fail_msg("triangle %zu corner %d differs", t, k);
        }
        if (patch_ids && a->triangle_patch[t] != b->triangle_patch[t])
            fail_msg("triangle %zu: patch %d read as %d", t, a->triangle_patch[t],
                     b->triangle_patch[t]);
    }
}

static void test_round_trip(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_mesh_read round trip", 17));
    for (int rep = 0; rep < 20; ++rep) {
        cj_mesh *m =
            random_mesh(&r, (size_t)cj_rng_int(&r, 3, 200), (size_t)cj_rng_int(&r, 1, 300));
        cj_mesh *o = NULL, *pa = NULL, *pb = NULL;
        assert_int_equal(cj_mesh_write_obj(m, file("m.obj")), CJ_OK);
        assert_int_equal(cj_mesh_write_ply(m, file("a.ply"), 0), CJ_OK);
        assert_int_equal(cj_mesh_write_ply(m, file("b.ply"), 1), CJ_OK);
        if (cj_mesh_read(file("m.obj"), NULL, &o)) fail_msg("%s", cj_last_error());
        if (cj_mesh_read(file("a.ply"), NULL, &pa)) fail_msg("%s", cj_last_error());
        if (cj_mesh_read(file("b.ply"), NULL, &pb)) fail_msg("%s", cj_last_error());
        same_corners(m, o, 1);
        /* PLY keeps the vertex order: the arrays are identical. */
        for (int k = 0; k < 2; ++k) {
            const cj_mesh *p = k ? pb : pa;
            assert_int_equal(p->vertex_count, m->vertex_count);
            assert_memory_equal(p->positions, m->positions, 3 * m->vertex_count * sizeof(double));
            assert_memory_equal(p->normals, m->normals, 3 * m->vertex_count * sizeof(double));
            assert_memory_equal(p->uvs, m->uvs, 2 * m->vertex_count * sizeof(double));
            assert_memory_equal(p->triangles, m->triangles,
                                3 * m->triangle_count * sizeof(uint32_t));
        }
        cj_mesh_destroy(m);
        cj_mesh_destroy(o);
        cj_mesh_destroy(pa);
        cj_mesh_destroy(pb);
    }
    printf("test_mesh_read: 20 random meshes written as OBJ, ASCII PLY and binary PLY read back "
           "bit-identical (positions, normals, uv, triangles, OBJ patch ids)\n");
}

static void test_polygons_and_indices(void **state) {
    (void)state;
    /* A pentagon (fan: 3 triangles) in z = 0, counter-clockwise, and a quad by negative
     * indices; no normals in the file: computed, +z for the planar fan. Comments, o/s/usemtl
     * lines, CRLF endings and a 4-coordinate v are accepted. */
    write_text("p.obj", "# test\r\no thing\r\nv 0 0 0\r\nv 2 0 0\r\nv 3 1 0\r\nv 1 2 0\r\n"
                        "v -1 1 0 1\r\nvt 0.5 0.25\r\ns off\r\nusemtl x\r\n"
                        "f 1/1 2/1 3/1 4/1 5/1\r\n"
                        "v 0 0 1 2\nv 1 0 1 2\nv 1 1 1 2\nv 0 1 1 2\nf -4 -3 -2 -1\n");
    cj_mesh *m = NULL;
    if (cj_mesh_read_obj(file("p.obj"), NULL, &m)) fail_msg("%s", cj_last_error());
    assert_int_equal(m->triangle_count, 5);
    assert_int_equal(m->vertex_count, 9);
    const uint32_t want[15] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 5, 6, 7, 5, 7, 8};
    assert_memory_equal(m->triangles, want, sizeof want);
    for (size_t i = 0; i < m->vertex_count; ++i) {
        assert_true(m->normals[3 * i] == 0 && m->normals[3 * i + 1] == 0);
        assert_true(m->normals[3 * i + 2] == 1);
    }
    assert_true(m->uvs[0] == 0.5 && m->uvs[1] == 0.25 && m->uvs[10] == 0);
    assert_true(m->positions[3 * 5 + 2] == 0.5); /* w = 2 divides */
    cj_mesh_destroy(m);

    /* v//vn corners and groups: one vertex per distinct (v, vt, vn). */
    write_text("g.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 1 0 0\n"
                        "g first\nf 1//1 2//1 3//1\ng patch_12\nf 1//2 3//2 2//2\ng first\n"
                        "f 1//1 3//1 2//2\n");
    assert_int_equal(cj_mesh_read(file("g.obj"), NULL, &m), CJ_OK);
    assert_int_equal(m->vertex_count, 6);
    const int32_t pid[3] = {0, 12, 0};
    assert_memory_equal(m->triangle_patch, pid, sizeof pid);
    cj_mesh_destroy(m);

    /* A PLY from elsewhere: float coordinates, s/t, an int list with a uchar count, an extra
     * element and an extra property, a quad. */
    write_text("f.ply", "ply\nformat ascii 1.0\ncomment other tool\nelement vertex 4\n"
                        "property float x\nproperty float y\nproperty float z\n"
                        "property uchar red\nproperty float s\nproperty float t\n"
                        "element edge 1\nproperty int a\nproperty int b\n"
                        "element face 1\nproperty list uchar int vertex_index\n"
                        "property int flags\nend_header\n"
                        "0 0 0 255 0 0\n1 0 0 0 1 0\n1 1 0 0 1 1\n0 1 0 0 0 1\n"
                        "0 1\n4 0 1 2 3 7\n");
    if (cj_mesh_read(file("f.ply"), NULL, &m)) fail_msg("%s", cj_last_error());
    assert_int_equal(m->vertex_count, 4);
    assert_int_equal(m->triangle_count, 2);
    assert_true(m->uvs[2 * 2] == 1 && m->uvs[2 * 2 + 1] == 1);
    assert_true(m->normals[2] == 1);
    cj_mesh_destroy(m);
    printf("test_mesh_read: polygons fan-triangulated, negative indices, v//vn, groups -> patch "
           "ids, computed normals, a foreign PLY layout\n");
}

typedef struct bad {
    const char *name, *text, *message; /* message: "%s" = the file's path */
    cj_status status;
} bad;

static void test_bad_input(void **state) {
    (void)state;
    static const bad BAD[] = {
        {"b1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nfoo 1 2\n", "%s:5: unknown statement 'foo'",
         CJ_ERR_PARSE},
        {"b2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\n# c\nf 1 2 40\n",
         "%s:6: face corner 3 names vertex 40 of 3", CJ_ERR_RANGE},
        {"b3.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "%s:3: a face needs at least 3 corners, found 2",
         CJ_ERR_RANGE},
        {"b4.obj", "v 0 0\n", "%s:1: expected at least 3 numbers, found 2", CJ_ERR_PARSE},
        {"b5.obj", "v 0 x 0\n", "%s:1: 'x 0' is not a number", CJ_ERR_PARSE},
        {"b6.obj", "v 0 0 0\nv nan 0 0\n", "%s:2: number 1 is not finite", CJ_ERR_NONFINITE},
        {"b7.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n",
         "%s:4: face corner 3 names vertex -4 of 3", CJ_ERR_RANGE},
        {"b8.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n",
         "%s:4: face corner 1 names texture coordinate 1 of 0", CJ_ERR_RANGE},
        {"b9.obj", "v 0 0 0\n", "%s: no faces", CJ_ERR_EMPTY},
        {"c1.ply", "plx\n", "%s:1: not a PLY file (no 'ply' line)", CJ_ERR_PARSE},
        {"c2.ply", "ply\nformat binary_big_endian 1.0\nend_header\n",
         "%s:2: PLY format 'binary_big_endian' is not supported", CJ_ERR_UNSUPPORTED},
        {"c3.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
         "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n",
         "%s:13: face 0: vertex index 5 out of range (3 vertices)", CJ_ERR_RANGE},
        {"c4.ply",
         "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
         "property double z\nend_header\n0 0 0\n1 0\n",
         "%s:9: vertex 1: the file ends early", CJ_ERR_PARSE},
        {"c5.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nend_header\n0\n",
         "%s: element vertex has no x, y, z properties", CJ_ERR_PARSE},
        {"c6.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
         "%s:4: unknown type 'quad'", CJ_ERR_PARSE},
        /* an element without properties and a huge count holds no data: skipped at once */
        {"c7.ply",
         "ply\nformat ascii 1.0\nelement nothing 18446744073709551615\nelement vertex 3\n"
         "property double x\nproperty double y\nproperty double z\nend_header\n0 0 0\n1 0 0\n"
         "0 1 0\n",
         "%s: no faces", CJ_ERR_EMPTY},
        {"c8.ply",
         "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty double x\nproperty double "
         "y\nproperty double z\nend_header\n0 0 0\n",
         "%s: 4000000000 vertices is more than the file holds", CJ_ERR_RANGE},
        /* found by fuzz_mesh_read: a second vertex element leaked the first one's buffers */
        {"c9.ply",
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
         "property double z\nelement vertex 1\nproperty double x\nproperty double y\nproperty "
         "double z\nend_header\n0 0 0\n1 1 1\n",
         "%s: element vertex appears twice", CJ_ERR_PARSE},
        /* found by fuzz_mesh_read: a corner count beyond int was converted to int (UB) */
        {"c10.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
         "property double z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n8.9e97 0 1 2\n",
         "%s:13: face 0 has 8.9e+97 corners (at least 3, at most the file's size)", CJ_ERR_RANGE},
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; ++i) {
        write_text(BAD[i].name, BAD[i].text);
        cj_mesh *m = (cj_mesh *)&BAD[i];
        cj_status st = cj_mesh_read(file(BAD[i].name), NULL, &m);
        assert_ptr_equal(m, &BAD[i]); /* untouched */
        char want[700];
        snprintf(want, sizeof want, BAD[i].message, file(BAD[i].name));
        if (st != BAD[i].status || strcmp(cj_last_error(), want))
            fail_msg("%s: %s '%s', want %s '%s'", BAD[i].name, cj_status_str(st), cj_last_error(),
                     cj_status_str(BAD[i].status), want);
    }
    /* Binary PLY: errors name the element and its index. */
    const char head[] = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 2\n"
                        "property list uchar int vertex_indices\nend_header\n";
    unsigned char buf[256];
    size_t n = strlen(head);
    memcpy(buf, head, n);
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    memcpy(buf + n, v, sizeof v); /* little-endian host assumed by this test */
    n += sizeof v;
    const int f0[3] = {0, 1, 2}, f1[3] = {0, 2, 9};
    buf[n++] = 3;
    memcpy(buf + n, f0, sizeof f0);
    n += sizeof f0;
    buf[n++] = 3;
    memcpy(buf + n, f1, sizeof f1);
    n += sizeof f1;
    write_bytes("d1.ply", buf, n);
    cj_mesh *m = NULL;
    assert_int_equal(cj_mesh_read(file("d1.ply"), NULL, &m), CJ_ERR_RANGE);
    char want[600];
    snprintf(want, sizeof want, "%s: face 1: vertex index 9 out of range (3 vertices)",
             file("d1.ply"));
    assert_string_equal(cj_last_error(), want);
    write_bytes("d2.ply", buf, n - 6); /* cut inside face 1 */
    assert_int_equal(cj_mesh_read(file("d2.ply"), NULL, &m), CJ_ERR_PARSE);
    snprintf(want, sizeof want, "%s: face 1: the file ends early", file("d2.ply"));
    assert_string_equal(cj_last_error(), want);
    /* The good part of it reads. */
    buf[n - 4] = 1;
    write_bytes("d3.ply", buf, n);
    assert_int_equal(cj_mesh_read(file("d3.ply"), NULL, &m), CJ_OK);
    assert_int_equal(m->triangle_count, 2);
    cj_mesh_destroy(m);
    assert_int_equal(cj_mesh_read(file("absent.obj"), NULL, &m), CJ_ERR_IO);
    assert_int_equal(cj_mesh_read(file("x.stl"), NULL, &m), CJ_ERR_ARGUMENT);
    printf("test_mesh_read: %zu bad files named by file and line (or element and index), the "
           "output untouched\n",
           sizeof BAD / sizeof BAD[0] + 4);
}

/* Random byte edits of valid OBJ, ASCII PLY and binary PLY files: each read either succeeds
 * with every index in range and finite data, or fails with a message naming the file; never a
 * crash (the sanitizer build runs this too). */
static void test_mutations(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_mesh_read mutations", 5));
    cj_mesh *m = random_mesh(&r, 12, 16);
    assert_int_equal(cj_mesh_write_obj(m, file("o.obj")), CJ_OK);
    assert_int_equal(cj_mesh_write_ply(m, file("o.ply"), 0), CJ_OK);
    assert_int_equal(cj_mesh_write_ply(m, file("b.ply"), 1), CJ_OK);
    cj_mesh_destroy(m);
    const char *src[3] = {"o.obj", "o.ply", "b.ply"}, *dst[3] = {"x.obj", "x.ply", "y.ply"};
    int ok = 0, refused = 0;
    for (int f = 0; f < 3; ++f) {
        FILE *in = fopen(file(src[f]), "rb");
        assert_non_null(in);
        static unsigned char orig[1 << 16], buf[(1 << 16) + 64];
        size_t len = fread(orig, 1, sizeof orig, in);
        fclose(in);
        for (int k = 0; k < 400; ++k) {
            memcpy(buf, orig, len);
            size_t n = len;
            for (int e = cj_rng_int(&r, 1, 4); e > 0 && n > 1; --e) {
                size_t at = (size_t)cj_rng_int(&r, 0, (int)n - 1);
                static const char pool[] = "0123456789-./ \n#fvtnxyz e";
                switch (cj_rng_int(&r, 0, 3)) {
                case 0:
                    memmove(buf + at, buf + at + 1, n - at - 1);
                    n--;
                    break;
                case 1:
                    buf[at] = (unsigned char)pool[cj_rng_int(&r, 0, (int)sizeof pool - 2)];
                    break;
                case 2:
                    buf[at] = (unsigned char)cj_rng_int(&r, 0, 255);
                    break;
                default:
                    n = at + 1;
                }
            }
            write_bytes(dst[f], buf, n);
            cj_mesh *o = NULL;
            cj_status st = cj_mesh_read(file(dst[f]), NULL, &o);
            if (st == CJ_OK) {
                for (size_t t = 0; t < 3 * o->triangle_count; ++t)
                    assert_true(o->triangles[t] < o->vertex_count);
                for (size_t i = 0; i < 3 * o->vertex_count; ++i)
                    assert_true(isfinite(o->positions[i]) && isfinite(o->normals[i]));
                cj_mesh_destroy(o);
                ok++;
            } else {
                assert_null(o);
                assert_non_null(strstr(cj_last_error(), file(dst[f])));
                refused++;
            }
        }
    }
    printf("test_mesh_read: 1200 randomly edited OBJ/PLY files: %d read with valid indices and "
           "finite data, %d refused naming the file\n",
           ok, refused);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_polygons_and_indices),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_mutations),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
