//! Predicted against measured on log–log axes, one plot a dataset: the
//! identity line, ±25 % dashed, each point marked by its role and labelled
//! with its id (Accel-Sim's `plot-correlation.py`).

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{DatasetResult, Role};
use crate::experiment::plot::{Figure, PlotError, SIZE, both, colour, footnote, log_log_chart, log_range};
use crate::output::folder::OutputFolder;

struct Correlated<'a> {
    d: &'a DatasetResult,
    version: String,
}

const ROLES: [(Role, &str); 3] =
    [(Role::Validation, "validation"), (Role::Calibration, "calibration (fitted)"), (Role::Sanity, "sanity")];

impl Figure for Correlated<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        let (plot, legend) = area.split_horizontally(SIZE.0 - 200);
        let values = self.d.points.iter().flat_map(|c| [c.measured, c.predicted]);
        let r = log_range(values, 1e-12);
        let mut units: Vec<&str> = Vec::new();
        for c in &self.d.points {
            if !units.contains(&c.unit) {
                units.push(c.unit);
            }
        }
        let unit = units.join(" or ");
        let title = format!("{}: predicted against measured", self.d.dataset.name);
        let (x, y) = (format!("measured ({unit})"), format!("predicted ({unit})"));
        let mut chart = log_log_chart(&plot, &title, (r.clone(), r.clone()), &x, &y, None)?;
        let line = |k: f64| [(r.start, r.start * k), (r.end / k.max(1.0), r.end.min(r.end * k))];
        chart.draw_series(LineSeries::new(line(1.0), BLACK.stroke_width(1))).map_err(|e| e.to_string())?;
        for k in [1.25, 0.75] {
            chart
                .draw_series(DashedLineSeries::new(line(k), 5, 4, BLACK.mix(0.4).stroke_width(1)))
                .map_err(|e| e.to_string())?;
        }
        for (k, (role, _)) in ROLES.iter().enumerate() {
            let color = colour(k, ROLES.len());
            for (i, c) in self.d.points.iter().enumerate().filter(|(_, c)| c.role == *role) {
                let at = (c.measured, c.predicted);
                // The label beside its marker, not over it: right of it
                // and left of it in turn, so that neighbours part.
                let (dx, h) = if i % 2 == 0 { (8, HPos::Left) } else { (-8, HPos::Right) };
                let font = TextStyle::from(("sans-serif", 11).into_font()).pos(Pos::new(h, VPos::Center));
                let mark = EmptyElement::at(at)
                    + Circle::new((0, 0), 5, color.stroke_width(2))
                    + Text::new(c.id.clone(), (dx, 0), font);
                chart.draw_series(std::iter::once(mark)).map_err(|e| e.to_string())?;
            }
        }
        let mut y0 = 40;
        for (k, (role, name)) in ROLES.iter().enumerate() {
            if self.d.points.iter().any(|c| c.role == *role) {
                let color = colour(k, ROLES.len());
                legend.draw(&Circle::new((16, y0), 5, color.stroke_width(2))).map_err(|e| e.to_string())?;
                legend.draw(&Text::new(*name, (28, y0 - 7), ("sans-serif", 13))).map_err(|e| e.to_string())?;
                y0 += 22;
            }
        }
        for (label, dashed) in [("identity", false), ("±25 %", true)] {
            let style = if dashed { BLACK.mix(0.4) } else { BLACK.into() };
            legend.draw(&PathElement::new(vec![(7, y0), (25, y0)], style)).map_err(|e| e.to_string())?;
            legend.draw(&Text::new(label, (28, y0 - 7), ("sans-serif", 13))).map_err(|e| e.to_string())?;
            y0 += 22;
        }
        footnote(&legend, &[self.version.clone(), self.d.dataset.source.clone()])
    }
}

/// Write `correlation-<dataset>.svg` and `.png` for each dataset with
/// points.
///
/// # Errors
/// [`PlotError::Draw`] or [`PlotError::Output`].
pub fn plot(folder: &mut OutputFolder, datasets: &[DatasetResult]) -> Result<(), PlotError> {
    for d in datasets.iter().filter(|d| !d.points.is_empty()) {
        // The release, not the revision: the picture a page shows must not
        // change with every commit (correlation.json and the manifest carry
        // the revision).
        let fig = Correlated { d, version: format!("umbra {} correlate", env!("CARGO_PKG_VERSION")) };
        both(folder, &format!("correlation-{}", d.dataset.name), &fig)?;
    }
    Ok(())
}
