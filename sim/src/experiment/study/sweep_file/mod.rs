//! Sweep files: every axis of a study in TOML, written by the user or
//! bundled (`sweeps/quick.toml`, `sweeps/full.toml`).
//!
//! ```toml
//! name = "mine"
//! scenes = ["table-and-sphere", "my-scene.toml"]      # bundled names or files (relative to this file)
//! images = [[640, 360], [1920, 1080]]     # an axis: width × height
//! reference_rays = 2                       # rays per pixel side for the area reference
//! formats = ["d16", "d24"]
//! maps = [256, 1024]
//! filters = ["point", "bilinear", { name = "jitter8", jitter = { num_samples = 8, res_factor = 3.0 } }]
//! archs = ["talisman", "my-gpu.toml"]     # bundled names or files
//! budgets = [1.0, 0.1, 0.01]              # percent artifacts
//!
//! [[arch_axes]]                            # any architecture key, with units as `--set` takes them
//! key = "map_cache.size"
//! values = ["0B", "16KiB", "64KiB"]
//!
//! [[algorithms]]                           # one entry per algorithm, each list an axis
//! algo = "first"                           # as `umbra render --algo` spells it
//! bias = [0.0, 0.001, 0.005]
//! ```
//!
//! An algorithm entry may list `bias`, `bias1` (bias-range), `offset`
//! (dual), `virtual_samples`, `cull` (as `umbra render --cull` takes it)
//! and `cascades` (as `umbra render --cascades` takes them: `"1"`, `"4"`,
//! `"4,lambda=1,sides=2048/1024/512/256"`, `"scene"`); each list
//! multiplies the variants.

use std::path::{Path, PathBuf};

use serde::Deserialize;
use umbra_core::shadow::{Bias, DepthTest, Filter, Jitter, MapCoord, ShadowConfig};
use umbra_core::{DepthFormatKind, RasterConfig};

mod algorithms;
mod arch_points;

use algorithms::AlgorithmText;

use super::{Spec, repeated};
use crate::experiment::study::budget::written::Written;
use crate::input::exact::Exact;
use crate::input::limits::Limits;
use crate::world::scene::Scene;
use crate::world::scene_file::BUNDLED;

/// The bundled sweep files, by name.
pub(crate) const BUNDLED_SWEEPS: [(&str, &str); 2] = [
    ("quick", include_str!("../../../../../sweeps/quick.toml")),
    ("full", include_str!("../../../../../sweeps/full.toml")),
];

/// Most values one axis of a sweep may list (an algorithm's variants
/// together count as one axis).
pub(crate) const MAX_AXIS_VALUES: usize = 4096;

