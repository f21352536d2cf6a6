"""The finite-difference side of a case: what ``[solver] kind = "fd"`` needs and ``[fd]`` holds."""

from __future__ import annotations

import warnings

from ._toml import check_keys, key_path, keyword_options, read_options, string, table

__all__ = ["check_fd_target", "fd_settings", "FD_BEAM_OPTIONS", "FD_RUN_OPTIONS"]

#: ``[fd]`` keys that configure the finite-difference beam (FDBeam fields).
FD_BEAM_OPTIONS = ("n_elements", "n_half_layers", "plastic", "hardening_modulus", "damping_per_length")
#: ``[fd]`` keys that configure the run (keyword options of ``simulate_fd``).
FD_RUN_OPTIONS = ("gravity", "safety_factor", "time_step", "history_stride", "gauge_positions")
#: Beam support codes of the modal targets mapped to the (left, right) ends of FDBeam.
FD_SUPPORTS = {"ss": ("ss", "ss"), "cc": ("cc", "cc"), "cs": ("cc", "ss"),
               "cf": ("cc", "free"), "ff": ("free", "free")}


def check_fd_target(data) -> None:
    """Refuse a ``[target]`` the finite-difference beam cannot model; warn on ignored keys."""
    path = "target"
    if path not in data:
        raise ValueError("[target] is required (type = 'beam' for the finite-difference solver)")
    entries = table(data[path], path)
    kind = string(entries, "type", path, required=True)
    if kind != "beam":
        raise ValueError(f"target.type = {kind!r} is invalid for the finite-difference solver: "
                         "valid values are 'beam'")
    if "plies" in entries or "layup" in entries:
        raise ValueError("target.plies/target.layup are not supported by the finite-difference "
                         "beam: give an isotropic target.material")
    check_keys(entries, path, entries, ("length", "width", "height", "material"))
    theory = entries.get("theory")
    if theory is not None and theory != "rayleigh":
        warnings.warn(f"target.theory = {theory!r}: the finite-difference beam is a Rayleigh beam "
                      "(no shear deformation); the key is ignored", UserWarning, stacklevel=4)
    for key in ("shear_correction", "damping_ratio"):
        if key in entries:
            warnings.warn(f"target.{key} is not used by the finite-difference beam (use "
                          "fd.damping_per_length for damping)", UserWarning, stacklevel=4)


def fd_settings(data, beam, material) -> dict:
    """``[fd]`` validated: ``{"beam": FDBeam, "run": simulate_fd options}``.

    ``beam`` is the case's :class:`~impactmaps.targets.beam.Beam` (its size and
    supports are the finite-difference beam's); ``material`` its isotropic material,
    which needs a yield strength (the layered section needs σ_y even when
    ``fd.plastic = false``).
    """
    from ..fd import FDBeam, simulate_fd

    path = "fd"
    entries = table(data.get(path, {}), path)
    beam_options = {k: v for k, v in keyword_options(FDBeam).items() if k in FD_BEAM_OPTIONS}
    run_options = {k: v for k, v in keyword_options(simulate_fd).items() if k in FD_RUN_OPTIONS}
    check_keys(entries, path, tuple(beam_options) + tuple(run_options))
    if not hasattr(beam, "supports") or not hasattr(beam, "length"):  # TEMPORARY: a modal non-beam case
        from ..materials import IsotropicMaterial  # validates [fd] on a probe beam
        beam = type("Probe", (), dict(length=1.0, width=0.1, height=0.1, supports="ss"))()
        material = IsotropicMaterial(2e11, 0.3, 7800.0, 2e8)
    if getattr(material, "yield_strength", None) is None:
        raise ValueError("target.material.yield_strength is required by the finite-difference "
                         "beam (valid range (0, inf) [Pa]); with fd.plastic = false any positive "
                         "value gives the elastic beam")
    units = {"hardening_modulus": "Pa", "damping_per_length": "N s/m^2", "time_step": "s",
             "gauge_positions": "m"}
    options = read_options(entries, path, beam_options, units)
    run = {"gravity": False, "safety_factor": 0.8, "time_step": None, "history_stride": 1,
           "gauge_positions": ()}
    run.update(read_options(entries, path, run_options, units))
    with key_path(path, tuple(beam_options) + tuple(run_options)):
        fd_beam = FDBeam.from_material(beam.length, beam.width, beam.height, material,
                                       supports=FD_SUPPORTS[beam.supports], **options)
        _check_run(run)
    return {"beam": fd_beam, "run": run}


def _check_run(run) -> None:
    from .._checks import require_in_range, require_nonnegative, require_positive

    require_in_range("safety_factor", run["safety_factor"], 0.0, 1.0, low_inclusive=False)
    if run["time_step"] is not None:
        require_positive("time_step", run["time_step"], "s")
    require_in_range("history_stride", run["history_stride"], 1, float("inf"))
    for index, position in enumerate(run["gauge_positions"]):
        require_nonnegative(f"gauge_positions[{index}]", position, "m")
