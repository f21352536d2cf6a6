"""Hertz impact of a 10 mm steel ball on a simply supported steel plate, from a case file.

Physics: a rigid structural-steel sphere (radius 5 mm, 4.1 g) strikes the centre of a
simply supported 250 mm × 250 mm × 4 mm steel plate at 2 m/s. The plate is a Mindlin
plate (modes up to 15 × the contact frequency plus the residual flexibility of the
rest), loaded by the Hertz pressure over the contact disc (the default on Mindlin
plates, docs/contact_patch.rst); the contact is Hertzian, F = K_h α^{3/2}. Part of the
impact energy is carried away into plate vibration, so the sphere rebounds with e < 1.

The whole case (sphere, plate, contact law, solver settings) lives in
``examples/steel_plate_hertz.toml``; the same file runs from the command line with
``impactmaps simulate examples/steel_plate_hertz.toml --out DIR``.

    python examples/steel_plate_hertz.py
"""

from pathlib import Path

from impactmaps.cases import load_case, run_case

case = load_case(Path(__file__).with_name("steel_plate_hertz.toml"))
result, summary = run_case(case)

print(case.name)
print(f"  peak force        {summary['peak_force_N']:.1f} N at {summary['peak_time_s'] * 1e6:.1f} μs")
print(f"  contact duration  {summary['total_contact_time_s'] * 1e6:.1f} μs ({summary['impacts']} impact(s))")
print(f"  restitution e     {summary['restitution']:.3f}")
print(f"  energy to plate   {summary['energy_transferred_J'] * 1e3:.2f} mJ "
      f"of {summary['impact_energy_J'] * 1e3:.2f} mJ")
print(f"  (ζ, λ)            ({summary['zeta']:.4f}, {summary['lambda']:.4f})")
peak_force = summary["peak_force_N"]
