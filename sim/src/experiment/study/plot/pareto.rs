//! Artifacts against cost, with the Pareto front as a staircase: each
//! design point (a base architecture at its axis values) in its own
//! colour, a hue for each base and a shade for each set of axis values,
//! each algorithm family its marker, and each budget a dashed line
//! labelled with its value right of the plot.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::legend::{Item, Legend};
use super::{ERROR_FLOOR, FAMILIES, marker, pareto_front, provenance};
use crate::experiment::plot::place::text_size;
use crate::experiment::plot::{Figure, both, colour, log_log_chart, log_range, shade, spread, zero_row};
use crate::experiment::study::budget::Measure;
use crate::experiment::study::{Manifest, Row, RowCost, StudyError, distinct};
use crate::output::folder::OutputFolder;

/// Artifacts against cost, with the Pareto front as a staircase.
struct Pareto<'a> {
    title: String,
    axis: &'a str,
    /// `(cost, artifacts %)` per row.
    points: Vec<(f64, f64)>,
    /// Each row's design point and family (indices into `archs`, [`FAMILIES`]).
    arch_of: Vec<usize>,
    family_of: Vec<usize>,
    /// Each design point: its base architecture and its axis values
    /// (indices into `bases` and `params`).
    archs: Vec<(usize, usize)>,
    bases: Vec<String>,
    /// Every set of axis values (`map_cache.size=16KiB`), empty for none.
    params: Vec<String>,
    /// The artifact budgets: the lines the y axis can draw.
    budgets: &'a [f64],
    /// What made it: the version, the sweep and its hash.
    provenance: [String; 2],
}

/// A budget's label: its value, `0.1 %`.
fn budget_label(b: f64) -> String {
    format!("{b} %")
}

impl Pareto<'_> {
    /// Design point `a`'s colour: its base's hue, in the shade of its axis
    /// values (darker to lighter in the sweep's order).
    fn colour_of(&self, a: usize) -> RGBColor {
        let (b, j) = self.archs[a];
        shade(colour(b, self.bases.len()), j, self.params.len())
    }

    /// The legend. In `full`, every design point by name, grouped under
    /// its base; else each base by its hue, and each set of axis values
    /// by its shade (drawn in grey). Then the front, the budgets and the
    /// families' markers.
    fn legend<DB: DrawingBackend>(&self, full: bool) -> Vec<Item<'_, DB>> {
        let dot = |c: RGBColor| {
            move |l: &DrawingArea<DB, Shift>, at: (i32, i32)| {
                l.draw(&Circle::new(at, 5, c.filled())).map_err(|e| e.to_string())
            }
        };
        let mut items = Vec::new();
        let named = |p: &str| p.replace(',', ", ");
        for (b, base) in self.bases.iter().enumerate() {
            let mine: Vec<usize> = (0..self.archs.len()).filter(|&a| self.archs[a].0 == b).collect();
            let axes = mine.iter().any(|&a| !self.params[self.archs[a].1].is_empty());
            if full && axes {
                items.push(Item::Heading(format!("{base}:")));
                items.extend(
                    mine.iter().map(|&a| Item::entry(named(&self.params[self.archs[a].1]), dot(self.colour_of(a)))),
                );
            } else {
                let hue = if full { self.colour_of(mine[0]) } else { colour(b, self.bases.len()) };
                items.push(Item::entry(base.clone(), dot(hue)));
            }
        }
        if !full && self.params.len() > 1 {
            items.push(Item::Heading("shade, by axis values:".to_owned()));
            let grey = RGBColor(128, 128, 128);
            let m = self.params.len();
            items.extend(self.params.iter().enumerate().map(|(j, p)| Item::entry(named(p), dot(shade(grey, j, m)))));
        }
        items.push(Item::entry("Pareto front", |l: &DrawingArea<DB, Shift>, (x, y): (i32, i32)| {
            l.draw(&PathElement::new(vec![(x - 9, y), (x + 9, y)], BLACK.mix(0.55).stroke_width(2)))
                .map_err(|e| e.to_string())
        }));
        if !self.budgets.is_empty() {
            items.push(Item::entry(
                "artifact budget (its value at the right)",
                |l: &DrawingArea<DB, Shift>, (x, y)| {
                    // Dashed, as the chart draws it.
                    for x0 in [x - 10, x + 2] {
                        l.draw(&PathElement::new(vec![(x0, y), (x0 + 7, y)], BLACK.mix(0.5)))
                            .map_err(|e| e.to_string())?;
                    }
                    Ok(())
                },
            ));
        }
        for f in (0..FAMILIES.len()).filter(|f| self.family_of.contains(f)) {
            items.push(Item::entry(FAMILIES[f].name(), move |l: &DrawingArea<DB, Shift>, c| {
                marker(l, c, f, 5, BLACK.stroke_width(2))
            }));
        }
        items
    }
}

