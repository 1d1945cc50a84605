"""Figures of hapstab's results, in python-control's style: the analysis computes, `.plot()`
draws. Each result's `.plot(ax=None)` draws on the given matplotlib Axes (or a new figure's)
and returns the Axes (Bode: the two Axes). Axes are in the user's units with engineering
prefixes (kN/m, Ns/m, Hz, ms). matplotlib is an optional dependency
(`pip install "./crates/hapstab-py[plot]"`); it is imported only when a figure is drawn.
"""

import numpy as np

STABLE = "#4c9f70"
PASSIVE = "#3b6ea8"
BOUNDARY = "#1b4332"
MARK = "#c0392b"


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - exercised only without matplotlib
        raise ImportError(
            "hapstab's .plot() needs matplotlib: pip install matplotlib "
            '(or the plotting extra, pip install "./crates/hapstab-py[plot]")'
        ) from e
    return plt


def _axes(ax):
    if ax is not None:
        return ax
    return _pyplot().subplots(figsize=(6.4, 4.8), layout="constrained")[1]


def _eng(ax, x_unit, y_unit):
    """Engineering-prefixed tick labels (20 k ... 120 k rather than 2e4 ... 1.2e5), the unit
    once in the axis label."""
    from matplotlib.ticker import EngFormatter

    for axis, unit in ((ax.xaxis, x_unit), (ax.yaxis, y_unit)):
        if unit is not None:
            axis.set_major_formatter(EngFormatter(sep=" "))
            axis.set_label_text(f"{axis.get_label_text()} ({unit})")


def _legend_outside(ax):
    """The legend below the axes, where it covers no data."""
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=min(3, len(handles)),
                  frameon=False)


def _k_max_mark(ax, k, b, label):
    if k is not None and b is not None and np.isfinite(k) and np.isfinite(b):
        ax.plot([k], [b], "o", color=MARK, label=label, zorder=5)


def _stable_polygons(ax, polygons):
    """Each stable polygon filled and outlined; one legend entry for them all."""
    for i, p in enumerate(polygons):
        closed = np.vstack([p, p[:1]])
        ax.fill(closed[:, 0], closed[:, 1], color=STABLE, alpha=0.35, lw=0,
                label="stable" if i == 0 else None)
        ax.plot(closed[:, 0], closed[:, 1], color=BOUNDARY, lw=1.0)


def region(r, ax=None):
    """The exact stable region over the wall (K, B): each polygon filled and outlined, K_max
    marked."""
    ax = _axes(ax)
    _stable_polygons(ax, r.polygons)
    if r.k_max is not None:
        _k_max_mark(ax, r.k_max, r.b_at_k_max, f"K_max = {_eng_text(r.k_max, 'N/m')}")
    _finish_wall_plane(ax, "Stable region of the wall")
    return ax


def stability_map(m, ax=None):
    """The grid method's map: stable walls green, unstable white (or the spectral radius
    where computed, with the |z| = 1 contour); walls given one by one are drawn as points."""
    ax = _axes(ax)
    k, b = np.asarray(m.wall_stiffness), np.asarray(m.wall_damping)
    stable = np.asarray(m.stable)
    if m.grid and m.spectral_radius is not None:
        rho = np.asarray(m.spectral_radius)
        mesh = ax.pcolormesh(k, b, rho, shading="nearest", cmap="viridis")
        ax.figure.colorbar(mesh, ax=ax, label="spectral radius")
        if rho.min() < 1.0 < rho.max():
            ax.contour(k, b, rho, levels=[1.0], colors="white", linewidths=1.2)
    elif m.grid:
        from matplotlib.colors import ListedColormap

        ax.pcolormesh(k, b, stable.astype(float), shading="nearest",
                      cmap=ListedColormap(["white", STABLE]), vmin=0.0, vmax=1.0)
        ax.plot([], [], "s", color=STABLE, label="stable")
    else:
        ax.scatter(k[stable], b[stable], s=8, color=STABLE, label="stable")
        ax.scatter(k[~stable], b[~stable], s=8, color="0.6", label="not stable")
    _finish_wall_plane(ax, "Stability map of the wall")
    return ax


def zwidth(z, ax=None):
    """Z-width: the stable region, the passive region outlined over it, K_max of each."""
    ax = _axes(ax)
    _stable_polygons(ax, z.stable)
    if z.passive is not None:
        v = np.asarray(z.passive.vertices)
        if len(v):
            closed = np.vstack([v, v[:1]])
            ax.fill(closed[:, 0], closed[:, 1], facecolor="none", edgecolor=PASSIVE,
                    hatch="//", lw=1.2, label="passive")
    if z.k_max is not None:
        _k_max_mark(ax, z.k_max, z.b_at_k_max, f"K_max = {_eng_text(z.k_max, 'N/m')}")
    _finish_wall_plane(ax, "Z-width")
    return ax


