//! Artifacts against cost, with the Pareto front as a staircase.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{ERROR_FLOOR, FAMILIES, Legend, marker, pareto_front, provenance, with_legend};
use crate::experiment::plot::{Figure, both, colour, footnote, log_log_chart, log_range, zero_row};
use crate::experiment::study::budget::Measure;
use crate::experiment::study::{Manifest, Row, RowCost, StudyError, distinct};
use crate::output::folder::OutputFolder;

/// Artifacts against cost, with the Pareto front as a staircase.
struct Pareto<'a> {
    title: String,
    axis: &'a str,
    /// `(cost, artifacts %)` per row.
    points: Vec<(f64, f64)>,
    /// Each row's architecture and family (indices into `archs`, [`FAMILIES`]).
    arch_of: Vec<usize>,
    family_of: Vec<usize>,
    /// Each architecture's label (its base and axis values).
    archs: Vec<String>,
    /// The artifact budgets: the lines the y axis can draw.
    budgets: &'a [f64],
    /// What made it: the version, the sweep and its hash.
    provenance: [String; 2],
}

impl Figure for Pareto<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        // The legend: architectures by colour, the families drawn by
        // marker; beside the chart, never over the data.
        let families: Vec<usize> = (0..FAMILIES.len()).filter(|f| self.family_of.contains(f)).collect();
        let budgets = self.budgets.iter().map(|b| format!("{b} %")).collect::<Vec<_>>().join(", ");
        let budget_label = format!("budgets: {budgets}");
        let mut labels = self.archs.clone();
        labels.extend(["Pareto front".to_owned(), budget_label.clone()]);
        labels.extend(families.iter().map(|&f| FAMILIES[f].name().to_owned()));
        let (plot, legend_area) = with_legend(area, &labels, 230);
        let xr = log_range(self.points.iter().map(|p| p.0), 1e-3);
        let ys = || self.points.iter().map(|p| p.1).chain(self.budgets.iter().copied());
        // No artifact at all is a row of its own, below every measured value.
        let zero = zero_row(ys(), ERROR_FLOOR);
        let any_zero = self.points.iter().any(|p| p.1 <= 0.0);
        let points: Vec<(f64, f64)> = self.points.iter().map(|&(x, y)| (x, if y > 0.0 { y } else { zero })).collect();
        let yr = log_range(ys(), if any_zero { zero } else { ERROR_FLOOR });
        let y_desc = "artifacts % (acne, detachment, leaks, clipped)";
        let (x0, x1) = (xr.start, xr.end);
        let mut chart = log_log_chart(&plot, &self.title, (xr, yr), self.axis, y_desc, any_zero.then_some(zero))?;
        // The budgets dashed, named in the legend: no label over a marker.
        for &b in self.budgets {
            chart
                .draw_series(DashedLineSeries::new([(x0, b), (x1, b)], 6, 4, BLACK.mix(0.5).stroke_width(1)))
                .map_err(|e| e.to_string())?;
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
        // Hollow markers of one size, each architecture its colour.
        let n = self.archs.len();
        for k in 0..n {
            let color = colour(k, n);
            for ((p, a), f) in points.iter().zip(&self.arch_of).zip(&self.family_of) {
                if *a == k {
                    marker(area, chart.backend_coord(p), *f, 5, color.stroke_width(2))?;
                }
            }
        }
        let mut legend = Legend::new(&legend_area, &labels);
        for (k, arch) in self.archs.iter().enumerate() {
            let color = colour(k, n);
            legend.entry(arch, &|l, c| l.draw(&Circle::new(c, 5, color.filled())).map_err(|e| e.to_string()))?;
        }
        legend.entry("Pareto front", &|l, (x, y)| {
            l.draw(&PathElement::new(vec![(x - 9, y), (x + 9, y)], BLACK.mix(0.55).stroke_width(2)))
                .map_err(|e| e.to_string())
        })?;
        legend.entry(&budget_label, &|l, (x, y)| {
            // Dashed, as the chart draws it.
            for x0 in [x - 10, x + 2] {
                l.draw(&PathElement::new(vec![(x0, y), (x0 + 7, y)], BLACK.mix(0.5))).map_err(|e| e.to_string())?;
            }
            Ok(())
        })?;
        for f in families {
            legend.entry(FAMILIES[f].name(), &|l, c| marker(l, c, f, 5, BLACK.stroke_width(2)))?;
        }
        footnote(&legend_area, &self.provenance)
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
    let archs: Vec<String> = names
        .iter()
        .map(|name| {
            let r = rows.iter().find(|r| r.config.arch == *name).map(|r| &r.config);
            match r {
                Some(c) if !c.arch_params.is_empty() => format!("{}: {}", c.base_arch, c.arch_params),
                _ => (*name).to_owned(),
            }
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
            budgets: &artifact_budgets,
            provenance: provenance(manifest),
        };
        both(folder, &format!("pareto-{scene}-{what}"), &fig)?;
    }
    Ok(())
}
