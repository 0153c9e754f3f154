//! Lines of a measure against a swept parameter on log axes, each series
//! told apart by colour, line style and marker, set a few pixels aside so
//! that series of equal values all show, and labelled at its end where
//! the label overlaps nothing (a leader line when it has to move).

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::legend::{Item, Legend};
use super::{ERROR_FLOOR, marker};
use crate::experiment::plot::place::{Placer, Rect, beside, draw_placed, label_size, text_size};
use crate::experiment::plot::{Figure, both, colour, dodge, dodge_step, log_log_chart, log_range, zero_row};
use crate::experiment::study::StudyError;
use crate::output::folder::OutputFolder;

/// One named series of `(x, y)` points.
pub(crate) type Series = (String, Vec<(f64, f64)>);

/// Lines on log axes.
struct Lines<'a> {
    title: &'a str,
    x_desc: &'a str,
    y_desc: &'a str,
    series: &'a [Series],
}

impl Lines<'_> {
    /// Whether series `k` is dashed: every other one, so that two series
    /// on one line still show both.
    const fn dashed(k: usize) -> bool {
        k % 2 == 1
    }

    /// Series `k`'s marker size: the dashed ones' larger.
    fn marker_size(k: usize) -> i32 {
        4 + 2 * i32::from(Self::dashed(k))
    }

    /// The legend: each series in full, its line and marker.
    fn legend<DB: DrawingBackend>(&self) -> Vec<Item<'_, DB>> {
        let n = self.series.len();
        let entry = |(k, (name, _)): (usize, &Series)| {
            let style = colour(k, n).stroke_width(2);
            Item::entry(name.clone(), move |l: &DrawingArea<DB, Shift>, (x, y): (i32, i32)| {
                let halves =
                    if Self::dashed(k) { [(x - 10, x - 3), (x + 3, x + 10)] } else { [(x - 10, x), (x, x + 10)] };
                for (a, b) in halves {
                    l.draw(&PathElement::new(vec![(a, y), (b, y)], style)).map_err(|e| e.to_string())?;
                }
                marker(l, (x, y), k % 5, 4, style)
            })
        };
        self.series.iter().enumerate().map(entry).collect()
    }
}

impl Figure for Lines<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        // The legend beside the chart, never over the data.
        let legend = Legend::new(area, self.legend(), &[])?;
        let (plot, legend_area) = legend.split(area);
        let n = self.series.len();
        // Each series' short name at its end, in a margin right of the
        // plot wide enough for the longest (the legend names them in full).
        let font = |k: usize| ("sans-serif", 11).into_font().color(&colour(k, n));
        let shorts: Vec<&str> = self.series.iter().map(|s| s.0.split(':').next().unwrap_or(&s.0)).collect();
        let mut right = 0;
        for (k, s) in shorts.iter().enumerate() {
            right = right.max(text_size(area, s, &font(k))?.0 + 30);
        }
        let xr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.0)), 1e-12);
        let ys = || self.series.iter().flat_map(|s| s.1.iter().map(|p| p.1));
        let zero = zero_row(ys(), ERROR_FLOOR);
        let any_zero = ys().any(|y| y <= 0.0);
        let yr = log_range(ys(), if any_zero { zero } else { ERROR_FLOOR });
        let descs = (self.x_desc, self.y_desc);
        let right = u32::try_from(right).unwrap_or(0);
        let chart = log_log_chart(&plot, self.title, (xr, yr), descs, any_zero.then_some(zero), right)?;
        // Each series a few pixels aside.
        let mut xs: Vec<i32> = self.series.iter().flat_map(|s| s.1.iter().map(|p| chart.backend_coord(p).0)).collect();
        xs.sort_unstable();
        xs.dedup();
        let step = dodge_step(xs.windows(2).map(|w| w[1] - w[0]).min().unwrap_or(100), n, 4.0);
        let pixels: Vec<Vec<(i32, i32)>> = self
            .series
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let at = |&(x, y): &(f64, f64)| chart.backend_coord(&(x, if y > 0.0 { y } else { zero }));
                s.1.iter().map(at).map(|(x, y)| (x + dodge(k, n, step), y)).collect()
            })
            .collect();
        // Every line first, then every marker over them.
        for (k, pts) in pixels.iter().enumerate() {
            let style = colour(k, n).stroke_width(2);
            if Self::dashed(k) {
                area.draw(&DashedPathElement::new(pts.clone(), 8, 5, style)).map_err(|e| e.to_string())?;
            } else {
                area.draw(&PathElement::new(pts.clone(), style)).map_err(|e| e.to_string())?;
            }
        }
        let (xp, yp) = chart.plotting_area().get_pixel_range();
        let margin = i32::try_from(right).unwrap_or(0) - 2;
        let mut placer = Placer::new(Rect::of_ranges((xp.start..xp.end + margin, yp.clone())));
        for (k, pts) in pixels.iter().enumerate() {
            for &p in pts {
                marker(area, p, k % 5, Self::marker_size(k), colour(k, n).stroke_width(2))?;
                placer.block(Rect::around(p, Self::marker_size(k) + 2));
            }
        }
        // Each short name in a column right of the last points, on its
        // series' row where that is free, else as near above or below it
        // as is, with a leader line.
        let ends: Vec<(usize, (i32, i32))> =
            pixels.iter().enumerate().filter_map(|(k, pts)| Some((k, *pts.last()?))).collect();
        let column = ends.iter().map(|(k, p)| p.0 + Self::marker_size(*k) + 4).max().unwrap_or(0);
        for (k, last) in ends {
            let size = label_size(area, shorts[k], &font(k))?;
            let reach = yp.end - yp.start;
            let near = column - last.0 + 4;
            if let Some(r) = placer.place(size, beside((column, last.1), size, 0, 2, reach)) {
                draw_placed(area, shorts[k], &font(k), r, (last, near), colour(k, n).mix(0.6))?;
            }
        }
        legend.draw(&legend_area)
    }
}

/// Lines of `y` against `x` on log axes (`y` of 0 on a row of its own),
/// one per series, into `base.svg` and `base.png`.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub(crate) fn lines(
    folder: &mut OutputFolder,
    base: &str,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
) -> Result<(), StudyError> {
    Ok(both(folder, base, &Lines { title, x_desc, y_desc, series })?)
}
