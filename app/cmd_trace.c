/* casteljau trace: a 3D scene (JSON or the built-in demo) through the ray tracer. */
#include "cli.h"

int cmd_trace(int argc, char **argv) {
    (void)argc;
    (void)argv;
    return cli_fail("trace", "not built yet");
}
