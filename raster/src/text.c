/* FreeType text rendering into bottom-up RGBA8 images (see casteljau/text.h). */
#include "casteljau/text.h"

#include "error_internal.h"

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

struct cj_font {
    FT_Library lib;
    FT_Face face;
    int size; /* pixel size currently set on the face, 0 = none */
};

static int readable(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fclose(f);
    return 1;
}

/* The fontconfig answer, looked up once per process (fontconfig's set-up costs a few
 * milliseconds: its configuration and cache files). */
static pthread_once_t lookup_once = PTHREAD_ONCE_INIT;
static char found_path[4096];
static char lookup_error[512];

static void lookup_font(void) {
    FcConfig *config = FcInitLoadConfigAndFonts();
    if (!config) {
        snprintf(lookup_error, sizeof lookup_error, "fontconfig could not load its configuration");
        return;
    }
    /* DejaVu Sans, the font the plots are laid out with; fontconfig's rules may substitute the
     * nearest sans-serif face when it is not installed. Scalable only: FreeType renders at
     * any size. */
    FcPattern *want = FcNameParse((const FcChar8 *)CJ_FONT_FAMILY);
    FcResult result = FcResultNoMatch;
    FcPattern *match = NULL;
    if (want) {
        FcPatternAddBool(want, FC_SCALABLE, FcTrue);
        FcConfigSubstitute(config, want, FcMatchPattern);
        FcDefaultSubstitute(want);
        match = FcFontMatch(config, want, &result);
    }
    FcChar8 *file = NULL;
    FcBool scalable = FcFalse;
    if (match && FcPatternGetString(match, FC_FILE, 0, &file) == FcResultMatch &&
        FcPatternGetBool(match, FC_SCALABLE, 0, &scalable) == FcResultMatch && scalable &&
        readable((const char *)file) &&
        snprintf(found_path, sizeof found_path, "%s", (const char *)file) <
            (int)sizeof found_path) {
        /* found */
    } else {
        found_path[0] = '\0';
        snprintf(lookup_error, sizeof lookup_error,
                 "no font for text: fontconfig finds no scalable font for '%s'%s%s%s (install "
                 "fonts-dejavu-core, or set CJ_FONT to a .ttf file)",
                 CJ_FONT_FAMILY, file ? " (it offered '" : "", file ? (const char *)file : "",
                 file ? "')" : "");
    }
    if (match) FcPatternDestroy(match);
    if (want) FcPatternDestroy(want);
    FcConfigDestroy(config);
}

const char *cj_font_find_default(void) {
    const char *env = getenv("CJ_FONT");
    if (env && *env) {
        if (readable(env)) return env;
        cj_fail(CJ_ERR_UNSUPPORTED, "CJ_FONT='%s' is not a readable font file", env);
        return NULL;
    }
    pthread_once(&lookup_once, lookup_font);
    if (found_path[0]) return found_path;
    cj_fail(CJ_ERR_UNSUPPORTED, "%s", lookup_error);
    return NULL;
}

cj_status cj_font_open(const char *path, cj_font **out) {
    assert(out);
    if (!path) {
        path = cj_font_find_default();
        if (!path) return CJ_ERR_UNSUPPORTED; /* message already recorded */
    }
    cj_font *f = calloc(1, sizeof *f);
    if (!f) return cj_fail(CJ_ERR_NOMEM, "no memory for a font");
    FT_Error e = FT_Init_FreeType(&f->lib);
    if (e) {
        free(f);
        return cj_fail(CJ_ERR_IO, "FreeType failed to initialise (error %d)", (int)e);
    }
    e = FT_New_Face(f->lib, path, 0, &f->face);
    if (e) {
        FT_Done_FreeType(f->lib);
        free(f);
        return cj_fail(CJ_ERR_IO, "cannot load font '%s' (FreeType error %d%s)", path, (int)e,
                       e == FT_Err_Cannot_Open_Resource  ? ": cannot open the file"
                       : e == FT_Err_Unknown_File_Format ? ": not a font file"
                                                         : "");
    }
    *out = f;
    return CJ_OK;
}

void cj_font_close(cj_font *font) {
    if (!font) return;
    FT_Done_Face(font->face);
    FT_Done_FreeType(font->lib);
    free(font);
}

