//! One row of the study: a configuration's accuracy against the reference and its cost on one architecture.
//!
//! A row is nested — the configuration, the metrics, the cost — in
//! `results.jsonl`, and flat in `results.csv`, whose column names are the
//! blocks' field names: each carries its unit (`_px`, `_bytes`, `_percent`,
//! `_texels`) and none is a pandas `DataFrame` attribute (`index`, `map`,
//! `filter`).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;

use super::{Config, Spec};
use crate::cost::arch::Arch;
use crate::cost::report::stats::RowCost;
use crate::pass::algorithm::{Culling, Family};
use crate::truth::metrics::Metrics;

/// A row's column: name, type (`integer`, `number`, `text`, `boolean`),
/// unit (`-` for none) and meaning.
pub(crate) type Column = (&'static str, &'static str, &'static str, &'static str);

/// Declares a block of a row's columns, each once: its field and Rust
/// type, its type, unit and meaning in the schema, and its value from the
/// block's sources. Makes the struct (each field's doc its meaning), its
/// `COLUMNS` in row order, and `new` from the sources.
macro_rules! columns {
    (
        $(#[$attr:meta])*
        $vis:vis struct $name:ident from ($($arg:ident: $argty:ty),*) {
            $($field:ident: $ty:ty, $kind:literal, $unit:literal, $meaning:literal = $value:expr;)+
        }
    ) => {
        $(#[$attr])*
        $vis struct $name {
            $(#[doc = $meaning] pub $field: $ty,)+
        }

        impl $name {
            /// Its columns, in row order, each as its declaration states it.
            $vis const COLUMNS: &'static [Column] = &[$((stringify!($field), $kind, $unit, $meaning)),+];

            /// The block's values from its sources.
            #[must_use]
            $vis fn new($($arg: $argty),*) -> Self {
                Self { $($field: $value,)+ }
            }
        }
    };
}

/// Whether a row was measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Rendered and costed.
    Ok,
    /// Refused or failed; the row's `reason` says why.
    Skipped,
}

/// One configuration on one architecture.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Row {
    /// The configuration's position in the sweep.
    pub config_index: usize,
    /// The architecture's position in the sweep (sort key).
    pub arch_index: usize,
    /// What was rendered, where, and how to render it again.
    pub config: RowConfig,
    /// Measured or skipped.
    pub status: Status,
    /// Why the row was skipped (empty when ok).
    pub reason: String,
    /// The error against the exact reference (absent when skipped).
    pub metrics: Option<RowMetrics>,
    /// The cost on the architecture (absent when skipped or when the sweep
    /// has no architecture).
    pub cost: Option<RowCost>,
}

/// A row's configuration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RowConfig {
    /// Scene name.
    pub scene: String,
    /// The algorithm, spelt as `umbra render --algo` takes it
    /// ([`Algorithm::name`](crate::pass::algorithm::Algorithm::name)).
    pub algorithm: String,
    /// Its family (first depth, second depth, midpoint and dual,
    /// silhouette map, shadow volumes).
    #[serde(with = "crate::base::text")]
    pub family: Family,
    /// Bias, a depth in `[0, 1]` (Reeves' `Bias0` for a bias range).
    pub bias: f64,
    /// Reeves' `Bias1`, for a bias range.
    pub bias1: Option<f64>,
    /// Weiskopf & Ertl's offset, for dual depth.
    pub offset: Option<f64>,
    /// Wang & Molnar's virtual samples on (null where they do not apply:
    /// every algorithm but second depth's).
    pub virtual_samples: Option<bool>,
    /// The light pass's culling per object class (`algorithm`, or
    /// `solids=…,open=…` as `umbra render --cull` takes it).
    #[serde(with = "crate::base::text")]
    pub culling: Culling,
    /// Depth format (`d16`, `d24`, `f32`).
    #[serde(with = "crate::base::text")]
    pub depth_format: DepthFormatKind,
    /// Map side.
    pub map_side_texels: u32,
    /// The filter, in its one spelling (`point`, `bilinear`, `box5`,
    /// `jitter16`, `jitter8,res-factor=1.5`: [`Filter`]'s `Display`).
    #[serde(with = "crate::base::text")]
    pub filter_name: Filter,
    /// Every directional light's cascades as `umbra render --cascades`
    /// spells them (`scene`: each light's own; rows written before
    /// cascades read as `scene`).
    #[serde(default = "scene_cascades")]
    pub cascades: String,
    /// Architecture name (`-` when the sweep has none; with its
    /// parameter-axis values when the sweep has such axes).
    pub arch: String,
    /// The architecture it was made from (`-` when the sweep has none).
    pub base_arch: String,
    /// The architecture's parameter-axis assignments (`key=value,…`;
    /// empty for none).
    pub arch_params: String,
    /// The same, one value per axis under its column's name
    /// (`column`: `arch_`, the key, its
    /// SI unit), numbers in SI base units.
    pub arch_axes: BTreeMap<String, serde_json::Value>,
    /// Camera image width.
    pub image_width_px: u32,
    /// Camera image height.
    pub image_height_px: u32,
    /// Reference rays per pixel side (`n` for `n × n` rays a pixel).
    pub reference_rays: u32,
    /// The `umbra render` command line that renders this configuration
    /// again.
    pub command: String,
    /// The version that made the row ([`crate::output::provenance::version`]).
    pub umbra_version: String,
    /// The sweep file's hash (`crate::output::provenance::hash`).
    pub sweep_hash: String,
}

