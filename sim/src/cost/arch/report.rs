//! The cost report: cycles, bytes and energy of a render on one architecture, with Sen et al.'s bandwidth terms.

use super::{ArchProbe, Dram, Stage};
use serde::Serialize;

/// The cost of one render on one architecture.
#[derive(Clone, Debug, Serialize)]
pub struct CostReport {
    /// The architecture.
    pub arch: &'static str,
    /// Light-pass cycles per stage, in [`Stage::ALL`] order.
    pub light_cycles: [u64; 5],
    /// The light pass's bottleneck stage and its cycles.
    pub light_bottleneck: (Stage, u64),
    /// Camera-pass cycles per stage.
    pub camera_cycles: [u64; 5],
    /// The camera pass's bottleneck stage and its cycles.
    pub camera_bottleneck: (Stage, u64),
    /// Light-pass DRAM traffic.
    pub light_dram: Dram,
    /// Camera-pass DRAM traffic (map reads as requested by the shadow unit;
    /// visibility depth if off chip).
    pub camera_dram: Dram,
    /// Map and silhouette-point bytes actually fetched through the
    /// preset's map cache (the requested bytes when it has none).
    pub map_bytes_fetched: u64,
    /// On-chip depth storage, bytes.
    pub on_chip_bytes: u64,
    /// Triangle-tile pairs and blocks skipped by max-z culling, as a
    /// fraction of those considered, light pass and camera visibility.
    pub max_z_cull_rate: [f64; 2],
    /// Shadow lookups decided by the tiles' bounds, per shaded pixel.
    pub lookups_culled_per_pixel: f64,
    /// Pixels that needed virtual samples, as a fraction of shaded pixels.
    pub virtual_sample_fraction: f64,
    /// Camera pixels on geometry.
    pub pixels: u64,
    /// Simulated camera-pass map bytes per pixel.
    pub map_bytes_per_pixel: f64,
    /// Sen et al.'s analytic shadow-map figure: 4 bytes per depth sample,
    /// times the samples the filter takes per pixel.
    pub sen_shadow_map_bytes_per_pixel: f64,
    /// Simulated camera-pass shadow bytes per pixel: map, silhouette
    /// points, volume depth and stencil.
    pub shadow_bytes_per_pixel: f64,
    /// Fragments of the camera's visibility pass (Sen et al.'s scene fill).
    pub scene_fill: u64,
    /// Sen et al.'s `P`: silhouette fragments over scene fill.
    pub silhouette_fill: f64,
    /// Sen et al.'s `O`: shadow-volume fragments over scene fill.
    pub overdraw: f64,
    /// Sen et al.'s silhouette-map figure, `4 + 24·P` bytes per pixel.
    pub sen_silhouette_bytes_per_pixel: f64,
    /// Sen et al.'s shadow-volume figure, `5.5·O` bytes per pixel.
    pub sen_volume_bytes_per_pixel: f64,
}

#[allow(clippy::cast_precision_loss, reason = "ratios of counts")]
/// Triangle-tile pairs and blocks skipped by max-z culling.
const fn culled(p: &ArchProbe) -> u64 {
    p.events.culled_triangles + p.events.culled_blocks
}

fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

impl CostReport {
    /// Combine the probes of the light pass and of the camera pass.
    #[must_use]
    pub fn new(
        light: &ArchProbe,
        camera: &ArchProbe,
        fetched: Option<u64>,
        pixels: u64,
        samples_per_pixel: u64,
    ) -> Self {
        let lookups = camera.events.trivial_pixels() + camera.events.tangent_setups;
        // Map texels and silhouette points go through the cache, when there is one.
        let requested = camera.dram.cached();
        let fetched = fetched.unwrap_or(requested);
        Self {
            arch: light.params.name,
            light_cycles: light.cycles,
            light_bottleneck: light.bottleneck(),
            camera_cycles: camera.cycles,
            camera_bottleneck: camera.bottleneck(),
            light_dram: light.dram,
            camera_dram: camera.dram,
            map_bytes_fetched: fetched,
            on_chip_bytes: light.on_chip_bytes(),
            max_z_cull_rate: [
                ratio(culled(light), culled(light) + light.events.rasterized),
                ratio(culled(camera), culled(camera) + camera.events.rasterized),
            ],
            lookups_culled_per_pixel: ratio(camera.events.lookups_culled, pixels),
            virtual_sample_fraction: ratio(camera.events.tangent_setups, lookups),
            pixels,
            map_bytes_per_pixel: ratio(fetched, pixels),
            #[allow(clippy::cast_precision_loss, reason = "a small count")]
            sen_shadow_map_bytes_per_pixel: 4.0 * samples_per_pixel as f64,
            shadow_bytes_per_pixel: ratio(camera.dram.camera_shadow_bytes() - requested + fetched, pixels),
            scene_fill: camera.events.fragments,
            silhouette_fill: ratio(light.events.silhouette_fragments, camera.events.fragments),
            overdraw: ratio(camera.events.volume_fragments, camera.events.fragments),
            sen_silhouette_bytes_per_pixel: 4.0
                + 24.0 * ratio(light.events.silhouette_fragments, camera.events.fragments),
            sen_volume_bytes_per_pixel: 5.5 * ratio(camera.events.volume_fragments, camera.events.fragments),
        }
    }

