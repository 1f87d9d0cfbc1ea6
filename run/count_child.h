/* count_child.h — the counting child of the Instructions pass (run/callgrind.h
 * starts it under Valgrind callgrind with --collect-atstart=no and
 * --instr-atstart=no).
 *
 * `dmbench __instructions SWEEP HASH [--source PATH HASH]... KEY...`
 * (argv[0] is "__instructions") loads the sweep named by SWEEP, checks its
 * hash and that of each user technique's file (the text it loaded, or the
 * file on disk when loading failed), then counts the configurations in
 * batches of up to 8: each prepared in a fresh GL context of its own and
 * warmed up (CALLGRIND_WARMUP_FRAMES, and one frame of each stage window
 * when stage counters are asked for) uninstrumented, then the batch's
 * CALLGRIND_SAMPLES samples of CALLGRIND_FRAMES frames per window with
 * instrumentation switched on once for the batch, each window after one
 * settling frame, collection on only around each sample and its closing
 * glFinish, one dump "KEY.S" per sample (a mesh of 2^18 triangles or more
 * is counted as soon as it is prepared, instrumentation on around each
 * window's samples only).  It writes "W KEY" (preparing it) / "B KEY"
 * (counting it) / "S KEY ok|unavailable REASON" / "I KEY ok|failed
 * REASON" lines to stdout, or one "C WHAT CHANGED" line and nothing else
 * when a file changed.  No store, no timing, no images.
 *
 * The process is made repeatable first: a fixed malloc mode, a fixed
 * arc4random_buf stream and a page-aligned stack (docs/counters.md,
 * "Repeatability").
 */
#ifndef RUN_COUNT_CHILD_H
#define RUN_COUNT_CHILD_H

/* The child's entry point; returns the process exit code. */
int count_child_main(int argc, char **argv);

#endif
