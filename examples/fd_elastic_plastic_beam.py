"""A heavy steel sphere on an elastic-plastic steel beam: finite-difference solver.

Physics: a 70 mm radius steel sphere (11.3 kg) strikes the mid-span of a simply supported
780 mm steel beam (60 mm wide, 27.8 mm high, S235) at 0.5 m/s. The beam is a
finite-difference Rayleigh beam whose section is split into layers that may yield
(elastic-perfectly plastic), and the contact follows the refined Stronge law (Hertz
loading, plastic indentation, elastic unloading). The beam swings back into the sphere
after the first contact, so there are several sub-impacts; energy is lost to contact
plasticity and left in beam vibration, and the sphere rebounds with e < 1.

The case lives in ``examples/steel_beam_fd_stronge.toml``; ``solver="fd"`` picks the
finite-difference solver (as ``impactmaps fd examples/steel_beam_fd_stronge.toml`` does).

    python examples/fd_elastic_plastic_beam.py
"""

from pathlib import Path

from impactmaps.cases import load_case, run_case

case = load_case(Path(__file__).with_name("steel_beam_fd_stronge.toml"), solver="fd")
result, summary = run_case(case)

print(case.name)
print(f"  peak force            {summary['peak_force_N'] / 1e3:.2f} kN")
print(f"  contacts              {len(summary['contact_intervals_s'])}")
print(f"  restitution e         {summary['restitution']:.3f}")
print(f"  energy loss           {summary['energy_loss_J']:.3f} J of {summary['impact_energy_J']:.3f} J")
print(f"  permanent indentation {summary['permanent_indentation_m'] * 1e6:.1f} μm")
print(f"  energy balance error  {summary['energy_balance_error']:.1e}")
restitution = summary["restitution"]
