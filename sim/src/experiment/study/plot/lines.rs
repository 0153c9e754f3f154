//! Lines of a measure against a swept parameter on log axes, each series
//! told apart by colour, line style and marker, and labelled at its end.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{ERROR_FLOOR, Legend, marker, with_legend};
use crate::experiment::plot::{Figure, both, colour, log_log_chart, log_range, spread, zero_row};
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

impl Figure for Lines<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        // The legend beside the chart, never over the data.
        let labels: Vec<String> = self.series.iter().map(|s| s.0.clone()).collect();
        let (plot, legend_area) = with_legend(area, &labels, 300);
        let xr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.0)), 1e-12);
        let ys = || self.series.iter().flat_map(|s| s.1.iter().map(|p| p.1));
        let zero = zero_row(ys(), ERROR_FLOOR);
        let any_zero = ys().any(|y| y <= 0.0);
        let yr = log_range(ys(), if any_zero { zero } else { ERROR_FLOOR });
        let mut chart = log_log_chart(&plot, self.title, (xr, yr), self.x_desc, self.y_desc, any_zero.then_some(zero))?;
        let n = self.series.len();
        let mut legend = Legend::new(&legend_area, &labels);
        let mut ends = Vec::new();
        for (k, (name, pts)) in self.series.iter().enumerate() {
            let color = colour(k, n);
            let style = color.stroke_width(2);
            // Every other series a little to the right (12 % on the log
            // axis, a few pixels), so that two series of equal values both show.
            let dodge = if k % 2 == 1 { 1.12 } else { 1.0 };
            let pts: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (x * dodge, if y > 0.0 { y } else { zero })).collect();
            // Every other series dashed, each its own hollow marker: two
            // series on one line still show both.
            let dashed = k % 2 == 1;
            if dashed {
                chart
                    .draw_series(DashedLineSeries::new(pts.iter().copied(), 8, 5, style))
                    .map_err(|e| e.to_string())?;
            } else {
                chart.draw_series(LineSeries::new(pts.iter().copied(), style)).map_err(|e| e.to_string())?;
            }
            for p in &pts {
                marker(area, chart.backend_coord(p), k % 5, 4 + 2 * i32::from(dashed), style)?;
            }
            // The series' short name at its last point: every one, spread
            // apart below (the legend names them in full).
            if let Some(last) = pts.last() {
                ends.push((chart.backend_coord(last), name.split(':').next().unwrap_or(name).to_owned(), color));
            }
            legend.entry(name, &|l, (x, y)| {
                let line = vec![(x - 10, y), (x + 10, y)];
                if dashed {
                    l.draw(&PathElement::new(vec![(x - 10, y), (x - 3, y)], style)).map_err(|e| e.to_string())?;
                    l.draw(&PathElement::new(vec![(x + 3, y), (x + 10, y)], style)).map_err(|e| e.to_string())?;
                } else {
                    l.draw(&PathElement::new(line, style)).map_err(|e| e.to_string())?;
                }
                marker(l, (x, y), k % 5, 4, style)
            })?;
        }
        let rows = spread(&ends.iter().map(|e| e.0.1 - 6).collect::<Vec<_>>(), 12);
        for (((x, _), short, color), y) in ends.into_iter().zip(rows) {
            area.draw(&Text::new(short, (x + 8, y), ("sans-serif", 11).into_font().color(&color)))
                .map_err(|e| e.to_string())?;
        }
        Ok(())
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
