/* Replay scripts of the viewer: one event per line, driving the same handlers as real input.
 *
 *   key NAME [ctrl] [shift] [alt]        a key press (NAME: a-z, 0-9, escape, tab, delete,
 *                                        backspace, home, space, f1, f5, [ ] + - /)
 *   press BUTTON X Y [mods]              BUTTON: left | right | middle; X Y window pixels
 *   move X Y [mods]                      (x right, y down from the top-left corner, as GLFW)
 *   release BUTTON X Y [mods]
 *   drag BUTTON X0 Y0 X1 Y1 [steps N] [mods]   press, N moves (default 8), release
 *   scroll DY                            wheel (positive = away from the user = zoom in)
 *   t VALUE                              2D: the parameter t of the selected curve
 *   select CURVE [POINT]                 2D: curve (and point) indices; 3D: a control point
 *   frame                                draw a frame now (each input event draws one anyway)
 *   screenshot PATH                      PNG of the back buffer
 *   save PATH                            save the document/scene to PATH
 * Blank lines and lines starting with # are ignored. */
#include "viewer_app.h"

#include "error_internal.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int key_code(const char *s) {
    static const struct {
        const char *name;
        int key;
    } named[] = {{"escape", GLFW_KEY_ESCAPE},  {"tab", GLFW_KEY_TAB},
                 {"delete", GLFW_KEY_DELETE},  {"backspace", GLFW_KEY_BACKSPACE},
                 {"home", GLFW_KEY_HOME},      {"space", GLFW_KEY_SPACE},
                 {"f1", GLFW_KEY_F1},          {"f5", GLFW_KEY_F5},
                 {"[", GLFW_KEY_LEFT_BRACKET}, {"]", GLFW_KEY_RIGHT_BRACKET},
                 {"+", GLFW_KEY_EQUAL},        {"=", GLFW_KEY_EQUAL},
                 {"-", GLFW_KEY_MINUS},        {"/", GLFW_KEY_SLASH}};
    for (size_t i = 0; i < sizeof named / sizeof named[0]; ++i)
        if (!strcmp(s, named[i].name)) return named[i].key;
    if (s[0] && !s[1]) {
        if (s[0] >= 'a' && s[0] <= 'z') return GLFW_KEY_A + (s[0] - 'a');
        if (s[0] >= '0' && s[0] <= '9') return GLFW_KEY_0 + (s[0] - '0');
    }
    return -1;
}

static int button_code(const char *s) {
    return !strcmp(s, "left")     ? VIEW_BUTTON_LEFT
           : !strcmp(s, "right")  ? VIEW_BUTTON_RIGHT
           : !strcmp(s, "middle") ? VIEW_BUTTON_MIDDLE
                                  : -1;
}

static int num(const char *s, double *out) {
    char *end;
    if (!s) return -1;
    *out = strtod(s, &end);
    return (end == s || *end) ? -1 : 0;
}

