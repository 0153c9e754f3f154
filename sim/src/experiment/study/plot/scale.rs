//! The architecture-axes plot's scales: where the swept values lie along
//! the x axis (evenly, linearly or logarithmically, `Spacing`), how wide
//! a range leaves room for the end labels, which ticks are labelled when
//! they crowd, and the frame-time axis (logarithmic when the times span
//! more than ten times), each ticked only where it is told (`Ticked`).

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

use crate::experiment::plot::{log_range, log_ticks};

/// One swept value of the x axis: its number (none for a flag or text)
/// and its text as the sweep file writes it.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Swept {
    pub number: Option<f64>,
    pub text: String,
}

/// How the swept values lie along the x axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Spacing {
    /// One step apart, in the sweep's order: text, flags, or numbers not
    /// all positive.
    Even,
    /// At their values: numbers within ten times of each other.
    Linear,
    /// At their logarithms: positive numbers spanning more than ten times.
    Log,
}

/// How `swept` (in order) lie along the axis.
pub(super) fn spacing(swept: &[Swept]) -> Spacing {
    let numbers: Option<Vec<f64>> = swept.iter().map(|s| s.number).collect();
    let Some(v) = numbers.filter(|v| v.len() >= 2) else { return Spacing::Even };
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    match (lo > 0.0, hi / lo > 10.0) {
        (true, true) => Spacing::Log,
        (true, false) => Spacing::Linear,
        _ => Spacing::Even,
    }
}

/// Where each of `swept` lies along the axis, from 0 (the first) to 1
/// (the last); a lone value at ½.
pub(super) fn positions(swept: &[Swept], spacing: Spacing) -> Vec<f64> {
    let n = swept.len();
    let number = |k: usize| swept[k].number.unwrap_or(0.0);
    let (lo, hi) = (number(0), number(n.saturating_sub(1)));
    #[allow(clippy::cast_precision_loss, reason = "a few values")]
    (0..n)
        .map(|k| match spacing {
            _ if n < 2 => 0.5,
            Spacing::Even => k as f64 / (n - 1) as f64,
            Spacing::Linear => (number(k) - lo) / (hi - lo),
            Spacing::Log => (number(k) / lo).ln() / (hi / lo).ln(),
        })
        .collect()
}

/// The x range over positions from 0 to 1 that leaves each end at least
/// `least` of the span, and room for half a label, `half` pixels, beyond
/// the first and last ticks of a plot `width` pixels wide.
pub(super) fn x_range(width: i32, half: i32, least: f64) -> Range<f64> {
    let h = f64::from(half + 4);
    let pad = (h / (f64::from(width) - 2.0 * h).max(1.0)).max(least);
    -pad..1.0 + pad
}

/// The ticks to label, of ticks at pixels `at` (ascending) whose labels
/// are `widths` wide: the first, then each whose label clears the last
/// labelled one's by 8 pixels.
pub(super) fn labelled(at: &[i32], widths: &[i32]) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    for k in 0..at.len() {
        let clear = out.last().is_none_or(|&j| at[k] - at[j] >= (widths[j] + widths[k]) / 2 + 8);
        if clear {
            out.push(k);
        }
    }
    out
}

/// A linear axis over `range` ticked where it is told: labelled ticks at
/// `bold`, light mesh lines at `light`.
#[derive(Clone)]
pub(super) struct Ticked {
    pub range: Range<f64>,
    pub bold: Vec<f64>,
    pub light: Vec<f64>,
}

impl Ranged for Ticked {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, (from, to): (i32, i32)) -> i32 {
        let along = (v - self.range.start) / (self.range.end - self.range.start);
        #[allow(clippy::cast_possible_truncation, reason = "pixels")]
        let px = (f64::from(to - from) * along + 1e-3).floor() as i32;
        from + px
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() { self.light.clone() } else { self.bold.clone() }
    }

    fn range(&self) -> Range<f64> {
        self.range.clone()
    }
}

/// The frame-time axis: logarithmic when the times span more than ten
/// times, in its own coordinate then (log₁₀ µs).
pub(super) struct TimeAxis {
    pub log: bool,
    pub axis: Ticked,
}

impl TimeAxis {
    /// The axis over `times`, µs.
    pub(super) fn over(times: &[f64]) -> Self {
        let (lo, hi) = times.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| (lo.min(t), hi.max(t)));
        if lo > 0.0 && hi / lo > 10.0 {
            let r = log_range(times.iter().copied(), lo);
            let (bold, light) = log_ticks(&r);
            let log10 = |v: Vec<f64>| v.into_iter().map(f64::log10).collect();
            let range = r.start.log10()..r.end.log10();
            return Self { log: true, axis: Ticked { range, bold: log10(bold), light: log10(light) } };
        }
        let range = if lo.is_finite() {
            let pad = if hi > lo { (hi - lo) * 0.08 } else { lo.abs().max(1.0) * 0.1 };
            (lo - pad)..(hi + pad)
        } else {
            0.0..1.0
        };
        // Six or so ticks at 1, 2 or 5 of a decade.
        let raw = (range.end - range.start) / 6.0;
        let decade = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * decade).find(|s| *s >= raw).unwrap_or(raw);
        let first = (range.start / step).ceil();
        let bold: Vec<f64> = (0..).map(|k| (first + f64::from(k)) * step).take_while(|v| *v <= range.end).collect();
        Self { log: false, axis: Ticked { light: bold.clone(), range, bold } }
    }

    /// A time, µs, in the axis's coordinate.
    pub(super) fn at(&self, t: f64) -> f64 {
        if self.log { t.log10() } else { t }
    }
}

#[cfg(test)]
mod tests {
    use super::{Spacing, Swept, labelled, positions, spacing};

    fn swept(numbers: &[f64]) -> Vec<Swept> {
        numbers.iter().map(|&n| Swept { number: Some(n), text: n.to_string() }).collect()
    }

    /// Values from zero, or text, are evenly spaced; numbers within ten
    /// times of each other linear; positive ones spanning more, log.
    #[test]
    fn the_x_axis_spaces_its_values_by_their_span() {
        assert_eq!(spacing(&swept(&[0.0, 16384.0, 65536.0])), Spacing::Even);
        assert_eq!(spacing(&swept(&[1e9, 2e9, 4e9])), Spacing::Linear);
        assert_eq!(spacing(&swept(&[1e3, 1e4, 1e5])), Spacing::Log);
        let text = [Swept { number: None, text: "a".into() }, Swept { number: None, text: "b".into() }];
        assert_eq!(spacing(&text), Spacing::Even);
        assert_eq!(positions(&swept(&[0.0, 16384.0, 65536.0]), Spacing::Even), [0.0, 0.5, 1.0]);
        let log = positions(&swept(&[1e3, 1e4, 1e5]), Spacing::Log);
        assert!((log[1] - 0.5).abs() < 1e-12, "{log:?}");
    }

    /// Labels too close for their widths are left out, from the second on.
    #[test]
    fn crowded_ticks_label_every_other() {
        assert_eq!(labelled(&[0, 100, 200], &[40, 40, 40]), [0, 1, 2]);
        assert_eq!(labelled(&[0, 30, 60, 90], &[40, 40, 40, 40]), [0, 2]);
    }
}