/* Decodes one UTF-8 code point at *s, advancing *s; returns -1 on malformed input. */
static long utf8_next(const unsigned char **s) {
    const unsigned char *p = *s;
    long c;
    int extra;
    if (p[0] < 0x80) {
        c = p[0];
        extra = 0;
    } else if ((p[0] & 0xE0) == 0xC0) {
        c = p[0] & 0x1F;
        extra = 1;
    } else if ((p[0] & 0xF0) == 0xE0) {
        c = p[0] & 0x0F;
        extra = 2;
    } else if ((p[0] & 0xF8) == 0xF0) {
        c = p[0] & 0x07;
        extra = 3;
    } else {
        return -1;
    }
    for (int k = 1; k <= extra; ++k) {
        if ((p[k] & 0xC0) != 0x80) return -1;
        c = (c << 6) | (p[k] & 0x3F);
    }
    *s = p + 1 + extra;
    return c;
}

static cj_status set_size(cj_font *font, double size_px) {
    if (!(size_px >= 4.0 && size_px <= 512.0))
        return cj_fail(CJ_ERR_RANGE, "text size %g px is not between 4 and 512", size_px);
    int px = (int)lround(size_px);
    if (px != font->size) {
        FT_Error e = FT_Set_Pixel_Sizes(font->face, 0, (FT_UInt)px);
        if (e)
            return cj_fail(CJ_ERR_ARGUMENT, "font has no %d px size (FreeType error %d)", px,
                           (int)e);
        font->size = px;
    }
    return CJ_OK;
}

typedef struct blit_target {
    cj_framebuffer *fb;
    long x0, y0; /* baseline origin in whole pixels */
    cj_rgba color;
} blit_target;

static void blit(const blit_target *t, const FT_Bitmap *bm, long left, long top) {
    /* Bitmap row r (top-down) lands on framebuffer row y0 + top - 1 - r (bottom-up). */
    for (unsigned r = 0; r < bm->rows; ++r) {
        long py = t->y0 + top - 1 - (long)r;
        if (py < 0 || py >= t->fb->height) continue;
        const unsigned char *src = bm->buffer + (long)r * bm->pitch;
        for (unsigned c = 0; c < bm->width; ++c)
            if (src[c])
                cj_framebuffer_blend_coverage(t->fb, t->x0 + left + (long)c, py, t->color,
                                              (float)src[c] / 255.0f);
    }
}

static cj_status run(cj_font *font, const char *utf8, const blit_target *t, long *advance26) {
    const unsigned char *s = (const unsigned char *)utf8;
    long pen = 0;
    FT_UInt prev = 0;
    const int kern = FT_HAS_KERNING(font->face);
    while (*s) {
        size_t at = (size_t)(s - (const unsigned char *)utf8);
        long cp = utf8_next(&s);
        if (cp < 0) return cj_fail(CJ_ERR_PARSE, "text has invalid UTF-8 at byte %zu", at);
        FT_UInt gi = FT_Get_Char_Index(font->face, (FT_ULong)cp);
        if (kern && prev && gi) {
            FT_Vector d;
            if (!FT_Get_Kerning(font->face, prev, gi, FT_KERNING_DEFAULT, &d)) pen += d.x;
        }
        FT_Error e = FT_Load_Glyph(font->face, gi, t ? FT_LOAD_RENDER : FT_LOAD_DEFAULT);
        if (e)
            return cj_fail(CJ_ERR_IO, "FreeType cannot load glyph U+%04lX (error %d)", cp, (int)e);
        FT_GlyphSlot g = font->face->glyph;
        if (t) blit(t, &g->bitmap, g->bitmap_left + (pen + 32) / 64, g->bitmap_top);
        pen += g->advance.x;
        prev = gi;
    }
    *advance26 = pen;
    return CJ_OK;
}

cj_status cj_font_measure(cj_font *font, double size_px, const char *utf8, double *advance,
                          double *ascent, double *descent) {
    assert(font && utf8);
    cj_status st = set_size(font, size_px);
    if (st) return st;
    long adv = 0;
    st = run(font, utf8, NULL, &adv);
    if (st) return st;
    if (advance) *advance = (double)adv / 64.0;
    if (ascent) *ascent = (double)font->face->size->metrics.ascender / 64.0;
    if (descent) *descent = -(double)font->face->size->metrics.descender / 64.0;
    return CJ_OK;
}

cj_status cj_font_draw(cj_font *font, cj_framebuffer *fb, double x, double y, double size_px,
                       cj_rgba color, const char *utf8) {
    assert(font && fb && utf8);
    if (!isfinite(x) || !isfinite(y))
        return cj_fail(CJ_ERR_NONFINITE, "text position (%g, %g) is not finite", x, y);
    cj_status st = set_size(font, size_px);
    if (st) return st;
    if (fabs(x) > 1e9 || fabs(y) > 1e9) return CJ_OK; /* far outside any framebuffer */
    blit_target t = {fb, lround(x), lround(y), color};
    long adv = 0;
    return run(font, utf8, &t, &adv);
}
