"""A trajectory drawn as an SVG: coordinates above, reaction multipliers below, events as lines."""

from __future__ import annotations

__all__ = ["plot_trajectory"]


def plot_trajectory(trajectory, path: str) -> None:
    """Write an SVG of ``trajectory`` (a :class:`~grader.simulate.trajectory.Trajectory`) to ``path``."""
    import matplotlib

    matplotlib.use("Agg")  # no display; nothing is shown, only written
    from matplotlib.figure import Figure

    figure = Figure(figsize=(8, 6))
    top, bottom = figure.subplots(2, 1, sharex=True)
    for j, name in enumerate(trajectory.coordinates):
        top.plot(trajectory.t, trajectory.q[:, j], label=name)
    for i, name in enumerate(trajectory.constraints):
        bottom.plot(trajectory.t, trajectory.multipliers[:, i], label=f"λ {name}")
    for axes in (top, bottom):
        for event in trajectory.events:
            axes.axvline(event.t, color="grey", linestyle=":", linewidth=1)
        if axes.get_legend_handles_labels()[0]:
            axes.legend(loc="best", fontsize="small")
    for event in trajectory.events:
        top.annotate(f"{event.effect} ({event.constraint})", (event.t, 1.0), xycoords=("data", "axes fraction"),
                     rotation=90, va="top", ha="right", fontsize="x-small")
    top.set_ylabel("coordinates")
    bottom.set_ylabel("multipliers")
    bottom.set_xlabel("t (s)")
    figure.tight_layout()
    figure.savefig(path, format="svg")
