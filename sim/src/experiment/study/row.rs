//! One row of the study: a configuration's accuracy against the reference and its cost on one architecture.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use super::{Config, Spec};
use crate::cost::arch::{Arch, CostReport};
use crate::truth::metrics::Metrics;

/// One configuration on one architecture: every metric and every cost.
/// Numbers are absent when the render or the costing was skipped (`status`
/// and `reason` say why).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// The configuration's index in the sweep.
    pub index: usize,
    /// The preset's position in the sweep (sort key).
    pub arch_index: usize,
    /// Scene name.
    pub scene: String,
    /// Algorithm name ([`Variant::name`](super::Variant::name)).
    pub algorithm: String,
    /// Bias, depth in `[0, 1]`.
    pub bias: f64,
    /// Dual offset, for dual depth.
    pub offset: Option<f64>,
    /// Reeves' `Bias1`, for a bias range (`bias` is `Bias0`).
    pub bias_hi: Option<f64>,
    /// Virtual samples on.
    pub virtual_samples: bool,
    /// The light pass's culling per object class (`algorithm`, or
    /// `solids=…,open=…` as `umbra render --cull` takes it).
    pub culling: String,
    /// Depth format.
    pub format: String,
    /// Map side.
    pub map: u32,
    /// Filter name.
    pub filter: String,
    /// Architecture preset (`-` when the sweep has none).
    pub arch: String,
    /// Camera image width.
    pub width: u32,
    /// Camera image height.
    pub height: u32,
    /// Reference rays per pixel side.
    pub reference_samples: u32,
    /// The `umbra render` command line that renders this row's
    /// configuration again.
    pub command: String,
    /// `ok` or `skipped`.
    pub status: String,
    /// Why the row was skipped (empty when ok).
    pub reason: String,
    /// Pixels compared (facing the light).
    pub evaluated: Option<u64>,
    /// Misclassified, percent of the evaluated pixels.
    pub misclassified_percent: Option<f64>,
    /// False shadows (acne, self-shadowing) per evaluated pixel.
    pub false_shadow_rate: Option<f64>,
    /// False light (leaks, self-unshadowing) per evaluated pixel.
    pub false_light_rate: Option<f64>,
    /// Mean |shadow fraction − true shadowed area|.
    pub mean_abs_error: Option<f64>,
    /// Root mean square of the same.
    pub rms_error: Option<f64>,
    /// Misclassified pixels at the reference's shadow boundary.
    pub edge_placement: Option<u64>,
    /// False shadows away from it.
    pub acne: Option<u64>,
    /// False light away from it.
    pub leaks: Option<u64>,
    /// Acne and leaks, percent of the evaluated pixels.
    pub artifact_percent: Option<f64>,
    /// Mean boundary displacement, pixels.
    pub displacement_mean: Option<f64>,
    /// 95th-percentile boundary displacement, pixels.
    pub displacement_p95: Option<f64>,
    /// The map's footprint on screen, texels per pixel (below 1: magnified).
    pub texels_per_pixel: Option<f64>,
    /// Light pass cycles (per-tile timing; silhouette pass included).
    pub light_cycles: Option<u64>,
    /// Light pass bottleneck stage.
    pub light_bottleneck: Option<String>,
    /// Camera pass cycles (per-tile timing).
    pub camera_cycles: Option<u64>,
    /// Camera pass: shadow-unit cycles summed over tiles.
    pub camera_shadow_cycles: Option<u64>,
    /// Camera pass bottleneck stage.
    pub camera_bottleneck: Option<String>,
    /// The frame: light pass then camera pass, cycles.
    pub total_cycles: Option<u64>,
    /// The frame's frames per second at the architecture's clock.
    pub fps: Option<f64>,
    /// The frame's energy, microjoules.
    pub energy_uj: Option<f64>,
    /// DRAM: map texels written by the light pass.
    pub dram_map_writes: Option<u64>,
    /// DRAM: depth read back by the light pass.
    pub dram_map_rmw_reads: Option<u64>,
    /// DRAM: bins and setup records of both passes.
    pub dram_bins: Option<u64>,
    /// DRAM: camera-pass visibility depth, when off chip.
    pub dram_camera_depth: Option<u64>,
    /// DRAM: map bytes the shadow unit requested.
    pub dram_map_reads_requested: Option<u64>,
    /// DRAM: map bytes fetched through the preset's cache.
    pub dram_map_reads_fetched: Option<u64>,
    /// DRAM: silhouette points written and read (fetched through the cache
    /// when the preset has one, with the map reads).
    pub dram_silhouette: Option<u64>,
    /// DRAM: scene depth read by shadow-volume fragments.
    pub dram_volume_depth: Option<u64>,
    /// DRAM: stencil read and written by shadow-volume fragments.
    pub dram_stencil: Option<u64>,
    /// All DRAM bytes (fetched map reads, not requested).
    pub total_bytes: Option<u64>,
    /// On-chip depth storage.
    pub on_chip_bytes: Option<u64>,
    /// Light-pass max-z cull rate.
    pub light_cull_rate: Option<f64>,
    /// Camera visibility max-z cull rate.
    pub camera_cull_rate: Option<f64>,
    /// Shadow lookups culled per pixel.
    pub lookups_culled_per_pixel: Option<f64>,
    /// Fraction of pixels with virtual samples.
    pub virtual_sample_fraction: Option<f64>,
    /// Camera-pass map bytes per pixel.
    pub map_bytes_per_pixel: Option<f64>,
}

