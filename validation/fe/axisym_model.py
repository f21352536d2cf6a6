"""Axisymmetric CalculiX model: an elastic sphere pressed into an elastic–perfectly
plastic flat, load to δ_m and unload to separation (quasi-static, frictionless).

Geometry in the (r, z) plane (ccx axisymmetric: x = r, y = z): the flat is the block
0 ≤ r ≤ L, −L ≤ z ≤ 0; the sphere (radius R) touches it at the origin and is cut at its
equator z = R, which is driven down by δ (``*BOUNDARY`` with an amplitude) while the
block's bottom is held in z.  The approach δ is the equator's displacement: the
Hertz approach of distant points, the block's finite-size compliance included.
Mesh: gmsh quadrilaterals, 8-node reduced integration (CAX8R; CAX4R does not converge
on unloading with this contact), size h0 = a_ref/``per_radius`` within ``FINE`` × a_ref
of the contact point, growing linearly (slope ``GROWTH``) beyond; a_ref = sqrt(2 R δ_m)
is an upper estimate of the contact radius.  Contact: ``SURFACE TO SURFACE``,
``SMALL SLIDING``, the sphere's arc the slave, linear penalty of slope
3Y / (``penalty`` × δ_m): a pressure of 3Y (about the largest there is) overcloses the
surfaces by ``penalty`` × δ_m.  The flat is von Mises with a small hardening
(:func:`plastic_card`).  Convergence, limits and what failed: docs/epp_calibration.rst.

Units SI.  Nothing here is part of the toolkit.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import ccx_tools as ct
import numpy as np

FINE = 1.6          # size h0 up to FINE × a_ref from the contact point
GROWTH = 0.25       # mesh size slope beyond the fine zone
C_Y = 1.6           # yield when the Hertz peak pressure reaches C_Y × Y (docs/physics_contract.md §2)


@dataclass(frozen=True)
class Case:
    """One load–unload run.  Lengths [m], moduli [Pa]."""

    x_m: float                  # δ_m / δ_y
    y_over_estar: float         # Y / E*
    nu_flat: float = 0.3
    stiffness_ratio: float = 1e3     # E_sphere / E_flat (1e3 stands for rigid)
    nu_sphere: float = 0.3
    radius: float = 5e-3
    e_flat: float = 70e9
    # numerics
    per_radius: float = 6.0     # a_ref / h0
    block: float = 60.0         # L / a_ref
    penalty: float = 2e-3       # overclosure at a contact pressure 3Y, over δ_m
    n_load: int = 20
    n_unload: int = 30
    nlgeom: bool = False
    print_stress: bool = False  # print the stresses near the contact (first-yield check)
    print_surface: bool = True  # print the flat's surface displacements
    element: str = "CAX8R"      # CAX8R (8-node, reduced) or CAX4R
    contact: str = "SURFACE TO SURFACE"
    small_sliding: bool = True  # ccx SMALL SLIDING: contact elements fixed per increment
    slave: str = "sphere"       # which surface is the slave: "sphere" or "flat"
    mapped: bool = False        # structured (transfinite) patches of size h0 at the contact
    tension: float = 0.0        # σ∞ / Y of the linear penalty (ccx *SURFACE BEHAVIOR)
    controls: str = ""          # extra ccx cards (e.g. *CONTROLS)
    hardening: float = 0.03     # slope of the *PLASTIC curve / Y (per unit plastic strain)
    plastic: bool = True        # False: the flat stays elastic (Hertz checks)

    @property
    def e_star(self):
        es = self.stiffness_ratio * self.e_flat
        return 1.0 / ((1 - self.nu_flat ** 2) / self.e_flat + (1 - self.nu_sphere ** 2) / es)

    @property
    def yield_strength(self):
        return self.y_over_estar * self.e_star

    @property
    def delta_y(self):
        return self.radius * (math.pi * C_Y * self.y_over_estar / 2) ** 2

    @property
    def force_y(self):
        return 4.0 / 3.0 * self.e_star * math.sqrt(self.radius) * self.delta_y ** 1.5

    @property
    def delta_m(self):
        return self.x_m * self.delta_y

    @property
    def a_ref(self):
        return math.sqrt(2.0 * self.radius * self.delta_m)


def build_mesh(case: Case):
    """CAX8R/CAX4R mesh: coordinates (n, 3), elements (e, 8 or 4) 1-based, sphere mask, and the
    boundary edges (node pairs) of the sphere's arc and the block's top."""
    import gmsh
    r, a = case.radius, case.a_ref
    h0 = a / case.per_radius
    side = case.block * a
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("axisym")
        g = gmsh.model.geo
        if case.mapped:
            blocks, sphs, tops, arcs = _mapped_geometry(g, case, side, h0)
        else:
            # block
            p = [g.addPoint(0, 0, 0), g.addPoint(side, 0, 0), g.addPoint(side, -side, 0),
                 g.addPoint(0, -side, 0)]
            top = g.addLine(p[0], p[1])
            lines = [top, g.addLine(p[1], p[2]), g.addLine(p[2], p[3]), g.addLine(p[3], p[0])]
            blocks, tops = [g.addPlaneSurface([g.addCurveLoop(lines)])], [top]
            # sphere, cut at the equator: quarter disc, arc from the tip to the equator
            tip, centre, equator = g.addPoint(0, 0, 0), g.addPoint(0, r, 0), g.addPoint(r, r, 0)
            arc = g.addCircleArc(tip, centre, equator)
            sphs, arcs = [g.addPlaneSurface([g.addCurveLoop([arc, g.addLine(equator, centre),
                                                             g.addLine(centre, tip)])])], [arc]
        g.synchronize()
        far_block, far_sphere = side / 8, r / 6
        expr = "Min({far}, {h0} + {k}*Max(Sqrt(x*x+y*y) - {rf}, 0))"
        fields = []
        for tag, surf, far in ((1, blocks, far_block), (3, sphs, far_sphere)):
            gmsh.model.mesh.field.add("MathEval", tag)
            gmsh.model.mesh.field.setString(tag, "F", expr.format(
                far=far, h0=h0, k=GROWTH, rf=FINE * a))
            gmsh.model.mesh.field.add("Restrict", tag + 1)
            gmsh.model.mesh.field.setNumber(tag + 1, "InField", tag)
            gmsh.model.mesh.field.setNumbers(tag + 1, "SurfacesList", list(surf))
            fields.append(tag + 1)
        gmsh.model.mesh.field.add("Min", 9)
        gmsh.model.mesh.field.setNumbers(9, "FieldsList", fields)
        ct.use_background_field(gmsh, 9)
        gmsh.option.setNumber("Mesh.Algorithm", 8)
        gmsh.option.setNumber("Mesh.RecombineAll", 1)
        gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 3)
        quadratic = case.element.startswith("CAX8")
        if quadratic:
            gmsh.option.setNumber("Mesh.ElementOrder", 2)
            gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.generate(2)
        qtype, ltype, nper = (16, 8, 8) if quadratic else (3, 1, 4)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        lookup = {int(t): i + 1 for i, t in enumerate(tags)}
        coords = xyz.reshape(-1, 3)
        elements, in_sphere = [], []
        for surf, flag in [(b, False) for b in blocks] + [(sp, True) for sp in sphs]:
            etypes, _, enodes = gmsh.model.mesh.getElements(2, surf)
            for et, en in zip(etypes, enodes):
                if et != qtype:
                    raise RuntimeError(f"gmsh left element type {et} (not a quadrangle)")
                conn = np.array([lookup[int(v)] for v in en]).reshape(-1, nper)
                elements.append(conn)
                in_sphere += [flag] * len(conn)
        edges = {}
        for key, curves in (("slave", arcs), ("master", tops)):
            parts = []
            for curve in curves:
                etypes, _, enodes = gmsh.model.mesh.getElements(1, curve)
                k = list(etypes).index(ltype)
                parts.append(np.array([lookup[int(v)] for v in enodes[k]]).reshape(-1, nper // 4 + 1)[:, :2])
            edges[key] = np.vstack(parts)
    finally:
        gmsh.finalize()
    elements = np.vstack(elements)
    # counter-clockwise in (r, z), as ccx expects
    xy = coords[elements[:, :4] - 1][:, :, :2]
    area = 0.5 * np.sum(xy[:, :, 0] * np.roll(xy[:, :, 1], -1, 1)
                        - np.roll(xy[:, :, 0], -1, 1) * xy[:, :, 1], axis=1)
    flip = [0, 3, 2, 1, 7, 6, 5, 4][:elements.shape[1]]
    elements[area < 0] = elements[area < 0][:, flip]
    return coords, elements, np.array(in_sphere), edges, h0


def _mapped_geometry(g, case: Case, side, h0):
    """Block and sphere with a structured patch each at the contact (``case.mapped``): the
    square 0 ≤ r ≤ m, −m ≤ z ≤ 0 of the block and the sphere's region between its arc
    (tip to r = m), r = m and z = z_m + min(m, 0.8 (R − z_m)), m = FINE a_ref, transfinite quads of
    size ≈ h0; the rest of each body is meshed as before, conforming to the patches.
    Returns (block surfaces, sphere surfaces, top curves, arc curves)."""
    import gmsh

    r, m = case.radius, FINE * case.a_ref
    n = int(math.ceil(m / h0)) + 1                     # nodes per patch side
    # block: square patch + the L-shaped rest
    o, a1, b1, c1 = g.addPoint(0, 0, 0), g.addPoint(m, 0, 0), g.addPoint(m, -m, 0), g.addPoint(0, -m, 0)
    far_top, far_corner, far_axis = g.addPoint(side, 0, 0), g.addPoint(side, -side, 0), g.addPoint(0, -side, 0)
    top1, right1, bottom1, axis1 = g.addLine(o, a1), g.addLine(a1, b1), g.addLine(b1, c1), g.addLine(c1, o)
    square = g.addPlaneSurface([g.addCurveLoop([top1, right1, bottom1, axis1])])
    top2 = g.addLine(a1, far_top)
    rest = g.addPlaneSurface([g.addCurveLoop([top2, g.addLine(far_top, far_corner),
                                              g.addLine(far_corner, far_axis),
                                              g.addLine(far_axis, c1), -bottom1, -right1])])
    # sphere: patch at the tip + the rest of the quarter disc
    zm = r - math.sqrt(r * r - m * m)
    tip, centre, equator = g.addPoint(0, 0, 0), g.addPoint(0, r, 0), g.addPoint(r, r, 0)
    hm = min(m, 0.8 * (r - zm))                         # patch height, below the centre
    pm, qm, sm = g.addPoint(m, zm, 0), g.addPoint(m, zm + hm, 0), g.addPoint(0, zm + hm, 0)
    arc1, arc2 = g.addCircleArc(tip, centre, pm), g.addCircleArc(pm, centre, equator)
    up, across, down = g.addLine(pm, qm), g.addLine(qm, sm), g.addLine(sm, tip)
    patch = g.addPlaneSurface([g.addCurveLoop([arc1, up, across, down])])
    rest_s = g.addPlaneSurface([g.addCurveLoop([arc2, g.addLine(equator, centre),
                                                g.addLine(centre, sm), -across, -up])])
    g.synchronize()
    for curve in (top1, right1, bottom1, axis1, arc1, across):
        gmsh.model.mesh.setTransfiniteCurve(curve, n)
    for curve in (up, down):
        gmsh.model.mesh.setTransfiniteCurve(curve, int(math.ceil(hm / h0)) + 1)
    for surf in (square, patch):
        gmsh.model.mesh.setTransfiniteSurface(surf)
        gmsh.model.mesh.setRecombine(2, surf)
    return [square, rest], [patch, rest_s], [top1, top2], [arc1, arc2]


def edge_faces(elements, edges, coords, within):
    """(element, face label) of the element sides that are boundary ``edges`` whose
    midpoint lies within ``within`` of the origin."""
    lookup = {}
    for e, row in enumerate(elements, start=1):
        for k in range(4):
            lookup[frozenset((int(row[k]), int(row[(k + 1) % 4])))] = (e, f"S{k + 1}")
    mid = coords[edges - 1].mean(axis=1)
    keep = edges[np.hypot(mid[:, 0], mid[:, 1]) < within]
    return [lookup[frozenset((int(a), int(b)))] for a, b in keep]


def amplitude(name, fractions):
    pts = ",\n".join(f"{t:.6f},{v:.9f}" for t, v in fractions)
    return f"*AMPLITUDE, NAME={name}\n{pts}\n"


def build_deck(case: Case, coords, elements, in_sphere, edges, h0):
    x, y = coords[:, 0], coords[:, 1]
    tol = 1e-12 * case.radius + 1e-15
    out = ["*HEADING\naxisymmetric sphere on elastic-perfectly plastic flat\n",
           "*NODE, NSET=NALL\n"]
    out += [f"{i},{px:.12e},{py:.12e}\n" for i, (px, py, _) in enumerate(coords, 1)]
    for name, mask in (("BLOCK", ~in_sphere), ("BALL", in_sphere)):
        out.append(f"*ELEMENT, TYPE={case.element}, ELSET={name}\n")
        out += [f"{i + 1},{','.join(map(str, elements[i]))}\n" for i in np.flatnonzero(mask)]
    sphere_nodes = np.zeros(len(coords), bool)
    sphere_nodes[elements[in_sphere].ravel() - 1] = True
    f = type("F", (), {"write": staticmethod(out.append)})
    ct.write_nset(f, "AXIS", np.flatnonzero(np.abs(x) < tol) + 1)
    ct.write_nset(f, "EQ", np.flatnonzero(sphere_nodes & (np.abs(y - case.radius) < tol)) + 1)
    ct.write_nset(f, "BOTTOM", np.flatnonzero(~sphere_nodes & (np.abs(y + case.block * case.a_ref) < tol * 1e3)) + 1)
    ct.write_nset(f, "DENT", np.flatnonzero(~sphere_nodes & (np.abs(x) < tol) & (np.abs(y) < tol)) + 1)
    centre = coords[elements[:, :4] - 1].mean(axis=1)
    near = ~in_sphere & (centre[:, 0] < case.a_ref) & (centre[:, 1] > -1.5 * case.a_ref)
    out.append("*ELSET, ELSET=NEAR\n" + "".join(f"{i + 1},\n" for i in np.flatnonzero(near)))
    top = ~sphere_nodes & (np.abs(y) < tol) & (x < 2.0 * case.a_ref)
    ct.write_nset(f, "TOP", np.flatnonzero(top) + 1)
    within = 3.0 * case.a_ref
    ct.write_element_surface(f, "SSPH", edge_faces(elements, edges["slave"], coords, within))
    ct.write_element_surface(f, "STGT", edge_faces(elements, edges["master"], coords, 2 * within))
    es = case.stiffness_ratio * case.e_flat
    out.append(f"*MATERIAL, NAME=FLAT\n*ELASTIC\n{case.e_flat:.6e},{case.nu_flat}\n"
               + (plastic_card(case) if case.plastic else "")
               + f"*SOLID SECTION, ELSET=BLOCK, MATERIAL=FLAT\n\n"
               f"*MATERIAL, NAME=SPH\n*ELASTIC\n{es:.6e},{case.nu_sphere}\n"
               f"*SOLID SECTION, ELSET=BALL, MATERIAL=SPH\n\n")
    slope = 3.0 * case.yield_strength / (case.penalty * case.delta_m)
    extra = f",{case.tension * case.yield_strength:.6e}" if case.tension else ""
    out.append(f"*CONTACT PAIR, INTERACTION=SI1, TYPE={case.contact}"
               + (", SMALL SLIDING\n" if case.small_sliding else "\n")
               + ("SSPH,STGT\n" if case.slave == "sphere" else "STGT,SSPH\n")
               + "*SURFACE INTERACTION, NAME=SI1\n*SURFACE BEHAVIOR, "
               f"PRESSURE-OVERCLOSURE=LINEAR\n{slope:.6e}{extra}\n")
    out.append(amplitude("LOAD", [(t, t * t) for t in np.linspace(0, 1, 41)]))
    out.append(amplitude("UNLOAD", [(t, 1 - t ** 3) for t in np.linspace(0, 1, 41)]))
    out.append("*BOUNDARY\nAXIS,1,1\nBOTTOM,2,2\n")
    nl = ", NLGEOM" if case.nlgeom else ""
    prints = ("*NODE PRINT, NSET=EQ, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=DENT\nU\n"
              + ("*NODE PRINT, NSET=TOP\nU\n" if case.print_surface else "")
              + ("*EL PRINT, ELSET=NEAR\nS\n" if case.print_stress else "")
              + "*END STEP\n")
    for amp, n in (("LOAD", case.n_load), ("UNLOAD", case.n_unload)):
        out.append(f"*STEP{nl}, INC=10000\n{case.controls}*STATIC\n{1 / n:.8f},1.0,{1e-4 / n:.3e},{1 / n:.8f}\n"
                   f"*BOUNDARY, AMPLITUDE={amp}\nEQ,2,2,{-case.delta_m:.12e}\n" + prints)
    return "".join(out)


def plastic_card(case: Case) -> str:
    """*PLASTIC: von Mises with the small linear hardening ``case.hardening`` × Y per
    unit plastic strain (0: perfectly plastic).  Perfectly plastic runs stall in the
    first unloading increments (ccx's contact loop does not converge at the contact
    edge); 0.03 Y (0.3 % of Y at 10 % plastic strain) lets them run, and the hardening
    study shows its effect on the results."""
    y = case.yield_strength
    card = f"*PLASTIC\n{y:.6e},0.0\n"
    if case.hardening:
        card += f"{y * (1.0 + case.hardening):.6e},1.0\n"
    return card


def max_von_mises(dat_text):
    """Largest von Mises stress [Pa] over the NEAR elements' integration points at the
    end of loading (the stress block printed at total time 1)."""
    header = "stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set NEAR and time"
    blocks = dat_text.split(header)[1:]
    block = next(b for b in blocks if abs(float(b.split()[0]) - 1.0) < 1e-6)
    vm = []
    for line in block.splitlines()[2:]:
        parts = line.split()
        if len(parts) != 8:
            if vm:
                break
            continue
        sx, sy, sz, txy, txz, tyz = (ct._fortran_float(v) for v in parts[2:])
        vm.append(np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                          + 3 * (txy ** 2 + txz ** 2 + tyz ** 2)))
    return float(np.max(vm))


def parse(dat_text):
    """(times, total equator reaction F_z [N] per increment, dent u_z [m])."""
    import level2_static_hertz as l2
    rf = l2.parse_totals(dat_text, "EQ")
    times = ct.parse_node_print_times(dat_text, "DENT")
    dent = np.array([next(iter(b.values()))[1] for b in ct.parse_node_prints(dat_text, "DENT")])
    return times, rf[:, 1], dent


def run(case: Case, workdir: Path, job: str, reuse: bool = False):
    """Mesh, run ccx (or, with ``reuse``, read the .dat of an earlier run of the same
    case), parse.  Returns (record dict, curve arrays dict)."""
    t0 = time.perf_counter()
    coords, elements, in_sphere, edges, h0 = build_mesh(case)
    deck = build_deck(case, coords, elements, in_sphere, edges, h0)
    t1 = time.perf_counter()
    failed = ""
    reused = None
    if reuse and (workdir / f"{job}.log").exists():     # the log is written at the end
        dat = workdir / f"{job}.dat"
        log = (workdir / f"{job}.log").read_text()
        failed = "*ERROR" if "*ERROR" in log else ""
        timed = re.search(r"Total CalculiX Time:\s*(\S+)", log)
        reused = float(timed.group(1)) if timed else float("nan")
    else:
        try:
            dat, _ = ct.run_ccx(deck, job, workdir)
        except RuntimeError as err:      # accepted below only if the sphere had left
            dat, failed = workdir / f"{job}.dat", str(err)[-400:]
    wall = time.perf_counter() - t1 if reused is None else reused
    text = dat.read_text()
    times, rf, _dent = parse(text)
    n1 = int(np.sum(times <= 1.0 + 1e-9))
    t = np.where(np.arange(len(times)) < n1, times, times - 1.0)
    frac = np.where(np.arange(len(times)) < n1, t ** 2, 1 - t ** 3)
    delta = case.delta_m * frac
    force = AXI_FORCE_FACTOR * rf        # reaction on the driven equator = contact force
    curve = dict(delta=np.r_[0.0, delta], force=np.r_[0.0, force],
                 loading=np.r_[True, np.arange(len(t)) < n1])
    rec = summarise(case, curve)
    rec.update(surface_measures(case, text, coords, h0, n1))
    if failed and not rec["separated"]:
        raise RuntimeError(f"ccx stopped before separation ({job}):\n{failed}")
    rec["ccx_stopped_after_separation"] = bool(failed)
    rec.update(asdict(case), h0_m=h0, n_elements=len(elements), n_nodes=len(coords),
               wall_s=(time.perf_counter() - t0 if reused is None else (t1 - t0) + reused),
               ccx_s=wall)
    return rec, curve


# ccx expands axisymmetric elements to a 2° wedge and prints the reaction forces of
# that wedge (RF_z > 0 pushes the sphere up): F = −180 RF_z.  The elastic Hertz check
# (axisym_indent.py --study elastic) confirms the factor to < 1 %.
AXI_FORCE_FACTOR = -180.0


def surface_measures(case: Case, text, coords, h0, n_loading):
    """Residual dent and contact radius from the flat's surface displacements.

    The element on the axis is unreliable (its axis node lags the sphere by up to
    half the approach: a spurious mode of the degenerate expanded element), so the
    dent is the fit ``w(r) = w0 + w2 r²`` of the surface depth over
    2 h0 ≤ r ≤ 2 h0 + 0.3 a_ref after separation, extrapolated to r = 0.  The contact
    radius at δ_m (rigid sphere only) is the largest surface radius still within
    0.5 % of δ_m of the sphere's surface.
    """
    blocks = ct.parse_node_prints(text, "TOP")
    if not blocks:
        return {}
    out = {}
    final, peak = blocks[-1], blocks[n_loading - 1]
    ids = np.array(sorted(final, key=lambda i: coords[i - 1, 0]))
    r = coords[ids - 1, 0]
    depth = -np.array([final[i][1] for i in ids])
    sel = (r >= 2 * h0) & (r <= 2 * h0 + 0.3 * case.a_ref)
    if sel.sum() >= 3:
        c = np.polyfit(r[sel] ** 2, depth[sel], 1)
        out["dent_m"] = float(c[1])
        out["dent_over_dm"] = float(c[1]) / case.delta_m
    out["dent_axis_node_over_dm"] = float(depth[0]) / case.delta_m
    if case.stiffness_ratio >= 100:
        depth_m = -np.array([peak[i][1] for i in ids])
        sphere = case.delta_m - (case.radius - np.sqrt(np.clip(case.radius ** 2 - r ** 2, 0, None)))
        touching = (np.abs(depth_m - sphere) < 5e-3 * case.delta_m) & (r > h0)
        if touching.any():
            out["contact_radius_m"] = float(r[touching].max())
            out["contact_radius_over_ay"] = out["contact_radius_m"] / math.sqrt(
                case.radius * case.delta_y)
    return out


def summarise(case: Case, curve):
    """F_m, the approach δ_0 where the unloading force vanishes (fit
    ``F = A (δ − δ_0)^n`` to the unloading points below 0.5 F_m, or the linear
    zero when fewer than 3), the absorbed and recovered work, normalised by F_y, δ_y."""
    from scipy.optimize import curve_fit
    d, f, load = curve["delta"], curve["force"], curve["loading"]
    fm = float(f[load][-1])
    un_d = np.r_[d[load][-1], d[~load]]
    un_f = np.r_[fm, f[~load]]
    w_abs = float(np.trapezoid(f[load], d[load]))
    pos = un_f > 1e-6 * fm
    k = int(np.flatnonzero(pos)[-1])            # last output still in contact
    separated = k + 2 < len(un_f)               # two outputs without force after it
    dk, fk = un_d[:k + 1], un_f[:k + 1]
    tail = fk < 0.5 * fm
    if k + 1 < len(un_f):
        d0 = un_d[k] - un_f[k] * (un_d[k + 1] - un_d[k]) / (un_f[k + 1] - un_f[k])
    else:
        d0 = float("nan")
    n_tail = float("nan")
    if tail.sum() >= 3:
        x, y = dk[tail] / case.delta_m, fk[tail] / fm
        try:
            (_a, x0, n_tail), _ = curve_fit(lambda x, a, x0, n: a * np.clip(x - x0, 1e-12, None) ** n,
                                           x, y, p0=(1.0, d0 / case.delta_m - 1e-3, 1.5),
                                           bounds=([0.0, 0.0, 1.0], [np.inf, 1.0, 3.0]),
                                           maxfev=20000)
            if x0 < x.min():       # a zero beyond the last point in contact is no fit
                d0 = x0 * case.delta_m
            else:
                n_tail = float("nan")
        except (RuntimeError, ValueError):
            pass
    w_tail = float(fk[-1] * (dk[-1] - d0) / ((n_tail if np.isfinite(n_tail) else 1.0) + 1.0))
    w_rec = float(-np.trapezoid(fk, dk)) + max(w_tail, 0.0)
    return dict(force_max_N=fm, delta_m_m=case.delta_m, delta_y_m=case.delta_y,
                force_y_N=case.force_y, e_star_Pa=case.e_star,
                delta_zero_force_m=float(d0), absorbed_J=w_abs, recovered_J=w_rec,
                dissipated_J=w_abs - w_rec, F_over_Fy=fm / case.force_y,
                d0_over_dm=float(d0) / case.delta_m, e2=w_rec / w_abs,
                absorbed_over_FyDy=w_abs / (case.force_y * case.delta_y),
                tail_exponent=n_tail, unload_outputs_in_contact=k, separated=separated)
