//! The cost report as a person reads it: the frame's line, each pass's
//! stages and bound, the DRAM, the caches, energy, the bytes' ledger and
//! Sen et al.'s figures, in Markdown.

use std::fmt::Write as _;

use super::CostReport;
use crate::cost::arch::derived::latency_ceiling;
use crate::cost::silicon::{Kind, Silicon};
use crate::cost::work::Bottleneck;
use crate::output::table::{Align, Table};

impl CostReport {
    /// The report as Markdown.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let a = &self.arch;
        let gb = |bytes_per_second: f64| format!("{:.1} GB/s", bytes_per_second / 1e9);
        let _ = writeln!(s, "### {} — {}\n", a.name, a.description);
        let _ = writeln!(
            s,
            "Frame: {:.0} cycles{}, {:.3} ms at {} MHz ({:.1} frames/s), {} DRAM bytes, {:.3} mJ; bound by {}.\n",
            self.cycles(),
            if self.host_cycles > 0.0 {
                format!(" ({:.0} in the host and driver)", self.host_cycles)
            } else {
                String::new()
            },
            self.seconds() * 1e3,
            a.clock / 1e6,
            self.fps(),
            self.bytes(),
            self.energy().total() * 1e3,
            self.bottleneck().words()
        );
        let unit = if a.immediate() { "draws" } else { "tiles" };
        let bounds = Bottleneck::ALL.map(Bottleneck::name).join("/");
        let mut columns: Vec<(String, Align)> = [
            "pass",
            "setup",
            "raster",
            "depth",
            "shadow",
            "shade",
            "memory",
            "memory at bandwidth / latency",
            "pass cycles",
            "bottleneck",
            "DRAM achieved",
        ]
        .iter()
        .map(|h| ((*h).to_owned(), if matches!(*h, "pass" | "bottleneck") { Align::Left } else { Align::Right }))
        .collect();
        columns.push((format!("{unit} bound ({bounds})"), Align::Left));
        let mut table = Table::new(&columns);
        // Each light's pass when there are several, then their sum.
        // Each named as the timeline names it (`light lights[1]`, `light lights[0].cascades[2]`).
        let each = self.light_passes.iter().zip(&self.timeline).map(|(t, line)| (line.name.clone(), t));
        let light = if self.light_passes.is_empty() { "light" } else { "light, every pass" };
        let rows = each.chain([(light.to_owned(), &self.light), ("camera".to_owned(), &self.camera)]);
        for (name, t) in rows {
            let mut cells = vec![name];
            cells.extend(t.stages.iter().map(|c| format!("{c:.0}")));
            cells.extend([
                format!("{:.0} / {:.0}", t.memory.bandwidth_cycles, t.memory.latency_cycles),
                format!("{:.0}", t.cycles()),
                t.bottleneck().to_string(),
                gb(t.achieved_bytes_per_second()),
                t.bound.map(|n| n.to_string()).join("/"),
            ]);
            table.row(cells);
        }
        s.push_str(&table.markdown());
        let _ = writeln!(
            s,
            "\nDRAM: achieved {} over the frame, against a peak of {} and a latency ceiling of {} ({} requests in flight × {} B / {:.1} ns).",
            gb(self.achieved_bytes_per_second()),
            gb(self.dram_peak_bytes_per_second),
            gb(self.dram_latency_ceiling_bytes_per_second),
            a.dram.requests_in_flight,
            a.dram.burst,
            a.dram.latency * 1e9
        );
        for (pass, name, c) in self.caches() {
            let p = if name == "Map cache" { &a.map_cache } else { &a.depth_cache };
            let _ = writeln!(
                s,
                "{name} ({pass} pass): {} accesses, {} hits, {} misses ({:.2} % hits), {} bytes fetched, {} bytes written back; its misses in flight cap its fetches at {} ({} × {} B / {:.1} ns).",
                c.accesses,
                c.hits,
                c.misses,
                100.0 * c.hit_rate,
                c.fetched_bytes,
                c.written_back_bytes,
                gb(latency_ceiling(p.misses_in_flight, p.line, a.dram.latency)),
                p.misses_in_flight,
                p.line,
                a.dram.latency * 1e9
            );
        }
        let e = &self.energy();
        let _ = writeln!(
            s,
            "Energy (µJ), {:.3} in all: dynamic {:.3} (DRAM {:.1}, on-chip buffers {:.1}, caches {:.1}, raster and depth {:.1}, shadow unit {:.1}); static {:.4} (the units' {:.3} mW of leakage over {:.3} ms).",
            e.total() * 1e6,
            e.dynamic() * 1e6,
            e.dram * 1e6,
            e.buffers * 1e6,
            e.caches * 1e6,
            e.raster * 1e6,
            e.shadow * 1e6,
            e.leakage * 1e6,
            self.silicon.leakage_watts() * 1e3,
            self.seconds() * 1e3
        );
        let _ = writeln!(
            s,
            "DRAM bytes, {} in all: light pass {} ({}); camera pass {} ({}). On-chip depth {} bytes.",
            self.bytes(),
            self.light.bytes(),
            self.light.dram.words(),
            self.camera.bytes(),
            self.camera.dram.words(),
            self.on_chip_bytes
        );
        if self.requested.map + self.requested.silhouette > 0 {
            let _ = writeln!(
                s,
                "The shadow unit requested {} map bytes and {} silhouette bytes{}.",
                self.requested.map,
                self.requested.silhouette,
                if a.map_cache.size > 0 { ", through the map cache" } else { ", each from DRAM" }
            );
        }
        let _ = writeln!(
            s,
            "Max-z culled: {:.1} % (light), {:.1} % (camera visibility); {:.2} lookups culled per covered pixel; virtual samples for {:.2} % of lookups.",
            100.0 * self.max_z_cull_rate[0],
            100.0 * self.max_z_cull_rate[1],
            self.lookups_culled_per_pixel,
            100.0 * self.virtual_sample_fraction
        );
        // Sen et al.'s figures, each where the render has what it counts:
        // P for a silhouette map, O for shadow volumes, map bytes for a map.
        let n = &self.sen;
        let silhouette = n.silhouette_fill > 0 || n.silhouette_bytes_per_pixel > 0.0;
        let volumes = n.volume_fill > 0;
        if silhouette {
            let _ = writeln!(
                s,
                "Sen et al.: P = {:.4} as silhouette fill over scene fill (their Table 1), {:.4} as the fraction of covered pixels reconstructed (their bandwidth model).",
                n.p_fill, n.p_lookup
            );
        }
        if volumes {
            let _ = writeln!(s, "Sen et al.: O = {:.2} (shadow-volume fragments over scene fill).", n.overdraw);
        }
        if silhouette || volumes {
            let _ = writeln!(
                s,
                "Their Table 1's columns: {} triangles, {} silhouette edges, scene fill {}, volume fill {}, silhouette fill {} (CROWD: 14 836, 4 800, 148.9 k, 22.96 M, 19.8 k).",
                n.triangles, n.silhouette_edges, n.scene_fill, n.volume_fill, n.silhouette_fill
            );
        }
        if volumes {
            let _ = writeln!(
                s,
                "Per scene-fill fragment: volumes {:.2} B simulated vs 5.5·O = {:.2} B.",
                n.volume_bytes_per_fill, n.model_volume_bytes_per_fill
            );
        } else {
            let points = if silhouette {
                format!(
                    "; silhouette points {:.2} B simulated vs 24·P = {:.2} B",
                    n.silhouette_bytes_per_pixel, n.model_silhouette_bytes_per_pixel
                )
            } else {
                String::new()
            };
            let _ = writeln!(
                s,
                "Per covered pixel (Sen et al.'s bandwidth model): map {:.2} B simulated vs 4 B × samples = {:.1} B{points}.",
                n.map_bytes_per_pixel, n.model_map_bytes_per_pixel
            );
        }
        s.push_str(&self.silicon.markdown());
        s
    }
}

