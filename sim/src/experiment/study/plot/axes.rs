//! Frame time against architecture axes: the first swept key on the x
//! axis, ticked at its swept values only, each written as the sweep file
//! writes it (`0B`, `16KiB`): evenly spaced, or on a linear scale when
//! they are numbers within ten times of each other, a logarithmic one
//! when they span more and are all positive. One line per base
//! architecture and algorithm family (the fastest configuration within
//! the loosest budget at each value), each set a few pixels aside so that
//! none hides another, what binds its frame written beside each point and
//! keyed in the legend; one panel per value of the other axes, every
//! panel on one time scale, logarithmic when the times span more than ten
//! times.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::legend::{Item, Legend};
use super::scale::{Spacing, Swept, Ticked, TimeAxis, labelled, positions, spacing, x_range};
use super::{FAMILIES, marker, provenance};
use crate::cost::arch::{PARAMS, Unit, column};
use crate::cost::work::Bottleneck;
use crate::experiment::plot::place::{Placer, Rect, around, draw_placed, label_size, text_size};
use crate::experiment::plot::{Figure, both, colour, dodge, dodge_step};
use crate::experiment::study::rank::{TIME, cheapest};
use crate::experiment::study::{Manifest, Row, StudyError, distinct, loosest};
use crate::output::folder::OutputFolder;

/// One point: its swept value (an index into them), the frame time in
/// µs, what binds the frame.
type Point = (usize, f64, Bottleneck);

/// One panel: its label, and per series (index into the series names)
/// its points.
type Panel = (String, Vec<(usize, Vec<Point>)>);

/// The panels of the plot.
struct AxisPlot {
    title: String,
    /// The swept key, its values written with their units on the ticks.
    key: String,
    /// The x axis's values, in order.
    swept: Vec<Swept>,
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

/// What binds a frame: the letters its points are marked with, and what
/// they stand for in the legend.
const fn key(b: Bottleneck) -> (&'static str, &'static str) {
    match b {
        Bottleneck::Setup => ("S", "triangle setup"),
        Bottleneck::Raster => ("R", "raster"),
        Bottleneck::Depth => ("D", "depth"),
        Bottleneck::Shadow => ("Sh", "shadow unit"),
        Bottleneck::Shade => ("Sd", "shade"),
        Bottleneck::DramBandwidth => ("BW", "DRAM bandwidth"),
        Bottleneck::DramLatency => ("LAT", "DRAM latency (requests in flight)"),
        Bottleneck::MapCacheMissesInFlight => ("MC", "map cache misses in flight"),
        Bottleneck::DepthCacheMissesInFlight => ("DC", "depth cache misses in flight"),
        Bottleneck::Nothing => ("-", "nothing (no work)"),
    }
}

impl AxisPlot {
    /// The legend: every series (its line and marker), then the letters
    /// beside the points that occur in the plot and what they stand for.
    fn legend<DB: DrawingBackend>(&self) -> Vec<Item<'_, DB>> {
        let n = self.names.len();
        let mut items: Vec<Item<'_, DB>> = self
            .names
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let (style, f) = (colour(k, n).stroke_width(2), self.family_of[k]);
                Item::entry(name.clone(), move |l: &DrawingArea<DB, Shift>, (x, y): (i32, i32)| {
                    l.draw(&PathElement::new(vec![(x - 10, y), (x + 10, y)], style)).map_err(|e| e.to_string())?;
                    marker(l, (x, y), f, 4, style)
                })
            })
            .collect();
        let bound: Vec<Bottleneck> =
            self.panels.iter().flat_map(|p| p.1.iter().flat_map(|s| s.1.iter().map(|p| p.2))).collect();
        let mut seen: Vec<Bottleneck> = Bottleneck::ALL.into_iter().chain([Bottleneck::Nothing]).collect();
        seen.retain(|b| bound.contains(b));
        if !seen.is_empty() {
            items.push(Item::Heading("beside each point, what binds its frame:".to_owned()));
            items.extend(seen.into_iter().map(|b| Item::Key(key(b).0.to_owned(), key(b).1.to_owned())));
        }
        items
    }
}

