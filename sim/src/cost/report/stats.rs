//! The cost report as a gem5-style stats file: `name value # description
//! (unit)`, one figure a line, every value a number in an SI base unit
//! whose name ends in that unit; what bounds each pass, an enumerated name,
//! in a section of its own.

use std::fmt::Write as _;

use super::CostReport;
use crate::cost::work::{Bottleneck, Stage};
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
    /// Bytes per fragment.
    BytesPerFragment,
    /// Joules.
    Joules,
    /// A ratio.
    Ratio,
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
            Self::BytesPerPixel => "B/pixel",
            Self::BytesPerFragment => "B/fragment",
            Self::Joules => "J",
            Self::Ratio => "ratio",
        }
    }
}

/// A doc comment as one line of plain text.
fn plain(doc: &str) -> String {
    doc.split_whitespace().collect::<Vec<_>>().join(" ").replace(['`', '[', ']'], "")
}

impl CostReport {
    /// The report as a gem5-style stats file: headed by the command line,
    /// the scene, the configuration, the version and the effective
    /// architecture; then one `name value # description (unit)` line per
    /// figure; then each pass's and the frame's bottleneck.
    #[must_use]
    pub fn stats(&self, command: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "---------- Begin Simulation Statistics ----------");
        let _ = writeln!(s, "# umbra {} — {command}", self.version);
        let _ = writeln!(s, "# scene: {}; configuration: {}", self.scene, self.config);
        for line in self.arch.to_toml().lines() {
            let _ = writeln!(s, "# arch.{line}");
        }
        let mut stat = |name: &str, unit: StatUnit, value: String, doc: &str| {
            let _ = writeln!(s, "{name:<48} {value:>20} # {doc} ({})", unit.symbol());
        };
        let count = |v: u64| v.to_string();
        let real = |v: f64| format!("{v:.6e}");
        stat("frame.cycles", StatUnit::Cycles, format!("{:.0}", self.cycles), "light pass then camera pass");
        stat("frame.seconds", StatUnit::Seconds, real(self.seconds), "the frame at the clock");
        stat("frame.frames_per_second", StatUnit::PerSecond, real(self.fps), "frames a second");
        stat("frame.dram_bytes", StatUnit::Bytes, count(self.bytes), "DRAM traffic of the frame");
        stat(
            "frame.dram.achieved_bytes_per_second",
            StatUnit::BytesPerSecond,
            real(self.achieved_bytes_per_second),
            "DRAM bytes over the frame's time",
        );
        stat(
            "frame.dram.peak_bytes_per_second",
            StatUnit::BytesPerSecond,
            real(self.dram_peak_bytes_per_second),
            "the DRAM's bandwidth",
        );
        stat(
            "frame.dram.latency_ceiling_bytes_per_second",
            StatUnit::BytesPerSecond,
            real(self.dram_latency_ceiling_bytes_per_second),
            "requests in flight x burst / latency (Little's law)",
        );
        for (unit, e) in self.energy.fields() {
            stat(&format!("frame.energy.{unit}_joules"), StatUnit::Joules, real(e), "energy of the unit");
        }
        stat("frame.energy.total_joules", StatUnit::Joules, real(self.energy.total()), "sum over units");
        for (pass, t, dram) in [("light", &self.light, &self.light_dram), ("camera", &self.camera, &self.camera_dram)] {
            stat(&format!("{pass}.cycles"), StatUnit::Cycles, format!("{:.0}", t.cycles), "the pass");
            stat(
                &format!("{pass}.seconds"),
                StatUnit::Seconds,
                real(t.cycles / self.arch.clock),
                "the pass at the clock",
            );
            stat(&format!("{pass}.front_cycles"), StatUnit::Cycles, format!("{:.0}", t.front), "setup and bin writes");
            stat(
                &format!("{pass}.tile_cycles"),
                StatUnit::Cycles,
                format!("{:.0}", t.tiles),
                "each tile (draw, on an immediate-mode machine) its slowest stage, summed",
            );
            for (k, stage) in Stage::ALL.iter().enumerate() {
                stat(
                    &format!("{pass}.stage.{}_cycles", stage.name()),
                    StatUnit::Cycles,
                    format!("{:.0}", t.stages[k]),
                    "stage cycles summed over tiles",
                );
            }
            stat(
                &format!("{pass}.memory.bandwidth_cycles"),
                StatUnit::Cycles,
                format!("{:.0}", t.memory.bandwidth_cycles),
                "memory cycles summed over tiles were the bytes at the bandwidth what bound them",
            );
            stat(
                &format!("{pass}.memory.latency_cycles"),
                StatUnit::Cycles,
                format!("{:.0}", t.memory.latency_cycles),
                "memory cycles summed over tiles were the requests at the latency what bound them",
            );
            for (k, b) in Bottleneck::ALL.iter().enumerate() {
                stat(
                    &format!("{pass}.bound.{}", b.name().replace('-', "_")),
                    StatUnit::Count,
                    count(t.bound[k]),
                    "tiles (draws) bound by it",
                );
            }
            stat(&format!("{pass}.dram_bytes"), StatUnit::Bytes, count(t.bytes), "DRAM traffic of the pass");
            stat(
                &format!("{pass}.dram.achieved_bytes_per_second"),
                StatUnit::BytesPerSecond,
                real(t.achieved_bytes_per_second),
                "DRAM bytes over the pass's time",
            );
            for (purpose, b) in dram.fields() {
                stat(&format!("{pass}.dram.{purpose}_bytes"), StatUnit::Bytes, count(b), "DRAM traffic by purpose");
            }
            for (cache, c) in [("map_cache", t.map_cache), ("depth_cache", t.depth_cache)] {
                let Some(c) = c else { continue };
                stat(
                    &format!("{pass}.{cache}.accesses"),
                    StatUnit::Count,
                    count(c.accesses),
                    "reads and read-modify-writes",
                );
                stat(&format!("{pass}.{cache}.hits"), StatUnit::Count, count(c.hits), "accesses that found their line");
                stat(
                    &format!("{pass}.{cache}.misses"),
                    StatUnit::Count,
                    count(c.misses),
                    "accesses that fetched their line",
                );
                stat(&format!("{pass}.{cache}.hit_rate"), StatUnit::Ratio, real(c.hit_rate), "hits over accesses");
                stat(
                    &format!("{pass}.{cache}.fetched_bytes"),
                    StatUnit::Bytes,
                    count(c.fetched_bytes),
                    "a line a miss",
                );
                stat(
                    &format!("{pass}.{cache}.written_back_bytes"),
                    StatUnit::Bytes,
                    count(c.written_back_bytes),
                    "a line a dirty eviction or flush",
                );
            }
            for (unit, e) in t.energy.fields() {
                stat(&format!("{pass}.energy.{unit}_joules"), StatUnit::Joules, real(e), "energy of the unit");
            }
        }
        let n = &self.sen;
        for (name, unit, v, doc) in [
            ("sen.triangles", StatUnit::Count, count(n.triangles), "scene triangles (Table 1)"),
            (
                "sen.silhouette_edges",
                StatUnit::Count,
                count(n.silhouette_edges),
                "silhouette edges under the light (Table 1)",
            ),
            ("sen.scene_fill", StatUnit::Count, count(n.scene_fill), "camera visibility fragments (Table 1)"),
            ("sen.volume_fill", StatUnit::Count, count(n.volume_fill), "shadow-volume fragments (Table 1)"),
            ("sen.silhouette_fill", StatUnit::Count, count(n.silhouette_fill), "silhouette-pass fragments (Table 1)"),
            ("sen.p_fill_ratio", StatUnit::Ratio, real(n.p_fill), "silhouette fill over scene fill (Table 1)"),
            ("sen.p_lookup_rate", StatUnit::Ratio, real(n.p_lookup), "covered pixels reconstructed (bandwidth model)"),
            ("sen.overdraw_ratio", StatUnit::Ratio, real(n.overdraw), "volume fragments over scene fill"),
            (
                "sen.map_bytes_per_pixel",
                StatUnit::BytesPerPixel,
                real(n.map_bytes_per_pixel),
                "simulated map bytes a covered pixel",
            ),
            (
                "sen.model_map_bytes_per_pixel",
                StatUnit::BytesPerPixel,
                real(n.model_map_bytes_per_pixel),
                "4 B x samples",
            ),
            (
                "sen.silhouette_bytes_per_pixel",
                StatUnit::BytesPerPixel,
                real(n.silhouette_bytes_per_pixel),
                "simulated point bytes a covered pixel",
            ),
            (
                "sen.model_silhouette_bytes_per_pixel",
                StatUnit::BytesPerPixel,
                real(n.model_silhouette_bytes_per_pixel),
                "24 P",
            ),
            (
                "sen.volume_bytes_per_fragment",
                StatUnit::BytesPerFragment,
                real(n.volume_bytes_per_fill),
                "simulated volume bytes a scene-fill fragment",
            ),
            (
                "sen.model_volume_bytes_per_fragment",
                StatUnit::BytesPerFragment,
                real(n.model_volume_bytes_per_fill),
                "5.5 O",
            ),
        ] {
            stat(name, unit, v, doc);
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
        s.push_str("---------- End Simulation Statistics   ----------\n\n");
        s.push_str("---------- Begin Bottlenecks ----------\n");
        let names = Bottleneck::ALL.map(Bottleneck::name).join(" ");
        for (what, b) in
            [("frame", self.bottleneck), ("light", self.light.bottleneck), ("camera", self.camera.bottleneck)]
        {
            let _ = writeln!(
                s,
                "{:<48} {:>20} # what bounds the most cycles (one of: {names})",
                format!("{what}.bottleneck"),
                b.name()
            );
        }
        s.push_str("---------- End Bottlenecks ----------\n");
        s
    }
}
