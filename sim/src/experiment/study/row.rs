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
use crate::cost::report::CostReport;
use crate::cost::work::Bottleneck;
use crate::pass::algorithm::{Culling, Family};
use crate::truth::metrics::Metrics;

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
    /// Architecture name (`-` when the sweep has none; with its
    /// parameter-axis values when the sweep has such axes).
    pub arch: String,
    /// The architecture it was made from (`-` when the sweep has none).
    pub base_arch: String,
    /// The architecture's parameter-axis assignments (`key=value,…`;
    /// empty for none).
    pub arch_params: String,
    /// The same, one value per axis under its column's name
    /// ([`column`](crate::cost::arch::file::column): `arch_`, the key, its
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
    /// The sweep file's hash ([`crate::output::provenance::hash`]).
    pub sweep_hash: String,
}

/// A row's error against the exact reference ([`Metrics`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RowMetrics {
    /// Pixels compared (facing the light).
    pub evaluated_px: u64,
    /// Misclassified, percent of the evaluated pixels.
    pub misclassified_percent: f64,
    /// Shadowed by the ½ verdict, lit in truth.
    pub false_shadow_px: u64,
    /// Lit by the ½ verdict, shadowed in truth.
    pub false_light_px: u64,
    /// Wrong because the taps straddle a true edge or miss the occluder:
    /// aliasing (edge placement).
    pub aliasing_px: u64,
    /// A filter's own partial shade across a true edge: penumbra.
    pub penumbra_px: u64,
    /// Too dark from the receiver's own surface: acne.
    pub acne_px: u64,
    /// Of the acne, on surfaces near grazing to the light: the terminator's.
    pub terminator_acne_px: u64,
    /// Too light because only the bias moved the test past an occluder
    /// the map holds: detached shadows.
    pub detachment_px: u64,
    /// Too light because the depth compared lies behind the receiver
    /// under a first-layer occluder: leaks.
    pub leaks_px: u64,
    /// The aliasing's summed shade difference, pixels.
    pub aliasing_area_px: f64,
    /// The penumbra's summed shade difference, pixels.
    pub penumbra_area_px: f64,
    /// The acne's summed excess shadow, pixels.
    pub acne_area_px: f64,
    /// The detachment's summed missing shadow, pixels.
    pub detachment_area_px: f64,
    /// The leaks' summed missing shadow, pixels.
    pub leak_area_px: f64,
    /// Acne, detachment and leaks, percent of the evaluated pixels: what
    /// error budgets apply to.
    pub artifact_percent: f64,
    /// The penumbra pixels' distance from the exact boundary, 95th
    /// percentile: the filter's soft edge's width to each side.
    pub penumbra_width_p95_px: f64,
    /// Mean |shadow fraction − true shadowed area|.
    pub mean_abs_error: f64,
    /// Root mean square of the same.
    pub rms_error: f64,
    /// Mean boundary displacement.
    pub displacement_mean_px: f64,
    /// 95th-percentile boundary displacement.
    pub displacement_p95_px: f64,
    /// The map's footprint along x, texels per pixel, median (below 1:
    /// magnified that way).
    pub footprint_x_texels_per_px: f64,
    /// The same along y.
    pub footprint_y_texels_per_px: f64,
    /// Lookups with virtual samples, percent.
    pub virtual_sample_percent: f64,
}

/// A row's cost on its architecture ([`CostReport`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RowCost {
    /// Light pass cycles (silhouette pass included).
    pub light_cycles: u64,
    /// What bounds the light pass (`dram-bandwidth` or `dram-latency` when
    /// memory does).
    pub light_bottleneck: Bottleneck,
    /// Camera pass cycles.
    pub camera_cycles: u64,
    /// Camera pass: shadow-unit cycles summed over tiles.
    pub camera_shadow_cycles: u64,
    /// What bounds the camera pass.
    pub camera_bottleneck: Bottleneck,
    /// The frame: light pass then camera pass.
    pub total_cycles: u64,
    /// The architecture's clock.
    pub clock_hertz: f64,
    /// The frame at the architecture's clock.
    pub frame_seconds: f64,
    /// Frames a second at the architecture's clock.
    pub frames_per_second: f64,
    /// The frame's energy.
    pub energy_joules: f64,
    /// The frame's DRAM bytes over its time.
    pub dram_achieved_bytes_per_second: f64,
    /// The DRAM's peak bandwidth.
    pub dram_peak_bytes_per_second: f64,
    /// The bandwidth the requests in flight sustain at the latency
    /// (Little's law).
    pub dram_latency_ceiling_bytes_per_second: f64,
    /// Map texels written by the light pass.
    pub dram_map_write_bytes: u64,
    /// Depth read back by the light pass.
    pub dram_map_readback_bytes: u64,
    /// Bins and setup records of both passes.
    pub dram_bin_bytes: u64,
    /// Camera-pass visibility depth, when off chip.
    pub dram_camera_depth_bytes: u64,
    /// Map bytes the shadow unit requested.
    pub dram_map_requested_bytes: u64,
    /// Map bytes fetched through the architecture's cache.
    pub dram_map_fetched_bytes: u64,
    /// Silhouette points written and read.
    pub dram_silhouette_bytes: u64,
    /// Scene depth read by shadow-volume fragments.
    pub dram_volume_depth_bytes: u64,
    /// Stencil read and written by shadow-volume fragments.
    pub dram_stencil_bytes: u64,
    /// All DRAM traffic (map reads as fetched).
    pub total_dram_bytes: u64,
    /// On-chip depth storage.
    pub on_chip_bytes: u64,
    /// Light-pass triangle-tile pairs and blocks max-z culled, percent.
    pub light_culled_percent: f64,
    /// The same of the camera's visibility, percent.
    pub camera_culled_percent: f64,
    /// Shadow lookups culled per covered pixel.
    pub lookups_culled_per_px: f64,
    /// Camera-pass map bytes per covered pixel.
    pub map_bytes_per_px: f64,
}