cj_status cj_viewer_parse_line(const char *script, int lineno, const char *line, cj_vevent *ev,
                               size_t cap, size_t *n) {
    char buf[1200];
    char *w[16];
    int nw = 0;
    *n = 0;
    snprintf(buf, sizeof buf, "%s", line);
    for (char *tok = strtok(buf, " \t\r\n"); tok && nw < 16; tok = strtok(NULL, " \t\r\n"))
        w[nw++] = tok;
    if (!nw || w[0][0] == '#') return CJ_OK;
    cj_vevent e;
    memset(&e, 0, sizeof e);
    /* trailing modifier words */
    while (nw > 1) {
        const char *m = w[nw - 1];
        const int bit = !strcmp(m, "shift")  ? VIEW_MOD_SHIFT
                        : !strcmp(m, "ctrl") ? VIEW_MOD_CTRL
                        : !strcmp(m, "alt")  ? VIEW_MOD_ALT
                                             : 0;
        if (!bit) break;
        e.mods |= bit;
        --nw;
    }
    const char *cmd = w[0];
    double a[4];
#define BAD(msg) cj_fail(CJ_ERR_PARSE, "%s:%d: %s", script, lineno, msg)
    if (!strcmp(cmd, "key")) {
        if (nw != 2 || (e.key = key_code(w[1])) < 0) return BAD("key NAME [ctrl] [shift] [alt]");
        e.type = VEV_KEY;
    } else if (!strcmp(cmd, "press") || !strcmp(cmd, "release")) {
        if (nw != 4 || (e.button = button_code(w[1])) < 0 || num(w[2], &e.x) || num(w[3], &e.y))
            return BAD("press|release left|right|middle X Y");
        e.type = cmd[0] == 'p' ? VEV_PRESS : VEV_RELEASE;
    } else if (!strcmp(cmd, "move")) {
        if (nw != 3 || num(w[1], &e.x) || num(w[2], &e.y)) return BAD("move X Y");
        e.type = VEV_MOVE;
    } else if (!strcmp(cmd, "drag")) {
        double steps = 8;
        if ((nw != 6 && nw != 8) || (e.button = button_code(w[1])) < 0 || num(w[2], &a[0]) ||
            num(w[3], &a[1]) || num(w[4], &a[2]) || num(w[5], &a[3]) ||
            (nw == 8 &&
             (strcmp(w[6], "steps") || num(w[7], &steps) || steps < 1 || steps > 100000)))
            return BAD("drag BUTTON X0 Y0 X1 Y1 [steps N] [mods]");
        const size_t ns = (size_t)steps;
        if (ns + 2 > cap) return BAD("drag has too many steps");
        e.type = VEV_PRESS;
        e.x = a[0], e.y = a[1];
        ev[(*n)++] = e;
        for (size_t i = 1; i <= ns; ++i) {
            e.type = VEV_MOVE;
            e.x = a[0] + (a[2] - a[0]) * (double)i / (double)ns;
            e.y = a[1] + (a[3] - a[1]) * (double)i / (double)ns;
            ev[(*n)++] = e;
        }
        e.type = VEV_RELEASE;
        ev[(*n)++] = e;
        return CJ_OK;
    } else if (!strcmp(cmd, "scroll")) {
        if (nw != 2 || num(w[1], &e.y)) return BAD("scroll DY");
        e.type = VEV_SCROLL;
    } else if (!strcmp(cmd, "t")) {
        if (nw != 2 || num(w[1], &e.x) || !(e.x >= 0 && e.x <= 1)) return BAD("t VALUE in [0, 1]");
        e.type = VEV_T;
    } else if (!strcmp(cmd, "select")) {
        e.y = -1;
        if ((nw != 2 && nw != 3) || num(w[1], &e.x) || (nw == 3 && num(w[2], &e.y)))
            return BAD("select CURVE [POINT]");
        e.type = VEV_SELECT;
    } else if (!strcmp(cmd, "frame")) {
        e.type = VEV_FRAME;
    } else if (!strcmp(cmd, "screenshot") || !strcmp(cmd, "save")) {
        if (nw != 2) return BAD("screenshot|save PATH");
        e.type = cmd[1] == 'c' ? VEV_SCREENSHOT : VEV_SAVE;
        snprintf(e.arg, sizeof e.arg, "%s", w[1]);
    } else {
        return BAD("unknown command (key press move release drag scroll t select frame "
                   "screenshot save)");
    }
#undef BAD
    ev[(*n)++] = e;
    return CJ_OK;
}

void cj_viewer_apply(cj_viewer *v, const cj_vevent *e) {
    switch (e->type) {
    case VEV_KEY:
        cj_viewer_key(v, e->key, e->mods);
        break;
    case VEV_PRESS:
        cj_viewer_button(v, e->button, 1, e->mods, e->x, e->y);
        break;
    case VEV_RELEASE:
        cj_viewer_button(v, e->button, 0, e->mods, e->x, e->y);
        break;
    case VEV_MOVE:
        cj_viewer_cursor(v, e->x, e->y, e->mods);
        break;
    case VEV_SCROLL:
        cj_viewer_scroll(v, e->y);
        break;
    case VEV_T:
        v->disp.t = e->x;
        v->dirty = 1;
        break;
    case VEV_SELECT:
        if (v->mode3d) {
            if (e->x >= 0 && e->x < (double)cj_vscene_point_count(v->vs)) v->sel3 = (long)e->x;
        } else if (e->x >= 0 && e->x < (double)cj_vdoc_curve_count(v->doc)) {
            v->disp.curve = (long)e->x;
            const cj_vcurve *c = cj_vdoc_curve(v->doc, (size_t)e->x);
            v->sel_point = (e->y >= 0 && e->y < (double)c->count) ? (long)e->y : -1;
        }
        v->dirty = 1;
        break;
    default:
        break;
    }
}