/// What is wrong with a sweep file: the file, the key, the problem.
#[derive(Debug, thiserror::Error)]
#[error("{}: {key}: {problem}", file.display())]
pub struct SweepError {
    /// The sweep file (or `--sweep` for a bundled name).
    pub file: PathBuf,
    /// The key, with its position in a list (`algorithms[2].offset`).
    pub key: String,
    /// What is wrong.
    pub problem: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileText {
    /// The file format version it is written for (`input::format::SWEEP`).
    #[serde(default)]
    format: Option<u32>,
    name: String,
    scenes: Vec<String>,
    images: Vec<Exact<2, u32>>,
    reference_rays: u32,
    formats: Vec<String>,
    maps: Vec<u32>,
    filters: Vec<FilterText>,
    #[serde(default)]
    archs: Vec<String>,
    #[serde(default)]
    arch_axes: Vec<AxisText>,
    budgets: Vec<Written>,
    algorithms: Vec<AlgorithmText>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum FilterText {
    Preset(String),
    Jitter {
        #[serde(default)]
        name: Option<String>,
        jitter: JitterText,
    },
    Box {
        #[serde(default)]
        name: Option<String>,
        #[serde(rename = "box")]
        size: u8,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JitterText {
    num_samples: u16,
    res_factor: f64,
    #[serde(default)]
    min_samples: Option<u16>,
    #[serde(default)]
    min_size: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AxisText {
    key: String,
    values: Vec<AxisValue>,
}

/// An architecture axis's value as the file writes it: text as `--set`
/// takes it (`"16KiB"`), or a number or flag where the key means one
/// (`180`, `true`; format 2).
#[derive(Deserialize)]
#[serde(untagged)]
enum AxisValue {
    Text(String),
    Integer(i64),
    Real(f64),
    Flag(bool),
}

impl AxisValue {
    /// The value as `--set` takes it.
    fn text(&self) -> String {
        match self {
            Self::Text(t) => t.clone(),
            Self::Integer(n) => n.to_string(),
            Self::Real(x) => x.to_string(),
            Self::Flag(b) => b.to_string(),
        }
    }
}

/// A sweep file's text and where it came from.
#[derive(Clone, Debug)]
pub struct SweepFile {
    /// The file (a bundled sweep: `sweeps/<name>.toml`).
    pub file: PathBuf,
    /// Its text.
    pub text: String,
    /// Whether it is bundled (its scenes and architectures are then
    /// bundled names).
    pub bundled: bool,
}

impl SweepFile {
    /// A bundled sweep by name.
    ///
    /// # Errors
    /// `SweepError` with key `(name)` for an unknown name.
    pub fn bundled(name: &str) -> Result<Self, SweepError> {
        let file = PathBuf::from(format!("sweeps/{name}.toml"));
        let (_, text) = BUNDLED_SWEEPS.iter().find(|(n, _)| *n == name).ok_or_else(|| SweepError {
            file: "--sweep".into(),
            key: "(name)".into(),
            problem: format!("no bundled sweep `{name}`; there are {}", BUNDLED_SWEEPS.map(|(n, _)| n).join(", ")),
        })?;
        Ok(Self { file, text: (*text).to_owned(), bundled: true })
    }

    /// A bundled sweep by name, or a sweep file (a path, or a name ending
    /// in `.toml`), read within `limits`.
    ///
    /// # Errors
    /// `SweepError` naming the file.
    pub fn open(name: &str, limits: &Limits) -> Result<Self, SweepError> {
        let path = Path::new(name);
        if !(path.extension().is_some_and(|e| e == "toml") || path.components().count() > 1 || path.is_file()) {
            return Self::bundled(name);
        }
        let bytes = limits.read_text_file(path).map_err(|e| SweepError {
            file: path.to_owned(),
            key: "(file)".into(),
            problem: e.to_string(),
        })?;
        let text = String::from_utf8(bytes).map_err(|e| SweepError {
            file: path.to_owned(),
            key: "(file)".into(),
            problem: format!("not UTF-8: {e}"),
        })?;
        Ok(Self { file: path.to_owned(), text, bundled: false })
    }

    /// The hash every row of this sweep carries.
    #[must_use]
    pub(crate) fn hash(&self) -> String {
        crate::output::provenance::hash(self.text.as_bytes())
    }

    fn err(&self, key: impl Into<String>, problem: impl Into<String>) -> SweepError {
        SweepError { file: self.file.clone(), key: key.into(), problem: problem.into() }
    }

    /// A scene or architecture named in the file: a bundled name as it is,
    /// a file relative to the sweep file's folder.
    fn relative(&self, name: &str, bundled: bool) -> String {
        if bundled || self.bundled {
            return name.to_owned();
        }
        self.file.parent().map_or_else(|| name.to_owned(), |d| d.join(name).display().to_string())
    }

    /// The sweep's axes, every one checked: scenes and architectures loaded,
    /// algorithms, formats, filters, maps and images valid.
    ///
    /// # Errors
    /// `SweepError` naming the key and the problem.
    #[allow(clippy::too_many_lines, reason = "one check per axis, in the file's order")]
    pub fn spec(&self, limits: &Limits) -> Result<Spec, SweepError> {
        let t: FileText = toml::from_str(&self.text).map_err(|e| {
            let key = e
                .span()
                .map_or_else(|| "(syntax)".to_owned(), |s| format!("({})", crate::input::at_line(&self.text, s.start)));
            self.err(key, e.message().trim().to_owned())
        })?;
        crate::input::format::SWEEP.stated(t.format.map(i64::from)).map_err(|e| self.err("format", e))?;
        self.lengths(&t)?;
        let mut scenes = Vec::new();
        for (i, s) in t.scenes.iter().enumerate() {
            let bundled = BUNDLED.iter().any(|(n, _)| n == s);
            let scene = Scene::open(&self.relative(s, bundled), limits)
                .map_err(|e| self.err(format!("scenes[{i}]"), e.to_string()))?;
            scenes.push(scene);
        }
        // Sizes beyond the limits are not refused here: each configuration
        // that asks for one is a skipped row naming the limit.
        for (i, &Exact([w, h])) in t.images.iter().enumerate() {
            RasterConfig::new(w, h, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
                .map_err(|e| self.err(format!("images[{i}]"), e.to_string()))?;
        }
        let rays = crate::render::RenderConfig::REFERENCE_RAYS;
        if !rays.contains(&t.reference_rays) {
            return Err(self.err("reference_rays", format!("{} is outside {rays:?}", t.reference_rays)));
        }
        let formats = t
            .formats
            .iter()
            .enumerate()
            .map(|(i, f)| {
                f.parse::<DepthFormatKind>().map_err(|e| self.err(format!("formats[{i}]"), format!("`{f}` is {e}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        for (i, &side) in t.maps.iter().enumerate() {
            RasterConfig::new(side, side, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
                .map_err(|e| self.err(format!("maps[{i}]"), e.to_string()))?;
        }
        let filters = t
            .filters
            .iter()
            .enumerate()
            .map(|(i, f)| self.filter(&format!("filters[{i}]"), f))
            .collect::<Result<Vec<_>, _>>()?;
        let (archs, arch_points) = self.archs(&t, limits)?;
        let budgets = t
            .budgets
            .iter()
            .enumerate()
            .map(|(i, b)| b.budget().map_err(|e| self.err(format!("budgets[{i}]"), e)))
            .collect::<Result<Vec<_>, _>>()?;
        if let Some((i, problem)) = super::budgets_problem(&budgets) {
            return Err(self.err(format!("budgets[{i}]"), problem));
        }
        let mut variants = Vec::new();
        for (i, a) in t.algorithms.iter().enumerate() {
            variants.extend(self.variants(&format!("algorithms[{i}]"), a)?);
        }
        // An axis that names one value twice would run every configuration
        // with it twice.
        // Each is compared as the value it means, and shown as written.
        if let Some((_, again, problem)) = super::same_names(&scenes) {
            return Err(self.err(format!("scenes[{again}]"), problem));
        }
        let shown = |v: &[String]| v.to_vec();
        let images: Vec<String> = t.images.iter().map(|Exact([w, h])| format!("[{w}, {h}]")).collect();
        let filter_names: Vec<String> = filters.iter().map(ToString::to_string).collect();
        self.once("images", &t.images, &images)?;
        self.once("formats", &formats, &shown(&t.formats))?;
        self.once("maps", &t.maps, &t.maps.iter().map(u32::to_string).collect::<Vec<_>>())?;
        self.once("filters", &filters, &filter_names)?;
        self.once("archs", &archs.iter().map(|a| a.name.clone()).collect::<Vec<_>>(), &shown(&t.archs))?;
        if let Some((first, again)) = repeated(&variants) {
            return Err(self.err("algorithms", format!("variant {again} repeats variant {first}")));
        }
        for (key, empty) in [
            ("scenes", t.scenes.is_empty()),
            ("images", t.images.is_empty()),
            ("formats", t.formats.is_empty()),
            ("maps", t.maps.is_empty()),
            ("filters", t.filters.is_empty()),
            ("algorithms", variants.is_empty()),
        ] {
            if empty {
                return Err(self.err(key, "the axis is empty"));
            }
        }
        let spec = Spec {
            scenes,
            variants,
            formats,
            map_sizes: t.maps,
            filters,
            archs,
            arch_points,
            images: t.images.iter().map(|i| i.0).collect(),
            reference_rays: t.reference_rays,
            budgets,
            cost_limits: super::objective::CostLimits::default(),
            name: t.name,
            hash: self.hash(),
            limits: *limits,
        };
        match spec.size_problem() {
            Some(problem) => Err(self.err("(axes)", problem)),
            None => Ok(spec),
        }
    }

    /// Refuse a value `key` lists twice: `parsed` compared as values,
    /// `written` (the same length) shown as the file writes them.
    fn once<T: PartialEq>(&self, key: &str, parsed: &[T], written: &[String]) -> Result<(), SweepError> {
        let Some((first, again)) = repeated(parsed) else { return Ok(()) };
        let (a, b) = (&written[first], &written[again]);
        let problem = if a == b {
            format!("`{b}` repeats {key}[{first}]: give each value once")
        } else {
            format!("`{b}` is {key}[{first}], `{a}`, written another way: give each value once")
        };
        Err(self.err(format!("{key}[{again}]"), problem))
    }

    /// Every list's length within [`MAX_AXIS_VALUES`], and the algorithm
    /// axis (every entry's lists multiplied) within it too: checked before
    /// anything is loaded, built or compared (the repeat checks compare
    /// every pair).
    fn lengths(&self, t: &FileText) -> Result<(), SweepError> {
        let too_long = |key: String, n: usize| {
            if n > MAX_AXIS_VALUES {
                Err(self.err(key, format!("{n} values; an axis has at most {MAX_AXIS_VALUES}")))
            } else {
                Ok(())
            }
        };
        for (key, n) in [
            ("scenes", t.scenes.len()),
            ("images", t.images.len()),
            ("formats", t.formats.len()),
            ("maps", t.maps.len()),
            ("filters", t.filters.len()),
            ("archs", t.archs.len()),
            ("arch_axes", t.arch_axes.len()),
            ("algorithms", t.algorithms.len()),
        ] {
            too_long(key.to_owned(), n)?;
        }
        for (i, axis) in t.arch_axes.iter().enumerate() {
            too_long(format!("arch_axes[{i}].values"), axis.values.len())?;
        }
        let mut variants = 0usize;
        for (i, a) in t.algorithms.iter().enumerate() {
            let lists = [
                ("bias", a.bias.as_ref().map_or(1, Vec::len)),
                ("offset", a.offset.as_ref().map_or(1, Vec::len)),
                ("virtual_samples", a.virtual_samples.as_ref().map_or(1, Vec::len)),
                ("cull", a.cull.as_ref().map_or(1, Vec::len)),
                ("cascades", a.cascades.as_ref().map_or(1, Vec::len)),
            ];
            let mut n = 1usize;
            for (key, len) in lists {
                too_long(format!("algorithms[{i}].{key}"), len)?;
                n = n.saturating_mul(len);
            }
            variants = variants.saturating_add(n);
            too_long(format!("algorithms[..={i}] (their variants together)"), variants)?;
        }
        Ok(())
    }

    fn filter(&self, key: &str, f: &FilterText) -> Result<Filter, SweepError> {
        let coord = |k: &str, v: f64| {
            MapCoord::checked_from_num(v).filter(|_| v.is_finite() && v >= 0.0).ok_or_else(|| {
                self.err(format!("{key}.jitter.{k}"), format!("{v} is not a non-negative number of texels"))
            })
        };
        let (name, filter) = match f {
            FilterText::Preset(text) => {
                (None, text.parse::<Filter>().map_err(|e| self.err(key, format!("`{text}`: {e}")))?)
            }
            FilterText::Jitter { name, jitter } => (
                name.as_ref(),
                Filter::Jittered(Jitter {
                    num_samples: jitter.num_samples,
                    res_factor: coord("res_factor", jitter.res_factor)?,
                    min_samples: jitter.min_samples.unwrap_or(1),
                    min_size: coord("min_size", jitter.min_size.unwrap_or(0.0))?,
                }),
            ),
            FilterText::Box { name, size } => (name.as_ref(), Filter::Box { size: *size }),
        };
        // A table's name, when given, is the filter's one spelling: rows,
        // summaries and `umbra render --filter` all use that spelling.
        if let Some(name) = name.filter(|n| **n != filter.to_string()) {
            return Err(self.err(
                format!("{key}.name"),
                format!("`{name}` is not this filter's name, `{filter}` (leave `name` out or write `{filter}`)"),
            ));
        }
        // The shadow unit's own check of the filter, as every render makes it.
        ShadowConfig::new(DepthTest::First, Bias::default(), filter, false)
            .map_err(|e| self.err(key, e.to_string()))?;
        Ok(filter)
    }
}
