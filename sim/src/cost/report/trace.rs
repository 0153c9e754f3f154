//! The frame's timeline in Chrome trace-event JSON, as Perfetto shows it:
//! one process per architecture; a slice per pass enclosing everything the
//! pass does; the host's wait, the front end, the tiles (or draws) and
//! what follows them; one track per stage.

use serde_json::{Value, json};

use super::CostReport;
use crate::cost::work::{Stage, Work};

/// Tracks of a process: passes, the front end, the tiles, then one per
/// stage after setup.
const TRACKS: [&str; 8] = ["passes", "front end", "tiles", "raster", "depth", "shadow", "shade", "memory"];
/// The track of the tiles.
const TILES: usize = 2;

/// The timelines of one render's reports: a process per architecture, each
/// starting at 0. Returns the trace and, per report, the tile (draw)
/// slices it holds.
#[must_use]
pub fn trace(reports: &[CostReport]) -> (Value, Vec<usize>) {
    let mut events = Vec::new();
    let mut counts = Vec::new();
    for (k, r) in reports.iter().enumerate() {
        counts.push(r.timeline(k + 1, &mut events));
    }
    let metadata: Vec<Value> = reports
        .iter()
        .map(|r| {
            json!({
                "umbra": r.version, "scene": r.scene, "configuration": r.config, "arch": r.arch,
                "dram_peak_gb_per_second": r.dram_peak_bytes_per_second / 1e9,
                "dram_latency_ceiling_gb_per_second": r.dram_latency_ceiling_bytes_per_second / 1e9,
            })
        })
        .collect();
    (json!({ "traceEvents": events, "displayTimeUnit": "ns", "metadata": metadata }), counts)
}

