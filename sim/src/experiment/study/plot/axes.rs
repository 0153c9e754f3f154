//! Frame time against architecture axes: the swept key on a numeric x
//! axis (logarithmic for a geometric series of values, `16KiB, 32KiB,
//! 64KiB`), one line per base architecture and algorithm family (the
//! fastest configuration within the loosest budget at each value), what
//! binds its frame written at each point, one panel per value of the other
//! axes, titled with SI prefixes, every panel on one time scale.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{FAMILIES, Legend, marker, provenance, with_legend};
use crate::cost::arch::{PARAMS, Unit, column};
use crate::cost::work::Bottleneck;
use crate::experiment::plot::{Figure, both, colour, footnote};
use crate::experiment::study::rank::{TIME, cheapest};
use crate::experiment::study::schema::axis_unit;
use crate::experiment::study::{Manifest, Row, StudyError, distinct, loosest};
use crate::output::folder::OutputFolder;

/// One point: the axis value, the frame time in µs, what binds the frame.
type Point = (f64, f64, Bottleneck);

/// One panel: its label, and per series (index into the series names)
/// its points.
type Panel = (String, Vec<(usize, Vec<Point>)>);

/// The panels of the plot.
struct AxisPlot {
    title: String,
    x_desc: String,
    /// The swept key's unit, which writes its values (`16KiB`).
    x_unit: Option<Unit>,
    /// Series names: base architecture and family.
    names: Vec<String>,
    /// Each series' family (an index into [`FAMILIES`]), for its marker.
    family_of: Vec<usize>,
    panels: Vec<Panel>,
    provenance: [String; 2],
}

/// `v` with an SI prefix (`25.6G`, `225n`), three significant digits.
#[must_use]
pub(crate) fn si(v: f64) -> String {
    const PREFIXES: [(f64, &str); 8] =
        [(1e12, "T"), (1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "µ"), (1e-9, "n")];
    if v == 0.0 {
        return "0".to_owned();
    }
    let (scale, p) = PREFIXES.iter().find(|(s, _)| v.abs() >= *s).copied().unwrap_or((1e-12, "p"));
    let s = format!("{:.3}", v / scale);
    format!("{}{p}", s.trim_end_matches('0').trim_end_matches('.'))
}

/// What binds a frame in two or three letters, as the points are marked.
const fn short(b: Bottleneck) -> &'static str {
    match b {
        Bottleneck::Setup => "S",
        Bottleneck::Raster => "R",
        Bottleneck::Depth => "D",
        Bottleneck::Shadow => "Sh",
        Bottleneck::Shade => "Sd",
        Bottleneck::DramBandwidth => "BW",
        Bottleneck::DramLatency => "LAT",
        Bottleneck::MapCacheMissesInFlight => "MC",
        Bottleneck::DepthCacheMissesInFlight => "DC",
        Bottleneck::Nothing => "-",
    }
}

/// Whether `xs` (distinct, ascending) is a geometric series of three or
/// more positive values: the axis is then logarithmic.
fn geometric(xs: &[f64]) -> bool {
    xs.len() >= 3
        && xs[0] > 0.0
        && xs.windows(3).all(|w| ((w[2] / w[1]) / (w[1] / w[0]) - 1.0).abs() < 1e-6 && w[1] / w[0] > 1.0)
}

/// A padded range over `values`.
fn range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return 0.0..1.0;
    }
    let pad = if hi > lo { (hi - lo) * 0.08 } else { lo.abs().max(1.0) * 0.1 };
    (lo - pad)..(hi + pad)
}

impl AxisPlot {
    /// An axis value as the key's files write it, else with an SI prefix.
    fn x_text(&self, x: f64) -> String {
        self.x_unit.filter(|u| u.symbol() != "-").map_or_else(|| si(x), |u| u.show(x))
    }
}

