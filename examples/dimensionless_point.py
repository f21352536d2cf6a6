"""One point (ζ, λ) of the maximum-force chart: simulation, shipped map and asymptotes.

Physics: with a linear contact spring K, the peak contact force of a sphere (mass m_i,
velocity V0) on a simply supported square Kirchhoff plate struck at its centre depends
on two numbers only: the loss factor ζ = (1/16) sqrt(m_i K/(ρh D)) (how much energy
the plate carries away before waves return) and the relative stiffness λ = K_st/K
(static plate stiffness over contact stiffness). F̄max = F_max/(m_i V0 ω), ω = sqrt(K/m_i),
is 1 on a rigid half-space.

The script realises (ζ, λ) = (1, 1) on a 300 mm aluminium plate (the impactor mass and
contact stiffness that give this point), simulates it, reads the same point from the
shipped design map without a simulation, and compares with the two asymptotes: the
infinite plate (F̄max depends on ζ alone) and the quasi-static spring pair
(F̄max = sqrt(λ/(1+λ))). The independent reference table gives F̄max = 0.720 ± 0.002
(tests/data/fmax_reference.csv).

    python examples/dimensionless_point.py
"""

from impactmaps.dimensionless import realise
from impactmaps import lookup
from impactmaps.maps.family.regimes import infinite_structure_peak, quasi_static_peak
from impactmaps.materials import material
from impactmaps.solvers.modal import simulate_normalised
from impactmaps.targets.plates.plate import Plate

zeta, lam = 1.0, 1.0
plate = Plate.isotropic(0.3, 0.3, 0.004, material("aluminium-6061-t6"), theory="kirchhoff")

impactor = realise(plate, zeta, lam)
print(f"(ζ, λ) = ({zeta}, {lam}) on this plate: impactor mass {impactor.impactor_mass:.3f} kg, "
      f"contact stiffness {impactor.contact_stiffness:.4g} N/m")

simulated = simulate_normalised(plate, zeta, lam, record=False)
mapped = lookup(zeta, lam, kind="plate", theory="kirchhoff")
print(f"F̄max simulated        {simulated.fmax_normalised:.4f} ({simulated.impacts} impact(s))")
print(f"F̄max shipped map      {mapped.fmax_normalised:.4f} (regime: {mapped.regime})")
print(f"F̄max infinite plate   {float(infinite_structure_peak(zeta, 'plate')):.4f}")
print(f"F̄max quasi-static     {float(quasi_static_peak(lam)):.4f}")
velocity = 1.0  # [m/s]; the linear problem scales with it
print(f"peak force at {velocity} m/s: {simulated.fmax_normalised * impactor.force_scale(velocity):.1f} N")
fmax_normalised = simulated.fmax_normalised
