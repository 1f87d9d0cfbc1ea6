/* fs_minimal.h — the minimal fragment shader of the stage-isolation passes
 * (docs/counters.md, "Stage costs").
 *
 * The raster pass draws a configuration with the same vertex and
 * tessellation stages, depth state and coverage as the full frame but with
 * almost no fragment shading.  Its fragment shader cannot simply be a
 * constant colour: the GL linker drops every vertex output the fragment
 * stage does not read, and the code computing it, so the geometry stages
 * would do less work than in the full frame.  fs_minimal_make therefore
 * rewrites the technique's own (composed) fragment shader: its main becomes
 * an unused function (the compiler removes it and everything only it
 * called), and a new main reads every input the original reads once, sums
 * them and writes the
 * sum to every output, plus gl_FragDepth = gl_FragCoord.z when the original
 * writes depth (so early depth testing stays off as in the full frame).
 * Pure text; no GL.
 */
#ifndef TECHNIQUES_FS_MINIMAL_H
#define TECHNIQUES_FS_MINIMAL_H

#include "core/dm_util.h"

/* The define that selects the minimal fragment shader in a program key;
 * its value is the rewrite's version (raise it when the rewrite changes, so
 * no cached binary of an older rewrite is loaded). */
#define FS_MINIMAL_DEFINE "#define STAGE_MINIMAL_FS 2\n"

/* What a fragment shader does that isolation cannot keep exactly. */
typedef struct fs_traits {
    int discards;        /* `discard`: the minimal shader keeps fragments the full one drops */
    int writes_depth;    /* gl_FragDepth: early depth off, kept by the minimal shader */
} fs_traits;

/* Scans a composed fragment shader (comments ignored). */
void fs_minimal_traits(const char *src, fs_traits *out);

/* Rewrites a composed fragment shader into its minimal form (see the top
 * comment) into out.  `active` lists, one per line, the inputs the
 * compiler found active in the original shader, as GL names them
 * ("Block.member", "name", "Block.arr[0]"): only those are read, as the
 * original reads them (an input it never reads is dropped by the linker in
 * the full frame too); NULL reads every input.  Returns 0, or DM_ERR_PARSE
 * with the reason in why (no main, an input of a type it cannot read); out
 * is then unchanged. */
int fs_minimal_make(const char *src, const char *active, dm_str *out, dm_str *why);

#endif
