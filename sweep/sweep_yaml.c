/* sweep_yaml.c — the guards of sweep_yaml.h. */
#include "sweep/sweep_yaml.h"
#include "core/dm_error.h"

#include <stdlib.h>

int sweep_yaml_depth_check(yaml_document_t *doc, const char *path, dm_str *err)
{
    size_t n = (size_t)(doc->nodes.top - doc->nodes.start);
    int *depth = dm_xcalloc(n + 2, sizeof *depth), rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++) {
        yaml_node_t *nd = &doc->nodes.start[i];
        int kids[2];
        for (size_t j = 0; ; j++) {
            size_t nk = 0;
            if (nd->type == YAML_SEQUENCE_NODE &&
                nd->data.sequence.items.start + j < nd->data.sequence.items.top)
                kids[nk++] = nd->data.sequence.items.start[j];
            if (nd->type == YAML_MAPPING_NODE &&
                nd->data.mapping.pairs.start + j < nd->data.mapping.pairs.top) {
                kids[nk++] = nd->data.mapping.pairs.start[j].key;
                kids[nk++] = nd->data.mapping.pairs.start[j].value;
            }
            if (nk == 0)
                break;
            for (size_t k = 0; k < nk; k++)
                if (kids[k] >= 1 && (size_t)kids[k] <= n && depth[kids[k] - 1] < depth[i] + 1)
                    depth[kids[k] - 1] = depth[i] + 1;
        }
        if (depth[i] > SWEEP_YAML_MAX_DEPTH) {
            dm_str_printf(err, "%s:%zu:%zu: nested deeper than %d levels; a sweep file is "
                          "never that deep", path, nd->start_mark.line + 1,
                          nd->start_mark.column + 1, SWEEP_YAML_MAX_DEPTH);
            rc = DM_ERR_PARSE;
        }
    }
    free(depth);
    return rc;
}
