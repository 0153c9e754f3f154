//! A cost report's statistics, each declared once — its name in the
//! stats file, its row column, unit, meaning and value — in the manner of
//! gem5's `ADD_STAT`: the gem5-style stats file (`name value # meaning
//! (unit)`, one number a line, what bounds each pass as a code its header
//! lists), the study's rows ([`RowCost`]) and the rows' schema all read the
//! declaration. The families declared by the units themselves (the
//! pipeline's stages, the bottlenecks, DRAM traffic by purpose, the
//! caches, energy by unit, the core's events) follow them.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use super::CostReport;
use crate::cost::dram::Purpose;
use crate::cost::work::{Bottleneck, QUEUE_NAMES, Stage};
use umbra_core::probe::{Counted, Totals};

/// The unit a statistic is counted in, declared with it; its name ends
/// in the unit's name (`_cycles`, `_bytes`, `_bytes_per_second`, …).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StatUnit {
    /// Events or items.
    Count,
    /// Clock cycles.
    Cycles,
    /// Seconds.
    Seconds,
    /// Per second.
    PerSecond,
    /// Bytes.
    Bytes,
    /// Bytes per second.
    BytesPerSecond,
    /// Bytes per covered pixel.
    BytesPerPixel,
    /// Per covered pixel.
    PerPixel,
    /// Bytes per fragment.
    BytesPerFragment,
    /// Joules.
    Joules,
    /// Square metres.
    SquareMetres,
    /// Watts.
    Watts,
    /// A ratio.
    Ratio,
    /// Percent.
    Percent,
    /// Hertz.
    Hertz,
    /// An enumerated code: a place in a list the stats file's header
    /// gives.
    Code,
}

impl StatUnit {
    /// Its symbol, as the stats file writes it.
    #[must_use]
    pub(crate) const fn symbol(self) -> &'static str {
        match self {
            Self::Count => "count",
            Self::Cycles => "cycles",
            Self::Seconds => "s",
            Self::PerSecond => "1/s",
            Self::Bytes => "B",
            Self::BytesPerSecond => "B/s",
            Self::BytesPerPixel => "B/px",
            Self::PerPixel => "1/px",
            Self::BytesPerFragment => "B/fragment",
            Self::Joules => "J",
            Self::SquareMetres => "m2",
            Self::Watts => "W",
            Self::Ratio => "ratio",
            Self::Percent => "percent",
            Self::Hertz => "Hz",
            Self::Code => "code",
        }
    }
}

/// A doc comment as one line of plain text.
fn plain(doc: &str) -> String {
    doc.split_whitespace().collect::<Vec<_>>().join(" ").replace(['`', '[', ']'], "")
}

/// A statistic's value: a count, a real number, or what bounds a pass
/// (its name in `cost.json` and the rows, its code in the stats file).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub(crate) enum Figure {
    /// A whole number.
    Count(u64),
    /// A real number.
    Real(f64),
    /// What bounds a pass or the frame.
    Bound(Bottleneck),
}

impl Figure {
    /// As the stats file prints it: a real to 7 significant digits, a
    /// bottleneck as its code (its place in [`Bottleneck::ALL`]).
    fn text(self) -> String {
        match self {
            Self::Count(n) => n.to_string(),
            Self::Real(x) => format!("{x:.6e}"),
            Self::Bound(b) => (b as usize).to_string(),
        }
    }
}

/// A declared statistic's Rust type: its type in the rows' schema and its
/// figure.
pub(crate) trait StatValue {
    /// Its type in the schema: `integer`, `number` or `text`.
    const KIND: &'static str;
    /// Its figure.
    fn figure(&self) -> Figure;
}

impl StatValue for u64 {
    const KIND: &'static str = "integer";
    fn figure(&self) -> Figure {
        Figure::Count(*self)
    }
}

impl StatValue for f64 {
    const KIND: &'static str = "number";
    fn figure(&self) -> Figure {
        Figure::Real(*self)
    }
}