    /// Light bottleneck plus camera bottleneck cycles: the passes run one
    /// after the other, each as slow as its slowest stage.
    #[must_use]
    pub const fn total_cycles(&self) -> u64 {
        self.light_bottleneck.1 + self.camera_bottleneck.1
    }

    /// Every DRAM byte of both passes, camera map reads as fetched through
    /// the cache.
    #[must_use]
    pub const fn total_bytes(&self) -> u64 {
        self.light_dram.total() + self.camera_dram.total() - self.camera_dram.cached() + self.map_bytes_fetched
    }

    /// The report as a Markdown table.
    #[must_use]
    pub fn markdown(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let _ = writeln!(s, "### {}\n", self.arch);
        let _ = writeln!(s, "| pass | setup | raster | depth | shadow | resolve | bottleneck |");
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---|");
        for (name, c, b) in [
            ("light", self.light_cycles, self.light_bottleneck),
            ("camera", self.camera_cycles, self.camera_bottleneck),
        ] {
            let _ = writeln!(
                s,
                "| {name} | {} | {} | {} | {} | {} | {:?} ({} cycles) |",
                c[0], c[1], c[2], c[3], c[4], b.0, b.1
            );
        }
        let d = &self.light_dram;
        let _ = writeln!(
            s,
            "\nDRAM bytes: map writes {}, light-pass depth reads {}, bins {}, camera map reads {} requested / {} fetched; on-chip depth {} bytes.",
            d.map_writes,
            d.map_rmw_reads,
            d.bins,
            self.camera_dram.map_reads,
            self.map_bytes_fetched,
            self.on_chip_bytes
        );
        let _ = writeln!(
            s,
            "Max-z culled: {:.1} % (light), {:.1} % (camera visibility); {:.2} lookups culled per pixel; virtual samples for {:.2} % of pixels.",
            100.0 * self.max_z_cull_rate[0],
            100.0 * self.max_z_cull_rate[1],
            self.lookups_culled_per_pixel,
            100.0 * self.virtual_sample_fraction
        );
        let _ = writeln!(
            s,
            "Camera-pass map bytes per pixel: simulated {:.2}, Sen's shadow-map model {:.1} (4 B per depth sample).",
            self.map_bytes_per_pixel, self.sen_shadow_map_bytes_per_pixel
        );
        let _ = writeln!(
            s,
            "Camera-pass shadow bytes per pixel (map, silhouette points, volume depth, stencil): simulated {:.2}; Sen's model: silhouette map 4 + 24·P = {:.2} (P = {:.3}), shadow volumes 5.5·O = {:.2} (O = {:.2}).",
            self.shadow_bytes_per_pixel,
            self.sen_silhouette_bytes_per_pixel,
            self.silhouette_fill,
            self.sen_volume_bytes_per_pixel,
            self.overdraw
        );
        s
    }

    /// A per-tile timeline of the light pass in Chrome trace-event JSON
    /// (opens in Perfetto): one slice per triangle-tile pair, in processing
    /// order, one microsecond per cycle, one track per tile row.
    #[must_use]
    pub fn trace(light: &ArchProbe) -> serde_json::Value {
        let mut t = 0u64;
        let events: Vec<serde_json::Value> = light
            .tile_cycles
            .iter()
            .map(|&(x, y, cycles)| {
                let e = serde_json::json!({
                    "name": format!("tile ({x}, {y})"),
                    "cat": "light",
                    "ph": "X",
                    "ts": t,
                    "dur": cycles.max(1),
                    "pid": 1,
                    "tid": y,
                });
                t += cycles.max(1);
                e
            })
            .collect();
        serde_json::json!({ "traceEvents": events, "displayTimeUnit": "ns" })
    }
}
