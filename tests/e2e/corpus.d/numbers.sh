# corpus.d/numbers.sh — numbers read back (non-finite or missing values in a
# store, results.json or CSV), `predict`, replicated `compare`; sourced by
# corpus.sh.