impl Row {
    /// A row for `config` with everything but the numbers.
    pub(super) fn new(spec: &Spec, c: &Config, arch: Option<(usize, &Arch)>) -> Self {
        let v = &spec.variants[c.variant];
        Self {
            index: c.index,
            arch_index: arch.map_or(0, |a| a.0),
            scene: spec.scenes[c.scene].name.clone(),
            algorithm: v.name.to_owned(),
            bias: v.bias,
            offset: v.algorithm.offset(),
            bias_hi: v.algorithm.bias_hi(),
            virtual_samples: v.virtual_samples,
            culling: v.culling.label(),
            format: c.format.name().to_owned(),
            map: c.map_size,
            filter: spec.filters[c.filter].0.clone(),
            arch: arch.map_or_else(|| "-".to_owned(), |a| a.1.name.clone()),
            width: spec.width,
            height: spec.height,
            reference_samples: spec.reference_samples,
            command: super::render_config(spec, c).command(&spec.scenes[c.scene].source),
            status: "ok".to_owned(),
            reason: String::new(),
            evaluated: None,
            misclassified_percent: None,
            false_shadow_rate: None,
            false_light_rate: None,
            mean_abs_error: None,
            rms_error: None,
            edge_placement: None,
            acne: None,
            leaks: None,
            artifact_percent: None,
            displacement_mean: None,
            displacement_p95: None,
            texels_per_pixel: None,
            light_cycles: None,
            light_bottleneck: None,
            camera_cycles: None,
            camera_shadow_cycles: None,
            camera_bottleneck: None,
            total_cycles: None,
            fps: None,
            energy_uj: None,
            dram_map_writes: None,
            dram_map_rmw_reads: None,
            dram_bins: None,
            dram_camera_depth: None,
            dram_map_reads_requested: None,
            dram_map_reads_fetched: None,
            dram_silhouette: None,
            dram_volume_depth: None,
            dram_stencil: None,
            total_bytes: None,
            on_chip_bytes: None,
            light_cull_rate: None,
            camera_cull_rate: None,
            lookups_culled_per_pixel: None,
            virtual_sample_fraction: None,
            map_bytes_per_pixel: None,
        }
    }

    pub(super) fn skip(&mut self, reason: String) {
        self.status = "skipped".to_owned();
        self.reason = reason;
    }