columns! {
    /// A row's error against the exact reference ([`Metrics`]).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct RowMetrics from (m: &Metrics, virtual_sample_fraction: f64) {
        evaluated_px: u64, "integer", "px", "pixels compared (facing the light)" = m.evaluated;
        misclassified_percent: f64, "number", "percent", "misclassified by the ½ verdict, of the evaluated pixels" = m.misclassified_percent;
        false_shadow_px: u64, "integer", "px", "shadowed by the ½ verdict, lit in truth" = m.false_shadow;
        false_light_px: u64, "integer", "px", "lit by the ½ verdict, shadowed in truth" = m.false_light;
        aliasing_px: u64, "integer", "px", "wrong because the taps straddle a true edge or miss the occluder: aliasing" = m.aliasing;
        penumbra_px: u64, "integer", "px", "a filter's own partial shade across a true edge: penumbra" = m.penumbra;
        acne_px: u64, "integer", "px", "too dark from the receiver's own surface: acne" = m.acne;
        terminator_acne_px: u64, "integer", "px", "of the acne, near grazing beside a surface facing away: the terminator's" = m.terminator_acne;
        detachment_px: u64, "integer", "px", "too light because only the bias moved the test past an occluder: detachment" = m.detachment;
        leaks_px: u64, "integer", "px", "too light because the depth compared lies behind the receiver: leaks" = m.leaks;
        clipped_px: u64, "integer", "px", "too light because what shadows it lies outside the light's frustum: an occluder the map never saw" = m.clipped;
        aliasing_area_px: f64, "number", "px", "the aliasing's summed shade difference" = m.aliasing_area;
        penumbra_area_px: f64, "number", "px", "the penumbra's summed shade difference" = m.penumbra_area;
        acne_area_px: f64, "number", "px", "the acne's summed excess shadow" = m.acne_area;
        detachment_area_px: f64, "number", "px", "the detachment's summed missing shadow" = m.detachment_area;
        leak_area_px: f64, "number", "px", "the leaks' summed missing shadow" = m.leak_area;
        clipped_area_px: f64, "number", "px", "the clipped occluders' summed missing shadow" = m.clipped_area;
        artifact_percent: f64, "number", "percent", "acne, detachment, leaks and clipped occluders, of the evaluated pixels: what budgets bound" = m.artifact_percent;
        penumbra_width_p95_px: f64, "number", "px", "95th percentile distance of penumbra pixels from the exact boundary" = m.penumbra_width[1];
        mean_abs_error: f64, "number", "shadow fraction", "mean |shadow fraction − true shadowed area|" = m.mean_abs_error;
        rms_error: f64, "number", "shadow fraction", "root mean square of the same" = m.rms_error;
        displacement_mean_px: f64, "number", "px", "mean distance of the rendered boundary from the exact one" = m.displacement[0];
        displacement_p95_px: f64, "number", "px", "its 95th percentile" = m.displacement[1];
        footprint_x_texels_per_px: f64, "number", "texels/px", "median map texels a pixel along x (below 1: magnified)" = m.footprint_x[0];
        footprint_y_texels_per_px: f64, "number", "texels/px", "the same along y" = m.footprint_y[0];
        receiver_fallback_px: u64, "integer", "px", "wrong pixels judged against a flat receiver (no plane could be set up)" = m.receiver_fallbacks;
        virtual_sample_percent: f64, "number", "percent", "lookups with virtual samples" = 100.0 * virtual_sample_fraction;
    }
}

impl RowConfig {
    /// The architecture point: its name and parameter assignments.
    #[must_use]
    pub(crate) fn arch_point(&self) -> (&str, &str) {
        (&self.arch, &self.arch_params)
    }
}

impl RowMetrics {
    /// Acne, detachment, leaks and clipped occluders, pixels.
    #[must_use]
    pub const fn artifacts_px(&self) -> u64 {
        self.acne_px + self.detachment_px + self.leaks_px + self.clipped_px
    }
}