def sweep(s, ax=None):
    """K_max against the swept parameter, with the passive bounds; a log K axis where the
    curves span more than two decades."""
    ax = _axes(ax)
    x = np.asarray(s.values)
    curves = [(s.k_max, "K_max (stable)", STABLE, "-"),
              (s.k_max_passive, "K_max (passive)", PASSIVE, "--"),
              (s.k_max_passive_with_arm, "K_max (passive with arm)", "#7d5ba6", ":")]
    finite = []
    for y, label, color, style in curves:
        y = np.asarray(y, dtype=float)
        if np.isfinite(y).any():
            ax.plot(x, y, style, color=color, marker="o", ms=3, label=label)
            finite.append(y[np.isfinite(y) & (y > 0)])
    values = np.concatenate(finite) if finite else np.array([])
    if len(values) and values.max() > 100.0 * values.min():
        ax.set_yscale("log")
    ax.set_xlabel(f"{s.param} ({s.unit})" if s.unit else s.param)
    ax.set_ylabel("K_max")
    if ax.get_yscale() == "log":
        ax.set_ylabel("K_max (N/m)")
    else:
        _eng(ax, None, "N/m")
    ax.set_title(f"K_max against {s.param}")
    ax.grid(True, alpha=0.3)
    _legend_outside(ax)
    return ax


def frequency_response(f, axes=None):
    """Bode diagram of the open loop L up to the Nyquist frequency: |L| in dB and its phase,
    the gain and phase crossovers marked; returns the (magnitude, phase) Axes."""
    if axes is None:
        fig, axes = _pyplot().subplots(2, 1, sharex=True, figsize=(6.4, 5.6),
                                       layout="constrained")
    mag, phase = axes
    hz = np.asarray(f.frequency_hz)
    mag.semilogx(hz, f.magnitude_db, color=BOUNDARY)
    phase.semilogx(hz, f.phase_deg, color=BOUNDARY)
    mag.axhline(0.0, color="0.5", lw=0.8)
    phase.axhline(-180.0, color="0.5", lw=0.8)
    for m in f.marks:
        target = mag if m.kind == "gain" else phase
        y = m.magnitude_db if m.kind == "gain" else m.phase_deg
        target.plot([m.frequency_hz], [y], "o", color=MARK if m.primary else "0.4", ms=5)
    mag.set_ylabel("|L| (dB)")
    phase.set_ylabel("arg L (deg)")
    phase.set_xlabel("frequency (Hz)")
    mag.set_title("Open loop L = (K·PK + B·PB)/P0")
    for a in axes:
        a.grid(True, which="both", alpha=0.3)
    return axes


def root_locus(r, ax=None):
    """The closed loop's roots in the z-plane as K runs at the given B, coloured by K, with
    the unit circle and the roots at K_max."""
    ax = _axes(ax)
    t = np.linspace(0.0, 2.0 * np.pi, 721)
    ax.plot(np.cos(t), np.sin(t), color="0.5", lw=0.8)
    roots = np.asarray(r.roots)
    k = np.asarray(r.wall_stiffness)
    kk = np.repeat(k[:, None], roots.shape[1], axis=1)
    pts = ax.scatter(roots.real.ravel(), roots.imag.ravel(), c=kk.ravel(), s=4,
                     cmap="viridis")
    bar = ax.figure.colorbar(pts, ax=ax, label="K (N/m)")
    from matplotlib.ticker import EngFormatter

    bar.formatter = EngFormatter()
    bar.update_ticks()
    if r.k_max_index is not None:
        at = roots[r.k_max_index]
        ax.plot(at.real, at.imag, "x", color=MARK, ms=7,
                label=f"roots at K_max = {_eng_text(r.k_max, 'N/m')}")
    ax.set_aspect("equal")
    ax.set_xlabel("Re z")
    ax.set_ylabel("Im z")
    ax.set_title(f"Root locus at B = {_eng_text(r.wall_damping, 'Ns/m')}")
    ax.grid(True, alpha=0.3)
    _legend_outside(ax)
    return ax


def simulation(s, ax=None):
    """Position against time (mm against ms), cut at the first blow-up with a note."""
    ax = _axes(ax)
    t, x = np.asarray(s.time), np.asarray(s.position)
    ok = np.isfinite(x)
    ax.plot(t[ok], 1e3 * x[ok], color=BOUNDARY, lw=1.0)
    ax.set_xlabel("time")
    _eng(ax, "s", None)
    ax.set_ylabel("position (mm)")
    title = f"Simulated contact: {s.outcome}"
    if s.blown_up:
        title += " (blew up; drawn until then)"
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    return ax


def _finish_wall_plane(ax, title):
    ax.set_xlabel("wall stiffness K")
    ax.set_ylabel("wall damping B")
    _eng(ax, "N/m", "Ns/m")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    _legend_outside(ax)


def _eng_text(x, unit):
    from matplotlib.ticker import EngFormatter

    return EngFormatter(unit=unit, places=4)(x)
