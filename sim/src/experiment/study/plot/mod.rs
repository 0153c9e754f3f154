//! The study's plots, as SVG and PNG (drawn through the shared
//! [`crate::experiment::plot`]): error against cost with the Pareto front
//! (`pareto`), cost against architecture axes (`arch_axes`), and error
//! against a swept parameter (`lines`); the algorithm families' markers,
//! and a legend that lists only what is drawn and wraps what is long.

mod axes;
mod lines;
mod pareto;

pub(crate) use axes::arch_axes;
pub(crate) use lines::{Series, lines};
pub(crate) use pareto::pareto;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::Manifest;
use crate::experiment::plot::SIZE;
use crate::pass::algorithm::Family;

/// The indices of the Pareto-optimal points (no other point is at most as
/// costly and strictly more accurate, or cheaper and as accurate), by
/// increasing cost.
#[must_use]
pub(crate) fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)));
    let mut best = f64::INFINITY;
    let mut front = Vec::new();
    for i in order {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

/// Errors of zero are drawn at this floor on the log axis (percent).
pub(crate) const ERROR_FLOOR: f64 = 1e-3;

/// The algorithm families in the order their markers are listed.
const FAMILIES: [Family; 5] = Family::ALL;

/// Draw the hollow marker of family `f` (an index into [`FAMILIES`]),
/// `size` pixels, at pixel `at` of `area` (a chart's points are mapped to
/// pixels first, so the chart and the legend draw the same shapes).
fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    at: (i32, i32),
    f: usize,
    size: i32,
    style: ShapeStyle,
) -> Result<(), String> {
    let e = EmptyElement::at(at);
    match f {
        0 => area.draw(&(e + Circle::new((0, 0), size, style))),
        1 => area.draw(
            &(e + PathElement::new(vec![(0, -size - 1), (size + 1, size), (-size - 1, size), (0, -size - 1)], style)),
        ),
        2 => area.draw(&(e + Rectangle::new([(-size, -size), (size, size)], style))),
        3 => area.draw(&(e + Cross::new((0, 0), size, style))),
        _ => area.draw(
            &(e + PathElement::new(
                vec![(0, -size - 1), (size + 1, 0), (0, size + 1), (-size - 1, 0), (0, -size - 1)],
                style,
            )),
        ),
    }
    .map_err(|e| e.to_string())
}

/// Draws a legend entry's swatch centred at a point of the legend's area.
type Swatch<'a, DB> = dyn Fn(&DrawingArea<DB, Shift>, (i32, i32)) -> Result<(), String> + 'a;

/// Characters a legend line holds before it wraps.
const LEGEND_CHARS: usize = 24;

/// `label` in lines of at most [`LEGEND_CHARS`], broken after a `:`, `,`,
/// `=` or space where it can be.
fn wrap(label: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut rest = label;
    while rest.chars().count() > LEGEND_CHARS {
        let head: String = rest.chars().take(LEGEND_CHARS).collect();
        let cut = head.rfind([':', ',', '=', ' ']).filter(|&k| k > 0).map_or(head.len(), |k| k + 1);
        lines.push(rest[..cut].trim_end().to_owned());
        rest = rest[cut..].trim_start();
    }
    lines.push(rest.to_owned());
    lines
}

/// A legend drawn down an area: each entry a swatch and its label,
/// wrapped; the spacing shrinks to fit every entry above the footnote.
struct Legend<'a, DB: DrawingBackend> {
    area: &'a DrawingArea<DB, Shift>,
    y: i32,
    step: i32,
}

impl<'a, DB: DrawingBackend> Legend<'a, DB> {
    /// A legend for `labels` (every entry's, in order).
    fn new(area: &'a DrawingArea<DB, Shift>, labels: &[String]) -> Self {
        let lines: usize = labels.iter().map(|l| wrap(l).len()).sum();
        #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a plot's size")]
        let room = SIZE.1 as i32 - 40 - 60;
        #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few entries")]
        let step = (room / (lines.max(1) as i32)).clamp(11, 20);
        Self { area, y: 30, step }
    }

    /// One entry.
    fn entry(&mut self, label: &str, swatch: &Swatch<'_, DB>) -> Result<(), String> {
        swatch(self.area, (14, self.y + self.step / 2))?;
        let size = (self.step - 6).clamp(10, 14);
        for line in wrap(label) {
            self.area.draw(&Text::new(line, (30, self.y), ("sans-serif", size))).map_err(|e| e.to_string())?;
            self.y += self.step;
        }
        Ok(())
    }
}

/// A plot's two lines of provenance: the version; the sweep and its hash.
fn provenance(m: &Manifest) -> [String; 2] {
    [m.umbra_version.clone(), format!("sweep {} {}", m.sweep, m.sweep_hash)]
}
