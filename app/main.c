/* casteljau: the command-line front end. Each sub-command lives in its own cmd_*.c file. */
#include "cli.h"
#include "file_internal.h"

#include <stdio.h>
#include <string.h>

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} command;

static const command commands[] = {
    {"eval", cmd_eval, "evaluate a Bezier curve (or a derivative) at parameters"},
    {"interp", cmd_interp, "curves through points (Catmull-Rom, polynomial) as Bezier segments"},
    {"fit", cmd_fit, "a B-spline through or near points (interpolation, least squares) as JSON"},
    {"contour", cmd_contour, "polylines of an implicit curve f(x,y) = 0 inside a box"},
    {"plot", cmd_plot, "render curves described in JSON (or --demo) to a PNG image"},
    {"tessellate", cmd_tessellate,
     "Bezier patches (or the Utah teapot) to an OBJ/PLY mesh within a tolerance"},
    {"render", cmd_render, "render a 3D scene (JSON, or --demo) to PNG/EXR with our rasterizer"},
    {"trace", cmd_trace, "ray-trace a 3D scene (JSON, or --demo): shadows, mirrors, glass"},
    {"animate", cmd_animate,
     "render an animation (keyframes, paths, cloth) as numbered PNG frames"},
    {"report", cmd_report, "measure accuracy against cost; HTML page with our charts (-o DIR)"},
    {"view", cmd_view, "interactive viewer and control-point editor (GLFW window, replay)"},
    {"intersect", cmd_intersect, "certified intersections of the curves of a plot JSON document"},
    {"nearest", cmd_nearest, "certified nearest point on the curves of a plot JSON document"},
    {"offset", cmd_offset, "offset curves of a plot JSON document, proven within a tolerance"},
    {"reduce", cmd_reduce, "degree reduction of the curves of a plot JSON document, proven bound"},
    {"section", cmd_section,
     "plane sections of patch models as joined cubic curves, proven deviation"},
};

static void usage(FILE *f) {
    fprintf(f, "usage: casteljau <command> [options]\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        fprintf(f, "  %-11s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\n'casteljau <command> --help' describes a command (its options, defaults and\n"
               "output); 'casteljau --version' prints the version. Exit status: 0 success, 2 a\n"
               "bad argument or input (one line on stderr), 1 a failure to write or allocate.\n"
               "\nManual pages: casteljau(1) and casteljau-<command>(1).\n"
               "Documentation: " CJ_DOC_DIR "\n"
               "Example scenes: " CJ_DATA_DIR "/scenes\n");
}

int main(int argc, char **argv) {
    /* Temporary files of the atomic writers are removed on Ctrl-C and SIGTERM. */
    cj_temp_install_signal_cleanup();
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("%s\n", cli_version());
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 1, argv + 1);
    enum { NCOMMANDS = sizeof commands / sizeof commands[0] };
    const char *names[NCOMMANDS];
    for (size_t i = 0; i < NCOMMANDS; ++i) names[i] = commands[i].name;
    const char *near = cli_suggest_word(argv[1], names, NCOMMANDS);
    char q[160];
    if (near)
        fprintf(stderr,
                "casteljau: unknown command '%s': did you mean '%s'? (try 'casteljau --help')\n",
                cli_quote(argv[1], q, sizeof q), near);
    else
        fprintf(stderr, "casteljau: unknown command '%s' (try 'casteljau --help')\n",
                cli_quote(argv[1], q, sizeof q));
    return CLI_EXIT_USAGE;
}
