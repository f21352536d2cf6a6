"""``impactmaps simulate CASE --vary KEY=A:B:N[:log]``: a parameter study of one case-file key.

Each value of the key gives a case (the file with that key set), run exactly as
``simulate`` runs it, its outputs in ``OUT/study/run_NNN/``. The study writes
``OUT/study.csv`` and ``OUT/study.json`` (one row per value: the key and every scalar of
the run's summary — peak force, restitution, contact durations, impacts, energies, the
law's normalised numbers), ``OUT/study_forces.png`` (the force histories overlaid) and
``OUT/study.png`` (peak force and restitution against the key, a log axis for a log
study; ``impactmaps plot OUT`` draws it again, with other quantities). A run whose
directory already holds the summary of the same case text is reused, so a study
interrupted with Ctrl-C resumes where it stopped.
"""

from __future__ import annotations

import json
import math
import sys
import tomllib
from pathlib import Path

from .._files import written_atomically

__all__ = ["MAX_STUDY_RUNS", "parse_vary", "vary_spacing", "set_key", "render_toml", "run_study", "study_scalars"]

#: Most runs a study may ask for (each is a full simulation).
MAX_STUDY_RUNS = 200
#: Summary keys the study table keeps, in order.
TABLE_KEYS = ("peak_force_N", "first_contact_duration_s", "total_contact_time_s", "impacts", "restitution",
              "fmax_normalised", "zeta", "lambda", "beta", "converged")


#: Significant digits the study's values keep: A + (B − A) i/(N − 1) and the log steps carry
#: round-off (1.9000000000000001); the values run, printed and stored are rounded to these.
VALUE_DIGITS = 12


def _clean(value: float) -> float:
    """``value`` rounded to :data:`VALUE_DIGITS` significant digits (no float noise)."""
    return float(f"{value:.{VALUE_DIGITS}g}")


def parse_vary(text: str) -> tuple[str, list[float]]:
    """``KEY=A:B:N`` (N values from A to B, evenly spaced), ``KEY=A:B:N:log`` (evenly spaced
    in log, A and B > 0) or ``KEY=V1,V2,…`` → (key, values), values rounded to 12
    significant digits."""
    key, sep, spec = str(text).partition("=")
    key = key.strip()
    if not sep or not key or "." not in key:
        raise ValueError(f"--vary = {text!r} is invalid: give SECTION.KEY=A:B:N (e.g. impactor.velocity=0.5:5:10), "
                         "SECTION.KEY=A:B:N:log or SECTION.KEY=V1,V2,…")
    try:
        if ":" in spec:
            parts = spec.split(":")
            if len(parts) == 4 and parts[3].strip().lower() == "log":
                parts, log = parts[:3], True
            elif len(parts) == 3:
                log = False
            else:
                raise ValueError
            low, high, count = parts
            low, high = float(low), float(high)
            if not float(count).is_integer():
                raise ValueError
            count = int(float(count))
            if not (math.isfinite(low) and math.isfinite(high)) or not 1 <= count <= MAX_STUDY_RUNS:
                raise ValueError
            if log:
                if not (low > 0 and high > 0):
                    raise ValueError(f"--vary = {text!r} is invalid: a log study needs A > 0 and B > 0") from None
                ratio = math.log(high / low)
                values = [low * math.exp(ratio * i / max(count - 1, 1)) for i in range(count)]
            else:
                values = [low + (high - low) * i / max(count - 1, 1) for i in range(count)]
            values = [_clean(v) for v in values]
        else:
            values = [float(v) for v in spec.split(",")]
            if not all(math.isfinite(v) for v in values) or not 1 <= len(values) <= MAX_STUDY_RUNS:
                raise ValueError
    except ValueError as error:
        if str(error).startswith("--vary"):
            raise
        raise ValueError(f"--vary = {text!r} is invalid: the values must be A:B:N or A:B:N:log (finite A, B; N an "
                         f"integer in [1, {MAX_STUDY_RUNS}]) or a list V1,V2,… of finite numbers") from None
    return key, values


def vary_spacing(text: str) -> str:
    """``"log"``, ``"even"`` or ``"list"``: how :func:`parse_vary` spaces the values of ``text``
    (evenly in log, evenly, as listed)."""
    spec = str(text).partition("=")[2]
    if ":" not in spec:
        return "list"
    return "log" if spec.split(":")[-1].strip().lower() == "log" else "even"


def study_scalars(summary: dict) -> dict:
    """The scalars of a run's summary (numbers, booleans, ``None``), in the summary's order,
    the study table's columns first."""
    first = {k: summary.get(k) for k in TABLE_KEYS}
    rest = {k: v for k, v in summary.items()
            if k not in first and (v is None or isinstance(v, (bool, int, float)))}
    return first | rest


