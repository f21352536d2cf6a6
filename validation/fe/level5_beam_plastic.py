"""Level 5: the FD beam's own plasticity against a 3D elastic–plastic CalculiX beam.

The case: the seed-000 example beam (``examples/steel_beam_fd_stronge.toml``: steel S235,
simply supported, span 780 mm, 60 mm wide, 27.8 mm high) struck at mid-span by a 30 kg
striker with a 70 mm radius steel nose at 2 m/s, elastic Hertz contact (``law =
"hertz"``, so the force does not depend on the plastic contact laws). The FD beam
(seed 000: layered elastic–perfectly plastic Rayleigh beam) yields over ±0.13 m about
mid-span and keeps a permanent deflection ≈ 40 % of its peak.

1. The coupled FD run (``N_l = 200, N_h = 10``, the example's grid) gives F(t).
2. F(t), sampled at the FE step Δt and linearly interpolated, is the prescribed load of
   * the 3D model: a quarter of the beam (symmetry planes x = L/2 and y = 0), C3D20R,
     von Mises elastic–perfectly plastic (``*PLASTIC`` σ_y, 0), small strains,
     ``*DYNAMIC, DIRECT, ALPHA=0`` (trapezoidal rule) with fixed Δt, the load a uniform
     pressure on a strip across the whole width of the top face, |x − L/2| ≤ c; the end
     face x = 0 held in z (the diaphragm support that is the beam's simple support,
     level 1). A ``*STATIC`` step with the load removed then unloads the final state
     elastically: its deflection is the permanent deflection, the same definition as
     the FD's ``permanent_beam_deflection`` (``w − K_e⁻¹ f_int``);
   * the FD beam itself (:func:`impactmaps.fd.simulate_fd_response`, point load at the
     mid-span node), so both see the identical load.
3. Compared: mid-span deflection history, its peak, the permanent deflection, the
   plastic zone. FE deflection = mean u_z over the mid-span section (the beam's w);
   the neutral-axis and bottom-face values are stored too.

Run (from the repository root, single thread, niced)::

    python validation/fe/level5_beam_plastic.py fd                     # FD case + grid study
    OMP_NUM_THREADS=1 nice -n 19 python validation/fe/level5_beam_plastic.py fe --mesh coarse --dt 5e-6
    ... fe --mesh fine --dt 5e-6;  fe --mesh coarse --dt 2.5e-6;  fe --mesh coarse --patch 2
    python validation/fe/level5_beam_plastic.py table

Outputs: ``results/level5_beam_plastic.json`` (every run), ``results/level5_force.csv``
(the prescribed force) and ``results/level5_fe_<tag>.csv`` (histories).
"""

from __future__ import annotations

import argparse
import io
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct

import impactmaps
from impactmaps import FDBeam, Sphere, law_for_sphere, simulate_fd
from impactmaps.fd import simulate_fd_response

STEEL = impactmaps.material("structural-steel")
LENGTH, WIDTH, HEIGHT = 0.78, 0.060, 0.0278      # m (examples/steel_beam_fd_stronge.toml)
MASS, RADIUS, VELOCITY = 30.0, 0.07, 2.0         # kg, m, m/s
LAW = "hertz"
FD_GRID = (200, 10)                               # (N_l, N_h) that makes F(t)
FD_DURATION = 0.03                                # s
FE_END = 0.0145                                   # s: dynamic step end (last contact 13.9 ms)
LOAD_DT = 5e-6                                    # s: sampling of the prescribed load
JSON = ct.RESULTS / "level5_beam_plastic.json"
FORCE_CSV = ct.RESULTS / "level5_force.csv"
#: The force of the coupled FD impact with the wide-section model (``level5_wide_fd.py``).
FORCE_WIDE_CSV = ct.RESULTS / "level5_force_wide.csv"
# FE meshes: (elements through the depth nz, across the half width ny, element length in
# the mid-span zone |x - L/2| <= ZONE in units of h/nz, growth factor outside the zone).
MESHES = {"coarse": dict(nz=4, ny=2), "fine": dict(nz=6, ny=2), "coarse1": dict(nz=4, ny=1),
          "fine1": dict(nz=6, ny=1), "smoke": dict(nz=2, ny=1)}
ZONE = 0.16                                       # m: fine zone half-length (FD zone 0.13)


