//! The cost report: time, bytes and energy of a render on one
//! architecture, what bounds each pass (memory told as bandwidth or
//! latency), its caches, and Sen et al.'s bandwidth figures; written as
//! Markdown, as a gem5-style stats file ([`CostReport::stats`]) and as a
//! timeline ([`trace`]).

mod compare;
pub mod files;
mod markdown;
pub(crate) mod stats;
mod trace;

pub use compare::{Compared, Comparison};
pub use trace::trace;

use crate::cost::arch::Arch;
use crate::cost::cache::CacheStats;
use crate::cost::dram::{Dram, Purpose, Requested};
use crate::cost::ledger::PassTiming;
use crate::cost::silicon::Silicon;
use crate::cost::timing::ArchProbe;
use crate::cost::work::{Bottleneck, EnergySplit, Work};
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
    /// the filter takes, per light the pixel is tested against.
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

/// The cost of one render on one architecture: each pass's timing and
/// ledgers, and the frame's totals computed from them
/// ([`CostReport::cycles`], [`CostReport::dram`], [`CostReport::energy`]).
#[derive(Clone, Debug)]
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
    /// The host and driver's fixed time of the frame, cycles (before the
    /// passes; none for a frame that draws nothing).
    pub host_cycles: f64,
    /// What the shadow unit asked of memory before any cache.
    pub requested: Requested,
    /// The DRAM's peak bandwidth, bytes a second.
    pub dram_peak_bytes_per_second: f64,
    /// The bandwidth the requests in flight sustain at the latency
    /// (Little's law), bytes a second.
    pub dram_latency_ceiling_bytes_per_second: f64,
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
    /// Each light's pass, in the scene's order, when there are several
    /// (the light pass above is their sum: they run one after another).
    pub light_passes: Vec<PassTiming>,
    /// Every pass in the order the frame runs them (each light's, then
    /// the camera's), for the timeline.
    pub timeline: Vec<PassTimeline>,
    /// The silicon of the units the render uses: their areas at the
    /// architecture's technology, and the leakage each pass's
    /// [`EnergySplit::leakage`] charges.
    pub silicon: Silicon,
}

impl CostReport {
    /// The frame's cycles: the host's, then the light pass, then the
    /// camera pass — each its ledger's sum.
    #[must_use]
    pub fn cycles(&self) -> f64 {
        self.host_cycles + self.light.cycles() + self.camera.cycles()
    }

    /// The frame's time at the clock, seconds.
    #[must_use]
    pub fn seconds(&self) -> f64 {
        self.cycles() / self.arch.clock
    }

    /// Frames per second.
    #[must_use]
    pub fn fps(&self) -> f64 {
        let s = self.seconds();
        if s > 0.0 { 1.0 / s } else { 0.0 }
    }

    /// The frame's cycles' ledger: both passes' added, by what bound them.
    #[must_use]
    pub fn bound_cycles(&self) -> [f64; 9] {
        core::array::from_fn(|k| self.light.bound_cycles[k] + self.camera.bound_cycles[k])
    }

    /// What bounds the most cycles of the frame.
    #[must_use]
    pub fn bottleneck(&self) -> Bottleneck {
        crate::cost::ledger::most(&self.bound_cycles())
    }

    /// The frame's DRAM traffic by purpose: both passes' ledgers added.
    #[must_use]
    pub fn dram(&self) -> Dram {
        self.light.dram.plus(&self.camera.dram)
    }

    /// Every DRAM byte of the frame: its ledger's sum.
    #[must_use]
    pub fn bytes(&self) -> u64 {
        self.dram().total()
    }

    /// The frame's DRAM bytes over its time, bytes a second.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "bytes far below 2^53")]
    pub fn achieved_bytes_per_second(&self) -> f64 {
        let s = self.seconds();
        if s > 0.0 { self.bytes() as f64 / s } else { 0.0 }
    }

    /// The frame's energy by unit, joules: both passes' added, and the
    /// units' leakage while the host works before them.
    #[must_use]
    pub fn energy(&self) -> EnergySplit {
        let host = EnergySplit { leakage: self.leakage_over(self.host_cycles), ..EnergySplit::default() };
        self.light.energy.plus(&self.camera.energy).plus(&host)
    }

