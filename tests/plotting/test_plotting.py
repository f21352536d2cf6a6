"""Plot functions (impactmaps.plotting): every one takes ``ax=None`` and returns the Axes
it drew on, and draws what its docstring promises."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
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