def fd_beam(n_elements=FD_GRID[0], n_half_layers=FD_GRID[1], width_constraint=True) -> FDBeam:
    """The FD beam of the case (``width_constraint``: the wide-section model, default on;
    False: the uniaxial layered section)."""
    return FDBeam.from_material(LENGTH, WIDTH, HEIGHT, STEEL, n_elements=n_elements,
                                n_half_layers=n_half_layers, width_constraint=width_constraint)


def fd_impact(n_elements=FD_GRID[0], n_half_layers=FD_GRID[1], duration=FD_DURATION,
              width_constraint=False):
    """The coupled FD impact (Hertz contact) of the case: an ImpactResult. The default is
    the uniaxial section, the run that made the committed force (FORCE_CSV)."""
    sphere = Sphere(RADIUS, STEEL, mass=MASS)
    law = law_for_sphere(LAW, sphere, STEEL)
    return simulate_fd(fd_beam(n_elements, n_half_layers, width_constraint), law, MASS,
                       VELOCITY, duration=duration)


def fd_prescribed(times, force, n_elements=FD_GRID[0], n_half_layers=FD_GRID[1],
                  duration=None, width_constraint=False, permanent=False):
    """FD beam under the piecewise-linear load (times, force): (t, w_mid) arrays, and with
    ``permanent=True`` also the permanent mid-span deflection at the end [m]."""
    response = simulate_fd_response(
        fd_beam(n_elements, n_half_layers, width_constraint),
        lambda t: np.interp(t, times, force, right=0.0),
        duration=times[-1] if duration is None else duration)
    h = response.history
    out = h["time_s"].to_numpy(), h["deflection_at_load_m"].to_numpy()
    if not permanent:
        return out
    residual = response.residual
    mid = int(np.argmin(np.abs(residual["x_m"].to_numpy() - 0.5 * LENGTH)))
    return (*out, float(residual["permanent_deflection_m"].to_numpy()[mid]))


def late_mean(t, w, start):
    """Mean of w over t >= start (the centre of the free vibration) [m]."""
    return float(np.mean(w[t >= start]))


# -- FD side -------------------------------------------------------------------------
def fd_summary(result) -> dict:
    h = result.history
    t, w = h["time_s"].to_numpy(), h["target_displacement_m"].to_numpy()
    d = result.details
    zone = d.plastic_zone
    return dict(peak_deflection_m=float(w.max()), peak_time_s=float(t[np.argmax(w)]),
                permanent_deflection_m=float(d.permanent_beam_deflection),
                late_mean_deflection_m=late_mean(t, w, 0.5 * t[-1]),
                plastic_half_length_m=None if zone is None else
                float(0.5 * LENGTH - zone[0]),
                max_plastic_strain=float(d.residual["max_plastic_strain"].max()),
                peak_force_N=float(result.peak_force), contacts=len(result.contact_intervals),
                last_separation_s=float(result.contact_intervals[-1, 1]),
                time_step_s=float(result.time_step))


def run_fd(args):
    """The coupled FD case (writes the force CSV) and its grid study."""
    base = fd_impact()
    h = base.history
    times = np.arange(0.0, FE_END + 0.5 * LOAD_DT, LOAD_DT)
    np.savetxt(FORCE_CSV, np.column_stack([times, *(np.interp(times, h["time_s"], h[c])
                                                     for c in ("force_N",
                                                               "target_displacement_m"))]),
               delimiter=",", fmt="%.9e", comments="",
               header="time_s,force_N,fd_midspan_deflection_m")
    study = {}
    for nl, nh in ((100, 10), (200, 10), (400, 10), (200, 20), (200, 40), (400, 20)):
        study[f"{nl}x{nh}"] = fd_summary(fd_impact(nl, nh))
        print(nl, nh, study[f"{nl}x{nh}"], flush=True)
    # the beam alone: the same prescribed load (the FE's) on every grid
    times, force = prescribed_force()
    prescribed = {}
    for nl, nh in ((100, 10), (200, 10), (400, 10), (200, 20), (200, 40)):
        t, w = fd_prescribed(times, force, nl, nh)
        prescribed[f"{nl}x{nh}"] = dict(peak_deflection_m=float(w.max()),
                                        deflection_at_end_m=float(w[-1]))
    # the dynamic step ends at FE_END: no yielding after it (same permanent deflection)
    early = fd_summary(fd_impact(duration=FE_END))["permanent_deflection_m"]
    data = load()
    data["case"] = dict(length_m=LENGTH, width_m=WIDTH, height_m=HEIGHT, impactor_mass_kg=MASS,
                        nose_radius_m=RADIUS, velocity_m_s=VELOCITY, law=LAW,
                        material=STEEL.name, youngs_modulus_Pa=STEEL.youngs_modulus,
                        poisson_ratio=STEEL.poisson_ratio, density_kg_m3=STEEL.density,
                        yield_strength_Pa=STEEL.yield_strength, fd_grid=list(FD_GRID),
                        fd_duration_s=FD_DURATION)
    data["fd_impact"] = fd_summary(base)
    data["fd_grid_study"] = study
    data["fd_prescribed_grid_study"] = prescribed
    data["fd_permanent_deflection_at_fe_end_m"] = early
    data["fd_command"] = "python validation/fe/level5_beam_plastic.py fd"
    save(data)


