# corpus.d/children.sh — child processes (probe, counting, driver runs) and
# the environment they meet; sourced by corpus.sh.