/// An architecture point's axis values on `arch`, each under its column's
/// name: numbers in SI base units, flags and text as they are.
fn axes(arch: &Arch, point: &super::ArchPoint) -> BTreeMap<String, serde_json::Value> {
    use crate::cost::arch::{Value, column};
    point
        .assignments
        .iter()
        .map(|(key, _)| {
            let value = match arch.get(key) {
                Some(Value::Number(x)) => serde_json::json!(x),
                Some(Value::Flag(b)) => serde_json::json!(b),
                Some(Value::Text(t)) => serde_json::json!(t),
                None => serde_json::Value::Null,
            };
            (column(key), value)
        })
        .collect()
}

impl Row {
    /// A row for `config` on `arch` (with its position), numbers to come.
    pub(super) fn new(spec: &Spec, c: &Config, arch: Option<(usize, &Arch)>) -> Self {
        let v = &spec.variants[c.variant];
        let cfg = super::render_config(spec, c);
        let point = arch.and_then(|a| spec.arch_points.get(a.0));
        let name = arch.map_or_else(|| "-".to_owned(), |a| a.1.name.clone());
        let base_arch = point.map_or_else(|| name.clone(), |p| p.base.clone());
        Self {
            config_index: c.index,
            arch_index: arch.map_or(0, |a| a.0),
            config: RowConfig {
                scene: spec.scenes[c.scene].name.clone(),
                algorithm: v.algorithm.name().to_owned(),
                family: v.algorithm.family(),
                bias: v.bias,
                bias1: v.algorithm.bias_hi(),
                offset: v.algorithm.offset(),
                virtual_samples: (v.algorithm.family() == Family::SecondDepth).then_some(v.virtual_samples),
                culling: v.culling,
                depth_format: c.format,
                map_side_texels: c.map_size,
                filter_name: spec.filters[c.filter],
                cascades: crate::world::cascade::choice_text(v.cascades),
                arch: name,
                base_arch,
                arch_params: point.map(super::ArchPoint::params).unwrap_or_default(),
                arch_axes: arch.zip(point).map(|(a, p)| axes(a.1, p)).unwrap_or_default(),
                image_width_px: cfg.width,
                image_height_px: cfg.height,
                reference_rays: cfg.reference_rays,
                command: cfg.command(&spec.scenes[c.scene]),
                umbra_version: crate::output::provenance::version(),
                sweep_hash: spec.hash.clone(),
            },
            status: Status::Ok,
            reason: String::new(),
            metrics: None,
            cost: None,
        }
    }

    pub(super) fn skip(&mut self, reason: String) {
        self.status = Status::Skipped;
        self.reason = reason;
        self.metrics = None;
        self.cost = None;
    }

    /// Whether the row has both an error and a cost.
    #[must_use]
    pub const fn complete(&self) -> bool {
        matches!(self.status, Status::Ok) && self.metrics.is_some() && self.cost.is_some()
    }

    /// The configuration and architecture in words, for tables: an
    /// architecture point its axes made by its base and its values as the
    /// sweep file writes them (`own-tbdr map_cache.size=16KiB`), said
    /// once; any other by its name (which names a `--set` too), with its
    /// axis values.
    #[must_use]
    pub fn label(&self) -> String {
        let c = &self.config;
        let made = c
            .arch_params
            .split(',')
            .filter_map(|kv| kv.split_once('='))
            .fold(c.base_arch.clone(), |name, (k, v)| crate::cost::arch::Arch::name_with(&name, k, v));
        if c.arch_params.is_empty() {
            format!("{}, {}", self.render_label(), c.arch)
        } else if made == c.arch {
            format!("{}, {} {}", self.render_label(), c.base_arch, c.arch_params)
        } else {
            format!("{}, {} ({})", self.render_label(), c.arch, c.arch_params)
        }
    }

    /// The render configuration in words (no architecture).
    #[must_use]
    pub(crate) fn render_label(&self) -> String {
        let c = &self.config;
        let mut s = c.algorithm.clone();
        // Shadow volumes use no map: no side, format or filter of one.
        if c.family == Family::Volumes {
            return s;
        }
        if let Some(hi) = c.bias1 {
            let _ = write!(s, " bias {}…{hi}", c.bias);
        } else if c.bias != 0.0 || c.family == Family::FirstDepth {
            let _ = write!(s, " bias {}", c.bias);
        }
        if let Some(o) = c.offset {
            let _ = write!(s, " offset {o}");
        }
        if c.virtual_samples == Some(false) {
            s.push_str(" no virtual samples");
        }
        if c.culling != Culling::ALGORITHM {
            let _ = write!(s, " cull {}", c.culling);
        }
        let _ = write!(s, ", {}, {}², {}", c.depth_format, c.map_side_texels, c.filter_name);
        if c.cascades != scene_cascades() {
            let _ = write!(s, ", cascades {}", c.cascades);
        }
        s
    }
}

/// The cascades of a row that asks for none: each light's own.
fn scene_cascades() -> String {
    crate::world::cascade::SCENE.to_owned()
}
