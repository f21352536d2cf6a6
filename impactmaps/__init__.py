"""impactmaps — low-velocity impact of a sphere on beams and plates.

Force histories for physical cases, the dimensionless (β, λ, ζ) picture of
Christoforou & Yigit (1998), the normalised maximum-force maps, regimes and design
lookups, all verified against exact solutions.
"""

__version__ = "0.1.0"
