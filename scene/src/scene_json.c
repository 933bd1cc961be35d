/* The JSON scene reader's entry points: parse, check the nesting, read the document's sections
 * (scene_json_parts.c, scene_json_nodes.c, scene_json_geom.c) through the checked-JSON kit
 * (json_read.c), which also gives the lines of messages. */
#include "scene_json_internal.h"
#include "file_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- entry points --------------------------------------------------------------------------- */

static const char *const TOP_KEYS[] = {"camera",    "settings",   "lights",  "textures",
                                       "materials", "geometries", "objects", NULL};

static cj_status read_document(jctx *c, const cJSON *root) {
    cj_status st = cj_json_object(&c->json, root, "", TOP_KEYS);
    if (st) return st;
    const cJSON *objects;
    st = cj_json_require(&c->json, root, "", "objects", &objects);
    if (st) return st;
    const cJSON *n;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "camera")) && (st = cj_json_read_camera_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "settings")) &&
        (st = cj_json_read_settings_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "lights")) && (st = cj_json_read_lights_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "textures")) &&
        (st = cj_json_read_textures_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "materials")) &&
        (st = cj_json_read_materials_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "geometries"))) {
        if (!cJSON_IsArray(n))
            return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "geometries must be an array, not %s",
                                cj_json_type_name(n));
        size_t k = (size_t)cJSON_GetArraySize(n);
        c->geometries = n;
        c->geometry_index = malloc((k ? k : 1) * sizeof(int));
        if (!c->geometry_index) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", c->name);
        for (size_t i = 0; i < k; ++i) c->geometry_index[i] = -1;
        /* Check every entry now (also the unused ones) so errors come in document order. */
        size_t i = 0;
        for (const cJSON *g = n->child; g; g = g->next, ++i) {
            char p[CJ_JSON_PATH];
            cj_json_index(p, "geometries", i);
            const char *name = NULL;
            if (!cJSON_IsObject(g))
                return cj_json_fail(&c->json, g, 0, CJ_ERR_PARSE, "%s must be an object, not %s", p,
                                    cj_json_type_name(g));
            if ((st = cj_json_string(&c->json, g, p, "name", &name))) return st;
            if (!name)
                return cj_json_fail(&c->json, g, 0, CJ_ERR_PARSE, "%s: missing key \"name\"", p);
            size_t j = 0;
            for (const cJSON *o = n->child; o != g; o = o->next, ++j) {
                const cJSON *on = cJSON_GetObjectItemCaseSensitive(o, "name");
                if (!strcmp(on->valuestring, name))
                    return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(g, "name"), 0,
                                        CJ_ERR_PARSE, "%s.name \"%s\" is already geometries[%zu]",
                                        p, name, j);
            }
            if ((st = cj_json_read_geometry_(c, g, p, &c->geometry_index[i]))) return st;
        }
    }
    st = cj_json_read_objects_(c, objects);
    if (st) return st;
    st = cj_scene_check(c->scene);
    if (st) {
        char msg[768];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_fail(st, "%s: %s", c->name, msg);
    }
    return CJ_OK;
}

cj_status cj_scene_parse_json_with_options(const char *text, const char *name, const char *base_dir,
                                           const cj_scene_json_options *options,
                                           const cj_allocator *alloc, cj_scene **out) {
    assert(text && out);
    if (!name) name = "<scene>";
    cJSON *root = NULL;
    CJ_JSON_TRY(cj_json_parse(name, text, &root));
    jctx c;
    memset(&c, 0, sizeof c);
    c.name = name;
    c.base_dir = base_dir ? base_dir : "";
    c.teapot_path = options ? options->teapot_path : NULL;
    c.default_material = -1;
    cj_json_lines lines;
    cj_json_doc_init(&c.json, &lines, name, text, root);
    cj_status st = cj_scene_create(alloc, &c.scene);
    if (!st) st = read_document(&c, root);
    if (st) {
        cj_scene_destroy(c.scene);
    } else {
        *out = c.scene;
    }
    cj_json_doc_free(&c.json);
    free(c.geometry_index);
    cJSON_Delete(root);
    return st;
}

cj_status cj_scene_parse_json(const char *text, const char *name, const char *base_dir,
                              const cj_allocator *alloc, cj_scene **out) {
    return cj_scene_parse_json_with_options(text, name, base_dir, NULL, alloc, out);
}

cj_status cj_scene_load_json_with_options(const char *path, const cj_scene_json_options *options,
                                          const cj_allocator *alloc, cj_scene **out) {
    assert(path && out);
    char *text = NULL;
    size_t len = 0;
    cj_status rs = cj_file_read_all(path, CJ_FILE_MAX_BYTES, "scene", &text, &len);
    if (rs) return rs;
    if (strlen(text) != len) {
        free(text);
        return cj_fail(CJ_ERR_PARSE, "%s: the file contains a NUL byte (not JSON text)", path);
    }
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (slash) {
        size_t k = (size_t)(slash - path);
        if (k >= sizeof dir) {
            free(text);
            return cj_fail(CJ_ERR_RANGE, "'%s': path too long", path);
        }
        memcpy(dir, path, k);
        dir[k] = '\0';
        if (k == 0) strcpy(dir, "/");
    } else {
        dir[0] = '\0';
    }
    cj_status st = cj_scene_parse_json_with_options(text, path, dir, options, alloc, out);
    free(text);
    return st;
}

cj_status cj_scene_load_json(const char *path, const cj_allocator *alloc, cj_scene **out) {
    return cj_scene_load_json_with_options(path, NULL, alloc, out);
}