impl Silicon {
    /// The units' areas as Markdown: a line with the total and the
    /// leakage, then a table of every unit; for an architecture with no
    /// technology, a line saying so.
    #[must_use]
    pub fn markdown(&self) -> String {
        if self.node.is_empty() {
            return "\nSilicon: the architecture states no technology (its `[technology]` table, format 3), so no area or leakage is modelled; `umbra arch upgrade` writes the table to fill in.\n".to_owned();
        }
        let mut s = format!(
            "\nSilicon at {}: {:.4} mm² for the units this render uses, leaking {:.3} mW.\n\n",
            self.node,
            self.square_metres() * 1e6,
            self.leakage_watts() * 1e3
        );
        let mut t = Table::new(&[
            ("unit", Align::Left),
            ("kind", Align::Left),
            ("size", Align::Right),
            ("counted as", Align::Left),
            ("mm²", Align::Right),
        ]);
        for u in &self.units {
            let (kind, size) = match u.kind {
                Kind::Storage => ("SRAM", format!("{:.0} bits", u.size)),
                Kind::Logic => ("logic", format!("{:.0} NAND2", u.size)),
            };
            t.row([u.unit.to_owned(), kind.to_owned(), size, u.how.clone(), format!("{:.6}", u.square_metres * 1e6)]);
        }
        s.push_str(&t.markdown());
        s
    }
}
