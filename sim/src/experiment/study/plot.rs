//! The study's plots, as SVG and PNG: error against cost with the Pareto
//! front, and error against a swept parameter.
//!
//! Text needs a font for its metrics in both backends: DejaVu Sans from the
//! system (`fonts-dejavu-core`), or the TrueType file `$UMBRA_FONT` names.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Row, StudyError};
pub use crate::io::output::FONT_PATHS;
use crate::io::output::font;

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

/// Draw `f` into `base.svg` and `base.png`.
fn both(base: &Path, f: &impl Figure) -> Result<(), StudyError> {
    let err = |path: &Path, problem: String| StudyError::Plot { path: path.to_owned(), problem };
    let svg_path = base.with_extension("svg");
    let png_path = base.with_extension("png");
    font().map_err(|e| err(&svg_path, e))?;
    let mut svg = String::new();
    {
        let area = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        f.draw(&area).map_err(|e| err(&svg_path, e))?;
        area.present().map_err(|e| err(&svg_path, e.to_string()))?;
    }
    crate::io::output::write_text(&svg_path, &svg)?;
    let mut rgb = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let area = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        f.draw(&area).map_err(|e| err(&png_path, e))?;
        area.present().map_err(|e| err(&png_path, e.to_string()))?;
    }
    image::save_buffer(&png_path, &rgb, SIZE.0, SIZE.1, image::ColorType::Rgb8)
        .map_err(|e| err(&png_path, e.to_string()))
}

/// Colours of the presets (and of series), in sweep order.
const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
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
        .caption(title, ("sans-serif", 22))
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
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// A scatter of error against cost with its Pareto front.
struct Pareto<'a> {
    title: String,
    axis: &'a str,
    /// `(cost, error %)` per row, with the row's preset.
    points: Vec<(f64, f64)>,
    arch_of: Vec<usize>,
    archs: Vec<&'a str>,
}

impl Figure for Pareto<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let xr = log_range(self.points.iter().map(|p| p.0), 1.0);
        let yr = log_range(self.points.iter().map(|p| p.1), ERROR_FLOOR);
        let y_desc = format!("misclassified % (0 drawn at {ERROR_FLOOR})");
        let mut chart = log_log_chart(area, &self.title, xr, yr, self.axis, &y_desc)?;
        for (k, arch) in self.archs.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let mine = self.points.iter().zip(&self.arch_of).filter(|(_, a)| **a == k).map(|(p, _)| *p);
            chart
                .draw_series(mine.map(|p| Circle::new(p, 3, color.mix(0.25).filled())))
                .map_err(|e| e.to_string())?
                .label(*arch)
                .legend(move |(x, y)| Circle::new((x, y), 4, color.filled()));
        }
        let line: Vec<(f64, f64)> = pareto_front(&self.points).iter().map(|&i| self.points[i]).collect();
        chart
            .draw_series(LineSeries::new(line.iter().copied(), BLACK.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x - 8, y), (x + 8, y)], BLACK.stroke_width(2)));
        chart.draw_series(line.iter().map(|&p| Circle::new(p, 4, BLACK.filled()))).map_err(|e| e.to_string())?;
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())
    }
}

/// Error against cost for one scene's rows: every point faint, coloured by
/// preset, the Pareto front drawn over them. Writes
/// `pareto-<scene>-cycles.{svg,png}` and `pareto-<scene>-bytes.{svg,png}`.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub fn pareto(dir: &Path, scene: &str, rows: &[&Row]) -> Result<(), StudyError> {
    let rows: Vec<&Row> = rows.iter().copied().filter(|r| r.complete()).collect();
    let mut archs: Vec<&str> = Vec::new();
    for r in &rows {
        if !archs.contains(&r.arch.as_str()) {
            archs.push(&r.arch);
        }
    }
    let arch_of: Vec<usize> = rows.iter().map(|r| archs.iter().position(|a| *a == r.arch).unwrap_or(0)).collect();
    for (what, axis, key) in [
        ("cycles", "cycles (light + camera bottleneck)", (|r: &Row| r.total_cycles) as fn(&Row) -> Option<u64>),
        ("bytes", "DRAM bytes (both passes)", |r: &Row| r.total_bytes),
    ] {
        #[allow(clippy::cast_precision_loss, reason = "plot coordinates")]
        let points: Vec<(f64, f64)> = rows
            .iter()
            .map(|r| ((key(r).unwrap_or(0).max(1)) as f64, r.misclassified_percent.unwrap_or(0.0).max(ERROR_FLOOR)))
            .collect();
        let fig = Pareto {
            title: format!("{scene}: error against {what}"),
            axis,
            points,
            arch_of: arch_of.clone(),
            archs: archs.clone(),
        };
        both(&dir.join(format!("pareto-{scene}-{what}")), &fig)?;
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
        let xr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.0)), 1e-12);
        let yr = log_range(self.series.iter().flat_map(|s| s.1.iter().map(|p| p.1)), ERROR_FLOOR);
        let mut chart = log_log_chart(area, self.title, xr, yr, self.x_desc, self.y_desc)?;
        for (k, (name, pts)) in self.series.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let pts: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (x, y.max(ERROR_FLOOR))).collect();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x - 8, y), (x + 8, y)], color.stroke_width(2)));
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled()))).map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())
    }
}

/// Lines of `y` against `x` on log axes (`y` floored at [`ERROR_FLOOR`]),
/// one per series, into `base.svg` and `base.png`.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub fn lines(base: &Path, title: &str, x_desc: &str, y_desc: &str, series: &[Series]) -> Result<(), StudyError> {
    both(base, &Lines { title, x_desc, y_desc, series })
}