    pub(super) fn set_metrics(&mut self, m: &Metrics) {
        self.evaluated = Some(m.evaluated);
        self.misclassified_percent = Some(m.misclassified_percent);
        self.false_shadow_rate = Some(m.false_shadow_rate);
        self.false_light_rate = Some(m.false_light_rate);
        self.mean_abs_error = Some(m.mean_abs_error);
        self.rms_error = Some(m.rms_error);
        self.edge_placement = Some(m.edge_placement);
        self.acne = Some(m.acne);
        self.texels_per_pixel = Some(m.texels_per_pixel);
        self.leaks = Some(m.leaks);
        self.artifact_percent = Some(m.artifact_percent);
        self.displacement_mean = Some(m.displacement[0]);
        self.displacement_p95 = Some(m.displacement[1]);
    }

    pub(super) fn set_cost(&mut self, r: &CostReport) {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "cycles, rounded")]
        let round = |c: f64| c.round() as u64;
        self.light_cycles = Some(round(r.light.cycles));
        self.light_bottleneck = Some(r.light.bottleneck.name().to_owned());
        self.camera_cycles = Some(round(r.camera.cycles));
        self.camera_shadow_cycles = Some(round(r.camera.stages[crate::cost::arch::Stage::Shadow as usize]));
        self.camera_bottleneck = Some(r.camera.bottleneck.name().to_owned());
        self.total_cycles = Some(round(r.cycles));
        self.fps = Some(r.fps);
        self.energy_uj = Some(r.energy.total() * 1e6);
        let (l, c) = (&r.light_dram, &r.camera_dram);
        self.dram_map_writes = Some(l.map_writes);
        self.dram_map_rmw_reads = Some(l.map_rmw_reads);
        self.dram_bins = Some(l.bins + c.bins);
        self.dram_camera_depth = Some(c.map_rmw_reads + c.depth_rmw);
        self.dram_map_reads_requested = Some(c.map_reads);
        self.dram_map_reads_fetched = Some(if r.arch.map_cache.size > 0 { c.map_fetched } else { c.map_reads });
        self.dram_silhouette = Some(l.silhouette_writes + c.silhouette_reads);
        self.dram_volume_depth = Some(c.volume_depth_reads);
        self.dram_stencil = Some(c.stencil);
        self.total_bytes = Some(r.bytes);
        self.on_chip_bytes = Some(r.on_chip_bytes);
        self.light_cull_rate = Some(r.max_z_cull_rate[0]);
        self.camera_cull_rate = Some(r.max_z_cull_rate[1]);
        self.lookups_culled_per_pixel = Some(r.lookups_culled_per_pixel);
        self.virtual_sample_fraction = Some(r.virtual_sample_fraction);
        self.map_bytes_per_pixel = Some(r.sen.map_bytes_per_pixel);
    }

    /// Whether the row has both an error and a cost.
    #[must_use]
    pub fn complete(&self) -> bool {
        self.status == "ok" && self.misclassified_percent.is_some() && self.total_cycles.is_some()
    }

    /// The configuration and preset in words, for tables.
    #[must_use]
    pub fn label(&self) -> String {
        format!("{}, {}", self.render_label(), self.arch)
    }

    /// The render configuration in words (no preset).
    #[must_use]
    pub fn render_label(&self) -> String {
        let mut s = self.algorithm.clone();
        if let Some(hi) = self.bias_hi {
            let _ = write!(s, " bias {}…{hi}", self.bias);
        } else if self.algorithm == "first" || self.bias != 0.0 {
            let _ = write!(s, " bias {}", self.bias);
        }
        if let Some(o) = self.offset.filter(|_| self.algorithm.starts_with("dual")) {
            let _ = write!(s, " offset {o}");
        }
        let _ = write!(s, ", {}, {}², {}", self.format, self.map, self.filter);
        s
    }
}
