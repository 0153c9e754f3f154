//! Plots drawn the same way on any backend, shared by the study and the
//! correlation: SVG and PNG of one figure (`both`), colours that stay
//! distinct for any number of series (`colour`) and shades of one
//! (`shade`), series set a few pixels apart (`dodge`), log–log charts
//! whose axes have labelled ticks (a log axis at each decade, at 2 and 5
//! too when it spans few, with minor ticks), labels that overlap nothing
//! (`place`), and a footnote.
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

pub(crate) mod place;
#[cfg(test)]
pub(crate) mod record;

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
    #[cfg(test)]
    record::keep(base, f).map_err(|e| err(&svg_path, e))?;
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

/// Shade `j` of `m` of colour `c`: from darker (the first) to lighter
/// (the last), `c` itself in the middle, every shade clear of white.
#[must_use]
pub(crate) fn shade(c: RGBColor, j: usize, m: usize) -> RGBColor {
    #[allow(clippy::cast_precision_loss, reason = "a few shades")]
    let t = if m > 1 { j as f64 / (m - 1) as f64 } else { 0.5 };
    // Up to 40 % of the way to black, or to white.
    let (towards, by) = if t < 0.5 { (0.0, 0.8 * (0.5 - t)) } else { (255.0, 0.8 * (t - 0.5)) };
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "a channel, 0 to 255")]
    let mix = |v: u8| (f64::from(v) + (towards - f64::from(v)) * by).round() as u8;
    RGBColor(mix(c.0), mix(c.1), mix(c.2))
}

/// How far series `k` of `n` is moved sideways, pixels: `step` apart,
/// the series centred on the true position, so that two series of one
/// value both show.
#[must_use]
pub(crate) fn dodge(k: usize, n: usize, step: f64) -> i32 {
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, reason = "a few series, pixels")]
    let d = ((k as f64 - (n.max(1) - 1) as f64 / 2.0) * step).round() as i32;
    d
}

/// The [`dodge`] step for `n` series whose points lie at least `gap`
/// pixels apart along x: all of them within 40 % of the gap, each at
/// most `most` pixels from the next.
#[must_use]
pub(crate) fn dodge_step(gap: i32, n: usize, most: f64) -> f64 {
    #[allow(clippy::cast_precision_loss, reason = "a few series")]
    let step = f64::from(gap) * 0.4 / n.saturating_sub(1).max(1) as f64;
    step.min(most)
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

/// A lone value's label: plain from 0.01 to 10 000, else `2e5`-style;
/// three significant digits at most.
#[must_use]
pub(crate) fn tick_label(v: f64) -> String {
    axis_label(v, plain_axis(&[v]))
}

/// Whether an axis with labelled ticks `ticks` writes them plainly
/// (`10`, `100`, `0.5`): when every one lies from 0.01 to 10 000; else
/// every one in the `1e4` style, so that one axis has one style.
#[must_use]
pub(crate) fn plain_axis(ticks: &[f64]) -> bool {
    ticks.iter().all(|v| (1e-2..1e4).contains(&v.abs()))
}

/// A tick's label in its axis's style ([`plain_axis`]): plain, or
/// `2e5`-style; three significant digits at most.
#[must_use]
pub(crate) fn axis_label(v: f64, plain: bool) -> String {
    if v == 0.0 || plain {
        let s = format!("{v:.3}");
        return s.trim_end_matches('0').trim_end_matches('.').to_owned();
    }
    let e = v.abs().log10().floor();
    let m = v / 10f64.powf(e);
    let m = format!("{m:.2}");
    format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
}

/// Where a log axis of `values` draws 0: a fifth of the smallest positive
/// value (of `floor` when none is), a row of its own below them all (its
/// dashed line, at √10 times it, passes under every measured value).
#[must_use]
pub(crate) fn zero_row(values: impl Iterator<Item = f64>, floor: f64) -> f64 {
    let least = values.filter(|v| *v > 0.0).fold(f64::INFINITY, f64::min);
    (if least.is_finite() { least } else { floor }) / 5.0
}

/// Screen rows for labels wanted at `ys` (pixels, any order): each moved
/// down as little as it can so that no two are closer than `gap`, the
/// order kept. Returns the rows in the order given.
#[must_use]
pub(crate) fn spread(ys: &[i32], gap: i32) -> Vec<i32> {
    let mut order: Vec<usize> = (0..ys.len()).collect();
    order.sort_by_key(|&k| (ys[k], k));
    let mut out = ys.to_vec();
    let mut last: Option<i32> = None;
    for k in order {
        let y = last.map_or(ys[k], |l| ys[k].max(l + gap));
        out[k] = y;
        last = Some(y);
    }
    out
}

/// A log axis over `range` with [`log_ticks`]'s ticks, and `zero` among
/// them when given.
fn log_axis(range: std::ops::Range<f64>, zero: Option<f64>) -> (WithKeyPoints<LogCoord<f64>>, bool) {
    let (mut bold, light) = log_ticks(&range);
    // No decade's label crowds the zero row's.
    bold.retain(|v| zero.is_none_or(|z| *v > z * 2.5));
    let plain = plain_axis(&bold);
    bold.extend(zero);
    (range.log_scale().with_key_points(bold).with_light_points(light), plain)
}

/// A chart on log–log axes.
pub(crate) type LogLogChart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<WithKeyPoints<LogCoord<f64>>, WithKeyPoints<LogCoord<f64>>>>;

/// A white area with a titled chart on log–log axes over `x` and `y`,
/// its mesh and labels drawn, each axis in one tick style, `right` pixels
/// kept free at its right for labels. With `zero`, the y axis has a row
/// of its own for 0 at that value ([`zero_row`]), labelled `0` and set
/// off from the decades above by a dashed line.
pub(crate) fn log_log_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    (x, y): (std::ops::Range<f64>, std::ops::Range<f64>),
    (x_desc, y_desc): (&str, &str),
    zero: Option<f64>,
    right: u32,
) -> Result<LogLogChart<'a, DB>, String> {
    area.fill(&WHITE).map_err(|e| e.to_string())?;
    let y = match zero {
        Some(z) => (z / 1.5).min(y.start)..y.end,
        None => y,
    };
    let (x_axis, plain_x) = log_axis(x, None);
    let (y_axis, plain_y) = log_axis(y, zero);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .margin_right(right.max(12))
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x_axis, y_axis)
        .map_err(|e| e.to_string())?;
    let is_zero = move |v: f64| zero.is_some_and(|z| (v - z).abs() <= z * 1e-9);
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|x| axis_label(*x, plain_x))
        .y_label_formatter(&|y| if is_zero(*y) { "0".to_owned() } else { axis_label(*y, plain_y) })
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    if let Some(z) = zero {
        let (x0, x1) = (chart.x_range().start, chart.x_range().end);
        let at = z * 10f64.sqrt();
        chart
            .draw_series(DashedLineSeries::new([(x0, at), (x1, at)], 3, 3, BLACK.mix(0.6).stroke_width(1)))
            .map_err(|e| e.to_string())?;
    }
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

