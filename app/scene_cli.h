/* Private to the casteljau tool: what the commands that draw scenes (render, trace, animate)
 * share: loading a scene file with its textures, checking the scene and output arguments, and
 * writing a rendered image. */
#ifndef CASTELJAU_APP_SCENE_CLI_H
#define CASTELJAU_APP_SCENE_CLI_H

#include "casteljau/render.h"
#include "casteljau/renderer.h"
#include "casteljau/scene.h"

/* Loads a JSON scene and its image textures (resolved against the scene file's folder) into
 * *out. On failure prints one line (file:line: JSON path ...) and returns CLI_EXIT_USAGE. */
int cli_load_scene(const char *cmd, const char *path, cj_scene **out);

/* Checks -o before any work: it must end in .png (8-bit sRGB) or .exr (linear float), in
 * a folder that can be written. Sets *exr; on failure prints one line and returns
 * CLI_EXIT_USAGE. */
int cli_render_output(const char *cmd, const char *out, int *exr);

/* Writes img opaque (alpha 1): sRGB PNG or linear EXR (exr 1: 32-bit float, 2: half float,
 * as --exr-half asks; cli_open_scene sets 2). Prints a line and returns non-zero on
 * failure (1 for a failed write, as every writer of the tool). */
int cli_write_render(const char *cmd, const char *out, int exr, const cj_render_image *img);

/* The built-in scene of a command (cj_render_demo_scene, cj_trace_demo_scene). */
typedef cj_status (*cli_demo_scene_fn)(const char *teapot_bpt, const cj_allocator *alloc,
                                       cj_scene **out);

/* The arguments render and trace share: their option tables start with CLI_SCENE_OPTIONS, in
 * the order of the CLI_SO_* indices; cli_scene_arg takes those and the scene file. */
#define CLI_SCENE_OPTIONS                                                                          \
    {"--demo", NULL, 0}, {"--stage-report", NULL, 0}, {"--output", "-o", 1}, {"--width", NULL, 1}, \
        {"--height", NULL, 1}, {"--threads", NULL, 1}, {                                           \
        "--exr-half", NULL, 0                                                                      \
    }
enum {
    CLI_SO_DEMO,
    CLI_SO_REPORT,
    CLI_SO_OUT,
    CLI_SO_WIDTH,
    CLI_SO_HEIGHT,
    CLI_SO_THREADS,
    CLI_SO_EXR_HALF,
    CLI_SO_COUNT /* the command's own options start here */
};

typedef struct cli_scene_args {
    const char *scene_path; /* SCENE.json, or NULL */
    const char *out;        /* -o */
    int demo, report;       /* --demo, --stage-report */
    int exr_half;           /* --exr-half: EXR stored as half floats (default 32-bit) */
} cli_scene_args;

/* Takes the positional argument (the scene file; a second one is an error) or the shared
 * option k < CLI_SO_COUNT with its value v into *a, or into opt->width, height, threads.
 * Returns 0, or CLI_EXIT_USAGE after a one-line message naming the bad value. */
int cli_scene_arg(const char *cmd, int k, const char *v, cli_scene_args *a, cj_render_options *opt);

/* What render and trace check once their options are parsed, in this order: exactly one of
 * SCENE.json and --demo, an output -o that cli_render_output accepts (*exr set); then the
 * scene: cli_load_scene, or make_demo of the installation's teapot. On failure prints one line
 * and returns CLI_EXIT_USAGE (nothing to free). */
int cli_open_scene(const char *cmd, const cli_scene_args *a, cli_demo_scene_fn make_demo, int *exr,
                   cj_scene **scene);

/* The end of render and trace: writes img (cli_write_render), prints the summary line
 * (cli_summary: file, size, time since t0, on a terminal), destroys img, then prints the stage
 * report as JSON on stdout when report is not NULL. Returns the command's exit status. */
int cli_finish_render(const char *cmd, const char *out, int exr, cj_render_image *img,
                      const cj_stage_report *report, double t0);

/* One draw of render and trace with a renderer made from ro, as a command shows it
 * (cli_progress.h): a warning first when the work is very large (width x height x samples,
 * times `ray_factor` rays per sample) and when the scene has no lights (unless only object ids
 * are asked for), the progress line on a terminal, Ctrl-C stopping it.
 * On success returns 0 with *img set (the caller writes it). On failure prints one line and
 * returns the exit status: CLI_EXIT_USAGE for a scene the library rejects, 130 after Ctrl-C
 * (nothing written). */
int cli_draw_scene(const char *cmd, const char *name, cj_renderer_options ro, const cj_scene *scene,
                   cj_backend backend, unsigned planes, double ray_factor, cj_render_image **img,
                   cj_stage_report *rep);

struct cli_parser; /* cli.h */

/* A command's own option: k (>= CLI_SO_COUNT) of its table with its value v (NULL for a flag),
 * into ctx (the command's) or opt. Returns 0, or CLI_EXIT_USAGE after a one-line message. */
typedef int (*cli_own_option_fn)(const char *cmd, int k, const char *v, void *ctx,
                                 cj_render_options *opt);

/* The whole first half of render and trace, written once: the argument loop over ps (a table
 * that starts with CLI_SCENE_OPTIONS; cli.h's parser), the shared arguments through
 * cli_scene_arg into *a and opt, the command's own through own_option; then cli_open_scene.
 * Returns -1 when the command goes on (*scene, *exr set), else the exit status to return now
 * (0 after --help or --version, CLI_EXIT_USAGE after a message; nothing to free). */
int cli_scene_command_args(struct cli_parser *ps, cli_own_option_fn own_option, void *ctx,
                           cli_demo_scene_fn make_demo, cli_scene_args *a, cj_render_options *opt,
                           int *exr, cj_scene **scene);

/* The whole second half of render and trace, written once: draws the scene opened by
 * cli_open_scene with a renderer made from ro (cli_draw_scene), destroys the scene, hands the
 * image to `touch` when not NULL (trace --signature recolours the object ids), then
 * cli_finish_render (the file, the summary line, the stage report when --stage-report).
 * Returns the command's exit status. */
int cli_render_scene(const char *cmd, const cli_scene_args *a, int exr, cj_scene *scene,
                     cj_renderer_options ro, cj_backend backend, unsigned planes, double ray_factor,
                     void (*touch)(cj_render_image *img));

#endif
