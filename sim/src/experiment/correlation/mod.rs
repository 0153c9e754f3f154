//! Correlation with published hardware, as simulators are judged
//! (Accel-Sim's correlator): datasets of measurements in files, one per
//! source (`data/correlation/`), each point simulated and set against its
//! measurement, the statistics per dataset and over every validation
//! point, and a predicted-against-measured plot.
//!
//! A dataset is one of three kinds. **Validation** points are predictions
//! the model is judged by (Weiskopf & Ertl's Table 1 frame rates on a
//! Radeon 9700). **Sanity** points check the model's accounting rather
//! than its predictions: a file's published peak rates reproduced by a
//! microbenchmark, Arm's measured attachment bandwidths. A source the
//! model can say nothing about is **not modelled**, with the reason.
//!
//! A parameter set from a measurement is declared in its architecture
//! file's `[calibration]` table with the point it came from; that point is
//! reported as calibration and left out of the statistics.

mod plot;
mod stats;

use crate::output::table::{Align, Table};
use std::fmt::Write as _;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;

pub use self::plot::plot;
pub use self::stats::Stats;
use crate::cost::arch::Arch;
use crate::cost::report::CostReport;
use crate::input::limits::Limits;
use crate::render::{Algorithm, RenderConfig, RenderError, cost, cost_unshadowed};
use crate::world::scene::Scene;

/// The bundled datasets, by name.
pub const BUNDLED: [(&str, &str); 4] = [
    ("weiskopf-ertl-2003", include_str!("../../../../data/correlation/weiskopf-ertl-2003.toml")),
    ("peak-rates", include_str!("../../../../data/correlation/peak-rates.toml")),
    ("arm-render-passes", include_str!("../../../../data/correlation/arm-render-passes.toml")),
    ("sen-cammarano-hanrahan-2003", include_str!("../../../../data/correlation/sen-cammarano-hanrahan-2003.toml")),
];

/// What a dataset's points are for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// Predictions the model is judged by.
    Validation,
    /// Checks of the model's accounting, not of its predictions.
    Sanity,
    /// A source the model cannot speak to (the file says why).
    NotModelled,
}

/// What is measured of a simulated point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Measure {
    /// Frames a second (a shadowed configuration, or none without one).
    Frame,
    /// Pixels a second of a pass, its waits for the host left out.
    Fill,
    /// DRAM bytes a second a pass achieves, its waits left out.
    Bandwidth,
    /// The bytes a frame of one attachment (the camera pass's colour),
    /// times `fps`.
    Attachment,
}

impl Measure {
    /// The unit of its values.
    #[must_use]
    pub(crate) const fn unit(self) -> &'static str {
        match self {
            Self::Frame => "fps",
            Self::Fill => "pixels/s",
            Self::Bandwidth | Self::Attachment => "B/s",
        }
    }
}

/// A pass of the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Pass {
    /// The light pass.
    Light,
    /// The camera pass.
    Camera,
}

/// A shadowed configuration of a point, as `umbra render` spells it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointConfig {
    /// `first` (constant bias 0.002) or `dual` (offset 0.01).
    pub algo: String,
    /// Map side.
    pub map: u32,
    /// The filter (`point`, `bilinear`, `box4`, …).
    pub filter: String,
    /// The map's depth format (default `f32`, their one-channel float).
    #[serde(default = "f32_name")]
    pub depth: String,
}

fn f32_name() -> String {
    "f32".into()
}

/// One measurement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// Its name within the dataset.
    pub id: String,
    /// What was measured, in words.
    pub what: String,
    /// The measured value, in `Measure::unit`.
    pub measured: f64,
    /// What is simulated.
    pub measure: Measure,
    /// The architecture (else the dataset's).
    pub arch: Option<String>,
    /// The pass a fill or bandwidth is of.
    pub pass: Option<Pass>,
    /// The shadowed configuration (none: a frame without shadows).
    pub config: Option<PointConfig>,
    /// Overrides of the architecture for this point (`key=value`).
    #[serde(default)]
    pub set: Vec<String>,
    /// Image size (else the scene's).
    pub image: Option<[u32; 2]>,
    /// Frames a second an attachment's bytes are counted at.
    pub fps: Option<f64>,
}