def prescribed_force(end=FE_END, csv=FORCE_CSV):
    """The prescribed load, (times, force): the FD force sampled every LOAD_DT (as
    committed in ``csv``: FORCE_CSV, the uniaxial section's coupled impact, or
    FORCE_WIDE_CSV, the wide-section model's), up to ``end``."""
    t, f = np.loadtxt(csv, delimiter=",", skiprows=1, usecols=(0, 1), unpack=True)
    times = np.arange(0.0, end + 0.5 * LOAD_DT, LOAD_DT)
    return times, np.interp(times, t, f, right=0.0)


def smoothed(force, window):
    """``force`` (sampled every LOAD_DT) averaged over the preceding ``window`` [s]
    (causal moving average: the impulse is kept, spikes shorter than the window are
    spread over it)."""
    n = max(1, int(round(window / LOAD_DT)))
    return np.convolve(force, np.ones(n) / n, mode="full")[:len(force)]


# -- FE side -------------------------------------------------------------------------
def x_knots(nz, patch):
    """Element boundaries along x in [0, L/2]: size h/nz in the zone (plus a boundary at
    the patch edge L/2 − ``patch``), growing by 1.25 per element outside, to ≤ 1.25 h."""
    size = HEIGHT / nz
    n_zone = int(round(ZONE / size))
    zone = 0.5 * LENGTH - size * np.arange(n_zone + 1)[::-1]
    if not np.isclose(zone, 0.5 * LENGTH - patch, atol=1e-9).any():
        zone = np.sort(np.append(zone, 0.5 * LENGTH - patch))
    outer, s = [], size
    x = zone[0]
    while x > 1e-12:
        s = min(1.25 * s, 1.25 * HEIGHT)
        x -= s
        outer.append(max(x, 0.0))
    outer = np.array(outer[::-1])
    if len(outer) > 1 and outer[1] < 0.5 * s:       # merge a sliver at the support
        outer = np.delete(outer, 1)
    outer[0] = 0.0
    return np.concatenate([outer, zone])


def quarter_mesh(nz, ny, patch, width=WIDTH):
    """C3D20R mesh of [0, L/2] × [0, b/2] × [0, h] with the graded x knots."""
    knots = x_knots(nz, patch)
    nx = len(knots) - 1
    mesh = ct.structured_box(1.0, 0.5 * width, HEIGHT, nx, ny, nz)
    s = mesh.coords[:, 0] * nx
    mesh.coords[:, 0] = np.interp(s, np.arange(nx + 1), knots)
    return mesh, knots


def top_faces(mesh, x_min):
    """(element, face label) of the top-face faces with x >= x_min (hex face numbering)."""
    faces = {"P1": (0, 1, 2, 3), "P2": (4, 7, 6, 5), "P3": (0, 4, 5, 1),
             "P4": (1, 5, 6, 2), "P5": (2, 6, 7, 3), "P6": (3, 7, 4, 0)}
    out = []
    for e, row in enumerate(mesh.elements, start=1):
        xyz = mesh.coords[row[:8] - 1]
        for label, corners in faces.items():
            c = xyz[list(corners)]
            if np.allclose(c[:, 2], HEIGHT, atol=1e-9) and c[:, 0].min() >= x_min - 1e-9:
                out.append((e, label))
    return out