impl Figure for Pareto<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        // The legend beside the chart, never over the data: every design
        // point named where they fit, else bases and shades apart.
        let mut legend = Legend::new(area, self.legend(true), &self.provenance)?;
        if !legend.fits(9) {
            legend = Legend::new(area, self.legend(false), &self.provenance)?;
        }
        let (plot, legend_area) = legend.split(area);
        let label_font = ("sans-serif", 11).into_font().color(&BLACK);
        let mut right = 0;
        for &b in self.budgets {
            right = right.max(text_size(area, &budget_label(b), &label_font)?.0 + 12);
        }
        let xr = log_range(self.points.iter().map(|p| p.0), 1e-3);
        let ys = || self.points.iter().map(|p| p.1).chain(self.budgets.iter().copied());
        // No artifact at all is a row of its own, below every measured value.
        let zero = zero_row(ys(), ERROR_FLOOR);
        let any_zero = self.points.iter().any(|p| p.1 <= 0.0);
        let points: Vec<(f64, f64)> = self.points.iter().map(|&(x, y)| (x, if y > 0.0 { y } else { zero })).collect();
        let mut yr = log_range(ys(), if any_zero { zero } else { ERROR_FLOOR });
        // Every budget on the axis, however small.
        let lowest = self.budgets.iter().copied().filter(|b| *b > 0.0).fold(f64::INFINITY, f64::min);
        yr.start = yr.start.min(lowest / 1.5);
        let y_desc = "artifacts % (acne, detachment, leaks, clipped)";
        let (x0, x1) = (xr.start, xr.end);
        let descs = (self.axis, y_desc);
        let right = u32::try_from(right).unwrap_or(0);
        let mut chart = log_log_chart(&plot, &self.title, (xr, yr), descs, any_zero.then_some(zero), right)?;
        // The budgets dashed, each labelled with its value right of the
        // plot, in rows apart.
        let mut rows = Vec::new();
        for &b in self.budgets {
            chart
                .draw_series(DashedLineSeries::new([(x0, b), (x1, b)], 6, 4, BLACK.mix(0.5).stroke_width(1)))
                .map_err(|e| e.to_string())?;
            rows.push(chart.backend_coord(&(x1, b)));
        }
        let height = text_size(area, "0", &label_font)?.1;
        let spread_rows = spread(&rows.iter().map(|r| r.1).collect::<Vec<_>>(), height + 2);
        let font = label_font.pos(Pos::new(HPos::Left, VPos::Center));
        for ((&b, (x, _)), y) in self.budgets.iter().zip(&rows).zip(spread_rows) {
            area.draw(&Text::new(budget_label(b), (x + 6, y), &font)).map_err(|e| e.to_string())?;
        }
        // The front first, lighter, so that every marker shows over it.
        let front: Vec<(f64, f64)> = pareto_front(&points).iter().map(|&i| points[i]).collect();
        let mut stairs = Vec::new();
        for (i, &(x, y)) in front.iter().enumerate() {
            if i > 0 {
                stairs.push((x, front[i - 1].1));
            }
            stairs.push((x, y));
        }
        if let Some(&(_, y)) = front.last() {
            stairs.push((x1, y));
        }
        chart.draw_series(LineSeries::new(stairs, BLACK.mix(0.55).stroke_width(2))).map_err(|e| e.to_string())?;
        // Hollow markers of one size, each design point its colour.
        for ((p, &a), &f) in points.iter().zip(&self.arch_of).zip(&self.family_of) {
            marker(area, chart.backend_coord(p), f, 5, self.colour_of(a).stroke_width(2))?;
        }
        legend.draw(&legend_area)
    }
}

