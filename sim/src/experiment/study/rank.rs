//! How rows are ranked: the costs the summary ranks by (time, or cycles
//! where every architecture shares one clock; DRAM bytes; energy), and the
//! cheapest complete row within an error budget.

use super::{Row, RowCost, distinct};
use crate::experiment::study::budget::Budget;

/// A cost the summary ranks by: its name with its unit, its value, and
/// the value as the table writes it.
#[derive(Clone, Copy)]
pub(super) struct Key {
    /// The name, with the unit the table writes.
    pub name: &'static str,
    /// The value of a row's cost.
    pub value: fn(&RowCost) -> f64,
    /// The value as written.
    pub show: fn(f64) -> String,
}

/// The frame's time in seconds (written in microseconds): the cost common
/// to architectures of different clocks.
pub(super) const TIME: Key =
    Key { name: "time (µs)", value: |c| c.frame_seconds, show: |v| format!("{:.3}", v * 1e6) };

/// The frame's cycles: ranks as time does where every architecture
/// shares one clock.
#[allow(clippy::cast_precision_loss, reason = "cycle counts far below 2^53")]
pub(super) const CYCLES: Key = Key { name: "cycles", value: |c| c.total_cycles as f64, show: |v| format!("{v:.0}") };

/// The costs the summary ranks by: time (cycles when every row's
/// architecture runs at one clock), DRAM bytes, energy.
pub(super) fn keys(rows: &[&Row]) -> [Key; 3] {
    #[allow(clippy::cast_precision_loss, reason = "byte counts far below 2^53")]
    let bytes = Key { name: "DRAM bytes", value: |c| c.total_dram_bytes as f64, show: |v| format!("{v:.0}") };
    let energy = Key { name: "energy (µJ)", value: |c| c.energy_joules, show: |v| format!("{:.3}", v * 1e6) };
    [if one_clock(rows).is_some() { CYCLES } else { TIME }, bytes, energy]
}

/// The objectives the summary names a best for: time (cycles on one
/// clock), energy, silicon area, energy × time and energy × time × area
/// ([`crate::experiment::plan::Objective::NAMED`], ranked on rows).
pub(super) fn objectives(rows: &[&Row]) -> [Key; 5] {
    let energy = Key { name: "energy (µJ)", value: |c| c.energy_joules, show: |v| format!("{:.3}", v * 1e6) };
    let area = Key { name: "area (mm²)", value: |c| c.area_square_metres, show: |v| format!("{:.4}", v * 1e6) };
    let edp =
        Key {
            name: "energy × time (J·s)", value: |c| c.energy_joules * c.frame_seconds, show: |v| format!("{v:.4e}")
        };
    let edap = Key {
        name: "energy × time × area (J·s·mm²)",
        value: |c| c.energy_joules * c.frame_seconds * c.area_square_metres,
        show: |v| format!("{:.4e}", v * 1e6),
    };
    [if one_clock(rows).is_some() { CYCLES } else { TIME }, energy, area, edp, edap]
}

/// The clock every costed row's architecture runs at, if they share one.
pub(super) fn one_clock(rows: &[&Row]) -> Option<f64> {
    let clocks = distinct(rows.iter().filter_map(|r| r.cost.as_ref()).map(|c| c.clock_hertz.to_bits()));
    match clocks[..] {
        [one] => Some(f64::from_bits(one)),
        _ => None,
    }
}

/// The complete rows within `budget`, the cheapest by `key`, and how many
/// tie with it (ties are broken by sweep order: the first configuration,
/// then the first architecture).
pub(super) fn cheapest<'a>(rows: &[&'a Row], budget: &Budget, key: Key) -> Option<(&'a Row, usize)> {
    let ok: Vec<(&Row, f64)> = rows
        .iter()
        .copied()
        .filter(|r| r.complete() && r.metrics.is_some_and(|m| budget.met_by(&m)))
        .filter_map(|r| Some((r, (key.value)(r.cost.as_ref()?))))
        .collect();
    let best = ok.iter().map(|(_, k)| *k).min_by(f64::total_cmp)?;
    let ties: Vec<&Row> = ok.iter().filter(|(_, k)| k.total_cmp(&best).is_eq()).map(|(r, _)| *r).collect();
    ties.iter().min_by_key(|r| (r.config_index, r.arch_index)).map(|r| (*r, ties.len()))
}