def section_weights(mesh, ids):
    """Area weights of the serendipity mid-span section nodes (mean u_z = Σ w_i u_i)."""
    y, z = mesh.coords[ids - 1, 1], mesh.coords[ids - 1, 2]
    ys, zs = np.unique(np.round(y, 12)), np.unique(np.round(z, 12))
    weights = np.zeros(len(ids))
    corners_y, corners_z = ys[::2], zs[::2]
    for y0, y1 in zip(corners_y[:-1], corners_y[1:]):
        for z0, z1 in zip(corners_z[:-1], corners_z[1:]):
            area = (y1 - y0) * (z1 - z0)
            ym, zm = 0.5 * (y0 + y1), 0.5 * (z0 + z1)
            for k, (yy, zz) in enumerate(zip(y, z)):
                inside = y0 - 1e-12 <= yy <= y1 + 1e-12 and z0 - 1e-12 <= zz <= z1 + 1e-12
                if not inside:
                    continue
                corner = np.isclose(yy, [y0, y1]).any() and np.isclose(zz, [z0, z1]).any()
                mid = (np.isclose(yy, ym) and np.isclose(zz, [z0, z1]).any()) or \
                      (np.isclose(zz, zm) and np.isclose(yy, [y0, y1]).any())
                weights[k] += area * (-1 / 12 if corner else (1 / 3 if mid else 0.0))
    return weights / weights.sum()


def fe_deck(mesh, times, force, dt, patch, auto=False, width=WIDTH, static_load=None):
    """The ccx deck: quarter beam, supports, the strip load, *DYNAMIC then *STATIC."""
    x, y, z = mesh.coords.T
    tol = 1e-9
    mid = np.isclose(x, 0.5 * LENGTH, atol=tol)
    f = io.StringIO()
    f.write("*HEADING\nlevel 5 plastic beam\n")
    ct.write_mesh_parts(f, mesh, [("EALL", np.ones(len(mesh.elements), bool), "STEEL",
                                   ct.material_cards(STEEL, STEEL.yield_strength))])
    ct.write_nset(f, "XSYM", mesh.nodes_where(mid))
    ct.write_nset(f, "YSYM", mesh.nodes_where(np.isclose(y, 0, atol=tol)))
    ct.write_nset(f, "END", mesh.nodes_where(np.isclose(x, 0, atol=tol)))
    ct.write_nset(f, "MID", mesh.nodes_where(mid))
    f.write("*BOUNDARY\nXSYM,1,1\nYSYM,2,2\nEND,3,3\n")
    if static_load is None:
        f.write("*AMPLITUDE, NAME=FORCE\n")
        f.write("".join(f"{t:.9e},{v:.9e}\n" for t, v in zip(times, force)))
    faces = top_faces(mesh, 0.5 * LENGTH - patch)
    pressure = 1.0 / (2 * patch * width)            # Pa per newton of the total force
    if static_load is not None:   # quasi-static 3-point bending to static_load [N], ≤ 2 % steps
        f.write("*STEP, INC=1000\n*STATIC\n0.02,1.0,1e-6,0.02\n*DLOAD\n")
        f.write("".join(f"{e},{label},{pressure * static_load:.9e}\n" for e, label in faces))
        f.write("*NODE PRINT, NSET=MID\nU\n*EL PRINT, ELSET=EALL\nPEEQ,S\n*END STEP\n")
        return f.getvalue(), faces
    if auto:      # automatic incrementation, Δt ≤ dt (ccx cuts the step where Newton fails)
        f.write(f"*STEP, INC=1000000\n*DYNAMIC, ALPHA=0.0\n{dt:.6e},{times[-1]:.9e},"
                f"{dt * 1e-4:.3e},{dt:.6e}\n")
    else:
        f.write(f"*STEP, INC=1000000\n*DYNAMIC, DIRECT, ALPHA=0.0\n{dt:.6e},{times[-1]:.9e}\n")
    f.write("*DLOAD, AMPLITUDE=FORCE\n")
    f.write("".join(f"{e},{label},{pressure:.9e}\n" for e, label in faces))
    f.write("*NODE PRINT, NSET=MID\nU\n*END STEP\n")
    f.write("*STEP\n*STATIC\n1.0,1.0\n*DLOAD, OP=NEW\n")
    f.write("*NODE PRINT, NSET=MID\nU\n*EL PRINT, ELSET=EALL\nPEEQ\n*END STEP\n")
    return f.getvalue(), faces


