"""Plot functions (impactmaps.plotting): every one takes ``ax=None`` and returns the Axes
it drew on, and draws what its docstring promises."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from pathlib import Path  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from impactmaps import plotting  # noqa: E402
from impactmaps.contact import LinearContact  # noqa: E402
from impactmaps.maps.family.structures import structure_from_name  # noqa: E402
from impactmaps.maps.compute.sweep import sweep  # noqa: E402
from impactmaps.solvers.modal import simulate  # noqa: E402

from ..analytic import ss_plate_impactor, ss_square_plate_basis  # noqa: E402

ZETAS = np.geomspace(0.01, 30.0, 8)
LAMBDAS = np.array([0.1, 1.0])


@pytest.fixture(scope="module")
def dataset():
    structures = [structure_from_name("beam-ss-euler"), structure_from_name("plate-ssss-kirchhoff")]
    return sweep(structures, ZETAS, LAMBDAS, progress=False, max_workers=1)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def test_fmax_chart_draws_every_curve_and_returns_axes(dataset):
    """One line per (structure, λ) with the data's values, plates solid, beams dashed."""
    ax = plotting.plot_fmax_chart(dataset, asymptotes=False)
    assert isinstance(ax, matplotlib.axes.Axes)
    curves = [line for line in ax.lines if len(line.get_xdata()) == ZETAS.size]
    assert len(curves) == 4
    styles = sorted(line.get_linestyle() for line in curves)
    assert styles == ["-", "-", "--", "--"]
    plate = dataset["fmax_normalised"].sel(structure="plate-ssss-kirchhoff", lambda_=1.0).values
    assert any(np.allclose(line.get_ydata(), plate) for line in curves)
    _figure, given = plt.subplots()
    assert plotting.plot_fmax_chart(dataset, ax=given) is given


def test_regime_strip_has_one_row_per_curve(dataset):
    ax = plotting.plot_regime_strip(dataset)
    assert isinstance(ax, matplotlib.axes.Axes)
    labels = [label.get_text() for label in ax.get_yticklabels()]
    assert labels == ["beam λ=0.1", "beam λ=1", "plate λ=0.1", "plate λ=1"]


def test_regime_map_returns_axes(dataset):
    ax = plotting.plot_regime_map(dataset, "plate-ssss-kirchhoff")
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"


def test_history_scaling_and_restitution_plots():
    mass, stiffness = ss_plate_impactor(1.198, 0.425)
    basis = ss_square_plate_basis(40 * np.sqrt(stiffness / mass), 4)


    result = simulate(basis, LinearContact(stiffness), mass, 1.0)
    ax = plotting.plot_force_history(result)
    assert isinstance(ax, matplotlib.axes.Axes)
    np.testing.assert_allclose(ax.lines[0].get_ydata(), result.normalised_history()["force_normalised"])
    ax = plotting.plot_scaling(result, result, quantity="deflection")
    assert len(ax.lines) == 2
    ax = plotting.plot_restitution([1.0, 10.0], [1.0, 0.5], points=([2.0], [0.8]))
    assert ax.get_xscale() == "log" and len(ax.lines) == 2


def test_impact_history_figure_has_three_panels_and_marks_contacts(tmp_path):
    mass, stiffness = ss_plate_impactor(1.198, 0.425)
    basis = ss_square_plate_basis(40 * np.sqrt(stiffness / mass), 4)
    result = simulate(basis, LinearContact(stiffness), mass, 1.0)
    figure = plotting.plot_impact_history(result, normalised=True)
    assert len(figure.axes) == 3
    assert all(len(ax.patches) >= result.impacts for ax in figure.axes)  # one shaded span per contact
    path = plotting.save_impact_history(result, tmp_path / "history.png")
    assert path.stat().st_size > 1000


def test_fmax_chart_legend_names_the_dotted_lines_and_sits_outside(dataset):
    ax = plotting.plot_fmax_chart(dataset)
    texts = [text.get_text() for text in ax.get_legend().get_texts()]
    assert any("quasi-static" in text for text in texts)
    assert ax.get_legend().get_bbox_to_anchor().x0 > ax.get_window_extent().x1 - 1
    assert "$" in ax.get_ylabel()  # m_i, V_0 typeset as subscripts


def test_regime_map_is_classified_on_a_dense_grid_when_complete(dataset):
    from matplotlib.collections import QuadMesh

    ax = plotting.plot_regime_map(dataset, "plate-ssss-kirchhoff")
    mesh = next(c for c in ax.collections if isinstance(c, QuadMesh))
    cells = dataset.sizes["zeta"] * dataset.sizes["lambda_"]
    if bool(dataset["done"].values.all()):
        assert mesh.get_array().size > cells
    coarse = plotting.plot_regime_map(dataset, "plate-ssss-kirchhoff", smooth=False)
    mesh = next(c for c in coarse.collections if isinstance(c, QuadMesh))
    assert mesh.get_array().size == cells


