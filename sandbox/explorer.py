"""A lesson's explorer cell: sliders and toggles that rerun a small simulation and redraw its
figure, so that a student can ask "what if?" (as PhET simulations and the Box2D samples do).

The lesson writes one function that runs the scene and returns a matplotlib figure; its keyword
defaults are the values the figure starts with. One control per keyword::

    def bounce(restitution=0.8, dt=1 / 60, solver="iterative"):
        ...
        return fig

    explore(bounce, OUT / "explore_bounce.png",
            restitution=Slider(0.0, 1.0, 0.05, "restitution e"),
            dt=Choice({"1/120 s": 1 / 120, "1/60 s": 1 / 60, "1/30 s": 1 / 30}, "dt", slider=True),
            solver=Choice(SOLVERS, "solver"))

The figure is always drawn once with the defaults, saved to the file and (in a notebook) shown:
that is all a script or an unattended notebook run does, and it needs no ipywidgets. In a live
notebook with ipywidgets the controls sit above the figure; changing one reruns the function
and redraws it.
"""

from __future__ import annotations

import inspect
import io
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any


@dataclass(frozen=True)
class Slider:
    """A number from ``low`` to ``high`` in steps of ``step`` (whole numbers when all three and
    the default are ints)."""

    low: float
    high: float
    step: float
    label: str = ""


@dataclass(frozen=True)
class Choice:
    """One of ``options``: a sequence of values, or a mapping label -> value. ``slider`` shows
    them on a slider (for ordered values such as time steps) instead of buttons or a menu."""

    options: Sequence[Any] | Mapping[str, Any]
    label: str = ""
    slider: bool = False
    pairs: tuple = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if isinstance(self.options, Mapping):
            pairs = tuple((str(k), v) for k, v in self.options.items())
        else:
            pairs = tuple((str(v), v) for v in self.options)
        if not pairs:
            raise ValueError("Choice: no options")
        object.__setattr__(self, "pairs", pairs)


@dataclass(frozen=True)
class Toggle:
    """On or off."""

    label: str = ""


Control = Slider | Choice | Toggle
CONTROLS_KEY = "sandbox_controls"  # output metadata of a live explorer: the names of its controls


def explore(draw: Callable[..., Any], path: str | os.PathLike, **controls: Control) -> Path:
    """Draw ``draw()`` (a matplotlib figure) with its defaults, save it to ``path`` (PNG) and show
    it; in a live notebook with ipywidgets, add one control per keyword of ``controls`` that
    reruns ``draw`` with the new value and redraws. Returns ``path``."""
    from sandbox.atomic import atomic_write_bytes
    from sandbox.lessonkit import ShownPath, show_image
    from sandbox.notebook import in_kernel

    defaults = check_controls(draw, controls)
    png = figure_png(draw(**defaults))
    path = Path(path)
    atomic_write_bytes(path, png)
    if in_kernel():
        try:
            import ipywidgets  # noqa: F401
        except ImportError:
            pass
        else:
            _display_live(draw, controls, defaults, png, path)
            return ShownPath(path)
    return show_image(path)


def check_controls(draw: Callable[..., Any], controls: Mapping[str, Control]) -> dict:
    """Each control names a keyword of ``draw`` with a default that the control can show;
    returns those defaults. Raises ``TypeError`` / ``ValueError`` naming the keyword."""
    params = inspect.signature(draw).parameters
    defaults = {}
    for key, control in controls.items():
        p = params.get(key)
        if p is None or p.default is inspect.Parameter.empty:
            raise TypeError(f"explore: {draw.__name__}() has no keyword {key!r} with a default")
        value = p.default
        if isinstance(control, Slider):
            ok = control.low <= value <= control.high
        elif isinstance(control, Choice):
            ok = any(v == value for _, v in control.pairs)
        elif isinstance(control, Toggle):
            ok = isinstance(value, bool)
        else:
            raise TypeError(f"explore: {key}: expected a Slider, Choice or Toggle")
        if not ok:
            raise ValueError(
                f"explore: {key}: default {value!r} is not one of the control's values"
            )
        defaults[key] = value
    return defaults


def figure_png(fig, dpi: float = 100) -> bytes:
    """The PNG bytes of a matplotlib figure, which is then closed."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    plt.close(fig)
    return buffer.getvalue()


def build_view(
    draw: Callable[..., Any], controls: Mapping[str, Control], defaults: dict, png: bytes
):
    """The explorer's widgets: ``(box, inputs, image)``; changing an input redraws ``image``."""
    import ipywidgets as w

    inputs = {key: _widget(key, c, defaults[key]) for key, c in controls.items()}
    image = w.Image(value=png, format="png", layout=w.Layout(max_width="100%", height="auto"))
    status = w.Label("defaults")
    reset = w.Button(description="defaults", tooltip="back to the lesson's values")
    holding = [False]

    def redraw(_change=None) -> None:
        if holding[0]:
            return
        values = {key: widget.value for key, widget in inputs.items()}
        status.value = "running ..."
        try:
            image.value = figure_png(draw(**values))
        except Exception as err:  # a diverging run or a bad value: say so, keep the last figure
            status.value = f"{type(err).__name__}: {err}"[:200]
            return
        same = all(values[k] == defaults[k] for k in values)
        status.value = (
            "defaults" if same else ", ".join(f"{k} = {_show(v)}" for k, v in values.items())
        )

    def back(_button=None) -> None:
        holding[0] = True
        for key, widget in inputs.items():
            widget.value = defaults[key]
        holding[0] = False
        redraw()

    for widget in inputs.values():
        widget.observe(redraw, names="value")
    reset.on_click(back)
    row = w.HBox([*inputs.values(), reset], layout=w.Layout(flex_flow="row wrap"))
    return w.VBox([row, status, image]), inputs, image


def _display_live(draw, controls, defaults, png: bytes, path: Path) -> None:
    """Show the widgets, with the default figure as the fallback for static viewers."""
    from IPython.display import display

    from sandbox.notebook import FILE_KEY, image_bundle

    box, _, _ = build_view(draw, controls, defaults, png)
    bundle = box._repr_mimebundle_()
    bundle.update(image_bundle(png, ".png", path.name))
    display(bundle, raw=True, metadata={FILE_KEY: path.name, CONTROLS_KEY: list(controls)})


def _widget(key: str, control: Control, value: Any):
    import ipywidgets as w

    label = control.label or key
    style = {"description_width": "initial"}
    if isinstance(control, Toggle):
        return w.Checkbox(value=value, description=label, indent=False, style=style)
    if isinstance(control, Choice):
        options = list(control.pairs)
        if control.slider:
            return w.SelectionSlider(
                options=options,
                value=value,
                description=label,
                continuous_update=False,
                style=style,
            )
        kind = w.ToggleButtons if len(options) <= 4 else w.Dropdown
        return kind(options=options, value=value, description=label, style=style)
    numbers = (control.low, control.high, control.step, value)
    if all(isinstance(v, int) and not isinstance(v, bool) for v in numbers):
        return w.IntSlider(
            value=value,
            min=control.low,
            max=control.high,
            step=control.step,
            description=label,
            continuous_update=False,
            style=style,
        )
    decimals = max(0, -int(f"{control.step:e}".split("e")[1]))
    return w.FloatSlider(
        value=value,
        min=control.low,
        max=control.high,
        step=control.step,
        description=label,
        readout_format=f".{decimals}f",
        continuous_update=False,
        style=style,
    )


def _show(value: Any) -> str:
    return f"{value:.4g}" if isinstance(value, float) else str(value)
