//! The study's plots, as SVG and PNG: error against cost with the Pareto
//! front, and error against a swept parameter.
//!
//! Text needs a font for its metrics in both backends: the bundled DejaVu
//! Sans.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::summary::{TIME, cheapest};
use super::{Manifest, Row, RowCost, StudyError, distinct, loosest};
use crate::io::folder::OutputFolder;
use crate::io::output::{font, png};
use crate::pass::algorithm::Family;

/// Plot size in pixels.
const SIZE: (u32, u32) = (900, 600);

/// The indices of the Pareto-optimal points (no other point is at most as
/// costly and strictly more accurate, or cheaper and as accurate), by
/// increasing cost.
#[must_use]
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
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

/// Something drawn the same way on any backend.
trait Figure {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Draw `f` into `base.svg` and `base.png` in `folder`.
fn both(folder: &mut OutputFolder, base: &str, f: &impl Figure) -> Result<(), StudyError> {
    let err = |path: &std::path::Path, problem: String| StudyError::Plot { path: path.to_owned(), problem };
    let (svg_name, png_name) = (format!("{base}.svg"), format!("{base}.png"));
    let svg_path = folder.dir().join(&svg_name);
    let png_path = folder.dir().join(&png_name);
    font().map_err(|e| err(&svg_path, e))?;
    let mut svg = String::new();
    {
        let area = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        f.draw(&area).map_err(|e| err(&svg_path, e))?;
        area.present().map_err(|e| err(&svg_path, e.to_string()))?;
    }
    folder.write_text(&svg_name, &svg)?;
    let mut rgb = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let area = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        f.draw(&area).map_err(|e| err(&png_path, e))?;
        area.present().map_err(|e| err(&png_path, e.to_string()))?;
    }
    let bytes = png(&png_path, &rgb, SIZE.0, SIZE.1, image::ColorType::Rgb8)?;
    folder.write(&png_name, &bytes)?;
    Ok(())
}

/// Colours of the presets (and of series), in sweep order.
const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// Errors of zero are drawn at this floor on the log axis (percent).
pub const ERROR_FLOOR: f64 = 1e-3;

/// A log range covering `values` with some margin.
fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v.max(floor)), hi.max(v)));
    if lo.is_finite() && hi > 0.0 { (lo / 1.5)..(hi.max(lo) * 1.5) } else { floor..floor * 10.0 }
}

/// A chart on log–log axes.
type LogLogChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// A white area with a titled chart on log–log axes over `x` and `y`,
/// its mesh and labels drawn.
fn log_log_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
    x_desc: &str,
    y_desc: &str,
) -> Result<LogLogChart<'a, DB>, String> {
    area.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x.log_scale(), y.log_scale())
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(6)
        .y_labels(8)
        .x_label_formatter(&|x| format!("{x:.1e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

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
        1 => area.draw(&(e + TriangleMarker::new((0, 0), size + 1, style))),
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

/// Artifacts against cost, with the Pareto front as a staircase.
struct Pareto<'a> {
    title: String,
    axis: &'a str,
    /// `(cost, artifacts %)` per row.
    points: Vec<(f64, f64)>,
    /// Each row's architecture and family (indices into `archs`, [`FAMILIES`]).
    arch_of: Vec<usize>,
    family_of: Vec<usize>,
    archs: Vec<&'a str>,
    budgets: &'a [f64],
    /// What made it: the version, the sweep and its hash.
    provenance: [String; 2],
}

/// `lines` at the foot of a legend area.
fn footnote<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, lines: &[String]) -> Result<(), String> {
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few lines on a small plot")]
    let top = SIZE.1 as i32 - 20 * lines.len() as i32 - 10;
    for (k, l) in lines.iter().enumerate() {
        #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few lines")]
        let y = top + 20 * k as i32;
        area.draw(&Text::new(l.clone(), (6, y), ("sans-serif", 11).into_font().color(&BLACK.mix(0.6))))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

impl Figure for Pareto<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        // The legend beside the chart, never over the data.
        let (plot, legend) = area.split_horizontally(SIZE.0 - 230);
        let xr = log_range(self.points.iter().map(|p| p.0), 1e-3);
        let yr = log_range(self.points.iter().map(|p| p.1).chain(self.budgets.iter().copied()), ERROR_FLOOR);
        let y_desc = format!("artifacts % (acne and leaks; 0 drawn at {ERROR_FLOOR})");
        let (x0, x1) = (xr.start, xr.end);
        let mut chart = log_log_chart(&plot, &self.title, xr, yr, self.axis, &y_desc)?;
        for &b in self.budgets {
            chart
                .draw_series(DashedLineSeries::new([(x0, b), (x1, b)], 6, 4, BLACK.mix(0.5).stroke_width(1)))
                .map_err(|e| e.to_string())?;
            chart
                .draw_series(std::iter::once(Text::new(format!("{b} %"), (x0 * 1.05, b), ("sans-serif", 12))))
                .map_err(|e| e.to_string())?;
        }
        // Each architecture's markers a size larger than the one before, so
        // none hides another.
        for (k, _) in self.archs.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few presets")]
            let size = 3 + 2 * k as i32;
            for ((p, a), f) in self.points.iter().zip(&self.arch_of).zip(&self.family_of) {
                if *a == k {
                    marker(area, chart.backend_coord(p), *f, size, color.mix(0.7).stroke_width(1))?;
                }
            }
        }
        let front: Vec<(f64, f64)> = pareto_front(&self.points).iter().map(|&i| self.points[i]).collect();
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
        chart.draw_series(LineSeries::new(stairs, BLACK.stroke_width(2))).map_err(|e| e.to_string())?;
        // The legend: architectures by colour, families by marker.
        let text = |s: &str| Text::new(s.to_owned(), (0, 0), ("sans-serif", 14));
        let mut y = 40;
        let mut line = |label: &str, draw: &Swatch<'_, DB>| {
            draw(&legend, (14, y + 7))?;
            legend.draw(&(EmptyElement::at((30, y)) + text(label))).map_err(|e| e.to_string())?;
            y += 22;
            Ok::<(), String>(())
        };
        for (k, arch) in self.archs.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            line(arch, &|l, c| l.draw(&Circle::new(c, 5, color.filled())).map_err(|e| e.to_string()))?;
        }
        line("Pareto front", &|l, (x, y)| {
            l.draw(&PathElement::new(vec![(x - 9, y), (x + 9, y)], BLACK.stroke_width(2))).map_err(|e| e.to_string())
        })?;
        line("budget", &|l, (x, y)| {
            l.draw(&PathElement::new(vec![(x - 9, y), (x + 9, y)], BLACK.mix(0.5))).map_err(|e| e.to_string())
        })?;
        for (f, name) in FAMILIES.iter().enumerate() {
            line(name.name(), &|l, c| marker(l, c, f, 5, BLACK.stroke_width(1)))?;
        }
        footnote(&legend, &self.provenance)
    }
}

