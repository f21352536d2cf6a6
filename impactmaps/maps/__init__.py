"""The ζ–λ maps: sweeps, resumable stores, regimes, lookup tables."""
