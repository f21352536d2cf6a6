"""The dimensionless framework of seed 001 (docs/physics_contract.md §1 and §4).

With a linear contact spring ``F = K α`` the impact of a sphere of mass ``m_i`` at
speed ``V0`` is scaled by the contact frequency ``ω = sqrt(K/m_i)``: time ``τ = ω t``,
indentation ``ᾱ = α/α*`` with the half-space indentation ``α* = V0/ω``, force
``F̄ = F/(m_i V0 ω)`` (seed 001 eq 26). The normalised response of a given structure type
then depends on two numbers only (seed 001 section 4):

* the relative stiffness ``λ = K_st/K`` (eq 29), ``K_st`` the static point stiffness of
  the target at the impact point, which governs the quasi-static limit;
* the loss factor ``ζ`` (eq 34 for plates, the corrected eq 38 for beams), which
  governs the response of the infinite structure (before reflections return).

Given a target, ``(ζ, λ)`` fixes the impactor: :func:`realise`.

:mod:`~impactmaps.dimensionless.groups` holds the groups and their formulas,
:mod:`~impactmaps.dimensionless.realisation` the way back from (ζ, λ) to SI.

All functions accept scalars or arrays (NumPy broadcasting) and validate their inputs
through :mod:`impactmaps._checks`, so bad input raises a ``ValueError`` naming the
parameter.

**Correction (beam loss factor, docs/physics_contract.md §1).** The driving-point velocity of an
infinite Euler–Bernoulli beam under a force ``F(t)`` is

    ẇ(t) = 1/(2 sqrt(2π) m' c^{1/2}) ∫0^t F(ξ)/sqrt(t − ξ) dξ,   c = sqrt(EI/m'),

(its Laplace transform is the textbook point mobility ``(1 − i)/(4 m' c_B)``,
``c_B = sqrt(ω c)``). Seed 001 eq (35) lacks the factor 1/2, and its eq (38) is twice
the loss factor for which the normalised infinite-beam equation (36),
``ᾱ'' + 2ζ ∫0^τ ᾱ'(s)/sqrt(τ − s) ds + ᾱ = 0``, holds. impactmaps therefore defines
``ζ_b = (1/(4 sqrt(2π))) (m_i/m')^{3/4} (K/(b D11))^{1/4}`` (:func:`loss_factor_beam`)
and offers :func:`loss_factor_beam_paper` ``= 2 ζ_b`` for comparison with the printed
paper. ``tests/test_dimensionless.py`` re-derives both constants from the wave-number
integrals of the infinite beam and plate.
"""

from __future__ import annotations

from . import groups, realisation

from .groups import *  # noqa: F403 (the names of groups.__all__)
from .realisation import *  # noqa: F403 (the names of realisation.__all__)

__all__ = groups.__all__ + realisation.__all__