impl Figure for AxisPlot {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        area.fill(&WHITE).map_err(|e| e.to_string())?;
        let legend = Legend::new(area, self.legend(), &self.provenance)?;
        let (plot, legend_area) = legend.split(area);
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
        // One time scale for every panel, so that panels compare.
        let times: Vec<f64> =
            self.panels.iter().flat_map(|p| p.1.iter().flat_map(|s| s.1.iter().map(|p| p.1))).collect();
        let y = TimeAxis::over(&times);
        let spacing = spacing(&self.swept);
        let t = positions(&self.swept, spacing);
        let tick_font = TextStyle::from(("sans-serif", 12));
        let mut widths = Vec::new();
        for s in &self.swept {
            widths.push(text_size(area, &s.text, &tick_font)?.0);
        }
        let x_desc = match spacing {
            Spacing::Even if self.swept.len() > 2 => format!("{} (values evenly spaced)", self.key),
            Spacing::Log => format!("{} (log scale)", self.key),
            _ => self.key.clone(),
        };
        let y_desc = if y.log { "frame time, µs (log scale)" } else { "frame time, µs" };
        let least =
            if spacing == Spacing::Even { 0.5 / self.swept.len().saturating_sub(1).max(1) as f64 } else { 0.06 };
        let letter_font = |c: RGBColor| ("sans-serif", 10).into_font().color(&c);
        for ((label, series), cell) in self.panels.iter().zip(&cells) {
            // The plot's width inside its labels and margins.
            let width = i32::try_from(cell.dim_in_pixel().0).unwrap_or(i32::MAX) - 60 - 20;
            let xr = x_range(width, widths.iter().copied().max().unwrap_or(0) / 2, least);
            let scale = f64::from(width) / (xr.end - xr.start);
            #[allow(clippy::cast_possible_truncation, reason = "pixels")]
            let px: Vec<i32> = t.iter().map(|&v| ((v - xr.start) * scale) as i32).collect();
            let named: Vec<f64> = labelled(&px, &widths).into_iter().map(|k| t[k]).collect();
            let mut builder = ChartBuilder::on(cell);
            if !label.is_empty() {
                builder.caption(label, ("sans-serif", 13));
            }
            let mut chart = builder
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(Ticked { range: xr, bold: named, light: t.clone() }, y.axis.clone())
                .map_err(|e| e.to_string())?;
            // A tick's label is its swept value's text.
            let text_at = |v: &f64| {
                let k = (0..t.len()).min_by(|&a, &b| (t[a] - v).abs().total_cmp(&(t[b] - v).abs()));
                k.map_or_else(String::new, |k| self.swept[k].text.clone())
            };
            chart
                .configure_mesh()
                .x_desc(x_desc.as_str())
                .y_desc(y_desc)
                .x_label_formatter(&text_at)
                .y_label_formatter(&|v| si(if y.log { 10f64.powf(*v) } else { *v }))
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| e.to_string())?;
            // Each series a few pixels aside.
            let step = dodge_step(px.windows(2).map(|w| w[1] - w[0]).min().unwrap_or(width), n, 10.0);
            let at = |k: usize, p: &Point| {
                let (x, y) = chart.backend_coord(&(t[p.0], y.at(p.1)));
                (x + dodge(k, n, step), y)
            };
            // Every line first, then every marker over them.
            for (k, pts) in series {
                let line: Vec<(i32, i32)> = pts.iter().map(|p| at(*k, p)).collect();
                area.draw(&PathElement::new(line, colour(*k, n).stroke_width(2))).map_err(|e| e.to_string())?;
            }
            let mut placer = Placer::new(Rect::of_ranges(chart.plotting_area().get_pixel_range()));
            for (k, pts) in series {
                for p in pts {
                    let c = at(*k, p);
                    marker(area, c, self.family_of[*k], 4, colour(*k, n).stroke_width(2))?;
                    placer.block(Rect::around(c, 6));
                }
            }
            // What binds each point beside it, where it overlaps nothing.
            for (k, pts) in series {
                let font = letter_font(colour(*k, n));
                for p in pts {
                    let (c, letters) = (at(*k, p), key(p.2).0);
                    let size = label_size(area, letters, &font)?;
                    if let Some(r) = placer.place(size, around(c, size, 8, 6, 6)) {
                        draw_placed(area, letters, &font, r, (c, 14), colour(*k, n).mix(0.5))?;
                    }
                }
            }
        }
        legend.draw(&legend_area)
    }
}

/// The axis keys of rows, in the sweep file's order (from `arch_params`).
fn axis_keys(rows: &[&Row]) -> Vec<String> {
    let params = rows.iter().map(|r| r.config.arch_params.as_str()).find(|p| !p.is_empty()).unwrap_or("");
    params.split(',').filter_map(|kv| kv.split_once('=')).map(|(k, _)| k.to_owned()).collect()
}

/// A row's value of axis `key`: its number (none for a flag or text), and
/// its text as the sweep file writes it (from `arch_params`; else the
/// number in the key's unit, or the flag or text).
fn swept(r: &Row, key: &str) -> Option<Swept> {
    let v = r.config.arch_axes.get(&column(key))?;
    let written = r.config.arch_params.split(',').filter_map(|kv| kv.split_once('=')).find(|(k, _)| *k == key);
    let unit = PARAMS.iter().find(|p| p.key == key).map(|p| p.unit).filter(|u| u.symbol() != "-");
    let text = match (written, v.as_f64(), unit) {
        (Some((_, w)), _, _) => w.to_owned(),
        (None, Some(x), Some(u)) => Unit::show(u, x),
        (None, Some(x), None) => x.to_string(),
        (None, None, _) => v.to_string().trim_matches('"').to_owned(),
    };
    Some(Swept { number: v.as_f64(), text })
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
    let mut values = distinct(rows.iter().filter_map(|r| swept(r, first)));
    if values.iter().all(|s| s.number.is_some()) {
        values.sort_by(|a, b| a.number.unwrap_or(0.0).total_cmp(&b.number.unwrap_or(0.0)));
    }
    // The panels: every combination of the other axes' values.
    let panel_of = |r: &Row| {
        let value = |k: &String| swept(r, k).map(|s| s.text).unwrap_or_default();
        keys[1..].iter().map(|k| format!("{k} = {}", value(k))).collect::<Vec<_>>().join(", ")
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
                    let pts: Vec<Point> = values
                        .iter()
                        .enumerate()
                        .filter_map(|(i, v)| {
                            let at: Vec<&Row> =
                                mine.iter().copied().filter(|r| swept(r, first).as_ref() == Some(v)).collect();
                            let (best, _) = cheapest(&at, &budget, TIME)?;
                            let c = best.cost.as_ref()?;
                            let bound =
                                if c.light_cycles > c.camera_cycles { c.light_bottleneck } else { c.camera_bottleneck };
                            Some((i, c.frame_seconds * 1e6, bound))
                        })
                        .collect();
                    (k, pts)
                })
                .filter(|(_, pts)| !pts.is_empty())
                .collect();
            (p.clone(), lines)
        })
        .collect();
    let fig = AxisPlot {
        title: format!("{scene}: fastest within {} against {first}", budget.short()),
        key: first.clone(),
        swept: values,
        names,
        family_of,
        panels,
        provenance: provenance(manifest),
    };
    Ok(both(folder, &format!("arch-axes-{scene}"), &fig)?)
}
