//! What runs: a render configuration checked once, and the render, the
//! cost, the study and the plan, each with the interpreter released.

use std::path::PathBuf;

use indicatif::ProgressBar;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use umbra_core::DepthFormatKind;
use umbra_sim::experiment::plan::{Budget, CostLimits, PlanSpec};
use umbra_sim::experiment::study::{Overrides, Request, Shard, SweepFile, schema::schema_csv, table};
use umbra_sim::input::limits::Limits;
use umbra_sim::render::arrays::PixelArrays;
use umbra_sim::render::{RenderConfig, RenderRequest, TruthSource};

use crate::arch::Arch;
use crate::scene::Scene;
use crate::{UmbraError, error, progress};

/// A render configuration, checked against its scene and the limits:
/// what `umbra render`'s flags name.
#[pyclass(frozen, module = "umbra._umbra")]
pub struct Config {
    inner: RenderConfig,
}

#[pymethods]
impl Config {
    /// The configuration in one line.
    fn describe(&self) -> String {
        self.inner.describe()
    }

    /// Its fields as JSON text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner).map_err(|e| error(&e))
    }

    fn __repr__(&self) -> String {
        format!("Config({})", self.inner.describe())
    }
}

/// `name: value` as an [`UmbraError`], for a value the argument `name` cannot take.
fn bad(name: &str, e: impl std::fmt::Display) -> PyErr {
    UmbraError::new_err(format!("{name}: {e}"))
}

/// The configuration of a render of `scene`: each keyword a render
/// parameter (`umbra schema render` lists them: `umbra render`'s flag of
/// the same name, an alias, or its `no-` switch's name with `False`),
/// each left out at its default; width and height default to the scene's
/// image. Checked against the scene and the limits.
#[pyfunction]
#[pyo3(signature = (scene, **flags))]
pub fn config(scene: &Scene, flags: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    let mut request = RenderRequest::DEFAULT;
    for (key, value) in flags.into_iter().flatten() {
        let name: String = key.extract()?;
        let text = if let Ok(b) = value.extract::<bool>() {
            b.to_string()
        } else if let Ok(n) = value.extract::<i64>() {
            n.to_string()
        } else if let Ok(x) = value.extract::<f64>() {
            x.to_string()
        } else if let Ok(t) = value.extract::<String>() {
            t
        } else {
            return Err(bad(&name, format!("{value} is not a number, a flag or text")));
        };
        request.set(&name, &text).map_err(|e| UmbraError::new_err(e.to_string()))?;
    }
    let cfg = request.config(scene.inner.image).map_err(|e| UmbraError::new_err(e.to_string()))?;
    cfg.check(&scene.inner, &Limits::for_machine()).map_err(|e| error(&e))?;
    Ok(Config { inner: cfg })
}

/// Render `scene` with `config` against the exact reference: the metrics
/// as JSON text, and the arrays (`z1`, `z2` as stored integers, `shadow`,
/// `reference` and `verdict`), with the `umbra render` command that
/// renders it again.
#[pyfunction]
#[pyo3(signature = (scene, config, progress=None, threads=None))]
pub fn render<'py>(
    py: Python<'py>,
    scene: &Scene,
    config: &Config,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<usize>,
) -> PyResult<(String, Bound<'py, PyDict>)> {
    let bar = ProgressBar::hidden();
    let lights = scene.inner.lights.len().max(1) as u64;
    bar.set_length(u64::from(config.inner.height) * lights);
    let r = progress::run(py, &bar, progress, threads, || {
        let job = config.inner.check(&scene.inner, &Limits::for_machine())?;
        umbra_sim::render(&job, TruthSource::Build(&bar))
    })?
    .map_err(|e| error(&e))?;
    // The frame's metrics, and with several lights each light's, as
    // `metrics.json` holds them; the arrays are the first light's.
    let mut record = serde_json::to_value(r.frame_metrics()).map_err(|e| error(&e))?;
    if let (false, Some(fields)) = (r.more.is_empty(), record.as_object_mut()) {
        let each =
            r.parts().map(|p| serde_json::to_value(p.metrics)).collect::<Result<Vec<_>, _>>().map_err(|e| error(&e))?;
        fields.insert("lights".to_owned(), serde_json::Value::Array(each));
    }
    if let (Some(cascades), Some(fields)) = (umbra_sim::render::files::cascades_json(&r), record.as_object_mut()) {
        fields.insert("cascades".to_owned(), cascades);
    }
    let metrics = record.to_string();
    let arrays = PixelArrays::of(&r);
    let out = PyDict::new(py);
    let (w, h) = (arrays.width as usize, arrays.height as usize);
    out.set_item("shadow", PyArray1::from_vec(py, arrays.shadow).reshape([h, w])?)?;
    out.set_item("reference", PyArray1::from_vec(py, arrays.reference).reshape([h, w])?)?;
    out.set_item("verdict", PyArray1::from_vec(py, arrays.verdict).reshape([h, w])?)?;
    let raster = r.maps.maps.config.raster;
    let side = [raster.height() as usize, raster.width() as usize];
    for name in ["z1", "z2"] {
        out.set_item(name, py.None())?;
    }
    for (name, raw) in r.maps.stored() {
        match r.maps.format {
            DepthFormatKind::D16 => {
                let v: Vec<u16> = raw.iter().map(|&t| u16::try_from(t).unwrap_or(u16::MAX)).collect();
                out.set_item(name, PyArray1::from_vec(py, v).reshape(side)?)?;
            }
            DepthFormatKind::D24 | DepthFormatKind::F32 => {
                out.set_item(name, PyArray1::from_slice(py, raw).reshape(side)?)?;
            }
        }
    }
    out.set_item("render_again", &r.command)?;
    out.set_item("configuration_text", config.inner.describe())?;
    Ok((metrics, out))
}

