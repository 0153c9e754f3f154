//! The cost report: time, bytes and energy of a render on one
//! architecture, with Sen et al.'s bandwidth figures, written as Markdown,
//! as a gem5-style stats file and as a timeline.

use std::fmt::Write as _;

use super::timing::{EnergySplit, PassTiming, Work};
use super::{Arch, ArchProbe, Dram, Stage};
use serde::Serialize;
use umbra_core::probe::Totals;

/// Sen, Cammarano & Hanrahan's (2003, §5) figures for a render, each in
/// the unit it is stated in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SenFigures {
    /// Their Table 1's scene information: the scene's triangles.
    pub triangles: u64,
    /// Silhouette edges under the light (what both the volumes and the
    /// silhouette map process).
    pub silhouette_edges: u64,
    /// Scene fill: fragments of the camera's visibility pass.
    pub scene_fill: u64,
    /// Volume fill: shadow-volume fragments.
    pub volume_fill: u64,
    /// Silhouette fill: fragments of the silhouette pass.
    pub silhouette_fill: u64,
    /// `P` as their Table 1 measures it: silhouette fill (fragments of the
    /// silhouette pass) over scene fill (fragments of the camera's
    /// visibility pass).
    pub p_fill: f64,
    /// `P` as their bandwidth model uses it: the fraction of covered pixels
    /// whose lookup needed the silhouette reconstruction.
    pub p_lookup: f64,
    /// `O`: shadow-volume fragments over scene fill.
    pub overdraw: f64,
    /// Simulated map bytes (as fetched) per covered pixel.
    pub map_bytes_per_pixel: f64,
    /// Their shadow-map figure per covered pixel: 4 bytes per depth sample
    /// the filter takes.
    pub model_map_bytes_per_pixel: f64,
    /// Simulated silhouette-point bytes read per covered pixel.
    pub silhouette_bytes_per_pixel: f64,
    /// Their silhouette-point figure per covered pixel, `24·P` (three
    /// 8-byte points per pixel near a silhouette, `P` = `p_lookup`).
    pub model_silhouette_bytes_per_pixel: f64,
    /// Simulated shadow-volume bytes (scene depth and stencil) per
    /// scene-fill fragment.
    pub volume_bytes_per_fill: f64,
    /// Their shadow-volume figure per scene-fill fragment, `5.5·O`.
    pub model_volume_bytes_per_fill: f64,
}

/// The cost of one render on one architecture.
#[derive(Clone, Debug, Serialize)]
pub struct CostReport {
    /// The scene's name.
    pub scene: String,
    /// The render configuration, in words.
    pub config: String,
    /// The effective architecture.
    pub arch: Arch,
    /// Umbra's version.
    pub version: &'static str,
    /// The light pass (and the silhouette pass, when there is one).
    pub light: PassTiming,
    /// The camera pass.
    pub camera: PassTiming,
    /// The frame: light pass, then camera pass.
    pub cycles: f64,
    /// The frame's time at the clock, seconds.
    pub seconds: f64,
    /// Frames per second.
    pub fps: f64,
    /// The frame's energy by unit, joules.
    pub energy: EnergySplit,
    /// Light-pass DRAM traffic.
    pub light_dram: Dram,
    /// Camera-pass DRAM traffic.
    pub camera_dram: Dram,
    /// Every DRAM byte of the frame.
    pub bytes: u64,
    /// On-chip depth storage of the light pass, bytes.
    pub on_chip_bytes: u64,
    /// Triangle-tile pairs and blocks skipped by max-z culling, as a
    /// fraction of those considered, light pass and camera visibility.
    pub max_z_cull_rate: [f64; 2],
    /// Shadow lookups decided by the tiles' bounds, per covered pixel.
    pub lookups_culled_per_pixel: f64,
    /// Pixels that needed virtual samples, as a fraction of shaded pixels.
    pub virtual_sample_fraction: f64,
    /// Covered camera pixels.
    pub pixels: u64,
    /// Fragments of the camera's visibility pass (Sen et al.'s scene fill).
    pub scene_fill: u64,
    /// Sen et al.'s figures.
    pub sen: SenFigures,
    /// Every event of the light pass.
    pub light_events: Totals,
    /// Every event of the camera pass.
    pub camera_events: Totals,
    /// Per tile of each pass (light, camera), for the timeline.
    #[serde(skip)]
    pub tiles: [Vec<Work>; 2],
    /// The silhouette pass's work, for the timeline.
    #[serde(skip)]
    pub silhouette: Work,
    /// The front ends' work (light, camera), for the timeline.
    #[serde(skip)]
    pub front: [Work; 2],
}

