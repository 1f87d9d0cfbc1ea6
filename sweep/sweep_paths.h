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

#endif
