//! Pickling of the result objects (multiprocessing, joblib and dask send them between
//! processes): the package registers with `copyreg` a reducer that gives each result as its
//! class name and its fields (numpy arrays and nested results pickle themselves), and
//! [`_rebuild`] makes the object again from them. The field lists are the structs' own, so a
//! field added to a result and not listed here does not compile.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::analysis::{PyCheck, PyEdge, PyRegion};
use crate::discretize::PyDiscretization;
use crate::freqresp::{PyFrequencyResponse, PyMark};
use crate::identify::PyIdentification;
use crate::kmax::{PyKmax, PyRenderableBand};
use crate::linear::PyLinearCondition;
use crate::locus::PyRootLocus;
use crate::map::PyStabilityMap;
use crate::margins::PyMargins;
use crate::nyquist::PyNyquistRegions;
use crate::passivity::{PyPassiveRegion, PyPassivity};
use crate::population::{PyStabilityCurve, PyWallProbability};
use crate::robust::PyRobustKmax;
use crate::simulate::PySimulation;
use crate::sweep::PySweep;
use crate::zwidth::PyZWidth;

/// The field `name` of a pickled state.
fn field<'py, T: FromPyObjectOwned<'py>>(state: &Bound<'py, PyDict>, name: &str) -> PyResult<T> {
    state
        .get_item(name)?
        .ok_or_else(|| PyValueError::new_err(format!("state: no field {name:?}")))?
        .extract()
        .map_err(Into::into)
}

/// The result classes with their fields: [`_rebuild`]'s match and [`_result_fields`]'s
/// table from one list.
macro_rules! results {
    ($($name:literal => $ty:ident { $($f:ident),* $(,)? }),* $(,)?) => {
        /// Makes the result object of class `name` from its pickled fields.
        #[pyfunction]
        pub fn _rebuild(py: Python<'_>, name: &str, state: &Bound<'_, PyDict>) -> PyResult<Py<PyAny>> {
            match name {
                $($name => Ok(Py::new(py, $ty { $($f: field(state, stringify!($f))?),* })?.into_any()),)*
                other => Err(PyValueError::new_err(format!("name: no result class {other:?}"))),
            }
        }

        /// Every result class's name and fields, for the package's `copyreg` reducers.
        #[pyfunction]
        pub fn _result_fields() -> Vec<(&'static str, Vec<&'static str>)> {
            vec![$(($name, vec![$(stringify!($f)),*])),*]
        }
    };
}

results! {
    "Check" => PyCheck { stable, verdict, spectral_radius, roots, wall_stiffness, wall_damping,
        k_interval, alpha, beta, alpha_interval, alpha_linear, k_linear, margins },
    "Edge" => PyEdge { start, stop, kind, theta_start, theta_end },
    "Region" => PyRegion { polygons, thetas, edges, k_max, b_at_k_max, k_max_attained,
        b_stable_near_k_max, k_stable_near_k_max, area, wall_units, normalized },
    "Kmax" => PyKmax { k_max, b_at_k_max, k_interval, k_linear, k_max_attained,
        b_stable_near_k_max, k_stable_near_k_max, k_max_at_zero_damping, renderable,
        normalized },
    "RobustKmax" => PyRobustKmax { wall_damping, k_max, k_min, k_max_nominal, worst_plant,
        plants_evaluated, plants_verified, verification_found },
    "WallProbability" => PyWallProbability { wall_stiffness, wall_damping, samples, stable,
        probability, interval, param_names, draws, verdicts },
    "StabilityCurve" => PyStabilityCurve { wall_damping, samples, k, probability,
        probability_lo, probability_hi, levels, param_names, draws, intervals },
    "RenderableBand" => PyRenderableBand { position_resolution, force_noise,
        velocity_noise_gain, b_max, k_max, b_at_k_max, k_max_attained },
    "Discretization" => PyDiscretization { period, plant_num, plant_den, plant_delay,
        velocity_num, velocity_den, p0, pk, pb, characteristic, wall_stiffness, wall_damping },
    "Mark" => PyMark { kind, omega, frequency_hz, value, magnitude_db, phase_deg, response,
        primary },
    "FrequencyResponse" => PyFrequencyResponse { period, nyquist_hz, omega, frequency_hz,
        response, magnitude_db, phase_deg, marks, closest, margins },
    "RootLocus" => PyRootLocus { wall_damping, k_max, k_interval, k_max_index, crossing,
        crossing_frequency_hz, wall_stiffness, roots, spectral_radius },
    "StabilityMap" => PyStabilityMap { stable, spectral_radius, wall_stiffness, wall_damping,
        grid },
    "Margins" => PyMargins { stable, gain_margin, gain_margin_lower, phase_crossover_hz,
        stiffness_margin, stiffness_margin_lower, stiffness_crossover_hz, phase_margin_deg,
        gain_crossover_hz, delay_margin, delay_margin_frequency_hz, delay_margin_pm_over_wc,
        delay_margin_at_least, stability_margin, stability_margin_hz, peak_gain, peak_gain_hz,
        crossings, notes },
    "PassiveRegion" => PyPassiveRegion { k_max, b_at_k_max, area, bounded, vertices },
    "Passivity" => PyPassivity { wall_stiffness, wall_damping, b_required,
        binding_frequency_hz, binding_theta, dc_stiffness, device_damping, effective_damping,
        effective_verdict, meets, verdict, note, stable, passive_region },
    "Simulation" => PySimulation { time, position, velocity, wall_force, human_force, outcome,
        reason, linear_window, measured_growth_per_sample, spectral_radius, linear_verdict,
        limit_cycle, contact, judged_samples, samples, trace_stride, blown_up, final_position,
        final_velocity, requested_samples, max_samples, duration, judged_from, judged_to,
        units, input },
    "Sweep" => PySweep { param, unit, values, k_max, b_at_k_max, k_max_passive,
        k_max_passive_with_arm, notes, passive_notes },
    "LinearCondition" => PyLinearCondition { gamma, delta, d, linear_slope, linear_intercept,
        alpha_lower, levels, beta, alpha, alpha_linear, error, at_start, wall_stiffness,
        wall_damping, k_linear, k_linear_slope, k_linear_intercept, k_lower },
    "NyquistRegions" => PyNyquistRegions { delta, d, gamma_nyquist, sweep_gamma,
        sweep_alpha_max, sweep_beta_at_alpha_max, sweep_alpha_min, sweep_beta_min,
        sweep_beta_max, sweep_area, sweep_empty, sweep_degenerate, robust_polygon,
        robust_alpha_max, robust_beta_at_alpha_max, robust_area, robust_gamma_hi,
        passive_polygon, passive_area, passive_inside_robust, passive_applies },
    "Identification" => PyIdentification { model, names, units, values, standard_errors,
        ci_low, ci_high, fixed, position_offset, period, nrmse, fit_percent, residual_rms,
        whiteness_passes, cross_correlation_passes, predicted, k_max, k_max_spread,
        k_max_robust, k_max_box_range, k_max_interval, k_max_standard_error, band_b_max,
        k_max_band, k_max_band_interval, position_offsets, fitted_loop },
    "ZWidth" => PyZWidth { stable, stable_area, k_max, b_at_k_max, k_max_nonnegative_damping,
        device_damping, passive, k_max_passive_with_arm, passive_inside_stable, linear,
        table_damping, table_k_max, table_k_min, table_k_max_passive, table_k_linear },
}