    /// The units' area, square metres.
    #[must_use]
    pub fn square_metres(&self) -> f64 {
        self.silicon.square_metres()
    }

    /// The units' leakage over `cycles` at the clock, joules.
    fn leakage_over(&self, cycles: f64) -> f64 {
        self.silicon.leakage_watts() * cycles / self.arch.clock
    }

    /// This report with `silicon` for its units: each pass's leakage
    /// charged over its time.
    #[must_use]
    pub fn with_silicon(mut self, silicon: Silicon) -> Self {
        let (watts, clock) = (silicon.leakage_watts(), self.arch.clock);
        let charge = |p: &mut PassTiming| p.energy.leakage = watts * p.cycles() / clock;
        charge(&mut self.light);
        charge(&mut self.camera);
        self.light_passes.iter_mut().for_each(charge);
        self.timeline.iter_mut().for_each(|t| charge(&mut t.timing));
        self.silicon = silicon;
        self
    }
}

impl Serialize for CostReport {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut m = s.serialize_struct("CostReport", 30)?;
        m.serialize_field("scene", &self.scene)?;
        m.serialize_field("config", &self.config)?;
        m.serialize_field("arch", &self.arch)?;
        m.serialize_field("version", &self.version)?;
        m.serialize_field("cycles", &self.cycles())?;
        m.serialize_field("host_cycles", &self.host_cycles)?;
        m.serialize_field("seconds", &self.seconds())?;
        m.serialize_field("frames_per_second", &self.fps())?;
        m.serialize_field("bottleneck", &self.bottleneck())?;
        m.serialize_field("bound_cycles", &BoundCycles(self.bound_cycles()))?;
        m.serialize_field("dram_bytes", &self.bytes())?;
        m.serialize_field("dram", &self.dram())?;
        m.serialize_field("energy_joules", &self.energy())?;
        m.serialize_field("area_square_metres", &self.square_metres())?;
        m.serialize_field("silicon", &self.silicon)?;
        m.serialize_field("light", &self.light)?;
        m.serialize_field("camera", &self.camera)?;
        m.serialize_field("requested_bytes", &self.requested)?;
        m.serialize_field("achieved_bytes_per_second", &self.achieved_bytes_per_second())?;
        m.serialize_field("dram_peak_bytes_per_second", &self.dram_peak_bytes_per_second)?;
        m.serialize_field("dram_latency_ceiling_bytes_per_second", &self.dram_latency_ceiling_bytes_per_second)?;
        m.serialize_field("on_chip_bytes", &self.on_chip_bytes)?;
        m.serialize_field("max_z_cull_rate", &self.max_z_cull_rate)?;
        m.serialize_field("lookups_culled_per_pixel", &self.lookups_culled_per_pixel)?;
        m.serialize_field("virtual_sample_fraction", &self.virtual_sample_fraction)?;
        m.serialize_field("pixels", &self.pixels)?;
        m.serialize_field("scene_fill", &self.scene_fill)?;
        m.serialize_field("sen", &self.sen)?;
        m.serialize_field("light_events", &self.light_events)?;
        m.serialize_field("camera_events", &self.camera_events)?;
        if !self.light_passes.is_empty() {
            m.serialize_field("light_passes", &self.light_passes)?;
        }
        m.end()
    }
}

/// A cycles' ledger as a map from each bottleneck's name.
struct BoundCycles([f64; 9]);

impl Serialize for BoundCycles {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(Bottleneck::ALL.iter().map(|b| b.name()).zip(self.0))
    }
}

