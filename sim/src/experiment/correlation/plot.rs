//! Predicted against measured on log–log axes, one plot a dataset: the
//! identity line, ±25 % dashed, each point marked by its role and labelled
//! with its id where the label overlaps no other label or marker, with a
//! leader line when it has to move away (Accel-Sim's
//! `plot-correlation.py`).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{DatasetResult, Role};
use crate::experiment::plot::place::{Placer, Rect, around, draw_placed, label_size};
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
        let mut chart = log_log_chart(&plot, &title, (r.clone(), r.clone()), (&x, &y), None, 12)?;
        let line = |k: f64| [(r.start, r.start * k), (r.end / k.max(1.0), r.end.min(r.end * k))];
        chart.draw_series(LineSeries::new(line(1.0), BLACK.stroke_width(1))).map_err(|e| e.to_string())?;
        for k in [1.25, 0.75] {
            chart
                .draw_series(DashedLineSeries::new(line(k), 5, 4, BLACK.mix(0.4).stroke_width(1)))
                .map_err(|e| e.to_string())?;
        }
        // Every marker first, then each label where it overlaps nothing.
        let role_colour = |role: Role| colour(ROLES.iter().position(|r| r.0 == role).unwrap_or(0), ROLES.len());
        let mut placer = Placer::new(Rect::of_ranges(chart.plotting_area().get_pixel_range()));
        let at: Vec<(i32, i32)> =
            self.d.points.iter().map(|c| chart.backend_coord(&(c.measured, c.predicted))).collect();
        for (c, &p) in self.d.points.iter().zip(&at) {
            area.draw(&Circle::new(p, 5, role_colour(c.role).stroke_width(2))).map_err(|e| e.to_string())?;
            placer.block(Rect::around(p, 7));
        }
        let font = ("sans-serif", 11).into_font().color(&BLACK);
        for (c, &p) in self.d.points.iter().zip(&at) {
            let size = label_size(area, &c.id, &font)?;
            if let Some(r) = placer.place(size, around(p, size, 9, 8, 8)) {
                draw_placed(area, &c.id, &font, r, (p, 14), BLACK.mix(0.4))?;
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

#[cfg(test)]
mod tests {
    use super::super::{Compared, Dataset, DatasetResult, Role, Stats};
    use crate::experiment::plot::record::{self, assert_legible};
    use crate::input::limits::Limits;
    use crate::output::folder::{Claim, OutputFolder, RunKind};

    /// A bundled dataset's result with its points' ids and measurements
    /// and the model's predictions (as a run gives them), `(id, unit,
    /// measured, predicted, role)`.
    fn result(name: &str, points: &[(&str, &'static str, f64, f64, Role)]) -> DatasetResult {
        let dataset = Dataset::open(name, &Limits::DEFAULT).expect("bundled");
        let points = points
            .iter()
            .map(|&(id, unit, measured, predicted, role)| Compared {
                id: id.to_owned(),
                what: id.to_owned(),
                arch: String::new(),
                unit,
                measured,
                predicted,
                role,
                fitted: Vec::new(),
            })
            .collect();
        DatasetResult { dataset, points, stats: Stats::default() }
    }

    /// No text overlaps another, nor leaves the image, in the plots of
    /// the bundled datasets as a run draws them: Weiskopf & Ertl's frame
    /// rates (a cluster of points in the lower left), the peak rates (four
    /// points decades apart) and Arm's attachments (two on one spot).
    #[test]
    fn no_label_overlaps_another() {
        let (v, c, s) = (Role::Validation, Role::Calibration, Role::Sanity);
        let datasets = [
            result(
                "weiskopf-ertl-2003",
                &[
                    ("no-shadow", "fps", 167.5, 167.5, c),
                    ("point-bias-256", "fps", 106.2, 97.85, v),
                    ("point-bias-2048", "fps", 69.1, 60.14, v),
                    ("point-dual-256", "fps", 85.3, 85.30, c),
                    ("point-dual-2048", "fps", 30.6, 27.09, v),
                    ("bilinear-bias-256", "fps", 44.8, 56.61, v),
                    ("bilinear-bias-2048", "fps", 36.6, 41.16, v),
                    ("bilinear-dual-256", "fps", 40.6, 52.04, v),
                    ("bilinear-dual-2048", "fps", 21.9, 22.44, v),
                    ("4x4-bias-256", "fps", 27.2, 27.76, v),
                    ("4x4-bias-2048", "fps", 23.9, 23.21, v),
                    ("4x4-dual-256", "fps", 25.5, 26.53, v),
                    ("4x4-dual-2048", "fps", 16.6, 15.76, v),
                ],
            ),
            result(
                "peak-rates",
                &[
                    ("r300-depth-fill", "pixels/s", 2.2e9, 2.16e9, s),
                    ("r300-bandwidth", "B/s", 1.728e10, 1.728e10, s),
                    ("mali-g710-bandwidth", "B/s", 5.12e10, 5.105e10, s),
                    ("rtx-3080-bandwidth", "B/s", 7.6e11, 7.6e11, s),
                ],
            ),
            result(
                "arm-render-passes",
                &[("colour-load", "B/s", 6.294e8, 5.754e8, s), ("depth-store", "B/s", 5.817e8, 5.754e8, s)],
            ),
        ];
        let dir = std::env::temp_dir().join(format!("umbra-correlation-plot-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut folder = OutputFolder::create(&dir, Claim::new(RunKind::Correlation)).expect("a folder");
        let _ = record::take();
        super::plot(&mut folder, &datasets).expect("drawn");
        folder.finish(None).expect("finished");
        let figures = record::take();
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(figures.len(), 3);
        for (name, record) in &figures {
            assert_legible(name, record);
            // Every point's id is written.
            let ids = datasets.iter().find(|d| *name == format!("correlation-{}", d.dataset.name)).expect("a dataset");
            for c in &ids.points {
                assert!(record.texts.iter().any(|t| t.text == c.id), "{name}: no `{}`", c.id);
            }
        }
    }
}
