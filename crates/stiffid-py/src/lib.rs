//! Python bindings of stiffid: the `stiffid` package (PyO3 + NumPy), a thin layer over the
//! library's API. Postures and points cross the boundary in degrees and millimetres, as in the
//! files and on the command line; Jacobians, compliances and stiffness in SI units, as the library
//! computes them. Every key and attribute carries its unit in its name.
//!
//! Errors: [`stiffid::Error`] becomes `stiffid.Error` (a `ValueError`), as its subclass
//! `InputError` (bad input), `InfeasibleError` (a search that found nothing feasible, a pose out
//! of reach) or `UnidentifiableError`, with the library's message. Long calls release the GIL.

mod arrays;
mod calibrate;
mod cartesian;
mod cli;
mod compare;
mod compensate;
mod count;
mod design;
mod documents;
mod error;
mod figures;
mod ik;
mod machining;
mod measure;
mod model;
mod output;
mod place;
mod plan;
mod predict;
mod register;
mod robot;
mod scene;
mod setup;
mod setups_new;
mod stiffness;
mod study;

use pyo3::prelude::*;

/// The native module, re-exported by the `stiffid` package.
#[pymodule]
fn _stiffid(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    error::register(m)?;
    // The worker threads RAYON_NUM_THREADS asks for, as the command starts them: a setting out
    // of range fails the import with the command's message.
    stiffid::internal::common::threads::start().map_err(error::value)?;
    m.add_class::<robot::Robot>()?;
    m.add_class::<setup::Setup>()?;
    m.add_function(wrap_pyfunction!(measure::identify, m)?)?;
    m.add_function(wrap_pyfunction!(measure::validate, m)?)?;
    m.add_function(wrap_pyfunction!(study::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(study::reproduce, m)?)?;
    m.add_function(wrap_pyfunction!(predict::deflection, m)?)?;
    m.add_function(wrap_pyfunction!(predict::predict, m)?)?;
    m.add_function(wrap_pyfunction!(cartesian::cartesian_compliance, m)?)?;
    m.add_function(wrap_pyfunction!(cartesian::cartesian_stiffness, m)?)?;
    m.add_function(wrap_pyfunction!(compensate::compensate, m)?)?;
    m.add_function(wrap_pyfunction!(machining::process_force, m)?)?;
    m.add_function(wrap_pyfunction!(machining::read_program, m)?)?;
    m.add_function(wrap_pyfunction!(place::place, m)?)?;
    m.add_function(wrap_pyfunction!(register::register, m)?)?;
    m.add_function(wrap_pyfunction!(register::calibrate_cell, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate::calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(figures::figures, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(scene::scene, m)?)?;
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(setups_new::setups_new, m)?)?;
    m.add_function(wrap_pyfunction!(cli::_cli, m)?)?;
    Ok(())
}
