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

/// The smallest error a log axis spans (percent); zero has a row of its
/// own below the values ([`zero_row`](crate::experiment::plot::zero_row)).
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
/// `=` or space where it can be, else after a `.`, `_` or `-`.
fn wrap(label: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut rest = label;
    while rest.chars().count() > LEGEND_CHARS {
        let head: String = rest.chars().take(LEGEND_CHARS).collect();
        let cut = head
            .rfind([':', ',', '=', ' '])
            .or_else(|| head.rfind(['.', '_', '-']))
            .filter(|&k| k > 0)
            .map_or(head.len(), |k| k + 1);
        lines.push(rest[..cut].trim_end().to_owned());
        rest = rest[cut..].trim_start();
    }
    lines.push(rest.to_owned());
    lines
}

/// The legend's first line, pixels from the top of its area.
const LEGEND_TOP: i32 = 30;
/// The legend's last line ends this far above the image's bottom, where
/// the footnote begins.
const LEGEND_FOOT: i32 = 70;
/// The closest the legend's lines are set, pixels.
const LEGEND_STEP: i32 = 12;

/// `area` split into the chart and, at its right, a legend for `labels`
/// of one column `width` pixels wide, or as many columns as its lines need
/// to stay above the footnote.
fn with_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    labels: &[String],
    width: u32,
) -> (DrawingArea<DB, Shift>, DrawingArea<DB, Shift>) {
    let columns = u32::try_from(Legend::<DB>::columns(labels)).unwrap_or(u32::MAX);
    area.split_horizontally(SIZE.0.saturating_sub(width.saturating_mul(columns)).max(SIZE.0 / 3))
}

/// A legend drawn down an area, in columns when one is not enough: each
/// entry a swatch and its label, wrapped; the spacing shrinks to fit,
/// and an entry that would leave the area (into the footnote, or past its
/// right edge) is an error, never drawn over something else.
struct Legend<'a, DB: DrawingBackend> {
    area: &'a DrawingArea<DB, Shift>,
    x: i32,
    y: i32,
    step: i32,
    column: i32,
}

impl<'a, DB: DrawingBackend> Legend<'a, DB> {
    /// The lines `labels` take, wrapped.
    fn lines(labels: &[String]) -> usize {
        labels.iter().map(|l| wrap(l).len()).sum()
    }

    /// The room a column has, pixels.
    fn room() -> i32 {
        i32::try_from(SIZE.1).unwrap_or(i32::MAX) - LEGEND_TOP - LEGEND_FOOT
    }

    /// The columns `labels` need at the closest spacing, each entry
    /// whole in one column.
    fn columns(labels: &[String]) -> usize {
        let per_column = usize::try_from(Self::room() / LEGEND_STEP).unwrap_or(1).max(1);
        let (mut columns, mut used) = (1, 0);
        for l in labels {
            let n = wrap(l).len();
            if used + n > per_column && used > 0 {
                (columns, used) = (columns + 1, 0);
            }
            used += n;
        }
        columns
    }

    /// A legend for `labels` (every entry's, in order) on `area`, which
    /// [`with_legend`] made wide enough for its columns.
    fn new(area: &'a DrawingArea<DB, Shift>, labels: &[String]) -> Self {
        let columns = Self::columns(labels);
        // One column spreads its lines up to 20 pixels apart; several are
        // packed at the closest spacing, as `columns` counted them.
        let lines = i32::try_from(Self::lines(labels).max(1)).unwrap_or(i32::MAX);
        let step = if columns > 1 { LEGEND_STEP } else { (Self::room() / lines).clamp(LEGEND_STEP, 20) };
        let columns = i32::try_from(columns).unwrap_or(1);
        let width = i32::try_from(area.dim_in_pixel().0).unwrap_or(i32::MAX);
        Self { area, x: 0, y: LEGEND_TOP, step, column: width / columns }
    }

    /// One entry.
    ///
    /// # Errors
    /// Drawing failed, or the entry would leave the legend's area.
    fn entry(&mut self, label: &str, swatch: &Swatch<'_, DB>) -> Result<(), String> {
        let lines = wrap(label);
        let height = self.step * i32::try_from(lines.len()).unwrap_or(i32::MAX);
        if self.y + height > LEGEND_TOP + Self::room() {
            self.x += self.column;
            self.y = LEGEND_TOP;
        }
        let width = i32::try_from(self.area.dim_in_pixel().0).unwrap_or(i32::MAX);
        if self.x + self.column > width || self.y + height > LEGEND_TOP + Self::room() {
            return Err(format!("the legend has no room for `{label}`"));
        }
        swatch(self.area, (self.x + 14, self.y + self.step / 2))?;
        let size = (self.step - 6).clamp(10, 14);
        for line in lines {
            self.area.draw(&Text::new(line, (self.x + 30, self.y), ("sans-serif", size))).map_err(|e| e.to_string())?;
            self.y += self.step;
        }
        Ok(())
    }
}

/// A plot's two lines of provenance: the version; the sweep and its hash.
fn provenance(m: &Manifest) -> [String; 2] {
    [m.umbra_version.clone(), format!("sweep {} {}", m.sweep, m.sweep_hash)]
}
