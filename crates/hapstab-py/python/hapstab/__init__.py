"""hapstab: exact stability of haptic virtual walls held by a human operator.

After Hulin, Preusche and Hirzinger, "Stability Boundary for Haptic Rendering: Influence of
Human Operator" (IROS 2008). An impedance-type haptic device renders a virtual wall
F = K·y + B·v, sampled with period T behind a zero-order hold, with the force delayed by t_d;
the device held by the arm is the plant 1/(m s² + b s + k) of eq. (1), m = m_L + m_H,
b = b_L + b_H, k = k_H. The paper's normalized parameters (Table I) are

    α = K T²/m,  β = B T/m,  γ = k T²/m,  δ = b T/m,  d = t_d/T,

and the closed loop is stable iff every root of its characteristic polynomial

    p(z) = z^(d+1) D(z) + N(z) ((α + β) z − β)                      (eq. 9)

lies inside the unit circle (Section V). This package generalizes the loop (two-mass
devices, any transfer function, actuator lag, fractional delays, other velocity estimators)
and answers from the same Rust engine as the `hapstab` command line:

- Loop description: MassSpringDamper, TwoMass, TransferFunction, Loop (Loop.paper,
  Loop.normalized).
- check: verdict, spectral radius, roots and the stable K interval at a wall.
- region: the exact stable region in the (K, B) plane as polygons, K_max and where.
- kmax: K_max overall, at a damping B, or over a damping range.
- stability_map: the grid method over numpy arrays of K and B, in parallel, GIL released.
- discretize: the exact discrete plant, velocity estimator and p(z) as coefficient arrays.
- simulate: the loop in the time domain with nonlinear effects, trace arrays and verdict.
- passivity: the device damping a wall requires to be passive (Colgate's condition, eq. 28,
  generalized to any delay and velocity estimator), the verdict, the passive region.
- margins: gain (on K, on (K, B)), phase and delay margins of a stable wall and the
  frequency at which it would oscillate.
- frequency_response: the open loop L(e^{jωT}) with its crossings (the data of a Bode and a
  Nyquist plot); root_locus: the roots of p(z) as K sweeps at a damping B.
- sweep: K_max (stable and passive) against one parameter of the loop.
- zwidth: the Z-width, stable and passive regions with K_max against the damping.
- linear_condition: the paper's linear condition (22)-(23) and the smallest damping at
  which it errs by a given fraction of the exact boundary (eq. 24, Fig. 7).
- identify: the plant from arrays of time, commanded force and measured position (a
  mass-spring-damper, a device held by an arm, a two-mass device or any transfer function),
  with standard errors, 95 % intervals and K_max at B = 0 with its uncertainty;
  identify_frequency: the same from a measured frequency response.
- nyquist_regions: Section VIII in normalized units: the stable regions as gamma sweeps up
  to the Nyquist frequency, the robustly stable region, Colgate's passive region inside it.

Units are SI throughout: K in N/m, B in Ns/m, masses in kg, times in s. Bad arguments raise
ValueError naming the keyword argument.
"""

import copyreg as _copyreg
import functools as _functools
import re as _re

from ._hapstab import (
    Check,
    Discretization,
    Edge,
    FrequencyResponse,
    Identification,
    Kmax,
    RenderableBand,
    RobustKmax,
    StabilityCurve,
    WallProbability,
    LinearCondition,
    Loop,
    Margins,
    Mark,
    MassSpringDamper,
    NumericalError,
    NyquistRegions,
    PassiveRegion,
    Passivity,
    Region,
    RootLocus,
    Simulation,
    StabilityMap,
    Sweep,
    TransferFunction,
    TwoMass,
    ZWidth,
)
from ._hapstab import __version__
from ._hapstab import _rebuild, _result_fields
from ._hapstab import check as _check
from ._hapstab import discretize as _discretize
from ._hapstab import frequency_response as _frequency_response
from ._hapstab import identify as _identify
from ._hapstab import identify_frequency as _identify_frequency
from ._hapstab import kmax as _kmax
from ._hapstab import linear_condition as _linear_condition
from ._hapstab import margins as _margins
from ._hapstab import nyquist_regions as _nyquist_regions
from ._hapstab import passivity as _passivity
from ._hapstab import region as _region
from ._hapstab import robust_kmax as _robust_kmax
from ._hapstab import root_locus as _root_locus
from ._hapstab import simulate as _simulate
from ._hapstab import stability_map as _stability_map
from ._hapstab import stability_probability as _stability_probability
from ._hapstab import sweep as _sweep
from ._hapstab import zwidth as _zwidth

