/* viewer_overlay.c — built-in font and the counters overlay (see viewer_overlay.h). */
#include "viewer/viewer_overlay.h"

#include <ctype.h>
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_util.h"

/* Each glyph: 5 rows of 3 pixels, top row first ('1' = lit). */
static const struct { char c; const char *rows; } viewer__glyphs[] = {
    {'0', "111101101101111"}, {'1', "010110010010111"}, {'2', "111001111100111"},
    {'3', "111001111001111"}, {'4', "101101111001001"}, {'5', "111100111001111"},
    {'6', "111100111101111"}, {'7', "111001010010010"}, {'8', "111101111101111"},
    {'9', "111101111001111"}, {'A', "010101111101101"}, {'B', "110101110101110"},
    {'C', "011100100100011"}, {'D', "110101101101110"}, {'E', "111100110100111"},
    {'F', "111100110100100"}, {'G', "011100101101011"}, {'H', "101101111101101"},
    {'I', "111010010010111"}, {'J', "001001001101010"}, {'K', "101101110101101"},
    {'L', "100100100100111"}, {'M', "101111111101101"}, {'N', "110101101101101"},
    {'O', "010101101101010"}, {'P', "110101110100100"}, {'Q', "010101101110011"},
    {'R', "110101110101101"}, {'S', "011100010001110"}, {'T', "111010010010010"},
    {'U', "101101101101111"}, {'V', "101101101101010"}, {'W', "101101111111101"},
    {'X', "101101010101101"}, {'Y', "101101010010010"}, {'Z', "111001010100111"},
    {' ', "000000000000000"}, {'.', "000000000000010"}, {':', "000010000010000"},
    {'/', "001001010100100"}, {'-', "000000111000000"}, {'=', "000111000111000"},
    {'%', "101001010100101"}, {'(', "010100100100010"}, {')', "010001001001010"},
    {'[', "110100100100110"}, {']', "011001001001011"}, {'?', "111001010000010"},
    {',', "000000000010100"}, {'_', "000000000000111"}, {'|', "010010010010010"},
    {'+', "000010111010000"},
};

static const char *viewer__glyph(char c)
{
    c = (char)toupper((unsigned char)c);
    for (size_t i = 0; i < sizeof viewer__glyphs / sizeof *viewer__glyphs; i++)
        if (viewer__glyphs[i].c == c)
            return viewer__glyphs[i].rows;
    return viewer__glyph('?');
}

static void viewer__put_glyph(uint8_t *px, int w, int x0, int y0, int scale, const char *rows)
{
    for (int gy = 0; gy < VIEWER_FONT_H; gy++)
        for (int gx = 0; gx < VIEWER_FONT_W; gx++) {
            if (rows[gy * VIEWER_FONT_W + gx] != '1')
                continue;
            for (int sy = 0; sy < scale; sy++)
                for (int sx = 0; sx < scale; sx++) {
                    size_t at = ((size_t)(y0 + gy * scale + sy) * (size_t)w +
                                 (size_t)(x0 + gx * scale + sx)) * 4;
                    memset(px + at, 255, 3);
                }
        }
}

uint8_t *viewer_font_raster(const char *text, int scale, int *w, int *h)
{
    int cols = 0, lines = 1, col = 0;
    for (const char *p = text; *p; p++) {
        col = *p == '\n' ? 0 : col + 1;
        lines += *p == '\n';
        cols = col > cols ? col : cols;
    }
    if (!*text || cols == 0)
        return NULL;
    int cw = (VIEWER_FONT_W + 1) * scale, lh = (VIEWER_FONT_H + 1) * scale;
    *w = cols * cw + scale;             /* one font pixel of margin left and top */
    *h = lines * lh + scale;
    uint8_t *px = dm_xcalloc((size_t)*w * (size_t)*h, 4);
    for (size_t i = 3; i < (size_t)*w * (size_t)*h * 4; i += 4)
        px[i] = 255;                    /* opaque black box */
    int x = 0, y = 0;
    for (const char *p = text; *p; p++) {
        if (*p == '\n') {
            x = 0;
            y++;
            continue;
        }
        viewer__put_glyph(px, *w, scale + x * cw, scale + y * lh, scale, viewer__glyph(*p));
        x++;
    }
    return px;
}

struct viewer_overlay {
    GLuint tex, fbo;
    int w, h;
};

/* (Re)creates the texture and its read framebuffer for a w×h box. */
static void viewer__overlay_resize(viewer_overlay *ov, int w, int h)
{
    if (ov->tex) {
        glDeleteFramebuffers(1, &ov->fbo);
        glDeleteTextures(1, &ov->tex);
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &ov->tex);
    glTextureStorage2D(ov->tex, 1, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &ov->fbo);
    glNamedFramebufferTexture(ov->fbo, GL_COLOR_ATTACHMENT0, ov->tex, 0);
    ov->w = w;
    ov->h = h;
}

void viewer_overlay_draw(viewer_overlay **pov, const char *text, int fb_w, int fb_h)
{
    int w = 0, h = 0, scale = fb_w >= 1024 ? 3 : 2;
    uint8_t *px = viewer_font_raster(text, scale, &w, &h);
    if (!px)
        return;
    if (!*pov)
        *pov = dm_xcalloc(1, sizeof **pov);
    viewer_overlay *ov = *pov;
    if (ov->w != w || ov->h != h)
        viewer__overlay_resize(ov, w, h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(ov->tex, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    free(px);
    /* The image is top-down: flip it by swapping the destination rows. */
    glBlitNamedFramebuffer(ov->fbo, 0, 0, 0, w, h, 0, fb_h, w, fb_h - h,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void viewer_overlay_destroy(viewer_overlay *ov)
{
    if (!ov)
        return;
    glDeleteFramebuffers(1, &ov->fbo);
    glDeleteTextures(1, &ov->tex);
    free(ov);
}
