/* count_child.h — the counting child of the Instructions pass (run/callgrind.h
 * starts it under Valgrind callgrind with --collect-atstart=no and
 * --instr-atstart=no).
 *
 * `dmbench __instructions SWEEP HASH [--source PATH HASH]... KEY...`
 * (argv[0] is "__instructions") loads the sweep named by SWEEP, checks its
 * hash and that of each user technique's file (the text it loaded, or the
 * file on disk when loading failed), then per configuration, each in a
 * fresh GL context: prepare, warm up (CALLGRIND_WARMUP_FRAMES), both
 * uninstrumented, then CALLGRIND_SAMPLES samples of CALLGRIND_FRAMES
 * frames with instrumentation on around the samples and collection on
 * only around each sample and its closing glFinish, one dump "KEY.S" per
 * sample; with stage counters asked for, the stage windows too, each
 * instrumented the same way.  It writes
 * "B KEY" / "S KEY ok|unavailable REASON" / "I KEY ok|failed REASON"
 * lines to stdout, or one "C WHAT CHANGED" line and nothing else when a
 * file changed.  No store, no timing, no images.
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