impl CostReport {
    /// The frame's timeline as process `pid`, pushed onto `events`; the
    /// number of tile (draw) slices. Both passes one after the other, each
    /// a slice on the passes track enclosing: the wait for the host; the
    /// front end (setup and bin writes, beside the tiles when the
    /// architecture overlaps them); each tile, named by its position (each
    /// draw, by its order), with its stages on their own tracks and its
    /// triangles, fragments, pixels, bytes and bound (memory told as
    /// bandwidth or one of its queues, each queue's cycles, each cache's
    /// misses, its DRAM bytes by purpose) in its arguments, each stage
    /// slice its cycles (memory's its bytes, by purpose, and misses too); the DRAM shared by the front end and the
    /// tiles, when it outlasts them; and the units after the tiles.
    /// Counters: the DRAM's bandwidth, and each cache's misses in flight on
    /// average over a slice (Little's law). Times in microseconds at the
    /// clock.
    pub(crate) fn timeline(&self, pid: usize, events: &mut Vec<Value>) -> usize {
        let a = &self.arch;
        let us = |cycles: f64| cycles / a.clock * 1e6;
        events.push(json!({ "name": "process_name", "ph": "M", "pid": pid, "args": { "name": format!("{} on {}", self.scene, a.name) } }));
        for (tid, name) in TRACKS.iter().enumerate() {
            events.push(json!({ "name": "thread_name", "ph": "M", "pid": pid, "tid": tid, "args": { "name": name } }));
            events.push(json!({ "name": "thread_sort_index", "ph": "M", "pid": pid, "tid": tid, "args": { "sort_index": tid } }));
        }
        // One slice of `w` named `label` on track `tid` at `t`, its stages
        // on their tracks and the DRAM rate over it when `staged`; its
        // cycles (none for no work).
        let slice = |events: &mut Vec<Value>, cat: &str, label: String, w: &Work, t: f64, tid: usize, staged: bool| {
            let cycles = w.stages(a);
            let Some((bound, dur)) = w.bottleneck(a) else { return 0.0 };
            let memory = w.memory(a);
            let [dram_queue, map_queue, depth_queue] = memory.queue_cycles;
            // The bytes each purpose moved (those a purpose counts).
            let purposes: serde_json::Map<String, Value> =
                w.dram.fields().filter(|&(_, b)| b > 0).map(|(p, b)| (p.name().to_owned(), json!(b))).collect();
            let args = json!({
                "triangles": w.triangles, "fragments": w.fragments, "pixels": w.pixels, "bytes": w.bytes(),
                "bytes by purpose": purposes, "cycles": dur, "bound by": bound.name(), "setup cycles": cycles[Stage::Setup as usize],
                "memory cycles at the bandwidth": memory.bandwidth_cycles,
                "memory cycles at the latency": memory.latency_cycles,
                "DRAM requests' cycles in flight": dram_queue,
                "map cache misses": w.map_misses, "map cache misses' cycles in flight": map_queue,
                "depth cache misses": w.depth_misses, "depth cache misses' cycles in flight": depth_queue,
            });
            events.push(json!({ "name": label, "cat": cat, "ph": "X", "ts": us(t), "dur": us(dur), "pid": pid, "tid": tid, "args": args }));
            if staged {
                for (k, stage) in Stage::ALL[1..].iter().enumerate() {
                    let c = cycles[*stage as usize];
                    if c > 0.0 {
                        let args = if *stage == Stage::Memory {
                            json!({ "cycles": c, "bytes": w.bytes(), "bytes by purpose": purposes, "map cache misses": w.map_misses, "depth cache misses": w.depth_misses })
                        } else {
                            json!({ "cycles": c })
                        };
                        events.push(json!({
                            "name": format!("{cat} {}", stage.name()), "cat": cat, "ph": "X",
                            "ts": us(t), "dur": us(c), "pid": pid, "tid": k + TILES + 1, "args": args,
                        }));
                    }
                }
                #[allow(clippy::cast_precision_loss, reason = "bytes far below 2^53")]
                let rate = w.bytes() as f64 / (dur / a.clock) / 1e9;
                events
                    .push(json!({ "name": "DRAM GB/s", "ph": "C", "ts": us(t), "pid": pid, "args": { "GB/s": rate } }));
                // Each cache's misses outstanding on average over the slice
                // (Little's law: misses × latency / time), against the
                // misses it can keep in flight.
                #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
                let outstanding = |misses: u64| misses as f64 * a.latency_cycles() / dur;
                for (name, misses) in
                    [("map cache misses in flight", w.map_misses), ("depth cache misses in flight", w.depth_misses)]
                {
                    events.push(json!({ "name": name, "ph": "C", "ts": us(t), "pid": pid, "args": { "misses": outstanding(misses) } }));
                }
            }
            dur
        };
        // The host and driver's time of the frame, before its passes.
        if self.host_cycles > 0.0 {
            let args = json!({ "cycles": self.host_cycles });
            events.push(json!({ "name": "host and driver", "cat": "host", "ph": "X", "ts": 0.0, "dur": us(self.host_cycles), "pid": pid, "tid": 0, "args": args }));
        }
        let mut start = self.host_cycles;
        let mut tiles = 0;
        for p in &self.timeline {
            let (pass, timing) = (p.name.as_str(), &p.timing);
            let args = json!({
                "cycles": timing.cycles(), "bottleneck": timing.bottleneck().name(), "bytes": timing.bytes(),
                "achieved GB/s": timing.achieved_bytes_per_second() / 1e9,
            });
            let name = format!("{pass} pass");
            events.push(json!({ "name": name, "cat": pass, "ph": "X", "ts": us(start), "dur": us(timing.cycles()), "pid": pid, "tid": 0, "args": args }));
            if timing.overhead > 0.0 {
                let label = format!("{pass}: waiting for the host");
                events.push(json!({ "name": label, "cat": pass, "ph": "X", "ts": us(start), "dur": us(timing.overhead), "pid": pid, "tid": 1 }));
            }
            let body_start = start + timing.overhead;
            let front = slice(events, pass, format!("{pass} front end"), &p.front, body_start, 1, false);
            let mut t = body_start + if a.front.overlap { 0.0 } else { front };
            for (i, w) in p.tiles.iter().enumerate() {
                let label = match p.tiles_across {
                    Some(across) => format!("{pass} tile ({}, {})", i % across.max(1), i / across.max(1)),
                    None => format!("{pass} draw {i}"),
                };
                let dur = slice(events, pass, label, w, t, TILES, true);
                tiles += usize::from(dur > 0.0);
                t += dur;
            }
            // The units after the tiles end the pass.
            let tail: Vec<(String, f64)> = p
                .tail
                .iter()
                .map(|(name, w)| (format!("{pass}: {name}"), w.bottleneck(a).map_or(0.0, |b| b.1)))
                .collect();
            let body_end = start + timing.cycles() - tail.iter().map(|u| u.1).sum::<f64>();
            if body_end > t * (1.0 + 1e-12) && body_end > body_start + front {
                let label = format!("{pass}: DRAM shared by the front end and the tiles");
                events.push(json!({ "name": label, "cat": pass, "ph": "X", "ts": us(t), "dur": us(body_end - t), "pid": pid, "tid": TILES }));
            }
            t = body_end;
            for ((label, _), (_, w)) in tail.into_iter().zip(&p.tail) {
                t += slice(events, pass, label, w, t, TILES, true);
            }
            start += timing.cycles();
        }
        events.push(json!({ "name": "DRAM GB/s", "ph": "C", "ts": us(start), "pid": pid, "args": { "GB/s": 0.0 } }));
        for name in ["map cache misses in flight", "depth cache misses in flight"] {
            events.push(json!({ "name": name, "ph": "C", "ts": us(start), "pid": pid, "args": { "misses": 0.0 } }));
        }
        tiles
    }
}
