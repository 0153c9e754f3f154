//! The frame's timeline in Chrome trace-event JSON.

use super::CostReport;
use crate::cost::arch::Stage;
use crate::cost::arch::timing::Work;

impl CostReport {
    /// The frame's timeline in Chrome trace-event JSON (opens in Perfetto):
    /// both passes one after the other; a front-end track (setup and bin
    /// writes, beside the tiles when the architecture overlaps them); a
    /// track with each tile's whole time, and one per stage with that
    /// tile's cycles in it; slices carry the tile's triangles, fragments,
    /// pixels and bytes, what bound it (memory told as bandwidth or
    /// latency) and its memory time by each limit; a DRAM-bandwidth counter
    /// track, with the peak and the latency ceiling in the metadata. Times
    /// in microseconds at the architecture's clock.
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
            let memory = w.memory(a);
            let args = serde_json::json!({
                "triangles": w.triangles, "fragments": w.fragments, "pixels": w.pixels, "bytes": w.bytes,
                "cycles": dur, "setup cycles": cycles[Stage::Setup as usize],
                "bound by": w.bottleneck(a).map_or("", |b| b.0.name()),
                "memory cycles at the bandwidth": memory.bandwidth_cycles,
                "memory cycles at the latency": memory.latency_cycles,
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
            "dram_peak_gb_per_second": self.dram_peak_bytes_per_second / 1e9,
            "dram_latency_ceiling_gb_per_second": self.dram_latency_ceiling_bytes_per_second / 1e9,
        });
        serde_json::json!({ "traceEvents": events, "displayTimeUnit": "ns", "metadata": metadata })
    }
}
