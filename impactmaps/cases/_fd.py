"""The finite-difference side of a case: what ``[solver] kind = "fd"`` needs and ``[fd]`` holds.

``[fd]`` maps onto :class:`impactmaps.fd.FDSettings` (its keys are that dataclass's
options, ``duration`` excepted: it is ``[solver] duration``); the finite-difference beam
is built from the case's :class:`~impactmaps.targets.beams.beam.Beam` by
:meth:`FDBeam.from_beam <impactmaps.fd.FDBeam.from_beam>`.
"""

from __future__ import annotations

import warnings

from ..targets.options import FD_BEAM_THEORY
from .._toml import check_keys, key_path, keyword_options, read_options, string, table

__all__ = ["check_fd_target", "fd_settings"]

_UNITS = {"hardening_modulus": "Pa", "damping_per_length": "N s/m^2", "time_step": "s",
          "gauge_positions": "m"}


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
    theory = entries.get("theory")
    if theory is not None and theory != FD_BEAM_THEORY:
        warnings.warn(f"target.theory = {theory!r}: the finite-difference beam is a Rayleigh beam "
                      "(no shear deformation); the key is ignored", UserWarning, stacklevel=4)
    for key in ("shear_correction", "damping_ratio"):
        if key in entries:
            warnings.warn(f"target.{key} is not used by the finite-difference beam (use "
                          "fd.damping_per_length for damping)", UserWarning, stacklevel=4)


def fd_settings(data, material, *, required: bool):
    """``[fd]`` as :class:`~impactmaps.fd.FDSettings` (validated by the dataclass).

    ``required`` (a ``kind = "fd"`` case): the target material must have a yield
    strength — the layered section needs σ_y even when ``fd.plastic = false``.
    """
    from ..fd import FDSettings

    path = "fd"
    entries = table(data.get(path, {}), path)
    options = {k: v for k, v in keyword_options(FDSettings).items() if k != "duration"}
    check_keys(entries, path, tuple(options))
    if required and getattr(material, "yield_strength", None) is None:
        raise ValueError("target.material.yield_strength is required by the finite-difference "
                         "beam (valid range (0, inf) [Pa]); with fd.plastic = false any positive "
                         "value gives the elastic beam")
    values = read_options(entries, path, options, _UNITS)
    with key_path(path, tuple(options)):
        return FDSettings(**values)
