# corpus.d/images.sh — images given to `diff` and maps: non-regular files,
# unreadable or huge images, channel layouts, outputs that cannot be
# written; sourced by corpus.sh.
