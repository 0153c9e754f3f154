//! Architectures: bundled, from a file, or a copy with keys set.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use umbra_sim::cost::arch::PARAMS;
use umbra_sim::input::limits::Limits;

use crate::error;

/// A machine the cost model times: its every key, with units.
#[pyclass(frozen, module = "umbra._umbra")]
#[derive(Clone)]
pub struct Arch {
    pub(crate) inner: umbra_sim::Arch,
}

#[pymethods]
impl Arch {
    /// The bundled architecture `name`, or the architecture file at that path.
    #[new]
    fn new(name: &str) -> PyResult<Self> {
        umbra_sim::Arch::open(name, &Limits::for_machine()).map(|inner| Self { inner }).map_err(|e| error(&e))
    }

    /// A copy with `key` set to `value`, written as an architecture file
    /// or `--set` writes it (`"25.6GB/s"`, `"800MHz"`, `"32KiB"`, `4`,
    /// `True`); the machine is checked as a whole afterwards.
    fn set(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Self> {
        let text = if value.is_instance_of::<pyo3::types::PyBool>() {
            value.extract::<bool>()?.to_string()
        } else {
            value.str()?.to_string()
        };
        let mut inner = self.inner.clone();
        inner.set(&format!("{key}={text}")).map_err(|e| error(&e))?;
        Ok(Self { inner })
    }

    /// Every key with its value as a file writes it, units included
    /// (`{"dram.bandwidth": "25.6GB/s", ...}`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for p in PARAMS {
            d.set_item(p.key, p.written(&self.inner))?;
        }
        Ok(d)
    }

    /// The architecture file that makes this machine.
    fn to_toml(&self) -> String {
        self.inner.to_toml()
    }

    /// Its name.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    fn __repr__(&self) -> String {
        format!("Arch({:?})", self.inner.name)
    }
}

/// The bundled architectures' names.
#[pyfunction]
pub fn bundled_archs() -> Vec<&'static str> {
    umbra_sim::cost::arch::BUNDLED.iter().map(|b| b.0).collect()
}
