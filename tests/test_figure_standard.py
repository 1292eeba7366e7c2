"""The figure standard checker (sandbox.figure_standard): each rule passes a figure that meets
it and fails one that breaks it, and save_figure raises only when checking is switched on."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from sandbox.figure_standard import ENV, FigureStandardError, check_figure
from sandbox.lessonkit import save_figure

T = np.linspace(0.0, 1.0, 50)


def good_figure():
    fig, ax = plt.subplots(figsize=(5, 3))
    ax.plot(T, T**2, label="x = t^2")
    ax.plot(T, T, label="x = t")
    ax.set(xlabel="t (s)", ylabel="x (m)", title="two curves")
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0))  # outside the data
    fig.tight_layout()
    return fig


def problems_of(fig) -> list[str]:
    try:
        return check_figure(fig)
    finally:
        plt.close(fig)


def test_a_figure_that_meets_the_standard_passes():
    assert problems_of(good_figure()) == []


def test_a_title_is_required_on_every_panel_or_as_a_suptitle():
    fig = good_figure()
    fig.axes[0].set_title("")
    assert any("no title" in p for p in problems_of(fig))
    fig = good_figure()
    fig.axes[0].set_title("")
    fig.suptitle("the whole figure")
    assert problems_of(fig) == []


@pytest.mark.parametrize("label", ["", "x", "drift"])
def test_a_data_axis_needs_a_label_ending_with_a_unit(label):
    fig = good_figure()
    fig.axes[0].set_ylabel(label)
    (problem,) = problems_of(fig)
    assert "y" in problem and ("no label" in problem or "no (unit)" in problem)


def test_hidden_ticks_and_categorical_ticks_need_no_label():
    fig, (ax, bx) = plt.subplots(1, 2)
    ax.plot(T, T)
    ax.set(xlabel="t (s)", yticks=[], title="no y ticks")
    bx.bar([0, 1, 2], [3.0, 1.0, 2.0])
    bx.set_xticks([0, 1, 2], ["angle", "matrix", "complex"])
    bx.set(ylabel="time (ns)", title="categories on x")
    assert problems_of(fig) == []


def test_several_series_need_a_legend_naming_each():
    fig = good_figure()
    fig.axes[0].get_legend().remove()
    assert any("no legend" in p for p in problems_of(fig))
    fig = good_figure()
    fig.axes[0].plot(T, 0.5 * T, color="C5")  # an unnamed third series in a new colour
    assert any("in no legend" in p for p in problems_of(fig))
    fig = good_figure()
    fig.axes[0].plot(T, 0.5 * T**2, color="C0", ls="--")  # same colour as a named series
    assert problems_of(fig) == []


def test_a_legend_over_data_fails_and_one_beside_it_passes():
    fig, ax = plt.subplots(figsize=(5, 3))
    ax.plot(T, np.full_like(T, 0.5), label="flat")
    ax.plot(T, T, label="rising")
    ax.set(xlabel="t (s)", ylabel="x (m)", title="legend placement")
    ax.legend(loc="center")  # right over both lines
    assert any("legend covers data" in p for p in problems_of(fig))
    fig, ax = plt.subplots(figsize=(5, 3))
    ax.plot(T, 0.2 * T, label="low")
    ax.plot(T, 0.3 * T, label="lower")
    ax.set(xlabel="t (s)", ylabel="x (m)", title="legend placement", ylim=(0, 1))
    ax.legend(loc="upper left")  # empty corner: the lines stay below 0.3
    assert problems_of(fig) == []


def test_a_segment_crossing_the_legend_without_a_vertex_inside_is_caught():
    fig, ax = plt.subplots(figsize=(5, 3))
    ax.plot([0.0, 1.0], [1.0, 1.0], label="one long segment")  # no vertex under the legend
    ax.plot(T, 0.1 * T, label="low")
    ax.set(xlabel="t (s)", ylabel="x (m)", title="segment", ylim=(0, 2), xlim=(0, 1))
    ax.legend(loc="center")
    assert any("one long segment" in p for p in problems_of(fig))


def test_save_figure_raises_only_when_checking_is_on(tmp_path, monkeypatch):
    def bad():
        fig, ax = plt.subplots()
        ax.plot(T, T)
        return fig

    monkeypatch.delenv(ENV, raising=False)
    assert save_figure(bad(), tmp_path / "off.png").exists()
    monkeypatch.setenv(ENV, "1")
    with pytest.raises(FigureStandardError, match="on.png"):
        save_figure(bad(), tmp_path / "on.png")
    assert not (tmp_path / "on.png").exists()
    assert save_figure(good_figure(), tmp_path / "good.png").exists()