impl RowConfig {
    /// The architecture point: its name and parameter assignments.
    #[must_use]
    pub fn arch_point(&self) -> (&str, &str) {
        (&self.arch, &self.arch_params)
    }
}

impl RowMetrics {
    /// The metrics of a render, with its fraction of virtual-sampled lookups.
    #[must_use]
    pub fn new(m: &Metrics, virtual_sample_fraction: f64) -> Self {
        Self {
            evaluated_px: m.evaluated,
            misclassified_percent: m.misclassified_percent,
            false_shadow_px: m.false_shadow,
            false_light_px: m.false_light,
            aliasing_px: m.aliasing,
            penumbra_px: m.penumbra,
            acne_px: m.acne,
            terminator_acne_px: m.terminator_acne,
            detachment_px: m.detachment,
            leaks_px: m.leaks,
            aliasing_area_px: m.aliasing_area,
            penumbra_area_px: m.penumbra_area,
            acne_area_px: m.acne_area,
            detachment_area_px: m.detachment_area,
            leak_area_px: m.leak_area,
            artifact_percent: m.artifact_percent,
            penumbra_width_p95_px: m.penumbra_width[1],
            mean_abs_error: m.mean_abs_error,
            rms_error: m.rms_error,
            displacement_mean_px: m.displacement[0],
            displacement_p95_px: m.displacement[1],
            footprint_x_texels_per_px: m.footprint_x[0],
            footprint_y_texels_per_px: m.footprint_y[0],
            virtual_sample_percent: 100.0 * virtual_sample_fraction,
        }
    }

    /// Acne, detachment and leaks, pixels.
    #[must_use]
    pub const fn artifacts_px(&self) -> u64 {
        self.acne_px + self.detachment_px + self.leaks_px
    }
}

impl RowCost {
    /// The cost of a report.
    #[must_use]
    pub fn new(r: &CostReport) -> Self {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "cycles, rounded")]
        let round = |c: f64| c.round() as u64;
        let (l, c) = (&r.light_dram, &r.camera_dram);
        Self {
            light_cycles: round(r.light.cycles),
            light_bottleneck: r.light.bottleneck,
            camera_cycles: round(r.camera.cycles),
            camera_shadow_cycles: round(r.camera.stages[crate::cost::work::Stage::Shadow as usize]),
            camera_bottleneck: r.camera.bottleneck,
            total_cycles: round(r.cycles),
            clock_hertz: r.arch.clock,
            frame_seconds: r.seconds,
            frames_per_second: r.fps,
            energy_joules: r.energy.total(),
            dram_achieved_bytes_per_second: r.achieved_bytes_per_second,
            dram_peak_bytes_per_second: r.dram_peak_bytes_per_second,
            dram_latency_ceiling_bytes_per_second: r.dram_latency_ceiling_bytes_per_second,
            dram_map_write_bytes: l.map_writes,
            dram_map_readback_bytes: l.map_rmw_reads,
            dram_bin_bytes: l.bins + c.bins,
            dram_camera_depth_bytes: c.map_rmw_reads + c.depth_rmw,
            dram_map_requested_bytes: c.map_reads,
            dram_map_fetched_bytes: if r.arch.map_cache.size > 0 { c.map_fetched } else { c.map_reads },
            dram_silhouette_bytes: l.silhouette_writes + c.silhouette_reads,
            dram_volume_depth_bytes: c.volume_depth_reads,
            dram_stencil_bytes: c.stencil,
            total_dram_bytes: r.bytes,
            on_chip_bytes: r.on_chip_bytes,
            light_culled_percent: 100.0 * r.max_z_cull_rate[0],
            camera_culled_percent: 100.0 * r.max_z_cull_rate[1],
            lookups_culled_per_px: r.lookups_culled_per_pixel,
            map_bytes_per_px: r.sen.map_bytes_per_pixel,
        }
    }
}

/// An architecture point's axis values on `arch`, each under its column's
/// name: numbers in SI base units, flags and text as they are.
fn axes(arch: &Arch, point: &super::ArchPoint) -> BTreeMap<String, serde_json::Value> {
    use crate::cost::arch::file::{Value, column};
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
                arch: name,
                base_arch,
                arch_params: point.map(super::ArchPoint::params).unwrap_or_default(),
                arch_axes: arch.zip(point).map(|(a, p)| axes(a.1, p)).unwrap_or_default(),
                image_width_px: cfg.width,
                image_height_px: cfg.height,
                reference_rays: cfg.reference_rays,
                command: cfg.command(&spec.scenes[c.scene].source),
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

    /// The metrics, when measured.
    #[must_use]
    pub const fn measured(&self) -> Option<&RowMetrics> {
        self.metrics.as_ref()
    }

    /// The configuration and architecture in words, for tables.
    #[must_use]
    pub fn label(&self) -> String {
        let (arch, params) = self.config.arch_point();
        if params.is_empty() {
            format!("{}, {arch}", self.render_label())
        } else {
            format!("{}, {arch} ({params})", self.render_label())
        }
    }

    /// The render configuration in words (no architecture).
    #[must_use]
    pub fn render_label(&self) -> String {
        let c = &self.config;
        let mut s = c.algorithm.clone();
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
        s
    }
}