#[allow(clippy::cast_precision_loss, reason = "ratios of counts")]
fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

/// Triangle-tile pairs and blocks skipped by max-z culling.
const fn culled(t: &Totals) -> u64 {
    t.culled_triangles + t.culled_blocks
}

impl CostReport {
    /// Combine the probes of the light pass and the camera pass of `scene`
    /// rendered with `config` (described in words), whose filter takes
    /// `samples_per_pixel` depth samples.
    #[must_use]
    pub fn new<const L: bool, const C: bool>(
        (scene, config): (&str, String),
        light: &ArchProbe<L>,
        camera: &ArchProbe<C>,
        samples_per_pixel: u64,
    ) -> Self {
        let arch = light.arch.clone();
        let (lt, ct) = (light.timing(), camera.timing());
        let (le, ce) = (light.events, camera.events);
        let cached = arch.map_cache.size > 0;
        let pixels = ce.pixels_shaded;
        let fill = ce.fragments;
        let cycles = lt.cycles + ct.cycles;
        let seconds = cycles / arch.clock;
        let p_lookup = ratio(camera.reconstructed_pixels, pixels);
        let overdraw = ratio(ce.volume_fragments, fill);
        let map = if cached { camera.dram.map_fetched } else { camera.dram.map_reads };
        let lookups = ce.trivial_pixels() + ce.tangent_setups;
        #[allow(clippy::cast_precision_loss, reason = "a small count")]
        let sen = SenFigures {
            triangles: 0,
            silhouette_edges: 0,
            scene_fill: fill,
            volume_fill: ce.volume_fragments,
            silhouette_fill: le.silhouette_fragments,
            p_fill: ratio(le.silhouette_fragments, fill),
            p_lookup,
            overdraw,
            map_bytes_per_pixel: ratio(map, pixels),
            model_map_bytes_per_pixel: 4.0 * samples_per_pixel as f64,
            silhouette_bytes_per_pixel: ratio(camera.dram.silhouette_reads, pixels),
            model_silhouette_bytes_per_pixel: 24.0 * p_lookup,
            volume_bytes_per_fill: ratio(ce.volume_depth_bytes + ce.stencil_read_bytes + ce.stencil_write_bytes, fill),
            model_volume_bytes_per_fill: 5.5 * overdraw,
        };
        Self {
            scene: scene.to_owned(),
            config,
            version: env!("CARGO_PKG_VERSION"),
            cycles,
            seconds,
            fps: if seconds > 0.0 { 1.0 / seconds } else { 0.0 },
            energy: lt.energy.plus(&ct.energy),
            bytes: lt.bytes + ct.bytes,
            light_dram: light.dram,
            camera_dram: camera.dram,
            on_chip_bytes: light.on_chip_bytes(),
            max_z_cull_rate: [
                ratio(culled(&le), culled(&le) + le.rasterized),
                ratio(culled(&ce), culled(&ce) + ce.rasterized),
            ],
            lookups_culled_per_pixel: ratio(ce.lookups_culled, pixels),
            virtual_sample_fraction: ratio(ce.tangent_setups, lookups),
            pixels,
            scene_fill: fill,
            sen,
            light_events: le,
            camera_events: ce,
            tiles: [light.tiles.clone(), camera.tiles.clone()],
            silhouette: light.silhouette,
            front: [light.front, camera.front],
            light: lt,
            camera: ct,
            arch,
        }
    }

