/* casteljau render: a 3D scene (JSON or the built-in demo) through the rasterizer. */
#include "cli.h"

int cmd_render(int argc, char **argv) {
    (void)argc;
    (void)argv;
    return cli_fail("render", "not built yet");
}