def test_fmax_chart_draws_sensitive_stretches_as_a_band(dataset):
    """Where the dataset marks points sensitive, the curve is a filled band between
    fmax_low and fmax_high (its colour), the line is not drawn there, and the legend
    says what the band means."""
    from impactmaps.maps.family.accuracy import STATUSES

    marked = dataset.copy(deep=True)
    name, lam = "beam-ss-euler", 0.1
    cell = {"structure": name, "lambda_": lam}
    status = marked["status"].loc[cell].values.copy()
    status[:] = STATUSES.index("converged")
    status[2:5] = STATUSES.index("sensitive")
    marked["status"].loc[cell] = status
    values = marked["fmax_normalised"].loc[cell].values
    marked["fmax_low"].loc[cell] = values - 0.05
    marked["fmax_high"].loc[cell] = values + 0.05
    for other in ("plate-ssss-kirchhoff",):
        marked["status"].loc[{"structure": other}] = STATUSES.index("converged")
    marked["status"].loc[{"structure": name, "lambda_": 1.0}] = STATUSES.index("converged")

    ax = plotting.plot_fmax_chart(marked, asymptotes=False, shade_regimes=False)
    bands = [patch for patch in ax.collections if len(patch.get_paths()) and patch.get_paths()[0].vertices.size]
    assert len(bands) == 1
    vertices = bands[0].get_paths()[0].vertices
    # the band spans the run widened to its neighbours (indices 1..5), between low and high
    assert np.isclose(vertices[:, 0].min(), ZETAS[1]) and np.isclose(vertices[:, 0].max(), ZETAS[5])
    assert np.isclose(vertices[:, 1].max(), np.max(values[1:6] + 0.05))
    assert np.isclose(vertices[:, 1].min(), np.min(values[1:6] - 0.05))
    curves = [line for line in ax.lines if len(line.get_xdata()) == ZETAS.size]
    beam = [line for line in curves if np.isnan(np.asarray(line.get_ydata(), float)).any()]
    assert len(beam) == 1
    drawn = np.asarray(beam[0].get_ydata(), float)
    assert np.all(np.isnan(drawn[2:5])) and np.allclose(drawn[[0, 1, 5, 6, 7]], values[[0, 1, 5, 6, 7]])
    assert matplotlib.colors.same_color(bands[0].get_facecolor()[0][:3], beam[0].get_color())
    assert bands[0].get_hatch() == "////"  # a beam's band is hatched, a plate's is not
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert any(label.startswith("sensitive") for label in labels)


def test_fmax_chart_without_sensitive_points_has_no_band(dataset):
    from impactmaps.maps.family.accuracy import STATUSES

    clean = dataset.copy(deep=True)
    clean["status"][:] = STATUSES.index("converged")
    ax = plotting.plot_fmax_chart(clean, asymptotes=False, shade_regimes=False)
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert not any(label.startswith("sensitive") for label in labels)


# -- issue 40 items 11 and 13 -------------------------------------------------------------------
def test_fmax_chart_labels_the_grid_lambda_it_draws(dataset):
    """An asked λ is drawn at the nearest grid λ, and the legend and the quasi-static line are
    that grid λ's (it labelled the asked λ: curves fell below 'their' asymptote)."""
    from impactmaps.maps.family.regimes import quasi_static_peak

    ax = plotting.plot_fmax_chart(dataset, lambdas=[0.3, 0.12], shade_regimes=False)
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert "λ = 0.1" in labels and "λ = 0.3" not in labels and "λ = 0.12" not in labels
    assert sum(label.startswith("λ =") for label in labels) == 1  # 0.3 and 0.12 are both the grid's 0.1
    dotted = {round(float(line.get_ydata()[0]), 12) for line in ax.lines
              if line.get_linestyle() == ":" and len(line.get_ydata()) == 2}
    assert dotted == {round(float(quasi_static_peak(0.1)), 12)}
    with pytest.raises(ValueError, match="lambdas"):
        plotting.plot_fmax_chart(dataset, lambdas=[-1.0])


def test_fmax_chart_has_one_local_shading_and_defines_omega(dataset):
    """The local regime is shaded once (the band F̄max ≥ 0.9), not again as a vertical band
    over it; a note defines ω, λ and ζ for the linear chart."""
    ax = plotting.plot_fmax_chart(dataset)
    local = matplotlib.colors.to_rgb(plotting.REGIME_COLOURS["local"])
    shaded = [patch for patch in ax.patches if matplotlib.colors.same_color(patch.get_facecolor()[:3], local)]
    assert len(shaded) == 1
    assert any("ω = √(K/m_i)" in text.get_text() for text in ax.texts)