def set_key(data: dict, key: str, value) -> dict:
    """A copy of the case ``data`` with the dotted ``key`` set to ``value`` (an integer where the
    file had one)."""
    import copy

    out = copy.deepcopy(data)
    node = out
    *sections, last = key.split(".")
    for section in sections:
        child = node.setdefault(section, {})
        if not isinstance(child, dict):
            raise ValueError(f"--vary {key}: {section} is not a table of the case file")
        node = child
    old = node.get(last)
    if isinstance(old, bool) or (old is not None and not isinstance(old, (int, float))):
        raise ValueError(f"--vary {key}: the case gives it {old!r}, not a number")
    if isinstance(old, int) and float(value).is_integer():
        value = int(value)
    node[last] = value
    return out


def _literal(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value) if math.isfinite(value) else ("nan" if math.isnan(value) else
                                                         ("inf" if value > 0 else "-inf"))
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_literal(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_literal(v)}" for k, v in value.items()) + "}"
    raise ValueError(f"cannot write {value!r} as TOML")


def render_toml(data: dict) -> str:
    """TOML text of a case (top-level values, then one table per section; deeper tables inline)."""
    lines = [f"{k} = {_literal(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for section, entries in data.items():
        if isinstance(entries, dict):
            lines.append(f"\n[{section}]")
            lines += [f"{k} = {_literal(v)}" for k, v in entries.items()]
    return "\n".join(lines) + "\n"


def run_study(case_path: Path, vary: str, out: Path, solver=None, progress: bool = True) -> dict:
    """Run the study ``vary`` of the case file ``case_path`` into ``out`` (see the module docstring);
    ``progress``: a line on stderr per run."""
    from ..cases import parse_case, run_case, write_case_outputs
    from ..jsonio import dumps
    from ._common import refuse_ignored_fd, text_file

    key, values = parse_vary(vary)
    spacing = vary_spacing(vary)
    source = text_file("case file", case_path)
    try:
        data = tomllib.loads(source.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{source}: not valid TOML: {error}") from None
    cases = []
    for value in values:  # every case validated before the first run
        text = render_toml(set_key(data, key, value))
        try:
            case = parse_case(text, name=source.stem, source=source, solver=solver)
        except ValueError as error:
            raise ValueError(f"--vary {key} = {value:g}: {error}") from None
        refuse_ignored_fd(case, source)
        cases.append((value, text, case))
    rows, histories, reused = [], [], 0
    for index, (value, text, case) in enumerate(cases):
        run_dir = out / "study" / f"run_{index:03d}"
        summary_path = run_dir / "summary.json"
        if summary_path.exists() and (run_dir / "case.toml").exists() \
                and (run_dir / "case.toml").read_text(encoding="utf-8") == text:
            summary = json.loads(summary_path.read_text(encoding="utf-8"))
            reused += 1
            state = "reused"
        else:
            result, summary = run_case(case)
            write_case_outputs(case, result, run_dir)
            state = "done"
        if progress:
            print(f"[{index + 1}/{len(cases)}] {key} = {value:g}: peak force {summary.get('peak_force_N') or math.nan:.6g} N"
                  f" ({state})", file=sys.stderr)
        rows.append({key: value, **study_scalars(summary)})
        histories.append((value, run_dir / "history.csv"))
    table = out / "study.csv"
    import pandas as pd

    with written_atomically(table) as part:
        pd.DataFrame(rows).to_csv(part, index=False)
    figure = _overlay(histories, key, out / "study_forces.png")
    with written_atomically(out / "study.json") as part:
        part.write_text(dumps({"vary": key, "spacing": spacing, "rows": rows}, indent=2) + "\n", encoding="utf-8")
    from .plot import draw_study

    picture = draw_study(out, out / "study.png")
    columns = list(dict.fromkeys(k for row in rows for k in row if k != key))
    return {"vary": key, "spacing": spacing, "values": values, "runs": len(cases), "reused": reused,
            "peak_force_N": [row.get("peak_force_N") for row in rows],
            "results": {column: [row.get(column) for row in rows] for column in columns},
            "table": str(table), "plot": str(picture),
            "figure": None if figure is None else str(figure),
            **({} if figure is not None else {"figure_note": "no run has a force history to draw"})}


def _overlay(histories, key: str, path: Path):
    """The force histories of the study on one figure, or None when no run has one."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    drawn = [(value, file) for value, file in histories if file.exists()]
    if not drawn:
        return None
    figure, axes = plt.subplots(figsize=(7, 4.5))
    colours = plt.cm.viridis([i / max(len(drawn) - 1, 1) for i in range(len(drawn))])
    for (value, file), colour in zip(drawn, colours):
        history = pd.read_csv(file, usecols=["time_s", "force_N"])
        axes.plot(history["time_s"] * 1e3, history["force_N"], color=colour, lw=1.0, label=f"{value:g}")
    axes.set_xlabel("time [ms]")
    axes.set_ylabel("contact force [N]")
    axes.set_title(f"force histories, {key} varied")
    axes.legend(title=key, fontsize="small", ncol=2 if len(drawn) > 8 else 1)
    figure.tight_layout()
    with written_atomically(path) as part:
        figure.savefig(part, dpi=120)
    plt.close(figure)
    return path
