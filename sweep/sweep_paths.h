/* sweep_paths.h — axis values that name files, resolved against the sweep
 * file's directory.
 *
 * A sweep file travels with the files it names (a study's OBJ models beside
 * its YAML), so `mesh: file:models/rock.obj` means models/rock.obj next to
 * the sweep file, whatever the working directory.  Absolute paths stay.
 */
#ifndef SWEEP_SWEEP_PATHS_H
#define SWEEP_SWEEP_PATHS_H

/* Returns the value `text` of axis `axis` with a relative file path made
 * relative to the directory of sweep_path: the mesh axis's "file:PATH" and
 * the technique axis's user GLSL files ("PATH.glsl").  Takes ownership of text (heap); returns it unchanged or
 * frees it and returns a new heap string. */
char *sweep_paths_resolve(const char *sweep_path, const char *axis, char *text);

/* The maps a scene.material block may name, in the order of the maps
 * value: height, normal, albedo. */
#define SWEEP_PATHS_MAPS 3
extern const char *const sweep_paths_map_kinds[SWEEP_PATHS_MAPS];
/* The maps axis value "height=P;normal=P;albedo=P" of the user's map files
 * paths[k] (NULL: not given; kinds in sweep_paths_map_kinds), each relative
 * path made relative to the directory of sweep_path and each ';' in a path
 * written ";;".  Heap string; NULL when no path is given. */
char *sweep_paths_maps(const char *sweep_path, const char *const paths[SWEEP_PATHS_MAPS]);

#endif
