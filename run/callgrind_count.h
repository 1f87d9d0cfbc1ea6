/* callgrind_count.h — the plain data of the Instructions pass: its
 * constants, the stage windows and the count of one configuration.  A leaf:
 * the parent side (run/callgrind.h), the counting child
 * (run/count_child.h) and the timed scene that records the counts
 * (run/measure.h) read it; it includes nothing of theirs.
 */
#ifndef RUN_CALLGRIND_COUNT_H
#define RUN_CALLGRIND_COUNT_H

/* Samples per configuration; they must agree (the count is deterministic). */
#define CALLGRIND_SAMPLES 2
/* Frames per sample, and warm-up frames before the first: every frame of a
 * configuration does the same work once the first has compiled its shaders
 * and touched its maps, and with the allocator left out the count repeats
 * to the instruction, so one frame (its draws and the glFinish that
 * completes them, as a presented frame would) is the count per frame.  At
 * ~300x slower frames under Valgrind, every frame not counted is cost. */
#define CALLGRIND_FRAMES 1
#define CALLGRIND_WARMUP_FRAMES 1
/* A configuration on a camera path counts one replay of its path instead
 * (its frames differ: a dolly changes the view every frame), at most this
 * many frames of it: every k-th frame, k = ceil(F / CALLGRIND_PATH_FRAMES),
 * so a path costs at most this many still configurations under Valgrind
 * (callgrind_path_frames; docs/counters.md, "On a camera path"). */
#define CALLGRIND_PATH_FRAMES 16
/* Samples whose counts differ by more than this relative amount are a
 * warning of the run (results.json, report) and in the configuration's log.
 * Within one child they agreed to <= 3.1e-5 everywhere measured; counts of
 * separate children can still differ more on tessellation (docs/counters.md,
 * "Repeatability"). */
#define CALLGRIND_AGREE 1e-4
/* The counting child's malloc: blocks from this size up are mmapped, the
 * heap's top is neither padded nor kept (docs/counters.md, "Repeatability"). */
#define CALLGRIND_MMAP_THRESHOLD 4096
/* The counting child's stack starts at the same offset in a page of this
 * size in every process, whatever the length of its arguments and
 * environment. */
#define CALLGRIND_STACK_ALIGN 4096
/* At most this many counting children by default, and no more than one
 * per CALLGRIND_JOB_GIB of available memory: each is a Valgrind of dmbench
 * and llvmpipe (measured: 0.5 GiB resident at 480x270). */
#define CALLGRIND_MAX_JOBS 8
#define CALLGRIND_JOB_GIB 2.0

/* The stage-isolation windows of a configuration whose sweep asks for a
 * stage counter (callgrind_wants_stages; docs/counters.md, "Stage costs"),
 * counted in the same child after the full frame's samples: the same
 * frames with GL_RASTERIZER_DISCARD (dumps "KEY.g.S") and with the minimal
 * fragment shader (techniques/fs_minimal.h, dumps "KEY.r.S"). */
typedef enum callgrind_window {
    CALLGRIND_FULL = 0,      /* the frame as measured: Instructions */
    CALLGRIND_GEOMETRY,      /* rasterizer discard: vertex, tessellation, assembly, clipping */
    CALLGRIND_RASTER,        /* minimal fragment shader: geometry + setup + rasterization */
    CALLGRIND_RESIDUAL,      /* minimal fragment shader with rasterizer discard ("KEY.m.S"):
                                equals GEOMETRY when the minimal shader kept the geometry's work */
    CALLGRIND_WINDOWS
} callgrind_window;

/* The result of one configuration. */
typedef struct callgrind_count {
    char key[17];
    int counted;             /* samples[] are set */
    double samples[CALLGRIND_SAMPLES];   /* instructions per frame, one per sample, allocator left out */
    double allocator[CALLGRIND_SAMPLES]; /* the C allocator's instructions per frame, left out of samples */
    int staged;              /* window[] are set (stage counters) */
    double window[CALLGRIND_WINDOWS][CALLGRIND_SAMPLES];   /* per frame; [FULL] = samples */
    char *stage_reason;      /* why the stage counters are unavailable, NULL when staged */
    int failed;              /* Valgrind crashed or timed out on it: the configuration fails */
    char *reason;            /* why not counted (unavailable or failed), NULL when counted */
} callgrind_count;

#endif
