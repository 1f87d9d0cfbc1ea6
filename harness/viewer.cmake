# The interactive viewer: `dmbench view` (docs/viewer.md).
set(DM_VIEWER_SOURCES viewer.c viewer_state.c viewer_script.c viewer_measure.c viewer_overlay.c)