/// Artifacts against cost for one scene's rows: hollow markers by
/// algorithm family, coloured by architecture, the Pareto front a
/// staircase, the budgets dashed lines, the legend beside the chart.
/// Writes `pareto-<scene>-time.{svg,png}` and
/// `pareto-<scene>-bytes.{svg,png}`.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub fn pareto(folder: &mut OutputFolder, scene: &str, rows: &[&Row], manifest: &Manifest) -> Result<(), StudyError> {
    let rows: Vec<&Row> = rows.iter().copied().filter(|r| r.complete()).collect();
    let archs = distinct(rows.iter().map(|r| r.config.arch.as_str()));
    let arch_of: Vec<usize> =
        rows.iter().map(|r| archs.iter().position(|a| *a == r.config.arch).unwrap_or(0)).collect();
    let family_of: Vec<usize> =
        rows.iter().map(|r| FAMILIES.iter().position(|&f| f == r.config.family).unwrap_or(4)).collect();
    for (what, axis, key) in [
        (
            "time",
            "frame time, µs (light + camera passes)",
            (|c: &RowCost| c.frame_seconds * 1e6) as fn(&RowCost) -> f64,
        ),
        #[allow(clippy::cast_precision_loss, reason = "plot coordinates")]
        ("bytes", "DRAM bytes (both passes)", |c: &RowCost| c.total_dram_bytes as f64),
    ] {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| Some((r.cost.as_ref()?, r.metrics.as_ref()?)))
            .map(|(c, m)| (key(c).max(1e-3), m.artifact_percent.max(ERROR_FLOOR)))
            .collect();
        let fig = Pareto {
            title: format!("{scene}: artifacts against {what}"),
            axis,
            points,
            arch_of: arch_of.clone(),
            family_of: family_of.clone(),
            archs: archs.clone(),
            budgets: &manifest.budgets,
            provenance: provenance(manifest),
        };
        both(folder, &format!("pareto-{scene}-{what}"), &fig)?;
    }
    Ok(())
}

/// One named series of `(x, y)` points.
pub type Series = (String, Vec<(f64, f64)>);

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
        let (plot, legend) = area.split_horizontally(SIZE.0 - 300);
        let xr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.0)), 1e-12);
        let yr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.1)), ERROR_FLOOR);
        let mut chart = log_log_chart(&plot, self.title, xr, yr, self.x_desc, self.y_desc)?;
        for (k, (name, pts)) in self.series.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let pts: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (x, y.max(ERROR_FLOOR))).collect();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?;
            // Hollow markers a size larger for each series, so that one on
            // another still shows.
            #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few series")]
            let size = 3 + k as i32;
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, size, color.stroke_width(2))))
                .map_err(|e| e.to_string())?;
            #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few series")]
            let y = 40 + 22 * k as i32;
            legend
                .draw(&PathElement::new(vec![(4, y + 7), (22, y + 7)], color.stroke_width(2)))
                .map_err(|e| e.to_string())?;
            legend.draw(&Text::new(name.clone(), (28, y), ("sans-serif", 13))).map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

