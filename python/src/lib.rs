//! Umbra from Python: the `umbra._umbra` extension module, which the
//! `umbra` package wraps (`umbra/__init__.py`). Scenes and architectures
//! are classes holding the simulator's own; renders, costs, studies and
//! plans run with the interpreter released and hand back numpy arrays and
//! JSON text the package turns into dicts and a `DataFrame`.
//!
//! Every error is an `UmbraError` carrying the message the command line
//! prints: the file (or `--set`, or the argument), the key and the problem.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

mod arch;
mod progress;
mod run;
mod scene;

create_exception!(
    _umbra,
    UmbraError,
    PyValueError,
    "A bad scene, architecture, sweep or configuration, with the file, the key and the problem."
);

/// `e` as an [`UmbraError`]: its message and each cause's, as the command
/// line prints them.
pub(crate) fn error(e: &(dyn std::error::Error + 'static)) -> PyErr {
    let mut message = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        let more = s.to_string();
        if !message.contains(&more) {
            message = format!("{message}: {more}");
        }
        source = s.source();
    }
    UmbraError::new_err(message)
}

/// The TOML text of the JSON text of a dict (a scene or sweep built in
/// code), named `what` in errors.
#[pyfunction]
fn toml_from_json(text: &str, what: &str) -> PyResult<String> {
    let value: toml::Value = serde_json::from_str(text).map_err(|e| UmbraError::new_err(format!("{what}: {e}")))?;
    toml::to_string(&value).map_err(|e| UmbraError::new_err(format!("{what}: {e}")))
}

/// Let glTF models read their buffers from `folder` too, besides their
/// own folder (the command's `--allow-read`).
#[pyfunction]
fn allow_read(folder: std::path::PathBuf) -> PyResult<()> {
    umbra_sim::base::reads::allow_folder(&folder)
        .map_err(|e| UmbraError::new_err(format!("allow_read {}: {e}", folder.display())))
}

/// The extension module.
#[pymodule]
fn _umbra(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("UmbraError", m.py().get_type::<UmbraError>())?;
    m.add("VERSION", umbra_sim::output::provenance::version())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<arch::Arch>()?;
    m.add_class::<run::Config>()?;
    m.add_function(wrap_pyfunction!(toml_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(allow_read, m)?)?;
    m.add_function(wrap_pyfunction!(scene::bundled_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(arch::bundled_archs, m)?)?;
    m.add_function(wrap_pyfunction!(run::config, m)?)?;
    m.add_function(wrap_pyfunction!(run::render, m)?)?;
    m.add_function(wrap_pyfunction!(run::cost, m)?)?;
    m.add_function(wrap_pyfunction!(run::study, m)?)?;
    m.add_function(wrap_pyfunction!(run::plan, m)?)?;
    Ok(())
}
