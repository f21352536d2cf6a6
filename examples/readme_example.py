"""A 12.7 mm steel ball strikes the centre of an aluminium plate at 3 m/s (the README's example).

Physics: a rigid steel sphere (radius 6.35 mm, mass 8.4 g) hits the centre of a simply
supported 300 mm × 300 mm × 4 mm aluminium 6061-T6 plate at V0 = 3 m/s. The plate is a
Mindlin (shear-deformable) plate represented by its modes; the contact is Hertzian,
F = K_h α^{3/2}. The modal solver integrates the sphere, the contact and the plate
together and returns the contact-force history, the contact intervals (every re-impact)
and the energy left in the plate.

    python examples/readme_example.py
"""

from impactmaps import Plate, Sphere, law_for_sphere, material, simulate

plate = Plate.isotropic(0.3, 0.3, 0.004, material("aluminium-6061-t6"), theory="mindlin")
sphere = Sphere(0.0127 / 2, material("structural-steel"))
law = law_for_sphere("hertz", sphere, material("aluminium-6061-t6"))
result = simulate(plate, law, sphere.mass, 3.0)
print(result.peak_force, result.contact_intervals, result.energy_transferred)
result.history  # pandas DataFrame: time_s, force_N, indentation_m, …
