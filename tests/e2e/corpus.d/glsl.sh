# corpus.d/glsl.sh — user GLSL techniques (header, parameters, sources
# changed during a run), sourced by corpus.sh.
