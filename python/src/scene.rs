//! Scenes: bundled, from a file, or built in code (a dict with the scene
//! file's keys, meshes as generators, OBJ files or vertex and index arrays).

use std::path::Path;

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use umbra_sim::input::limits::Limits;

use crate::error;

/// A scene: objects with their meshes placed, lights and a camera.
#[pyclass(frozen, module = "umbra._umbra")]
pub struct Scene {
    pub(crate) inner: umbra_sim::Scene,
}

#[pymethods]
impl Scene {
    /// The bundled scene `name`, or the scene file or glTF file at that
    /// path; for a glTF file, `camera` chooses its camera by name or index.
    #[new]
    #[pyo3(signature = (name, camera=None))]
    fn new(name: &str, camera: Option<&str>) -> PyResult<Self> {
        umbra_sim::Scene::open_with_camera(name, camera, &Limits::for_machine())
            .map(|inner| Self { inner })
            .map_err(|e| error(&e))
    }

    /// The scene with its first light moved to `point` `(x, y, z)`, aimed
    /// at the centre of the scene's bounds (as `--light-from`).
    fn with_light_from(&self, point: [f32; 3]) -> PyResult<Self> {
        self.inner.clone().with_light_from(point.into()).map(|inner| Self { inner }).map_err(|e| error(&e))
    }

    /// What the scene's loader supplied that its file did not say (a
    /// default camera or light).
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.inner.notes.clone()
    }

    /// A scene from the text of a scene file, named `file` in errors
    /// (relative OBJ paths are taken from `file`'s folder).
    #[staticmethod]
    fn from_toml(text: &str, file: &str) -> PyResult<Self> {
        let mut inner =
            umbra_sim::Scene::parse(text, Path::new(file), &Limits::for_machine()).map_err(|e| error(&e))?;
        inner.source = file.to_owned();
        Ok(Self { inner })
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// Where it came from: a bundled scene's name, a file's path, or the
    /// name a built scene was given.
    #[getter]
    fn source(&self) -> &str {
        &self.inner.source
    }

    /// The camera image's width and height, pixels.
    #[getter]
    fn image(&self) -> (u32, u32) {
        (self.inner.image[0], self.inner.image[1])
    }

    /// Each object as a dict: `name`, `solid`, and its mesh as placed in
    /// the scene, `positions` (`n × 3` float32) and `triangles` (`m × 3`
    /// uint32, counter-clockwise seen from outside).
    fn objects<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.inner
            .objects
            .iter()
            .map(|o| {
                let d = PyDict::new(py);
                d.set_item("name", &o.name)?;
                d.set_item("solid", o.solid)?;
                let positions: Vec<f32> = o.mesh.positions.iter().flat_map(|p| p.to_array()).collect();
                let triangles: Vec<u32> = o.mesh.triangles.iter().flatten().copied().collect();
                d.set_item("positions", PyArray1::from_vec(py, positions).reshape([o.mesh.positions.len(), 3])?)?;
                d.set_item("triangles", PyArray1::from_vec(py, triangles).reshape([o.mesh.triangles.len(), 3])?)?;
                Ok(d)
            })
            .collect()
    }

    fn __repr__(&self) -> String {
        let triangles: usize = self.inner.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        format!(
            "Scene({:?}: {} objects, {triangles} triangles, {}×{} image)",
            self.inner.name,
            self.inner.objects.len(),
            self.inner.image[0],
            self.inner.image[1]
        )
    }
}

/// The bundled scenes' names.
#[pyfunction]
pub fn bundled_scenes() -> Vec<&'static str> {
    umbra_sim::world::scene_file::BUNDLED.iter().map(|(n, _)| *n).collect()
}