/// What the timeline draws of one pass.
#[derive(Clone, Debug)]
pub struct PassTimeline {
    /// Its name: `light`, `light lights[1]`, `light lights[0].cascades[2]`, `camera`.
    pub name: String,
    /// Its time.
    pub timing: PassTiming,
    /// Per tile (per draw on an immediate-mode machine).
    pub tiles: Vec<Work>,
    /// The units after its tiles, named.
    pub tail: [(&'static str, Work); 3],
    /// Tiles a row of its target; `None` for a pass timed per draw.
    pub tiles_across: Option<usize>,
    /// Its front end's work.
    pub front: Work,
}

impl PassTimeline {
    fn of<const D: bool>(name: String, probe: &ArchProbe<D>, timing: PassTiming) -> Self {
        Self {
            name,
            timing,
            tiles: probe.tiles.clone(),
            tail: probe.tail(),
            tiles_across: probe.tiles_across(),
            front: probe.front,
        }
    }
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
    /// Combine the probes of the light passes (one a map, each named by
    /// `maps`: `lights[k]`, or `lights[k].cascades[c]`) and the camera
    /// pass of `scene` rendered with `config` (described in words), whose
    /// filter takes `samples_per_pixel` depth samples and whose shading
    /// unit shades each covered pixel `shadings` times (once a light; a
    /// cascaded light's blend bands add theirs as lookups, not shadings).
    #[must_use]
    pub(crate) fn new<const L: bool, const C: bool>(
        (scene, config): (&str, String),
        (lights, maps): (&[ArchProbe<L>], &[String]),
        camera: &ArchProbe<C>,
        (samples_per_pixel, shadings): (u64, usize),
    ) -> Self {
        let arch = camera.arch.clone();
        // The light passes run one after another: their times, ledgers,
        // energy and events add.
        let each: Vec<PassTiming> = lights.iter().map(ArchProbe::timing).collect();
        let lt = each.iter().skip(1).fold(each.first().cloned().unwrap_or_default(), |a, b| a.then(b));
        let ct = camera.timing();
        let le = lights.iter().fold(Totals::ZERO, |a, l| a.plus(&l.events));
        let ce = camera.events;
        let several = lights.len() > 1;
        let mut timeline: Vec<PassTimeline> = lights
            .iter()
            .zip(&each)
            .enumerate()
            .map(|(k, (l, t))| {
                let name = match maps.get(k) {
                    Some(map) if several => format!("light {map}"),
                    _ => "light".to_owned(),
                };
                PassTimeline::of(name, l, t.clone())
            })
            .collect();
        timeline.push(PassTimeline::of("camera".to_owned(), camera, ct.clone()));
        // The shading unit shades each covered pixel once per light.
        let looked_up = shadings.max(1) as u64;
        let pixels = ce.pixels_shaded / looked_up;
        let fill = ce.fragments;
        let drew = le.submitted + ce.submitted > 0;
        let host_cycles = if drew { arch.front.frame_overhead_cycles } else { 0.0 };
        let p_lookup = ratio(camera.reconstructed_pixels, pixels);
        let overdraw = ratio(ce.volume_fragments, fill);
        let map = ct.dram.get(Purpose::MapReads) + ct.dram.get(Purpose::MapCacheFills);
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
            model_map_bytes_per_pixel: 4.0 * (samples_per_pixel * looked_up) as f64,
            silhouette_bytes_per_pixel: ratio(camera.requested.silhouette, pixels),
            model_silhouette_bytes_per_pixel: 24.0 * p_lookup,
            volume_bytes_per_fill: ratio(ce.volume_depth_bytes + ce.stencil_read_bytes + ce.stencil_write_bytes, fill),
            model_volume_bytes_per_fill: 5.5 * overdraw,
        };
        Self {
            scene: scene.to_owned(),
            config,
            version: env!("CARGO_PKG_VERSION"),
            host_cycles,
            requested: lights.iter().fold(camera.requested, |a, l| a.plus(&l.requested)),
            dram_peak_bytes_per_second: arch.dram.bandwidth,
            dram_latency_ceiling_bytes_per_second: arch.dram_latency_ceiling(),
            on_chip_bytes: lights.iter().map(ArchProbe::on_chip_bytes).max().unwrap_or(0),
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
            light_passes: if several { each } else { Vec::new() },
            timeline,
            light: lt,
            camera: ct,
            arch,
            silicon: Silicon::default(),
        }
    }

    /// Every cache a pass used: the pass, the cache's name (capitalised, as
    /// a line begins), its statistics.
    #[must_use]
    pub(crate) fn caches(&self) -> Vec<(&'static str, &'static str, CacheStats)> {
        let mut out = Vec::new();
        for (pass, t) in [("light", &self.light), ("camera", &self.camera)] {
            for (name, c) in [("Map cache", t.map_cache), ("Depth cache", t.depth_cache)] {
                if let Some(c) = c {
                    out.push((pass, name, c));
                }
            }
        }
        out
    }
}