def parse_peeq(text):
    """element -> max PEEQ over its integration points (last *EL PRINT block)."""
    block = text.rsplit("equivalent plastic strain", 1)[1]
    out = {}
    for line in block.splitlines()[1:]:
        parts = line.split()
        if len(parts) != 3:
            if out:
                break
            continue
        e, value = int(parts[0]), ct._fortran_float(parts[2])
        out[e] = max(out.get(e, 0.0), value)
    return out


def run_fe(args):
    """One FE run: writes its CSV and adds its entry to the JSON."""
    spec = MESHES[args.mesh]
    patch = args.patch * 1e-3 if args.patch else HEIGHT / 8
    width = args.width * 1e-3 if args.width else WIDTH
    mesh, knots = quarter_mesh(patch=patch, width=width, **spec)
    if not np.isclose(knots, 0.5 * LENGTH - patch).any():
        raise RuntimeError(f"patch half-length {patch} m is not an element boundary")
    wide = args.force == "wide"
    times, force = prescribed_force(args.end, FORCE_WIDE_CSV if wide else FORCE_CSV)
    if args.smooth:
        force = smoothed(force, args.smooth * 1e-6)
    # a beam of another width carries the force scaled by width/WIDTH: the same stresses,
    # and the same beam-theory deflection (mass, stiffness and M_p all ∝ b)
    deck, faces = fe_deck(mesh, times, force * width / WIDTH, args.dt, patch, args.auto,
                          width=width)
    tag = args.tag or (f"{args.mesh}_dt{args.dt * 1e6:g}us{'auto' if args.auto else ''}"
                       f"_c{patch * 1e3:.3g}mm")
    dat, wall = ct.run_ccx(deck, f"level5_{tag}", ct.WORK / "level5")
    text = dat.read_text()
    blocks = ct.parse_node_prints(text, "MID")
    t_fe = ct.parse_node_print_times(text, "MID")
    ids = mesh.nodes_where(np.isclose(mesh.coords[:, 0], 0.5 * LENGTH, atol=1e-9))
    weights = section_weights(mesh, ids)
    uz = np.array([[-b[i][2] for i in ids] for b in blocks])
    yz = mesh.coords[ids - 1, 1:]
    axis = ids[np.argmin(np.hypot(yz[:, 0], yz[:, 1] - 0.5 * HEIGHT))]
    bottom = ids[np.argmin(np.hypot(yz[:, 0], yz[:, 1]))]
    mean = uz @ weights
    na = np.array([-b[axis][2] for b in blocks])
    bot = np.array([-b[bottom][2] for b in blocks])
    n_dyn = int(np.count_nonzero(t_fe <= times[-1] + 1e-9))     # then the static step
    dyn_t, dyn_mean = t_fe[:n_dyn], mean[:n_dyn]
    peeq = parse_peeq(text)
    centres = {e: mesh.coords[mesh.elements[e - 1][:8] - 1, 0].mean() for e in peeq}
    yielded = [0.5 * LENGTH - centres[e] for e, v in peeq.items() if v > 0]
    t_fd, w_fd = fd_prescribed(times, force, width_constraint=wide)
    w_fd_at = np.interp(dyn_t, t_fd, w_fd)
    entry = dict(mesh=args.mesh, **spec, n_nodes=len(mesh.coords),
                 n_elements=len(mesh.elements), element_type=mesh.element_type,
                 zone_element_length_m=HEIGHT / spec["nz"], x_elements=len(knots) - 1,
                 patch_half_length_m=patch, loaded_faces=len(faces), time_step_s=args.dt, automatic_increments=bool(args.auto), width_m=width,
                 load_smoothing_window_s=args.smooth * 1e-6, force=args.force,
                 dynamic_increments=n_dyn,
                 dynamic_end_s=float(times[-1]), ccx_wall_time_s=wall,
                 ccx_version=ct.ccx_version(),
                 peak_deflection_m=float(dyn_mean.max()),
                 peak_time_s=float(dyn_t[np.argmax(dyn_mean)]),
                 peak_deflection_axis_m=float(na[:n_dyn].max()),
                 peak_deflection_bottom_m=float(bot[:n_dyn].max()),
                 permanent_deflection_m=float(mean[-1]),
                 permanent_deflection_axis_m=float(na[-1]),
                 permanent_deflection_bottom_m=float(bot[-1]),
                 plastic_half_length_m=float(max(yielded)) if yielded else None,
                 max_peeq=float(max(peeq.values())),
                 fd_prescribed_peak_deflection_m=float(w_fd.max()),
                 fd_prescribed_max_abs_difference_over_peak=float(
                     np.abs(w_fd_at - dyn_mean).max() / dyn_mean.max()),
                 command="python validation/fe/level5_beam_plastic.py " + " ".join(sys.argv[1:]))
    np.savetxt(ct.RESULTS / f"level5_fe_{tag}.csv",
               np.column_stack([dyn_t, np.interp(dyn_t, times, force), dyn_mean, na[:n_dyn],
                                bot[:n_dyn], w_fd_at])[::max(1, int(round(1e-5 / args.dt)))],
               delimiter=",", fmt="%.6e", comments="",
               header="time_s,force_N,fe_section_mean_m,fe_axis_m,fe_bottom_m,fd_prescribed_m")
    data = load()
    data.setdefault("fe_runs", {})[tag] = entry
    save(data)
    print(json.dumps(entry, indent=1))


