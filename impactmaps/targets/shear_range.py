"""Where a shear-deformable structural theory stops holding: the thickness-shear cut-off.

Timoshenko beams and Mindlin plates describe flexural waves longer than a few
thicknesses. Their second branch (thickness-shear) starts at the cut-off frequency

* Mindlin plate: ``ω_s = sqrt(k min(A44, A55) / (ρh³/12))``;
* Timoshenko beam: ``ω_s = sqrt(kGA / (ρI))``,

which for an isotropic section is ``sqrt(12 k G/(ρ h²)) ≈ 3.2 c_s/h`` either way. An impact
whose contact frequency ω = sqrt(K/m_i) comes near it excites waves as short as the
thickness, where neither theory describes the solid (and where 3D effects the contact
law does not hold take over). The toolkit therefore refuses to vouch for a shear-deformable
result whose contact frequency exceeds :data:`SHEAR_VALIDITY_FRACTION` of ω_s: map points
there are ``unresolved`` (:mod:`impactmaps.maps.family.accuracy`). At that fraction the flexural
wavelength at ω is ≈ 4.5 thicknesses (kh ≈ 1.4 for steel), where Mindlin's flexural
branch still follows the exact Rayleigh–Lamb A0 branch closely.

Nor do the closed-form infinite-structure solutions of the classical theories (the
Kirchhoff plate's dashpot 8 sqrt(Dρh), the Euler beam's t^(-1/2) kernel) answer for a
shear-deformable target: a point-loaded Mindlin plate's deflection under the load is
unbounded (logarithmic), a Timoshenko beam's carries the shear compliance.
:func:`has_classical_asymptote` says which targets the asymptotes serve.

Each target says its own range (:meth:`~impactmaps.targets.base.Target.thickness_shear_frequency`,
:attr:`~impactmaps.targets.base.Target.has_classical_asymptote`); the functions here ask it,
and answer for any other object (a :class:`~impactmaps.targets.base.ModalBasis`) as for a
classical theory without an asymptote.
"""

from __future__ import annotations

__all__ = ["SHEAR_VALIDITY_FRACTION", "beyond_shear_theory", "has_classical_asymptote",
           "thickness_shear_frequency"]

#: Largest contact frequency, as a fraction of the thickness-shear cut-off, at which a
#: shear-deformable result is vouched for.
SHEAR_VALIDITY_FRACTION = 0.25


def thickness_shear_frequency(target) -> float | None:
    """The thickness-shear cut-off ω_s [rad/s] of a shear-deformable target.

    Parameters
    ----------
    target : Target
        Any target (or object); it says its cut-off
        (:meth:`~impactmaps.targets.base.Target.thickness_shear_frequency`).

    Returns
    -------
    float or None
        ``sqrt(k min(A44, A55)/(ρh³/12))`` (Mindlin plate), ``sqrt(kGA/(ρI))`` (Timoshenko
        beam) [rad/s]; None for the classical theories and objects that are no target.
    """
    method = getattr(target, "thickness_shear_frequency", None)
    return None if method is None else method()


def beyond_shear_theory(target, contact_frequency: float) -> bool:
    """Whether a contact frequency [rad/s] lies beyond what a shear-deformable theory holds.

    True when ``contact_frequency > SHEAR_VALIDITY_FRACTION · ω_s``
    (:func:`thickness_shear_frequency`); always False for the classical theories.
    """
    cutoff = thickness_shear_frequency(target)
    return cutoff is not None and float(contact_frequency) > SHEAR_VALIDITY_FRACTION * cutoff


def has_classical_asymptote(target) -> bool:
    """Whether the closed-form infinite-structure solutions hold for ``target``'s theory.

    True for Euler beams and Kirchhoff plates, as the target says
    (:attr:`~impactmaps.targets.base.Target.has_classical_asymptote`).
    """
    return bool(getattr(target, "has_classical_asymptote", False))
