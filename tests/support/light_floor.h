/* The scene the light tests measure irradiance on: a Lambertian floor seen from straight above. */
#ifndef CJ_TEST_LIGHT_FLOOR_H
#define CJ_TEST_LIGHT_FLOOR_H

#include "casteljau/scene.h"

/* A two-sided Lambertian floor [-half, half]² at height floor_z (albedo rho: ka 0, kd 1, ks 0),
 * seen by an orthographic camera at height cam_z looking down (+y up on screen) whose view
 * covers the floor exactly, w × h pixels, 1 spp, the given light model, and no light: pixel
 * (x, y) shows the floor point (-half + (x + ½)·2half/w, -half + (y + ½)·2half/h). NULL (with
 * the library's message printed) if the library refuses any part. */
cj_scene *cj_test_light_floor(int w, int h, double half, double floor_z, double cam_z, double rho,
                              cj_light_model model);

#endif