/// A dataset: one source's measurements.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dataset {
    /// Its name (the file's stem).
    pub name: String,
    /// The source, short.
    pub source: String,
    /// What its points measure.
    pub what: String,
    /// What they are for.
    pub kind: Kind,
    /// The architecture of its points (else each point's).
    pub arch: Option<String>,
    /// The scene simulated.
    pub scene: Option<String>,
    /// The measurements.
    #[serde(default)]
    pub points: Vec<Point>,
}

/// What is wrong with a dataset or one of its points.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {key}: {problem}")]
pub struct DatasetError {
    /// The file (or bundled dataset's name).
    pub file: String,
    /// The point (`points.<id>`) or key.
    pub key: String,
    /// What is wrong.
    pub problem: String,
}

impl Dataset {
    /// Parse a dataset's text; `file` names it in errors.
    ///
    /// # Errors
    /// [`DatasetError`]: TOML, an unknown or missing key, a point that
    /// cannot be simulated as given.
    pub fn parse(text: &str, file: &str) -> Result<Self, DatasetError> {
        let err = |key: &str, problem: String| DatasetError { file: file.into(), key: key.into(), problem };
        let d: Self = toml::from_str(text).map_err(|e| err("(file)", e.message().to_owned()))?;
        for p in &d.points {
            let key = format!("points.{}", p.id);
            if !(p.measured.is_finite() && p.measured > 0.0) {
                return Err(err(&key, format!("measured {} is not a positive number", p.measured)));
            }
            if p.arch.is_none() && d.arch.is_none() {
                return Err(err(&key, "no arch: give one for the point or the dataset".into()));
            }
            if d.scene.is_none() {
                return Err(err("scene", "missing: the scene its points are simulated on".into()));
            }
            let needs = match p.measure {
                Measure::Fill => p.pass.is_none() || (p.pass == Some(Pass::Light) && p.config.is_none()),
                Measure::Bandwidth => p.pass.is_none(),
                Measure::Attachment => p.fps.is_none(),
                Measure::Frame => false,
            };
            if needs {
                return Err(err(&key, format!("a {:?} point needs a pass (a light pass, a config) or fps", p.measure)));
            }
            if let Some(c) = &p.config {
                c.render(1, 1).map_err(|e| err(&format!("{key}.config"), e))?;
            }
        }
        Ok(d)
    }

    /// A bundled dataset by name, or a dataset file.
    ///
    /// # Errors
    /// [`DatasetError`].
    pub fn open(name: &str, limits: &Limits) -> Result<Self, DatasetError> {
        if let Some((_, text)) = BUNDLED.iter().find(|b| b.0 == name) {
            return Self::parse(text, name);
        }
        let path = std::path::Path::new(name);
        let bytes = limits.read_text_file(path).map_err(|e| DatasetError {
            file: name.into(),
            key: "(file)".into(),
            problem: format!(
                "{e} (the bundled datasets are: {})",
                BUNDLED.iter().map(|b| b.0).collect::<Vec<_>>().join(", ")
            ),
        })?;
        let text = String::from_utf8(bytes).map_err(|_| DatasetError {
            file: name.into(),
            key: "(file)".into(),
            problem: "not UTF-8 text".into(),
        })?;
        Self::parse(&text, name)
    }
}

impl PointConfig {
    /// The render configuration at `width × height`.
    fn render(&self, width: u32, height: u32) -> Result<RenderConfig, String> {
        let (algorithm, bias) = match self.algo.as_str() {
            "first" => (Algorithm::First, 0.002),
            "dual" => (Algorithm::Dual { offset: 0.01 }, 0.0),
            other => return Err(format!("algo `{other}`: expected first or dual")),
        };
        let filter: Filter = self.filter.parse().map_err(|e| format!("filter `{}`: {e}", self.filter))?;
        let format: DepthFormatKind = self.depth.parse().map_err(|e| format!("depth `{}`: {e}", self.depth))?;
        Ok(RenderConfig {
            algorithm,
            format,
            map_size: self.map,
            filter,
            bias,
            virtual_samples: false,
            width,
            height,
            reference_rays: 1,
            ..RenderConfig::DEFAULT
        })
    }
}

/// What a point's result is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Role {
    /// Judges the model.
    Validation,
    /// A parameter was set from it: it judges nothing.
    Calibration,
    /// Checks the accounting.
    Sanity,
}