def _loop_from_json(text):
    """A pickled Loop back from its JSON (Loop.__reduce__)."""
    return Loop.from_json(text)


def _register_pickling():
    """Every result class pickles as its class name and fields (numpy arrays and nested
    results pickle themselves), rebuilt by the extension's `_rebuild`."""
    from . import _hapstab

    for name, fields in _result_fields():

        def reduce(obj, name=name, fields=tuple(fields)):
            return _rebuild, (name, {f: getattr(obj, f) for f in fields})

        _copyreg.pickle(getattr(_hapstab, name), reduce)


_register_pickling()


def _register_plots():
    """Each figure-shaped result draws itself: `result.plot(ax=None)` (hapstab.plotting)."""
    from . import plotting

    for cls, draw in [
        (Region, plotting.region),
        (StabilityMap, plotting.stability_map),
        (ZWidth, plotting.zwidth),
        (Sweep, plotting.sweep),
        (FrequencyResponse, plotting.frequency_response),
        (RootLocus, plotting.root_locus),
        (Simulation, plotting.simulation),
    ]:
        cls.plot = draw


_register_plots()


_PROCESSING = _re.compile(r"while processing '([^']+)'")


def _named(fn):
    """The extension function with its argument type errors named by keyword: a TypeError
    raised while converting an argument ("must be real number, not str") reads
    "wall_stiffness: must be real number, not str", as every ValueError does."""

    @_functools.wraps(fn)
    def call(*args, **kwargs):
        try:
            return fn(*args, **kwargs)
        except TypeError as e:
            notes = getattr(e, "__notes__", None) or []
            # the Rust name of the keyword `loop` is the raw identifier `r#loop`
            names = [m.group(1).removeprefix("r#") for n in notes if (m := _PROCESSING.search(n))]
            message = str(e)
            if names and not message.startswith(names[0] + ":"):
                raise TypeError(f"{names[0]}: {message}") from None
            raise

    return call


check = _named(_check)
discretize = _named(_discretize)
frequency_response = _named(_frequency_response)
identify = _named(_identify)
identify_frequency = _named(_identify_frequency)
kmax = _named(_kmax)
linear_condition = _named(_linear_condition)
margins = _named(_margins)
nyquist_regions = _named(_nyquist_regions)
passivity = _named(_passivity)
region = _named(_region)
robust_kmax = _named(_robust_kmax)
root_locus = _named(_root_locus)
simulate = _named(_simulate)
stability_map = _named(_stability_map)
stability_probability = _named(_stability_probability)
sweep = _named(_sweep)
zwidth = _named(_zwidth)

__all__ = [
    "__version__",
    "Check",
    "Discretization",
    "Edge",
    "FrequencyResponse",
    "Identification",
    "Kmax",
    "RenderableBand",
    "RobustKmax",
    "StabilityCurve",
    "WallProbability",
    "LinearCondition",
    "Loop",
    "Margins",
    "Mark",
    "MassSpringDamper",
    "NumericalError",
    "NyquistRegions",
    "PassiveRegion",
    "Passivity",
    "Region",
    "RootLocus",
    "Simulation",
    "StabilityMap",
    "Sweep",
    "TransferFunction",
    "TwoMass",
    "ZWidth",
    "check",
    "discretize",
    "frequency_response",
    "identify",
    "identify_frequency",
    "kmax",
    "linear_condition",
    "margins",
    "nyquist_regions",
    "passivity",
    "region",
    "robust_kmax",
    "root_locus",
    "simulate",
    "stability_map",
    "stability_probability",
    "sweep",
    "zwidth",
]