    /// The report as Markdown.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let a = &self.arch;
        let _ = writeln!(s, "### {} — {}\n", a.name, a.description);
        let _ = writeln!(
            s,
            "Frame: {:.0} cycles, {:.3} ms at {} MHz ({:.1} frames/s), {} DRAM bytes, {:.3} mJ.\n",
            self.cycles,
            self.seconds * 1e3,
            a.clock / 1e6,
            self.fps,
            self.bytes,
            self.energy.total() * 1e3
        );
        let _ = writeln!(
            s,
            "| pass | setup | raster | depth | shadow | shade | memory | pass cycles | bottleneck | {} bound (setup/raster/depth/shadow/shade/memory) |",
            if a.immediate() { "draws" } else { "tiles" }
        );
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|---|---|");
        for (name, t) in [("light", &self.light), ("camera", &self.camera)] {
            let c = t.stages;
            let b = t.bound;
            let _ = writeln!(
                s,
                "| {name} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {} | {}/{}/{}/{}/{}/{} |",
                c[0],
                c[1],
                c[2],
                c[3],
                c[4],
                c[5],
                t.cycles,
                t.bottleneck.name(),
                b[0],
                b[1],
                b[2],
                b[3],
                b[4],
                b[5]
            );
        }
        let e = &self.energy;
        let _ = writeln!(
            s,
            "\nEnergy (µJ): DRAM {:.1}, on-chip buffers {:.1}, caches {:.1}, raster and depth {:.1}, shadow unit {:.1}.",
            e.dram * 1e6,
            e.buffers * 1e6,
            e.caches * 1e6,
            e.raster * 1e6,
            e.shadow * 1e6
        );
        let (l, c) = (&self.light_dram, &self.camera_dram);
        let _ = writeln!(
            s,
            "DRAM bytes: map writes {}, tile reloads {}, off-chip depth {} (light) + {} (camera), bins {} + {}, map reads {} requested / {} fetched, colour {}; on-chip depth {} bytes.",
            l.map_writes,
            l.map_rmw_reads,
            l.depth_rmw,
            c.depth_rmw,
            l.bins,
            c.bins,
            c.map_reads,
            c.map_fetched,
            c.colour,
            self.on_chip_bytes
        );
        let _ = writeln!(
            s,
            "Max-z culled: {:.1} % (light), {:.1} % (camera visibility); {:.2} lookups culled per covered pixel; virtual samples for {:.2} % of lookups.",
            100.0 * self.max_z_cull_rate[0],
            100.0 * self.max_z_cull_rate[1],
            self.lookups_culled_per_pixel,
            100.0 * self.virtual_sample_fraction
        );
        let n = &self.sen;
        let _ = writeln!(
            s,
            "Sen et al.: P = {:.4} as silhouette fill over scene fill (their Table 1), {:.4} as the fraction of covered pixels reconstructed (their bandwidth model); O = {:.2}.",
            n.p_fill, n.p_lookup, n.overdraw
        );
        let _ = writeln!(
            s,
            "Their Table 1's columns: {} triangles, {} silhouette edges, scene fill {}, volume fill {}, silhouette fill {} (CROWD: 14 836, 4 800, 148.9 k, 22.96 M, 19.8 k).",
            n.triangles, n.silhouette_edges, n.scene_fill, n.volume_fill, n.silhouette_fill
        );
        let _ = writeln!(
            s,
            "Per covered pixel: map {:.2} B simulated vs 4 B × samples = {:.1} B; silhouette points {:.2} B simulated vs 24·P = {:.2} B. Per scene-fill fragment: volumes {:.2} B simulated vs 5.5·O = {:.2} B.",
            n.map_bytes_per_pixel,
            n.model_map_bytes_per_pixel,
            n.silhouette_bytes_per_pixel,
            n.model_silhouette_bytes_per_pixel,
            n.volume_bytes_per_fill,
            n.model_volume_bytes_per_fill
        );
        s
    }

    /// The report as a gem5-style stats file: one `name value # description
    /// (unit)` line per figure, headed by the scene, the configuration, the
    /// version and the effective architecture.
    #[must_use]
    pub fn stats(&self, command: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "---------- Begin Simulation Statistics ----------");
        let _ = writeln!(s, "# umbra {} — {command}", self.version);
        let _ = writeln!(s, "# scene: {}; configuration: {}", self.scene, self.config);
        for line in self.arch.to_toml().lines() {
            let _ = writeln!(s, "# arch.{line}");
        }
        let mut stat = |name: &str, value: String, doc: &str, unit: &str| {
            let _ = writeln!(s, "{name:<44} {value:>20} # {doc} ({unit})");
        };
        stat("frame.cycles", format!("{:.0}", self.cycles), "light pass then camera pass", "cycles");
        stat("frame.seconds", format!("{:.9}", self.seconds), "the frame at the clock", "s");
        stat("frame.fps", format!("{:.3}", self.fps), "frames per second", "1/s");
        stat("frame.dram_bytes", self.bytes.to_string(), "DRAM traffic of the frame", "bytes");
        for (unit, e) in [
            ("dram", self.energy.dram),
            ("buffers", self.energy.buffers),
            ("caches", self.energy.caches),
            ("raster", self.energy.raster),
            ("shadow", self.energy.shadow),
        ] {
            stat(&format!("frame.energy.{unit}"), format!("{e:.6e}"), "energy of the unit", "J");
        }
        stat("frame.energy.total", format!("{:.6e}", self.energy.total()), "sum over units", "J");
        for (pass, t) in [("light", &self.light), ("camera", &self.camera)] {
            stat(&format!("{pass}.cycles"), format!("{:.0}", t.cycles), "the pass", "cycles");
            stat(&format!("{pass}.front_cycles"), format!("{:.0}", t.front), "setup and bin writes", "cycles");
            stat(
                &format!("{pass}.tile_cycles"),
                format!("{:.0}", t.tiles),
                "each tile (draw, on an immediate-mode machine) its slowest stage, summed",
                "cycles",
            );
            stat(&format!("{pass}.bottleneck"), t.bottleneck.name().to_owned(), "stage bounding most cycles", "stage");
            for (k, stage) in Stage::ALL.iter().enumerate() {
                stat(
                    &format!("{pass}.stage.{}", stage.name()),
                    format!("{:.0}", t.stages[k]),
                    "stage cycles summed over tiles",
                    "cycles",
                );
                stat(
                    &format!("{pass}.bound.{}", stage.name()),
                    t.bound[k].to_string(),
                    "tiles (draws) bound by the stage",
                    "tiles or draws",
                );
            }
            stat(&format!("{pass}.dram_bytes"), t.bytes.to_string(), "DRAM traffic of the pass", "bytes");
        }
        let n = &self.sen;
        for (name, v, doc) in [
            ("sen.triangles", n.triangles, "scene triangles (Table 1)"),
            ("sen.silhouette_edges", n.silhouette_edges, "silhouette edges under the light (Table 1)"),
            ("sen.scene_fill", n.scene_fill, "camera visibility fragments (Table 1)"),
            ("sen.volume_fill", n.volume_fill, "shadow-volume fragments (Table 1)"),
            ("sen.silhouette_fill", n.silhouette_fill, "silhouette-pass fragments (Table 1)"),
        ] {
            stat(name, v.to_string(), doc, "count");
        }
        for (name, v, doc, unit) in [
            ("sen.p_fill", n.p_fill, "silhouette fill over scene fill (Table 1)", "ratio"),
            ("sen.p_lookup", n.p_lookup, "covered pixels reconstructed (bandwidth model)", "ratio"),
            ("sen.overdraw", n.overdraw, "volume fragments over scene fill", "ratio"),
            ("sen.map_bytes", n.map_bytes_per_pixel, "simulated map bytes", "bytes/covered pixel"),
            ("sen.model_map_bytes", n.model_map_bytes_per_pixel, "4 B x samples", "bytes/covered pixel"),
            ("sen.silhouette_bytes", n.silhouette_bytes_per_pixel, "simulated point bytes", "bytes/covered pixel"),
            ("sen.model_silhouette_bytes", n.model_silhouette_bytes_per_pixel, "24 P", "bytes/covered pixel"),
            ("sen.volume_bytes", n.volume_bytes_per_fill, "simulated volume bytes", "bytes/scene-fill fragment"),
            ("sen.model_volume_bytes", n.model_volume_bytes_per_fill, "5.5 O", "bytes/scene-fill fragment"),
        ] {
            stat(name, format!("{v:.6}"), doc, unit);
        }
        for (pass, t) in [("light", &self.light_events), ("camera", &self.camera_events)] {
            for (name, v) in t.fields() {
                stat(&format!("{pass}.events.{name}"), v.to_string(), "event total", "count");
            }
        }
        s.push_str("---------- End Simulation Statistics   ----------\n");
        s
    }

    /// The frame's timeline in Chrome trace-event JSON (opens in Perfetto):
    /// both passes one after the other; a front-end track (setup and bin
    /// writes, beside the tiles when the architecture overlaps them); a
    /// track with each tile's whole time, and one per stage with that
    /// tile's cycles in it; slices carry the tile's triangles, fragments,
    /// pixels and bytes; a DRAM-bandwidth counter track. Times in
    /// microseconds at the architecture's clock.
    #[must_use]
    pub fn trace(&self) -> serde_json::Value {
        let a = &self.arch;
        let us = |cycles: f64| cycles / a.clock * 1e6;
        let mut events = vec![serde_json::json!({
            "name": "process_name", "ph": "M", "pid": 1, "args": { "name": format!("{} on {}", self.scene, a.name) }
        })];
        let stages = &Stage::ALL[1..];
        let names = ["front end", "tiles"].into_iter().chain(stages.iter().map(|s| s.name()));
        for (tid, name) in names.enumerate() {
            events.push(
                serde_json::json!({ "name": "thread_name", "ph": "M", "pid": 1, "tid": tid, "args": { "name": name } }),
            );
        }
        // One slice of `w` on track `tid` at `t`, its stages on their own
        // tracks when `staged`; the DRAM rate over it. Returns its cycles.
        let mut slice = |pass: &str, label: String, w: &Work, t: f64, tid: usize, staged: bool| {
            let cycles = w.stages(a);
            let dur = cycles.iter().copied().fold(0.0, f64::max);
            if dur <= 0.0 {
                return 0.0;
            }
            let args = serde_json::json!({
                "triangles": w.triangles, "fragments": w.fragments, "pixels": w.pixels, "bytes": w.bytes,
                "cycles": dur, "setup cycles": cycles[Stage::Setup as usize],
            });
            events.push(serde_json::json!({
                "name": label, "cat": pass, "ph": "X", "ts": us(t), "dur": us(dur), "pid": 1, "tid": tid, "args": args
            }));
            if staged {
                for (k, stage) in stages.iter().enumerate() {
                    let c = cycles[*stage as usize];
                    if c > 0.0 {
                        events.push(serde_json::json!({
                            "name": format!("{pass} {}", stage.name()), "cat": pass, "ph": "X",
                            "ts": us(t), "dur": us(c), "pid": 1, "tid": k + 2,
                        }));
                    }
                }
                #[allow(clippy::cast_precision_loss, reason = "bytes far below 2^53")]
                let rate = w.bytes as f64 / (dur / a.clock) / 1e9;
                events.push(serde_json::json!({ "name": "DRAM GB/s", "ph": "C", "ts": us(t), "pid": 1, "args": { "GB/s": rate } }));
            }
            dur
        };
        let mut t = 0.0f64;
        for (p, pass) in ["light", "camera"].iter().enumerate() {
            let timing = if p == 0 { &self.light } else { &self.camera };
            let start = t;
            let front = slice(pass, format!("{pass} front end"), &self.front[p], t, 0, false);
            // Overlapped, the tiles start with the front end.
            if !a.front.overlap {
                t += front;
            }
            let unit = if a.immediate() { "draw" } else { "tile" };
            for (i, w) in self.tiles[p].iter().enumerate() {
                t += slice(pass, format!("{pass} {unit} {i}"), w, t, 1, true);
            }
            if p == 0 {
                t += slice(pass, "silhouette pass".to_owned(), &self.silhouette, t, 1, true);
            }
            t = t.max(start + timing.cycles);
        }
        events.push(
            serde_json::json!({ "name": "DRAM GB/s", "ph": "C", "ts": us(t), "pid": 1, "args": { "GB/s": 0.0 } }),
        );
        let metadata = serde_json::json!({
            "umbra": self.version, "scene": self.scene, "configuration": self.config, "arch": self.arch,
        });
        serde_json::json!({ "traceEvents": events, "displayTimeUnit": "ns", "metadata": metadata })
    }
}
