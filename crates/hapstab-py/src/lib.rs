//! Python bindings of hapstab: the `hapstab._hapstab` extension module that the `hapstab`
//! Python package re-exports. A thin front end over the library: it builds loops from
//! keyword arguments, calls the library (releasing the GIL for the long computations) and
//! returns numpy arrays; errors become `ValueError`s naming the keyword argument.

use pyo3::prelude::*;

mod analysis;
mod budget;
mod dicts;
mod discretize;
mod errors;
mod freqresp;
mod identify;
mod kmax;
mod linear;
mod locus;
mod loops;
mod map;
mod margins;
mod nyquist;
mod passivity;
mod pickle;
mod population;
mod robust;
mod simulate;
mod sweep;
mod text;
mod wall;
mod zwidth;

/// Exact stability of haptic virtual walls (Hulin, Preusche and Hirzinger, IROS 2008).
#[pymodule]
fn _hapstab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add(
        "NumericalError",
        m.py().get_type::<errors::NumericalError>(),
    )?;
    m.add_class::<loops::PyMassSpringDamper>()?;
    m.add_class::<loops::PyTwoMass>()?;
    m.add_class::<loops::PyTransferFunction>()?;
    m.add_class::<loops::PyLoop>()?;
    m.add_class::<analysis::PyCheck>()?;
    m.add_class::<analysis::PyEdge>()?;
    m.add_class::<analysis::PyRegion>()?;
    m.add_class::<kmax::PyKmax>()?;
    m.add_class::<kmax::PyRenderableBand>()?;
    m.add_class::<robust::PyRobustKmax>()?;
    m.add_class::<population::PyWallProbability>()?;
    m.add_class::<population::PyStabilityCurve>()?;
    m.add_class::<map::PyStabilityMap>()?;
    m.add_class::<discretize::PyDiscretization>()?;
    m.add_class::<simulate::PySimulation>()?;
    m.add_class::<passivity::PyPassivity>()?;
    m.add_class::<passivity::PyPassiveRegion>()?;
    m.add_class::<margins::PyMargins>()?;
    m.add_class::<freqresp::PyMark>()?;
    m.add_class::<freqresp::PyFrequencyResponse>()?;
    m.add_class::<locus::PyRootLocus>()?;
    m.add_class::<sweep::PySweep>()?;
    m.add_class::<zwidth::PyZWidth>()?;
    m.add_class::<linear::PyLinearCondition>()?;
    m.add_class::<nyquist::PyNyquistRegions>()?;
    m.add_class::<identify::PyIdentification>()?;
    m.add_function(wrap_pyfunction!(analysis::check, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::region, m)?)?;
    m.add_function(wrap_pyfunction!(kmax::kmax, m)?)?;
    m.add_function(wrap_pyfunction!(robust::robust_kmax, m)?)?;
    m.add_function(wrap_pyfunction!(population::stability_probability, m)?)?;
    m.add_function(wrap_pyfunction!(map::stability_map, m)?)?;
    m.add_function(wrap_pyfunction!(discretize::discretize, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(passivity::passivity, m)?)?;
    m.add_function(wrap_pyfunction!(margins::margins, m)?)?;
    m.add_function(wrap_pyfunction!(freqresp::frequency_response, m)?)?;
    m.add_function(wrap_pyfunction!(locus::root_locus, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(zwidth::zwidth, m)?)?;
    m.add_function(wrap_pyfunction!(linear::linear_condition, m)?)?;
    m.add_function(wrap_pyfunction!(nyquist::nyquist_regions, m)?)?;
    m.add_function(wrap_pyfunction!(identify::identify, m)?)?;
    m.add_function(wrap_pyfunction!(identify::identify_frequency, m)?)?;
    m.add_function(wrap_pyfunction!(pickle::_rebuild, m)?)?;
    m.add_function(wrap_pyfunction!(pickle::_result_fields, m)?)?;
    m.add_function(wrap_pyfunction!(errors::_parameter_keywords, m)?)?;
    Ok(())
}