/// A simulated point against its measurement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Compared {
    /// The point's id.
    pub id: String,
    /// What was measured.
    pub what: String,
    /// The architecture simulated, overrides included.
    pub arch: String,
    /// The unit of both values.
    pub unit: &'static str,
    /// The measurement.
    pub measured: f64,
    /// The model's value.
    pub predicted: f64,
    /// Its role.
    pub role: Role,
    /// The parameters fitted to it (calibration only).
    pub fitted: Vec<String>,
}

impl Compared {
    /// predicted / measured − 1.
    #[must_use]
    pub fn error(&self) -> f64 {
        self.predicted / self.measured - 1.0
    }
}

/// One dataset's points, simulated, and their statistics.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DatasetResult {
    /// The dataset.
    pub dataset: Dataset,
    /// Each point, in the file's order.
    pub points: Vec<Compared>,
    /// Over the points that are not calibration.
    pub stats: Stats,
}

/// Every dataset, and the statistics over all validation points.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Correlation {
    /// Each dataset.
    pub datasets: Vec<DatasetResult>,
    /// Over every validation point of every dataset.
    pub validation: Stats,
}

/// The model's value for `point` of `dataset` on `arch` (overrides
/// applied) and `scene`.
fn simulate(point: &Point, scene: &Scene, arch: &Arch, limits: &Limits) -> Result<f64, RenderError> {
    let [w, h] = point.image.unwrap_or(scene.image);
    let report: CostReport = match &point.config {
        Some(c) => cost(&c.render(w, h).map_err(RenderError::Cost)?.check(scene, limits)?, arch)?,
        None => cost_unshadowed(scene, (w, h), arch, limits)?,
    };
    let pass = match point.pass {
        Some(Pass::Light) => &report.light,
        _ => &report.camera,
    };
    // A pass's own time: without its waits for the host.
    let seconds = (pass.cycles() - pass.overhead) / arch.clock;
    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    Ok(match point.measure {
        Measure::Frame => report.fps(),
        Measure::Fill => {
            let events = if point.pass == Some(Pass::Light) { &report.light_events } else { &report.camera_events };
            events.fragments as f64 / seconds
        }
        Measure::Bandwidth => pass.bytes() as f64 / seconds,
        Measure::Attachment => {
            report.camera.dram.get(crate::cost::dram::Purpose::Colour) as f64 * point.fps.unwrap_or(0.0)
        }
    })
}

/// Resolves an architecture's name and a point's overrides to the
/// architecture (the bundled one, or a file standing in for it).
pub(crate) type ArchResolver<'a> = dyn Fn(&str, &[String]) -> Result<Arch, String> + Sync + 'a;

/// Simulate every point of `datasets`, each architecture resolved by
/// `arch` (a name, then the point's overrides), and compare.
///
/// # Errors
/// A dataset's scene or architecture that cannot be opened, or a render
/// that fails, as text naming the point.
pub fn run(datasets: &[Dataset], arch: &ArchResolver<'_>, limits: &Limits) -> Result<Correlation, String> {
    let mut out = Vec::new();
    for d in datasets {
        let scene = match &d.scene {
            Some(s) => Some(Scene::open(s, limits).map_err(|e| format!("{}: scene: {e}", d.name))?),
            None => None,
        };
        let points: Vec<Result<Compared, String>> = d
            .points
            .par_iter()
            .map(|p| {
                let name = p.arch.as_deref().or(d.arch.as_deref()).unwrap_or_default();
                let a = arch(name, &p.set).map_err(|e| format!("{}/{}: {e}", d.name, p.id))?;
                let scene = scene.as_ref().ok_or_else(|| format!("{}: no scene", d.name))?;
                let predicted = simulate(p, scene, &a, limits).map_err(|e| format!("{}/{}: {e}", d.name, p.id))?;
                let here = format!("{}/{}", d.name, p.id);
                let fitted: Vec<String> =
                    a.calibration.iter().filter(|c| c.point == here).map(|c| c.key.clone()).collect();
                let role = match d.kind {
                    Kind::Sanity => Role::Sanity,
                    _ if !fitted.is_empty() => Role::Calibration,
                    _ => Role::Validation,
                };
                let label =
                    if p.set.is_empty() { a.name.clone() } else { format!("{} ({})", a.name, p.set.join(", ")) };
                Ok(Compared {
                    id: p.id.clone(),
                    what: p.what.clone(),
                    arch: label,
                    unit: p.measure.unit(),
                    measured: p.measured,
                    predicted,
                    role,
                    fitted,
                })
            })
            .collect();
        let points = points.into_iter().collect::<Result<Vec<_>, _>>()?;
        let judged: Vec<&Compared> = points.iter().filter(|c| c.role != Role::Calibration).collect();
        let one_unit = judged.windows(2).all(|w| w[0].unit == w[1].unit);
        let stats = Stats::of(&judged.iter().map(|c| (c.predicted, c.measured)).collect::<Vec<_>>(), one_unit);
        out.push(DatasetResult { dataset: d.clone(), points, stats });
    }
    let validation: Vec<(f64, f64)> = out
        .iter()
        .flat_map(|d| &d.points)
        .filter(|c| c.role == Role::Validation)
        .map(|c| (c.predicted, c.measured))
        .collect();
    let units: Vec<&str> =
        out.iter().flat_map(|d| &d.points).filter(|c| c.role == Role::Validation).map(|c| c.unit).collect();
    let one_unit = units.windows(2).all(|w| w[0] == w[1]);
    Ok(Correlation { datasets: out, validation: Stats::of(&validation, one_unit) })
}