impl Figure for AxisPlot {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut labels = self.names.clone();
        labels.push(BOUND_KEY.to_owned());
        let (plot, legend_area) = with_legend(area, &labels, 250);
        let plot = plot.titled(&self.title, ("sans-serif", 18)).map_err(|e| e.to_string())?;
        #[allow(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            clippy::cast_precision_loss,
            reason = "a few panels"
        )]
        let across = (self.panels.len() as f64).sqrt().ceil().max(1.0) as usize;
        let down = self.panels.len().div_ceil(across).max(1);
        let cells = plot.split_evenly((down, across));
        let n = self.names.len();
        let all = || self.panels.iter().flat_map(|p| p.1.iter().flat_map(|s| s.1.iter()));
        // One time scale for every panel, so that panels compare.
        let yr = range(all().map(|p| p.1));
        let mut xs: Vec<f64> = distinct(all().map(|p| p.0.to_bits())).into_iter().map(f64::from_bits).collect();
        xs.sort_by(f64::total_cmp);
        let log = geometric(&xs);
        // A geometric series is drawn in log₂ of its values, labelled with
        // the values themselves.
        let at = |x: f64| if log { x.log2() } else { x };
        for ((label, series), cell) in self.panels.iter().zip(&cells) {
            let mut builder = ChartBuilder::on(cell);
            if !label.is_empty() {
                builder.caption(label, ("sans-serif", 13));
            }
            let mut chart = builder
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(range(xs.iter().map(|&x| at(x))), yr.clone())
                .map_err(|e| e.to_string())?;
            let x_desc = if log { format!("{} (log scale)", self.x_desc) } else { self.x_desc.clone() };
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc("frame time, µs")
                .x_labels(if log { 0 } else { 8 })
                .y_labels(6)
                .x_label_formatter(&|x| self.x_text(if log { x.exp2() } else { *x }))
                .y_label_formatter(&|y| si(*y))
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| e.to_string())?;
            if log {
                // The values themselves label a geometric axis.
                for &x in &xs {
                    let (px, py) = chart.backend_coord(&(at(x), yr.start));
                    area.draw(&PathElement::new(vec![(px, py), (px, py + 5)], BLACK)).map_err(|e| e.to_string())?;
                    let centre_top = Pos::new(HPos::Center, VPos::Top);
                    let label = Text::new(
                        self.x_text(x),
                        (px, py + 8),
                        ("sans-serif", 12).into_text_style(area).pos(centre_top),
                    );
                    area.draw(&label).map_err(|e| e.to_string())?;
                }
            }
            for (k, pts) in series {
                let style = colour(*k, n).stroke_width(2);
                let line = pts.iter().map(|p| (at(p.0), p.1));
                chart.draw_series(LineSeries::new(line, style)).map_err(|e| e.to_string())?;
                for p in pts {
                    let (px, py) = chart.backend_coord(&(at(p.0), p.1));
                    marker(area, (px, py), self.family_of[*k], 4, style)?;
                    area.draw(&Text::new(
                        short(p.2),
                        (px + 6, py - 14),
                        ("sans-serif", 10).into_font().color(&style.color),
                    ))
                    .map_err(|e| e.to_string())?;
                }
            }
        }
        let mut legend = Legend::new(&legend_area, &labels);
        for (k, name) in self.names.iter().enumerate() {
            let style = colour(k, n).stroke_width(2);
            let f = self.family_of[k];
            legend.entry(name, &|l, (x, y)| {
                l.draw(&PathElement::new(vec![(x - 10, y), (x + 10, y)], style)).map_err(|e| e.to_string())?;
                marker(l, (x, y), f, 4, style)
            })?;
        }
        legend.entry(BOUND_KEY, &|_, _| Ok(()))?;
        footnote(&legend_area, &self.provenance)
    }
}

/// The legend's key to the letters beside each point.
const BOUND_KEY: &str = "beside each point, what binds the frame: S setup, R raster, D depth, Sh shadow, Sd shade, BW DRAM bandwidth, LAT DRAM requests in flight, MC map cache misses in flight, DC depth cache misses in flight";

/// The axis keys of rows, in the sweep file's order (from `arch_params`).
fn axis_keys(rows: &[&Row]) -> Vec<String> {
    let params = rows.iter().map(|r| r.config.arch_params.as_str()).find(|p| !p.is_empty()).unwrap_or("");
    params.split(',').filter_map(|kv| kv.split_once('=')).map(|(k, _)| k.to_owned()).collect()
}