#: The FE reference (coarse1 mesh: 4 × 1 elements in depth × half width, automatic
#: Δt ≤ 20 µs, strip c = h/8) and the pairs (coarser, finer) that bound its error:
#: step (≤ 20 µs automatic → fixed 10 µs, to 7.5 ms), width (ny 1 → 2 at fixed 10 µs,
#: to 7.5 ms), depth (nz 4 → 6 with the zone element h/4 → h/6, to 4.3 ms: stopped),
#: patch (c 6.95 → 3.475 mm, whole run).
REFERENCE = "coarse1_dt20usauto_c3.47mm"
#: The same mesh and step driven by the force of the coupled FD impact with the wide-section
#: model (FORCE_WIDE_CSV): a second load history for that model.
REFERENCE_WIDE_FORCE = "coarse1_dt20usauto_c3.47mm_forcewide"
#: The same run on a 10 mm wide beam (force scaled by b/WIDTH): the beam-theory answer is
#: unchanged, the 3D hinge is no longer restrained across the width.
NARROW = "coarse1_dt20usauto_c3.47mm_b10mm"
PAIRS = {"step": (REFERENCE, "coarse1_dt10us_c3.47mm_to7.5ms"),
         "width": ("coarse1_dt10us_c3.47mm_to7.5ms", "coarse_dt10us_c3.47mm"),
         "depth": (REFERENCE, "fine1_dt20usauto_c3.47mm"),
         "patch": ("coarse1_dt20usauto_c6.95mm", REFERENCE)}
COMPARED = ("peak_deflection_m", "permanent_deflection_m")


def fe_reference(runs):
    """(reference run, {pair: {quantity: relative change}}) for the pairs of PAIRS.

    The change is finer minus coarser over finer. For ``patch`` it is the change from
    halving the strip half-length c, i.e. (linear in c) the estimated distance of the
    reference from a point load.
    """
    ref = runs.get(REFERENCE)
    changes = {}
    for name, (a, b) in PAIRS.items():
        if a in runs and b in runs:
            changes[name] = {q: runs[b][q] / runs[a][q] - 1.0 for q in COMPARED}
    return ref, changes


def load():
    return json.loads(JSON.read_text()) if JSON.exists() else {}


def save(data):
    JSON.write_text(json.dumps(data, indent=1) + "\n")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="what", required=True)
    sub.add_parser("fd")
    fe = sub.add_parser("fe")
    fe.add_argument("--mesh", default="coarse", choices=sorted(MESHES))
    fe.add_argument("--dt", type=float, default=5e-6)
    fe.add_argument("--patch", type=float, default=None, help="patch half-length [mm]")
    fe.add_argument("--tag", default=None)
    fe.add_argument("--auto", action="store_true",
                    help="automatic incrementation with Δt ≤ --dt (default: fixed Δt)")
    fe.add_argument("--smooth", type=float, default=0.0,
                    help="moving-average window of the load [µs] (0: the FD force as is)")
    fe.add_argument("--width", type=float, default=None,
                    help="beam width [mm] (default the case's 60 mm); the force is scaled by b")
    fe.add_argument("--end", type=float, default=FE_END, help="dynamic step end [s]")
    fe.add_argument("--force", default="uniaxial", choices=("uniaxial", "wide"),
                    help="prescribed force: the coupled FD impact with the uniaxial section "
                         "(level5_force.csv) or with the wide-section model (level5_force_wide.csv)")
    a = p.parse_args(argv)
    if a.what == "fd":
        run_fd(a)
    else:
        run_fe(a)


if __name__ == "__main__":
    main()
