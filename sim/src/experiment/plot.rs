//! Plots drawn the same way on any backend, shared by the study and the
//! correlation: SVG and PNG of one figure (`both`), colours that stay
//! distinct for any number of series (`colour`), log–log charts whose
//! axes have labelled ticks (a log axis at each decade, at 2 and 5 too when
//! it spans few, with minor ticks), and a footnote.
//!
//! Text needs a font for its metrics in both backends: the bundled DejaVu
//! Sans.

use std::path::PathBuf;

use plotters::coord::Shift;
use plotters::coord::combinators::WithKeyPoints;
use plotters::prelude::*;

use crate::output::OutputError;
use crate::output::folder::OutputFolder;
use crate::output::formats::{font, png};

/// Why a plot could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// A figure could not be drawn.
    #[error("plot {path}: {problem}")]
    Draw {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        problem: String,
    },
    /// A file could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// Plot size in pixels.
pub(crate) const SIZE: (u32, u32) = (900, 600);

/// Something drawn the same way on any backend.
pub(crate) trait Figure {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Draw `f` into `base.svg` and `base.png` in `folder`.
///
/// # Errors
/// [`PlotError::Draw`] naming the file a drawing failed in, or
/// [`PlotError::Output`].
pub(crate) fn both(folder: &mut OutputFolder, base: &str, f: &impl Figure) -> Result<(), PlotError> {
    let err = |path: &std::path::Path, problem: String| PlotError::Draw { path: path.to_owned(), problem };
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

/// Ten colours told apart at a glance (Tableau's), for up to ten series.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The colour of series `k` of `n`: the palette's for up to ten; past it,
/// hues spaced evenly round the wheel, lightness alternating, so that no
/// two of any number repeat.
#[must_use]
pub(crate) fn colour(k: usize, n: usize) -> RGBColor {
    if n <= PALETTE.len() {
        return PALETTE[k % PALETTE.len()];
    }
    #[allow(clippy::cast_precision_loss, reason = "a few series")]
    let hue = k as f64 / n as f64;
    let light = if k.is_multiple_of(2) { 0.38 } else { 0.55 };
    let (r, g, b) = HSLColor(hue, 0.75, light).rgb();
    RGBColor(r, g, b)
}

/// A log range covering `values` with some margin.
pub(crate) fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v.max(floor)), hi.max(v)));
    if lo.is_finite() && hi > 0.0 { (lo / 1.5)..(hi.max(lo) * 1.5) } else { floor..floor * 10.0 }
}

/// Ticks of a log axis over `range`: labelled ones at each decade (and at
/// 2 and 5 of each when the range spans fewer than three decades), minor
/// ones at every whole multiple of each decade.
#[must_use]
pub(crate) fn log_ticks(range: &std::ops::Range<f64>) -> (Vec<f64>, Vec<f64>) {
    let (lo, hi) = (range.start.max(f64::MIN_POSITIVE), range.end);
    #[allow(clippy::cast_possible_truncation, reason = "decades of finite numbers")]
    let decades = lo.log10().floor() as i32..=hi.log10().ceil() as i32;
    let inside = |v: &f64| (lo..=hi).contains(v);
    let few = hi / lo < 1e3;
    let mut bold = Vec::new();
    let mut light = Vec::new();
    for d in decades {
        let unit = 10f64.powi(d);
        for m in 1..10 {
            let v = f64::from(m) * unit;
            if inside(&v) {
                light.push(v);
                if m == 1 || (few && (m == 2 || m == 5)) {
                    bold.push(v);
                }
            }
        }
    }
    (bold, light)
}

/// A tick's label: plain for 0.01 to 10 000, else `2e5`-style; three
/// significant digits at most.
#[must_use]
pub(crate) fn tick_label(v: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    if (1e-2..1e4).contains(&v.abs()) {
        let s = format!("{v:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        return s.to_owned();
    }
    let e = v.abs().log10().floor();
    let m = v / 10f64.powf(e);
    let m = format!("{m:.2}");
    format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
}

/// A log axis over `range` with [`log_ticks`]'s ticks.
fn log_axis(range: std::ops::Range<f64>) -> WithKeyPoints<LogCoord<f64>> {
    let (bold, light) = log_ticks(&range);
    range.log_scale().with_key_points(bold).with_light_points(light)
}

/// A chart on log–log axes.
pub(crate) type LogLogChart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<WithKeyPoints<LogCoord<f64>>, WithKeyPoints<LogCoord<f64>>>>;

/// A white area with a titled chart on log–log axes over `x` and `y`,
/// its mesh and labels drawn.
pub(crate) fn log_log_chart<'a, DB: DrawingBackend>(
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
        .build_cartesian_2d(log_axis(x), log_axis(y))
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|x| tick_label(*x))
        .y_label_formatter(&|y| tick_label(*y))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// `lines` at the foot of a legend area.
pub(crate) fn footnote<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, lines: &[String]) -> Result<(), String> {
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