#[cfg(test)]
mod tests {
    use plotters::style::RGBColor;

    use super::{axis_label, dodge, plain_axis, shade, spread, zero_row};

    /// Shades of one colour run from darker to lighter, the middle one the
    /// colour itself; series are set aside evenly about their value.
    #[test]
    fn shades_run_dark_to_light_and_series_dodge_about_their_value() {
        let c = RGBColor(31, 119, 180);
        let shades: Vec<RGBColor> = (0..5).map(|j| shade(c, j, 5)).collect();
        assert_eq!(shades[2], c);
        assert!(shades.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1 && w[0].2 < w[1].2), "{shades:?}");
        assert_eq!((0..4).map(|k| dodge(k, 4, 10.0)).collect::<Vec<_>>(), [-15, -5, 5, 15]);
        assert_eq!(dodge(0, 1, 10.0), 0);
    }

    /// One axis, one style: an axis whose ticks pass 10 000 writes every
    /// tick in the `1e4` style (it wrote `5000` beside `1e4`), one within
    /// 0.01 to 10 000 every tick plainly.
    #[test]
    fn an_axis_writes_its_ticks_in_one_style() {
        let label = |ticks: &[f64]| ticks.iter().map(|&v| axis_label(v, plain_axis(ticks))).collect::<Vec<_>>();
        assert_eq!(label(&[10.0, 100.0, 1000.0, 1e4]), ["1e1", "1e2", "1e3", "1e4"]);
        assert_eq!(label(&[0.001, 0.01, 0.1]), ["1e-3", "1e-2", "1e-1"]);
        assert_eq!(label(&[0.01, 0.1, 1.0, 2.0, 5000.0]), ["0.01", "0.1", "1", "2", "5000"]);
    }

    /// Zero's row sits below every positive value, its dashed line (at √10
    /// times it) too; with no positive value, below the floor.
    #[test]
    fn zero_has_a_row_below_every_value() {
        let z = zero_row([0.0, 0.03, 2.0, 0.0].into_iter(), 1e-3);
        assert!(z * 10f64.sqrt() < 0.03 && z > 0.0, "{z}");
        assert!(zero_row([0.0].into_iter(), 1e-3) < 1e-3);
    }

    /// Labels wanted on one row are spread `gap` apart, in their order;
    /// labels already apart stay where they are.
    #[test]
    fn end_labels_are_spread_apart() {
        assert_eq!(spread(&[100, 100, 104, 300], 12), [100, 112, 124, 300]);
        assert_eq!(spread(&[50, 10], 12), [50, 10]);
        let rows = spread(&[7, 7, 7, 7, 7], 11);
        assert!(rows.windows(2).all(|w| w[1] - w[0] == 11), "{rows:?}");
    }
}