/// Lines of `y` against `x` on log axes (`y` floored at [`ERROR_FLOOR`]),
/// one per series, into `base.svg` and `base.png`.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub fn lines(
    folder: &mut OutputFolder,
    base: &str,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
) -> Result<(), StudyError> {
    both(folder, base, &Lines { title, x_desc, y_desc, series })
}

/// A plot's two lines of provenance: the version; the sweep and its hash.
fn provenance(m: &Manifest) -> [String; 2] {
    [m.umbra_version.clone(), format!("sweep {} {}", m.sweep, m.sweep_hash)]
}

/// The fastest frame time per algorithm family at each architecture point.
struct AxisPlot<'a> {
    title: String,
    /// The points' labels, in order (x = 0, 1, …).
    points: Vec<String>,
    /// Per family: `(point, µs)`.
    series: Vec<(&'a str, Vec<(f64, f64)>)>,
    provenance: [String; 2],
}

impl Figure for AxisPlot<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        let (plot, legend) = area.split_horizontally(SIZE.0 - 230);
        #[allow(clippy::cast_precision_loss, reason = "a few points")]
        let xr = -0.5..(self.points.len() as f64 - 0.5);
        let yr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.1)), 1e-3);
        let mut chart = ChartBuilder::on(&plot)
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(xr, yr.log_scale())
            .map_err(|e| e.to_string())?;
        let labels = self.points.clone();
        chart
            .configure_mesh()
            .x_desc("architecture point")
            .y_desc("frame time of the fastest configuration, µs")
            .x_labels(self.points.len())
            .x_label_formatter(&move |x| {
                let k = x.round();
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "an index")]
                let label = labels.get(k as usize).filter(|_| (x - k).abs() < 1e-6 && k >= 0.0);
                label.cloned().unwrap_or_default()
            })
            .y_label_formatter(&|y| format!("{y:.3}"))
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(|e| e.to_string())?;
        for (k, (name, pts)) in self.series.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?;
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled()))).map_err(|e| e.to_string())?;
            #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a few families")]
            let y = 40 + 22 * k as i32;
            legend.draw(&Circle::new((14, y + 7), 5, color.filled())).map_err(|e| e.to_string())?;
            legend.draw(&Text::new((*name).to_owned(), (30, y), ("sans-serif", 14))).map_err(|e| e.to_string())?;
        }
        footnote(&legend, &self.provenance)
    }
}

/// For a sweep with architecture-parameter axes: the frame time of the
/// fastest configuration of each algorithm family within the loosest
/// budget, at
/// every architecture point. Writes `arch-axes-<scene>.{svg,png}`; nothing
/// when the rows have no parameter axis.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub fn arch_axes(folder: &mut OutputFolder, scene: &str, rows: &[&Row], manifest: &Manifest) -> Result<(), StudyError> {
    let Some(budget) = loosest(&manifest.budgets) else { return Ok(()) };
    if rows.iter().all(|r| r.config.arch_params.is_empty()) {
        return Ok(());
    }
    let points = distinct(rows.iter().map(|r| r.config.arch_point()));
    let one_arch = points.windows(2).all(|w| w[0].0.split('-').next() == w[1].0.split('-').next());
    let labels = points.iter().map(|(a, p)| if one_arch { (*p).to_owned() } else { format!("{a}: {p}") }).collect();
    let series = FAMILIES
        .iter()
        .map(|&f| {
            let pts = points
                .iter()
                .enumerate()
                .filter_map(|(k, &point)| {
                    let mine: Vec<&Row> = rows
                        .iter()
                        .copied()
                        .filter(|r| r.config.family == f && r.config.arch_point() == point)
                        .collect();
                    let (best, _) = cheapest(&mine, budget, TIME)?;
                    #[allow(clippy::cast_precision_loss, reason = "plot coordinates")]
                    Some((k as f64, best.cost.as_ref()?.frame_seconds * 1e6))
                })
                .collect::<Vec<_>>();
            (f.name(), pts)
        })
        .filter(|(_, pts)| !pts.is_empty())
        .collect();
    let fig = AxisPlot {
        title: format!("{scene}: cheapest within {budget} % at each architecture point"),
        points: labels,
        series,
        provenance: provenance(manifest),
    };
    both(folder, &format!("arch-axes-{scene}"), &fig)
}