/// The cost of `config` on `scene` on `arch`, as the JSON text of
/// `cost.json`'s report.
#[pyfunction]
pub fn cost(py: Python<'_>, scene: &Scene, config: &Config, arch: &Arch) -> PyResult<String> {
    let report = py
        .detach(|| umbra_sim::cost(&config.inner.check(&scene.inner, &Limits::for_machine())?, &arch.inner))
        .map_err(|e| error(&e))?;
    serde_json::to_string(&report).map_err(|e| error(&e))
}

/// Run a sweep: the bundled sweep or sweep file `name`, or the sweep
/// file's `text` named `file` in errors; shard `index` of `count`. The
/// rows as `results.csv` holds them, and `schema.csv`.
#[pyfunction]
#[pyo3(signature = (name=None, text=None, file="(sweep dict)", shard=(0, 1), progress=None, threads=None))]
pub fn study(
    py: Python<'_>,
    name: Option<&str>,
    text: Option<String>,
    file: &str,
    shard: (usize, usize),
    progress: Option<&Bound<'_, PyAny>>,
    threads: Option<usize>,
) -> PyResult<(String, String)> {
    let limits = Limits::for_machine();
    let sweep = match (name, text) {
        (Some(name), None) => SweepFile::open(name, &limits).map_err(|e| error(&e))?,
        (None, Some(text)) => SweepFile { file: PathBuf::from(file), text, bundled: false },
        _ => return Err(UmbraError::new_err("study: give a sweep's name or file, or its text, not both")),
    };
    let (index, count) = shard;
    // The library's one check of a study: the sweep, its size, the shard
    // and the memory of the renders run at once.
    let request = Request {
        sweep: sweep.file.display().to_string(),
        overrides: Overrides::default(),
        shard: Some(format!("{index}/{count}")),
        extremes: false,
        out: PathBuf::new(),
        replace: false,
    };
    let at_once = threads.unwrap_or_else(rayon::current_num_threads);
    let spec = request.prepare_file(sweep, &limits, at_once).map_err(|e| error(&e))?.spec;
    let bar = ProgressBar::hidden();
    let rows = progress::run(py, &bar, progress, threads, || umbra_sim::study(&spec, Shard { index, count }, &bar))?
        .map_err(|e| error(&e))?;
    let (csv, header) = table(&rows);
    Ok((csv, schema_csv(&header)))
}

/// The cheapest configuration of `scene` on `arch` meeting every budget
/// (`budgets` spelt as `umbra plan --budget` spells them: `acne=0.01%`;
/// none: the planner's default budgets),
/// as the JSON text of `plan.json`. `sweep` (a bundled sweep or a sweep
/// file), `maps` and `image` narrow the candidates as the command's flags
/// do; `objective`, `max_area` and `max_energy` are spelt as `umbra plan`'s
/// flags are (`"edp"`, `"2mm2"`, `"150uJ"`).
#[pyfunction]
#[pyo3(signature = (scene, budgets, arch, sweep=None, maps=None, image=None, objective=None, max_area=None, max_energy=None, progress=None, threads=None))]
#[allow(clippy::too_many_arguments, reason = "Python's keyword arguments")]
pub fn plan(
    py: Python<'_>,
    scene: &Scene,
    budgets: Vec<String>,
    arch: &Arch,
    sweep: Option<String>,
    maps: Option<Vec<u32>>,
    image: Option<(u32, u32)>,
    objective: Option<String>,
    max_area: Option<String>,
    max_energy: Option<String>,
    progress: Option<&Bound<'_, PyAny>>,
    threads: Option<usize>,
) -> PyResult<String> {
    let mut budgets =
        budgets.iter().map(|b| b.parse()).collect::<Result<Vec<Budget>, String>>().map_err(|e| bad("budget", e))?;
    if budgets.is_empty() {
        budgets = umbra_sim::experiment::plan::DEFAULT_BUDGETS.to_vec();
    }
    let mut spec = match sweep {
        Some(name) => {
            let limits = Limits::for_machine();
            let sweep = SweepFile::open(&name, &limits).and_then(|f| f.spec(&limits)).map_err(|e| error(&e))?;
            PlanSpec::from_sweep(&scene.inner, budgets, &sweep)
        }
        None => PlanSpec::new(&scene.inner, budgets),
    };
    spec.arch = arch.inner.clone();
    if let Some(o) = objective {
        spec.objective = o.parse().map_err(|e| bad("objective", e))?;
    }
    spec.cost_limits =
        CostLimits::parse(max_area.as_deref(), max_energy.as_deref()).map_err(|e| bad("max_area or max_energy", e))?;
    if let Some(maps) = maps {
        spec.map_sizes = maps;
    }
    if let Some((w, h)) = image {
        spec.image = [w, h];
    }
    let bar = ProgressBar::hidden();
    let p = progress::run(py, &bar, progress, threads, || umbra_sim::plan(&scene.inner, &spec, &bar))?
        .map_err(|e| error(&e))?;
    serde_json::to_string(&p).map_err(|e| error(&e))
}