/// A value for a table: three significant digits, SI-scaled past 10⁴.
fn value(v: f64) -> String {
    if v.abs() >= 1e4 { crate::experiment::plot::tick_label(v) } else { format!("{v:.1}") }
}

fn stats_cells(s: &Stats) -> Vec<String> {
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or_else(|| "—".to_owned(), f);
    vec![
        s.points.to_string(),
        // No statistic of an empty set: a dataset of no points has no error.
        if s.points == 0 { "—".to_owned() } else { format!("{:.1} %", s.mean_absolute_error_percent) },
        opt(s.pearson_r, &|r| format!("{r:.3}")),
        opt(s.nrmse_percent, &|n| format!("{n:.1} %")),
        s.within_10_percent.to_string(),
        s.within_25_percent.to_string(),
        s.over.to_string(),
        s.under.to_string(),
    ]
}

impl Correlation {
    /// Every dataset's table, the statistics and the calibrations, as
    /// Markdown.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let (l, r) = (Align::Left, Align::Right);
        let mut t = Table::new(&[
            ("dataset", l),
            ("kind", l),
            ("points", r),
            ("mean abs. error", r),
            ("Pearson r", r),
            ("NRMSE", r),
            ("within 10 %", r),
            ("within 25 %", r),
            ("over", r),
            ("under", r),
        ]);
        for d in &self.datasets {
            let kind = serde_json::to_value(d.dataset.kind).ok().and_then(|v| v.as_str().map(str::to_owned));
            t.row([d.dataset.name.clone(), kind.unwrap_or_default()].into_iter().chain(stats_cells(&d.stats)));
        }
        t.row(
            ["**all validation points**".to_owned(), "validation".to_owned()]
                .into_iter()
                .chain(stats_cells(&self.validation)),
        );
        s.push_str(&t.markdown());
        for d in &self.datasets {
            let _ = writeln!(s, "\n**{}** — {}: {}.\n", d.dataset.name, d.dataset.source, d.dataset.what);
            if d.points.is_empty() {
                let _ = writeln!(s, "No points: the model cannot speak to this source (its file says why).");
                continue;
            }
            let mut t = Table::new(&[
                ("point", l),
                ("arch", l),
                ("measured", r),
                ("predicted", r),
                ("unit", l),
                ("error", r),
                ("role", l),
            ]);
            for c in &d.points {
                let role = match c.role {
                    Role::Calibration => format!("calibration ({})", c.fitted.join(", ")),
                    Role::Validation => "validation".into(),
                    Role::Sanity => "sanity".into(),
                };
                t.row([
                    c.what.to_string(),
                    c.arch.to_string(),
                    value(c.measured),
                    value(c.predicted),
                    c.unit.to_string(),
                    format!("{:+.1} %", 100.0 * c.error()),
                    role,
                ]);
            }
            s.push_str(&t.markdown());
        }
        s
    }
}
