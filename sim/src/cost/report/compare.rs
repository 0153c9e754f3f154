//! Reports of one render on several architectures, compared: time (the
//! cost common to every clock), DRAM bytes, energy and what binds, each
//! against the first architecture.

use crate::output::table::{Align, Table};
use std::fmt::Write as _;

use super::CostReport;
use crate::cost::work::Bottleneck;
use serde::Serialize;

/// One architecture's line of a [`Comparison`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Compared {
    /// The architecture.
    pub arch: String,
    /// Its clock, hertz.
    pub clock_hertz: f64,
    /// The frame, cycles.
    pub cycles: f64,
    /// The frame, seconds.
    pub seconds: f64,
    /// The frame's DRAM bytes.
    pub dram_bytes: u64,
    /// The frame's energy, joules.
    pub energy_joules: f64,
    /// What bounds the frame.
    pub bottleneck: Bottleneck,
    /// Change of the time against the first architecture's, a fraction.
    pub seconds_change: f64,
    /// Change of the DRAM bytes, a fraction.
    pub dram_bytes_change: f64,
    /// Change of the energy, a fraction.
    pub energy_change: f64,
    /// Its place, fastest first (1-based; ties share the first place).
    pub rank: usize,
}

/// Several architectures' reports compared against the first.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// Every architecture share one clock (so cycles rank as time does).
    pub one_clock: bool,
    /// In the reports' order.
    pub archs: Vec<Compared>,
}

/// A ratio as a reader compares it: three significant digits and `×`
/// (`0.00142×`, `0.512×`, `1.24×`, `141×`).
fn times(r: f64) -> String {
    if !r.is_finite() || r <= 0.0 {
        return format!("{r}×");
    }
    let mut digits = [(100.0, 0), (10.0, 1), (1.0, 2)].into_iter().find(|&(at, _)| r >= at).map_or(2, |(_, d)| d);
    let mut v = r;
    while v < 1.0 && digits < 15 {
        (v, digits) = (v * 10.0, digits + 1);
    }
    format!("{r:.digits$}×")
}

/// `b` against `a`, a fraction (0 when `a` is 0).
fn change(a: f64, b: f64) -> f64 {
    if a == 0.0 { 0.0 } else { (b - a) / a }
}

impl Comparison {
    /// The reports compared; `None` for fewer than two.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "bytes far below 2^53")]
    pub fn new(reports: &[CostReport]) -> Option<Self> {
        let first = reports.first().filter(|_| reports.len() > 1)?;
        let archs = reports
            .iter()
            .map(|r| Compared {
                arch: r.arch.name.clone(),
                clock_hertz: r.arch.clock,
                cycles: r.cycles(),
                seconds: r.seconds(),
                dram_bytes: r.bytes(),
                energy_joules: r.energy().total(),
                bottleneck: r.bottleneck(),
                seconds_change: change(first.seconds(), r.seconds()),
                dram_bytes_change: change(first.bytes() as f64, r.bytes() as f64),
                energy_change: change(first.energy().total(), r.energy().total()),
                rank: 1 + reports.iter().filter(|o| o.seconds() < r.seconds()).count(),
            })
            .collect();
        let one_clock = reports.iter().all(|r| r.arch.clock.to_bits() == first.arch.clock.to_bits());
        Some(Self { one_clock, archs })
    }

    /// The comparison as a Markdown table ranked fastest first (ties in
    /// the reports' order), each change as a ratio beside its percentage,
    /// with a line saying what ranks.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let first = self.archs.first().map_or("", |a| a.arch.as_str());
        let rank = if self.one_clock {
            "every architecture runs at one clock, so cycles rank as time does"
        } else {
            "the clocks differ, so time ranks, not cycles"
        };
        let _ = writeln!(
            s,
            "### Compared against {first}\n\nRanked by frame time: {rank}. Changes are against {first}: the ratio, then the change in percent.\n"
        );
        let (l, r) = (Align::Left, Align::Right);
        let mut t = Table::new(&[
            ("rank", r),
            ("architecture", l),
            ("clock (MHz)", r),
            ("cycles", r),
            ("time (µs)", r),
            ("time change", r),
            ("DRAM bytes", r),
            ("bytes change", r),
            ("energy (µJ)", r),
            ("energy change", r),
            ("bottleneck", l),
        ]);
        let pct = |f: f64| format!("{} ({:+.1} %)", times(1.0 + f), 100.0 * f);
        let mut ranked: Vec<&Compared> = self.archs.iter().collect();
        ranked.sort_by_key(|a| a.rank);
        for a in ranked {
            t.row([
                a.rank.to_string(),
                a.arch.clone(),
                (a.clock_hertz / 1e6).to_string(),
                format!("{:.0}", a.cycles),
                format!("{:.3}", a.seconds * 1e6),
                pct(a.seconds_change),
                a.dram_bytes.to_string(),
                pct(a.dram_bytes_change),
                format!("{:.3}", a.energy_joules * 1e6),
                pct(a.energy_change),
                a.bottleneck.to_string(),
            ]);
        }
        s.push_str(&t.markdown());
        s
    }
}