def test_sensitive_points_stay_visible_when_their_band_is_thin(dataset):
    """A sensitive point whose band is narrower than the line is still marked (×): the
    legend entry 'sensitive' always has something drawn to point at."""
    from impactmaps.maps.family.accuracy import STATUSES

    marked = dataset.copy(deep=True)
    marked["status"][:] = STATUSES.index("converged")
    cell = {"structure": "plate-ssss-kirchhoff", "lambda_": 1.0}
    status = marked["status"].loc[cell].values.copy()
    status[4] = STATUSES.index("sensitive")
    marked["status"].loc[cell] = status
    values = marked["fmax_normalised"].loc[cell].values
    marked["fmax_low"].loc[cell], marked["fmax_high"].loc[cell] = values - 1e-4, values + 1e-4
    ax = plotting.plot_fmax_chart(marked, asymptotes=False, shade_regimes=False)
    crosses = [line for line in ax.lines if line.get_marker() == "x" and len(line.get_xdata()) == 1]
    assert len(crosses) == 1 and np.isclose(crosses[0].get_xdata()[0], ZETAS[4])


def test_regime_map_labels_sit_upright_on_their_lines_inside_the_axes(dataset):
    """Contour labels are horizontal, inside the axes, on a point of their own contour;
    the title names the structure in words, not by its internal id."""
    ax = plotting.plot_regime_map(dataset, "plate-ssss-kirchhoff")
    labels = [text for text in ax.texts if "F}_{max}" in text.get_text()]
    assert labels
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for text in labels:
        x, y = text.get_position()
        assert text.get_rotation() == 0 and x0 < x < x1 and y0 < y < y1
    assert "plate-ssss" not in ax.get_title() and "simply supported Kirchhoff plate" in ax.get_title()


def test_classifier_never_calls_a_peak_before_the_first_reflection_quasi_static():
    """Where the two asymptotes cross (F̄∞(ζ) = sqrt(λ/(1+λ))), a peak before any wave
    returns is the infinite structure's, however near the quasi-static value it lies (the
    regime maps showed a quasi-static sliver through the infinite-structure area);
    without the times the nearer asymptote still decides."""
    from impactmaps.maps.family.regimes import classify, infinite_structure_peak, quasi_static_peak

    zeta, lam = 0.199, 0.822  # measured on the beam chart: F̄max 0.668, F̄∞ 0.690, sqrt(λ/(1+λ)) 0.672
    fmax = 0.668
    assert abs(fmax - float(quasi_static_peak(lam))) < abs(fmax - float(infinite_structure_peak(zeta, "beam")))
    assert classify(fmax, zeta, lam, "beam", peak_time=1.1, reflection_time=2.45)[()] == "infinite-structure"
    assert classify(fmax, zeta, lam, "beam")[()] == "quasi-static"
    assert classify(fmax, zeta, lam, "beam", peak_time=4.0, reflection_time=2.1)[()] == "quasi-static"


def test_impact_history_legend_sits_above_the_force_panel():
    """The legend is above the top panel, so it never hides the peak marker."""
    mass, stiffness = ss_plate_impactor(1.198, 0.425)
    basis = ss_square_plate_basis(40 * np.sqrt(stiffness / mass), 4)
    result = simulate(basis, LinearContact(stiffness), mass, 1.0)
    figure = plotting.plot_impact_history(result)
    top = figure.axes[0]
    figure.canvas.draw()
    legend = top.get_legend().get_window_extent()
    assert legend.y0 >= top.get_window_extent().y1 - 1


def test_plot_command_draws_a_users_sweep_and_asks_for_beta_on_a_plastic_map(dataset, tmp_path, capsys):
    """`impactmaps plot` draws a sweep result's F̄max chart (the λ asked drawn at the grid's
    nearest); an elastic-plastic map needs --beta and says which β it has."""
    import json

    from impactmaps.cli import main
    from impactmaps.maps.files.data_io import write_dataset

    path = tmp_path / "sweep.nc"
    write_dataset(dataset, path)
    assert main(["plot", str(tmp_path), "--lambdas", "0.3", "--json"]) == 0
    drawn = json.loads(capsys.readouterr().out)
    assert drawn["kind"] == "sweep" and (tmp_path / "sweep_chart.png").stat().st_size > 1000
    shipped = Path(plotting.__file__).resolve().parents[1] / "maps" / "data" / "beam-ss-euler-epp.npz"
    assert main(["plot", str(shipped), "--out", str(tmp_path / "epp.png")]) == 2
    assert "--beta" in capsys.readouterr().err
    assert main(["plot", str(shipped), "--beta", "10", "--out", str(tmp_path / "epp.png")]) == 0
    assert (tmp_path / "epp.png").stat().st_size > 1000
    capsys.readouterr()
    (tmp_path / "junk.nc").write_text("not a map")
    for argv in (["plot", str(tmp_path), "--out", str(tmp_path / "missing" / "x.png")],
                 ["plot", str(tmp_path), "--out", str(tmp_path / "x.txt")],
                 ["plot", str(tmp_path / "junk.nc")]):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "Traceback" not in err
