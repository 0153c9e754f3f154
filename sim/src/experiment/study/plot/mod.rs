//! The study's plots, as SVG and PNG (drawn through the shared
//! [`crate::experiment::plot`]): error against cost with the Pareto front
//! (`pareto`), cost against architecture axes (`arch_axes`, its scales in
//! `scale`), and error against a swept parameter (`lines`); the algorithm
//! families' markers, and a legend that lists only what is drawn
//! (`legend`).

mod axes;
mod legend;
mod lines;
mod pareto;
mod scale;

pub(crate) use axes::arch_axes;
pub(crate) use lines::{Series, lines};
pub(crate) use pareto::pareto;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::Manifest;
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

/// A plot's two lines of provenance: the version; the sweep and its hash.
fn provenance(m: &Manifest) -> [String; 2] {
    [m.umbra_version.clone(), format!("sweep {} {}", m.sweep, m.sweep_hash)]
}
