"""Reading maps: one reader of (ζ, λ) and (β, ζ, λ) maps and the lookups; imports nothing of the build side."""