impl StatValue for Bottleneck {
    const KIND: &'static str = "text";
    fn figure(&self) -> Figure {
        Figure::Bound(*self)
    }
}

/// One statistic of a report, as every writer reads it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct Statistic {
    /// Its name in the stats file (`frame.cycles`).
    #[serde(skip)]
    pub(crate) name: String,
    /// Its value.
    pub(crate) value: Figure,
    /// Its unit's symbol.
    pub(crate) unit: &'static str,
    /// What it means.
    pub(crate) meaning: String,
}

impl Statistic {
    fn new(name: &str, unit: StatUnit, meaning: &str, value: Figure) -> Self {
        Self { name: name.to_owned(), value, unit: unit.symbol(), meaning: meaning.to_owned() }
    }
}

/// Declares a report's statistics, each once: those a study's row carries
/// (the stats file's name `=>` the row's field), then those only the
/// stats file does. Makes the row block (each field's doc its meaning),
/// its `COLUMNS` in row order, `new` from a report, and `declared`, every
/// statistic in order.
macro_rules! stats {
    (
        $(#[$attr:meta])*
        $vis:vis struct $name:ident from ($r:ident: &CostReport) {
            $($stat:literal => $field:ident: $ty:ty, $unit:ident, $meaning:literal = $value:expr;)+
        }
        only {
            $($only:literal: $oty:ty, $ounit:ident, $omeaning:literal = $ovalue:expr;)+
        }
    ) => {
        $(#[$attr])*
        $vis struct $name {
            $(#[doc = $meaning] pub $field: $ty,)+
        }

        impl $name {
            /// Its columns, in row order, each as its statistic's
            /// declaration states it: field, type, unit and meaning.
            pub(crate) const COLUMNS: &'static [(&'static str, &'static str, &'static str, &'static str)] =
                &[$((stringify!($field), <$ty as StatValue>::KIND, StatUnit::$unit.symbol(), $meaning)),+];

            /// The block's values from a report.
            #[must_use]
            pub(crate) fn new($r: &CostReport) -> Self {
                Self { $($field: $value,)+ }
            }
        }

        /// Every declared statistic of `r`, in declaration order.
        fn declared($r: &CostReport) -> Vec<Statistic> {
            vec![
                $(Statistic::new($stat, StatUnit::$unit, $meaning, StatValue::figure(&{ let v: $ty = $value; v })),)+
                $(Statistic::new($only, StatUnit::$ounit, $omeaning, StatValue::figure(&{ let v: $oty = $ovalue; v })),)+
            ]
        }
    };
}

/// Cycles, rounded to whole ones (half away from zero), as every writer
/// of a report rounds them.
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    reason = "cycles, rounded; non-negative and below 2^64"
)]
pub(crate) fn whole_cycles(c: f64) -> u64 {
    c.round() as u64
}

stats! {
    /// A study's row's cost on its architecture: the statistics of a
    /// [`CostReport`] a row carries.
    #[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct RowCost from (r: &CostReport) {
        "light.cycles" => light_cycles: u64, Cycles, "the light pass (silhouette pass included)" = whole_cycles(r.light.cycles());
        "light.bottleneck" => light_bottleneck: Bottleneck, Code, "what bounds the most cycles of the light pass: setup, raster, depth, shadow, shade, dram-bandwidth, dram-latency, map-cache-misses-in-flight, depth-cache-misses-in-flight, or none (no work)" = r.light.bottleneck();
        "camera.cycles" => camera_cycles: u64, Cycles, "the camera pass" = whole_cycles(r.camera.cycles());
        "camera.stage.shadow_cycles" => camera_shadow_cycles: u64, Cycles, "the camera pass's shadow-unit cycles summed over tiles" = whole_cycles(r.camera.stages[Stage::Shadow as usize]);
        "camera.bottleneck" => camera_bottleneck: Bottleneck, Code, "what bounds the most cycles of the camera pass" = r.camera.bottleneck();
        "frame.cycles" => total_cycles: u64, Cycles, "the frame: host, light pass then camera pass" = whole_cycles(r.cycles());
        "arch.clock_hertz" => clock_hertz: f64, Hertz, "the architecture's clock" = r.arch.clock;
        "frame.seconds" => frame_seconds: f64, Seconds, "the frame at the clock" = r.seconds();
        "frame.frames_per_second" => frames_per_second: f64, PerSecond, "frames a second at the clock" = r.fps();
        "frame.energy.total_joules" => energy_joules: f64, Joules, "the frame's energy, dynamic and static" = r.energy().total();
        "silicon.square_metres" => area_square_metres: f64, SquareMetres, "the silicon of the units the render uses, at the architecture's technology" = r.square_metres();
        "frame.dram.achieved_bytes_per_second" => dram_achieved_bytes_per_second: f64, BytesPerSecond, "the frame's DRAM bytes over its time" = r.achieved_bytes_per_second();
        "frame.dram.peak_bytes_per_second" => dram_peak_bytes_per_second: f64, BytesPerSecond, "the DRAM's bandwidth" = r.dram_peak_bytes_per_second;
        "frame.dram.latency_ceiling_bytes_per_second" => dram_latency_ceiling_bytes_per_second: f64, BytesPerSecond, "requests in flight × burst / latency (Little's law)" = r.dram_latency_ceiling_bytes_per_second;
        "frame.dram.map_writes_bytes" => dram_map_writes_bytes: u64, Bytes, "map texels written by the light pass's resolve" = r.dram().get(Purpose::MapWrites);
        "frame.dram.tile_reloads_bytes" => dram_tile_reloads_bytes: u64, Bytes, "tile depth loaded back on chip by a later flush of its bins" = r.dram().get(Purpose::TileReloads);
        "frame.dram.map_combine_bytes" => dram_map_combine_bytes: u64, Bytes, "two maps read and one written by the pass combining them" = r.dram().get(Purpose::MapCombine);
        "frame.dram.off_chip_depth_bytes" => dram_off_chip_depth_bytes: u64, Bytes, "depth kept off chip, read and written per fragment" = r.dram().get(Purpose::OffChipDepth);
        "frame.dram.map_reads_bytes" => dram_map_reads_bytes: u64, Bytes, "map texels the shadow unit read without a map cache" = r.dram().get(Purpose::MapReads);
        "frame.dram.silhouette_reads_bytes" => dram_silhouette_reads_bytes: u64, Bytes, "silhouette points the shadow unit read without a map cache" = r.dram().get(Purpose::SilhouetteReads);
        "frame.dram.map_cache_fills_bytes" => dram_map_cache_fills_bytes: u64, Bytes, "lines the map cache fetched" = r.dram().get(Purpose::MapCacheFills);
        "frame.dram.colour_bytes" => dram_colour_bytes: u64, Bytes, "shaded pixels' colour written to the frame buffer" = r.dram().get(Purpose::Colour);
        "frame.dram.bins_bytes" => dram_bins_bytes: u64, Bytes, "bins and setup records written and read" = r.dram().get(Purpose::Bins);
        "frame.dram.silhouette_writes_bytes" => dram_silhouette_writes_bytes: u64, Bytes, "silhouette points written by the silhouette pass" = r.dram().get(Purpose::SilhouetteWrites);
        "frame.dram.volume_depth_reads_bytes" => dram_volume_depth_reads_bytes: u64, Bytes, "scene depth read by shadow-volume fragments" = r.dram().get(Purpose::VolumeDepthReads);
        "frame.dram.stencil_bytes" => dram_stencil_bytes: u64, Bytes, "stencil read and written by shadow-volume fragments" = r.dram().get(Purpose::Stencil);
        "frame.dram_bytes" => total_dram_bytes: u64, Bytes, "all DRAM traffic: the sum of the dram_*_bytes columns" = r.bytes();
        "camera.requested.map_bytes" => map_requested_bytes: u64, Bytes, "map bytes the shadow unit requested, before any cache (not traffic when cached)" = r.requested.map;
        "light.on_chip_bytes" => on_chip_bytes: u64, Bytes, "on-chip depth storage of the light pass" = r.on_chip_bytes;
        "light.max_z_culled_percent" => light_culled_percent: f64, Percent, "light-pass triangle-tile pairs and blocks max-z culled" = 100.0 * r.max_z_cull_rate[0];
        "camera.max_z_culled_percent" => camera_culled_percent: f64, Percent, "the same of the camera's visibility" = 100.0 * r.max_z_cull_rate[1];
        "camera.lookups_culled_per_pixel" => lookups_culled_per_px: f64, PerPixel, "shadow lookups decided by the tiles' bounds a covered pixel" = r.lookups_culled_per_pixel;
        "sen.map_bytes_per_pixel" => map_bytes_per_px: f64, BytesPerPixel, "camera-pass map bytes a covered pixel" = r.sen.map_bytes_per_pixel;
    }
    only {
        "frame.bottleneck": Bottleneck, Code, "what bounds the most cycles of the frame" = r.bottleneck();
        "frame.host_cycles": u64, Cycles, "the host and driver's cycles a frame" = whole_cycles(r.host_cycles);
        "light.seconds": f64, Seconds, "the light pass at the clock" = r.light.cycles() / r.arch.clock;
        "camera.seconds": f64, Seconds, "the camera pass at the clock" = r.camera.cycles() / r.arch.clock;
        "light.front_cycles": u64, Cycles, "setup and bin writes of the light pass" = whole_cycles(r.light.front);
        "camera.front_cycles": u64, Cycles, "setup and bin writes of the camera pass" = whole_cycles(r.camera.front);
        "light.tile_cycles": u64, Cycles, "the light pass's tiles (draws, on an immediate-mode machine), each its slowest stage, summed" = whole_cycles(r.light.tiles);
        "camera.tile_cycles": u64, Cycles, "the camera pass's tiles (draws), each its slowest stage, summed" = whole_cycles(r.camera.tiles);
        "light.memory.bandwidth_cycles": u64, Cycles, "the light pass's memory cycles summed over tiles were the bytes at the bandwidth what bound them" = whole_cycles(r.light.memory.bandwidth_cycles);
        "camera.memory.bandwidth_cycles": u64, Cycles, "the camera pass's memory cycles summed over tiles were the bytes at the bandwidth what bound them" = whole_cycles(r.camera.memory.bandwidth_cycles);
        "light.memory.latency_cycles": u64, Cycles, "the light pass's memory cycles summed over tiles were the requests at the latency what bound them" = whole_cycles(r.light.memory.latency_cycles);
        "camera.memory.latency_cycles": u64, Cycles, "the camera pass's memory cycles summed over tiles were the requests at the latency what bound them" = whole_cycles(r.camera.memory.latency_cycles);
        "light.dram_bytes": u64, Bytes, "DRAM traffic of the light pass" = r.light.bytes();
        "camera.dram_bytes": u64, Bytes, "DRAM traffic of the camera pass" = r.camera.bytes();
        "light.dram.achieved_bytes_per_second": f64, BytesPerSecond, "the light pass's DRAM bytes over its time" = r.light.achieved_bytes_per_second();
        "camera.dram.achieved_bytes_per_second": f64, BytesPerSecond, "the camera pass's DRAM bytes over its time" = r.camera.achieved_bytes_per_second();
        "sen.triangles": u64, Count, "scene triangles (Table 1)" = r.sen.triangles;
        "sen.silhouette_edges": u64, Count, "silhouette edges under the light (Table 1)" = r.sen.silhouette_edges;
        "sen.scene_fill": u64, Count, "camera visibility fragments (Table 1)" = r.sen.scene_fill;
        "sen.volume_fill": u64, Count, "shadow-volume fragments (Table 1)" = r.sen.volume_fill;
        "sen.silhouette_fill": u64, Count, "silhouette-pass fragments (Table 1)" = r.sen.silhouette_fill;
        "sen.p_fill_ratio": f64, Ratio, "silhouette fill over scene fill (Table 1)" = r.sen.p_fill;
        "sen.p_lookup_rate": f64, Ratio, "covered pixels reconstructed (bandwidth model)" = r.sen.p_lookup;
        "sen.overdraw_ratio": f64, Ratio, "volume fragments over scene fill" = r.sen.overdraw;
        "sen.model_map_bytes_per_pixel": f64, BytesPerPixel, "4 B x samples" = r.sen.model_map_bytes_per_pixel;
        "sen.silhouette_bytes_per_pixel": f64, BytesPerPixel, "simulated point bytes a covered pixel" = r.sen.silhouette_bytes_per_pixel;
        "sen.model_silhouette_bytes_per_pixel": f64, BytesPerPixel, "24 P" = r.sen.model_silhouette_bytes_per_pixel;
        "sen.volume_bytes_per_fragment": f64, BytesPerFragment, "simulated volume bytes a scene-fill fragment" = r.sen.volume_bytes_per_fill;
        "sen.model_volume_bytes_per_fragment": f64, BytesPerFragment, "5.5 O" = r.sen.model_volume_bytes_per_fill;
    }
}