/// Artifacts against cost for one scene's rows: hollow markers by
/// algorithm family, coloured by architecture, the Pareto front a
/// staircase, the budgets dashed lines, the legend beside the chart.
/// Writes `pareto-<scene>-time.{svg,png}`,
/// `pareto-<scene>-bytes.{svg,png}` and, where an architecture states its
/// technology, `pareto-<scene>-area.{svg,png}`.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub(crate) fn pareto(
    folder: &mut OutputFolder,
    scene: &str,
    rows: &[&Row],
    manifest: &Manifest,
) -> Result<(), StudyError> {
    let rows: Vec<&Row> = rows.iter().copied().filter(|r| r.complete()).collect();
    let names = distinct(rows.iter().map(|r| r.config.arch.as_str()));
    let arch_of: Vec<usize> =
        rows.iter().map(|r| names.iter().position(|a| *a == r.config.arch).unwrap_or(0)).collect();
    let bases = distinct(rows.iter().map(|r| r.config.base_arch.clone()));
    let params = distinct(rows.iter().map(|r| r.config.arch_params.clone()));
    let archs: Vec<(usize, usize)> = names
        .iter()
        .filter_map(|name| rows.iter().find(|r| r.config.arch == *name))
        .map(|r| {
            let base = bases.iter().position(|b| *b == r.config.base_arch).unwrap_or(0);
            (base, params.iter().position(|p| *p == r.config.arch_params).unwrap_or(0))
        })
        .collect();
    let family_of: Vec<usize> =
        rows.iter().map(|r| FAMILIES.iter().position(|&f| f == r.config.family).unwrap_or(4)).collect();
    // The y axis is artifacts: budgets on other measures draw no line.
    let artifact_budgets: Vec<f64> =
        manifest.budgets.iter().filter(|b| b.measure == Measure::Artifacts).map(|b| b.percent).collect();
    for (what, axis, key) in [
        (
            "time",
            "frame time, µs (light + camera passes)",
            (|c: &RowCost| c.frame_seconds * 1e6) as fn(&RowCost) -> f64,
        ),
        #[allow(clippy::cast_precision_loss, reason = "plot coordinates")]
        ("bytes", "DRAM bytes (both passes)", |c: &RowCost| c.total_dram_bytes as f64),
        ("area", "silicon area, µm² (the units each configuration uses)", |c: &RowCost| c.area_square_metres * 1e12),
    ] {
        // No area where no architecture states its technology.
        if what == "area" && rows.iter().filter_map(|r| r.cost.as_ref()).all(|c| c.area_square_metres <= 0.0) {
            continue;
        }
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| Some((r.cost.as_ref()?, r.metrics.as_ref()?)))
            .map(|(c, m)| (key(c).max(1e-3), m.artifact_percent))
            .collect();
        let fig = Pareto {
            title: format!("{scene}: artifacts against {what}"),
            axis,
            points,
            arch_of: arch_of.clone(),
            family_of: family_of.clone(),
            archs: archs.clone(),
            bases: bases.clone(),
            params: params.clone(),
            budgets: &artifact_budgets,
            provenance: provenance(manifest),
        };
        both(folder, &format!("pareto-{scene}-{what}"), &fig)?;
    }
    Ok(())
}