/// A row's value on the axis whose column is `col`: the number, or (a flag
/// or text) its position among `values`.
fn value(r: &Row, col: &str, values: &[String]) -> Option<f64> {
    let v = r.config.arch_axes.get(col)?;
    #[allow(clippy::cast_precision_loss, reason = "a few values")]
    let text = v.to_string();
    v.as_f64().or_else(|| values.iter().position(|s| *s == text).map(|k| k as f64))
}

/// For a sweep with architecture-parameter axes: the frame time of the
/// fastest configuration of each base architecture and algorithm family
/// within the loosest budget, against the first axis's value, one panel
/// per value of the others. Writes `arch-axes-<scene>.{svg,png}`; nothing
/// when the rows have no parameter axis.
///
/// # Errors
/// [`StudyError::Plot`] or [`StudyError::Output`].
pub(crate) fn arch_axes(
    folder: &mut OutputFolder,
    scene: &str,
    rows: &[&Row],
    manifest: &Manifest,
) -> Result<(), StudyError> {
    let Some(budget) = loosest(&manifest.budgets) else { return Ok(()) };
    let keys = axis_keys(rows);
    let Some(first) = keys.first() else { return Ok(()) };
    let x_col = column(first);
    let texts = distinct(rows.iter().filter_map(|r| r.config.arch_axes.get(&x_col)).map(ToString::to_string));
    // The panels: every combination of the other axes' values.
    let panel_of = |r: &Row| {
        keys[1..]
            .iter()
            .map(|k| {
                let col = column(k);
                // A number as the key's files write it (`16KiB`, `38.4GB/s`).
                let unit = PARAMS.iter().find(|p| column(p.key) == col).map(|p| p.unit);
                let value = match (r.config.arch_axes.get(&col), unit) {
                    (Some(v), Some(unit)) if unit.symbol() != "-" => {
                        v.as_f64().map_or_else(|| v.to_string(), |x| unit.show(x))
                    }
                    (Some(v), _) => v.as_f64().map_or_else(|| v.to_string().trim_matches('"').to_owned(), si),
                    (None, _) => String::new(),
                };
                format!("{k} = {value}")
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let panel_names = distinct(rows.iter().map(|r| panel_of(r)));
    let series = distinct(rows.iter().map(|r| (r.config.base_arch.clone(), r.config.family)));
    let names: Vec<String> = series.iter().map(|(b, f)| format!("{b}, {f}")).collect();
    let family_of = series.iter().map(|(_, f)| FAMILIES.iter().position(|g| g == f).unwrap_or(0)).collect();
    let panels = panel_names
        .iter()
        .map(|p| {
            let lines = series
                .iter()
                .enumerate()
                .map(|(k, (base, family))| {
                    let mine: Vec<&Row> = rows
                        .iter()
                        .copied()
                        .filter(|r| &r.config.base_arch == base && r.config.family == *family && panel_of(r) == *p)
                        .collect();
                    let mut pts: Vec<Point> =
                        distinct(mine.iter().filter_map(|r| value(r, &x_col, &texts)).map(f64::to_bits))
                            .into_iter()
                            .filter_map(|bits| {
                                let x = f64::from_bits(bits);
                                let at: Vec<&Row> =
                                    mine.iter().copied().filter(|r| value(r, &x_col, &texts) == Some(x)).collect();
                                let (best, _) = cheapest(&at, &budget, TIME)?;
                                let c = best.cost.as_ref()?;
                                let bound = if c.light_cycles > c.camera_cycles {
                                    c.light_bottleneck
                                } else {
                                    c.camera_bottleneck
                                };
                                Some((x, c.frame_seconds * 1e6, bound))
                            })
                            .collect();
                    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                    (k, pts)
                })
                .filter(|(_, pts)| !pts.is_empty())
                .collect();
            (p.clone(), lines)
        })
        .collect();
    let unit = axis_unit(&x_col);
    let fig = AxisPlot {
        title: format!("{scene}: fastest within {} against {first}", budget.short()),
        x_unit: PARAMS.iter().find(|p| p.key == first.as_str()).map(|p| p.unit),
        x_desc: if unit == "-" { first.clone() } else { format!("{first} ({unit})") },
        names,
        family_of,
        panels,
        provenance: provenance(manifest),
    };
    Ok(both(folder, &format!("arch-axes-{scene}"), &fig)?)
}