impl CostReport {
    /// Every statistic of the report, each once: the declared numbers,
    /// then the families the units declare, then what bounds each pass and
    /// the frame.
    #[must_use]
    pub(crate) fn statistics(&self) -> Vec<Statistic> {
        let (numbers, names): (Vec<_>, Vec<_>) =
            declared(self).into_iter().partition(|s| !matches!(s.value, Figure::Bound(_)));
        let declared: BTreeSet<String> = numbers.iter().map(|s| s.name.clone()).collect();
        let mut all = numbers;
        // A family's member declared on its own is listed once, declared.
        self.families(&mut |name, unit, value, meaning| {
            if !declared.contains(name) {
                all.push(Statistic::new(name, unit, meaning, value));
            }
        });
        all.extend(names);
        all
    }

    /// The report as a gem5-style stats file: headed by the command line,
    /// the scene, the configuration, the version, the effective
    /// architecture and the legend of the bottleneck codes; then one
    /// `name value # meaning (unit)` line per statistic (the same
    /// `statistics` `cost.json` holds), every value a number.
    #[must_use]
    pub fn stats(&self, command: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "---------- Begin Simulation Statistics ----------");
        let _ = writeln!(s, "# umbra {} — {command}", self.version);
        let _ = writeln!(s, "# scene: {}; configuration: {}", self.scene, self.config);
        for line in self.arch.to_toml().lines() {
            let _ = writeln!(s, "# arch.{line}");
        }
        let legend: Vec<String> = Bottleneck::ALL
            .iter()
            .chain([&Bottleneck::Nothing])
            .map(|b| format!("{} {}", *b as usize, b.name()))
            .collect();
        let _ = writeln!(s, "# bottleneck codes: {}", legend.join(", "));
        for Statistic { name, value, unit, meaning } in self.statistics() {
            let _ = writeln!(s, "{name:<48} {:>20} # {meaning} ({unit})", value.text());
        }
        s.push_str("---------- End Simulation Statistics   ----------\n");
        s
    }

    /// The statistics of the families the units declare: each pass's
    /// stages, bottleneck counts, DRAM traffic by purpose, caches and
    /// energy by unit, the frame's energy by unit, and the core's events.
    fn families(&self, stat: &mut impl FnMut(&str, StatUnit, Figure, &str)) {
        let count = Figure::Count;
        let cycles = |v: f64| Figure::Count(whole_cycles(v));
        let real = Figure::Real;
        for (unit, e) in self.energy().fields() {
            stat(&format!("frame.energy.{unit}_joules"), StatUnit::Joules, real(e), "energy of the unit");
        }
        stat("silicon.leakage_watts", StatUnit::Watts, real(self.silicon.leakage_watts()), "the units' leakage power");
        for u in &self.silicon.units {
            let name = format!("silicon.{}.square_metres", u.unit.replace([' ', '-'], "_"));
            stat(&name, StatUnit::SquareMetres, real(u.square_metres), &format!("area of the unit: {}", u.how));
        }
        for (pass, t) in [("light", &self.light), ("camera", &self.camera)] {
            for (k, stage) in Stage::ALL.iter().enumerate() {
                let name = format!("{pass}.stage.{}_cycles", stage.name());
                stat(&name, StatUnit::Cycles, cycles(t.stages[k]), "stage cycles summed over tiles");
            }
            for (queue, c) in QUEUE_NAMES.iter().zip(t.memory.queue_cycles) {
                let name = format!("{pass}.memory.{queue}_cycles");
                stat(
                    &name,
                    StatUnit::Cycles,
                    cycles(c),
                    "the queue's requests at the latency over those it keeps in flight, summed over tiles",
                );
            }
            for (k, b) in Bottleneck::ALL.iter().enumerate() {
                let name = format!("{pass}.bound.{}", b.name().replace('-', "_"));
                stat(&name, StatUnit::Count, count(t.bound[k]), "tiles (draws) bound by it");
            }
            for (purpose, b) in t.dram.fields() {
                stat(&format!("{pass}.dram.{}_bytes", purpose.name()), StatUnit::Bytes, count(b), purpose.meaning());
            }
            for (k, b) in Bottleneck::ALL.iter().enumerate() {
                let name = format!("{pass}.bound_cycles.{}", b.name().replace('-', "_"));
                stat(
                    &name,
                    StatUnit::Cycles,
                    cycles(t.bound_cycles[k]),
                    "the pass's cycles charged to what bound them",
                );
            }
            stat(&format!("{pass}.overhead_cycles"), StatUnit::Cycles, cycles(t.overhead), "waiting for the host");
            for (cache, c) in [("map_cache", t.map_cache), ("depth_cache", t.depth_cache)] {
                let Some(c) = c else { continue };
                for (what, unit, value, doc) in [
                    ("accesses", StatUnit::Count, count(c.accesses), "reads and read-modify-writes"),
                    ("hits", StatUnit::Count, count(c.hits), "accesses that found their line"),
                    ("misses", StatUnit::Count, count(c.misses), "accesses that fetched their line"),
                    ("hit_rate", StatUnit::Ratio, real(c.hit_rate), "hits over accesses"),
                    ("fetched_bytes", StatUnit::Bytes, count(c.fetched_bytes), "a line a miss"),
                    (
                        "written_back_bytes",
                        StatUnit::Bytes,
                        count(c.written_back_bytes),
                        "a line a dirty eviction or flush",
                    ),
                ] {
                    stat(&format!("{pass}.{cache}.{what}"), unit, value, doc);
                }
            }
            for (unit, e) in t.energy.fields() {
                stat(&format!("{pass}.energy.{unit}_joules"), StatUnit::Joules, real(e), "energy of the unit");
            }
        }
        for (pass, t) in [("light", &self.light_events), ("camera", &self.camera_events)] {
            for (((name, v), doc), counted) in t.fields().into_iter().zip(Totals::DOCS).zip(Totals::UNITS) {
                let unit = match counted {
                    Counted::Count => StatUnit::Count,
                    Counted::Bytes => StatUnit::Bytes,
                };
                stat(&format!("{pass}.events.{name}"), unit, count(v), &plain(doc));
            }
        }
    }
}
