/* Shared by the two source files of test_scene_json. */
#ifndef CJ_TEST_SCENE_JSON_H
#define CJ_TEST_SCENE_JSON_H

#include "casteljau/scene_json.h"

/* A unit sphere's geometry member, for documents written inline. */
#define SPHERE "\"geometry\": {\"type\": \"sphere\", \"radius\": 1}"

/* The loader options (the teapot's path) and the temporary folder of the run. */
extern const cj_scene_json_options sj_opts;
extern char sj_tmpdir[256];

/* The whole file as a NUL-terminated string (the caller frees it); fails the test otherwise. */
char *sj_read_all(const char *path);

/* scene_json_bad.c */
void test_bad_documents(void **state);

/* scene_json_round_trip.c */
void test_round_trip_shipped(void **state);
void test_round_trip_everything(void **state);

#endif
