//! The figures a study draws, kept as they are drawn (every text with the
//! box it takes, every stroke with its colour) and read back from their
//! PNGs: the architecture-axes plot ticks its x axis at the swept values
//! as the sweep file writes them, no text overlaps another in any figure,
//! and every line's markers show over everything drawn after them.

use super::{bandwidth_rows, manifest, row, twelve_rows};
use crate::experiment::plot::colour;
use crate::experiment::plot::record::{self, Record, assert_legible, showing};
use crate::experiment::study::tests::scratch::Scratch;
use crate::experiment::study::tests::scratch_dir;
use crate::experiment::study::{Row, RowConfig, write_run};
use crate::output::folder::{Claim, OutputFolder, RunKind};

/// Rows as `examples/sweep.toml` makes them: talisman and own-tbdr, each
/// at map-cache sizes of 0B, 16KiB and 64KiB, with first depth at three
/// biases and dual depth at two. Talisman is raster-bound near 1.2 ms;
/// own-tbdr is bound by DRAM latency near 13 µs, where both families take
/// the same time, so that their lines coincide.
fn sweep_rows() -> Vec<Row> {
    let variants = [
        ("first", "first depth", 6.4),
        ("first", "first depth", 1.3),
        ("first", "first depth", 0.26),
        ("dual", "midpoint and dual", 0.15),
        ("dual", "midpoint and dual", 0.03),
    ];
    let mut rows = Vec::new();
    for (base, cycles, bound) in [("talisman", 120_000u64, "raster"), ("own-tbdr", 1_300, "dram-latency")] {
        for (k, (size, bytes)) in [("0B", 0.0), ("16KiB", 16_384.0), ("64KiB", 65_536.0)].into_iter().enumerate() {
            for (index, &(algorithm, family, artifacts)) in variants.iter().enumerate() {
                let arch = format!("{base}-map_cache_size-{size}");
                let params = format!("map_cache.size={size}");
                // Talisman's first depth a little slower than its dual.
                let slower = if base == "talisman" && family == "first depth" { 4_000 } else { 0 };
                let camera = cycles - cycles / 5 + slower + 100 * k as u64;
                let r = row(
                    index,
                    (algorithm, family),
                    [320, 180],
                    (&arch, &params),
                    artifacts,
                    (cycles / 5, camera),
                    1_000,
                    1.0,
                    bound,
                );
                let mut axes = std::collections::BTreeMap::new();
                axes.insert("arch_map_cache_size_bytes".to_owned(), serde_json::json!(bytes));
                let config = RowConfig { base_arch: base.to_owned(), arch_axes: axes, ..r.config };
                rows.push(Row { arch_index: rows.len(), config, ..r });
            }
        }
    }
    rows
}

/// The near/far curves of the extremes' precision plot as a run of
/// table-and-sphere draws them: misclassified % against the light's
/// far/near for four algorithms in d16 and d24, several on one value.
fn precision_series() -> Vec<(String, Vec<(f64, f64)>)> {
    let curves: [(&str, [f64; 6]); 8] = [
        ("first d16: breaks down at 1e3", [0.24, 0.45, 15.5, 15.5, 15.5, 15.5]),
        ("first d24: breaks down at 1e3", [0.24, 0.44, 15.5, 15.5, 15.5, 15.5]),
        ("second d16: breaks down at 1e5", [0.16, 0.16, 0.16, 0.5, 9.0, 15.5]),
        ("second d24: never breaks down", [0.16, 0.17, 0.16, 0.17, 0.16, 0.23]),
        ("midpoint d16: breaks down at 1e5", [0.25, 0.23, 0.26, 0.75, 7.1, 15.3]),
        ("midpoint d24: never breaks down", [0.25, 0.25, 0.25, 0.25, 0.25, 0.35]),
        ("dual d16: breaks down at 1e5", [0.19, 0.18, 0.17, 0.37, 7.0, 15.3]),
        ("dual d24: never breaks down", [0.19, 0.18, 0.18, 0.18, 0.18, 0.18]),
    ];
    let ratios = [1e1, 1e2, 1e3, 1e4, 1e5, 1e6];
    curves
        .iter()
        .map(|(name, ys)| ((*name).to_owned(), ratios.iter().copied().zip(ys.iter().copied()).collect()))
        .collect()
}

/// The study `rows` make, written into a scratch folder `name` (of this
/// test alone): the folder (removed when dropped) and every figure as it
/// was drawn.
fn study(name: &str, rows: &[Row]) -> (Scratch, Vec<(String, Record)>) {
    let dir = scratch_dir("umbra-figures", name);
    let _ = record::take();
    write_run(&dir.0, rows, &manifest()).expect("written");
    let figures = record::take();
    assert!(!figures.is_empty(), "{name}: no figure drawn");
    (dir, figures)
}

/// The precision plot of [`precision_series`], as the extremes draw it,
/// written into a scratch folder `name` (of this test alone): the folder
/// and the figure as drawn.
fn precision(name: &str) -> (Scratch, Record) {
    let dir = scratch_dir("umbra-figures", name);
    let out = dir.0.join("out");
    let mut folder = OutputFolder::create(&out, Claim::new(RunKind::Study)).expect("a folder");
    let _ = record::take();
    let series = precision_series();
    let title = "Depth precision against the light's far/near (table-and-sphere)";
    let descs = ("light far / near (f32 lies on d24)", "misclassified %");
    crate::experiment::study::plot::lines(&mut folder, "precision", title, descs.0, descs.1, &series).expect("drawn");
    folder.finish(None).expect("finished");
    let mut figures = record::take();
    assert_eq!(figures.len(), 1);
    (dir, figures.remove(0).1)
}

/// The record of the figure `name` among `figures`.
fn figure<'a>(figures: &'a [(String, Record)], name: &str) -> &'a Record {
    &figures.iter().find(|f| f.0 == name).unwrap_or_else(|| panic!("no {name}")).1
}

/// The architecture-axes plot ticks its x axis at the swept values only,
/// each as the sweep file writes it — `0B`, `16KiB`, `64KiB` (evenly
/// spaced: they start at zero), bandwidths within ten times linearly and
/// spanning more on a log scale — each labelled once a panel; the axis
/// names the key alone (its ticks carry the unit); the time axis is
/// logarithmic where the times span more than ten times.
#[test]
fn arch_axes_ticks_are_the_swept_values_as_written() {
    let cases: [(&str, Vec<Row>, &[&str], &str); 4] = [
        ("sweep", sweep_rows(), &["0B", "16KiB", "64KiB"], "map_cache.size (values evenly spaced)"),
        ("linear", bandwidth_rows(&[1, 2, 4]), &["1GB/s", "2GB/s", "4GB/s"], "dram.bandwidth"),
        ("log", bandwidth_rows(&[1, 4, 16, 64]), &["1GB/s", "4GB/s", "16GB/s", "64GB/s"], "dram.bandwidth (log scale)"),
        ("twelve", twelve_rows(), &["1GB/s", "2GB/s", "4GB/s"], "dram.bandwidth"),
    ];
    for (name, rows, written, desc) in cases {
        let (_dir, figures) = study(&format!("ticks-{name}"), &rows);
        let axes = figure(&figures, "arch-axes-synthetic");
        // An x axis's tick labels hang centred below their ticks; the
        // title and the panels' captions are the other texts set so.
        let ticks: Vec<&str> = axes
            .texts
            .iter()
            .filter(|t| t.upright && t.anchor == "center top")
            .map(|t| t.text.as_str())
            .filter(|t| !t.starts_with("synthetic:") && !t.contains(" = "))
            .collect();
        assert!(!ticks.is_empty(), "{name}: no ticks");
        for t in &ticks {
            assert!(written.contains(t), "{name}: tick `{t}` is not a swept value as written ({written:?})");
        }
        // Each value labelled once in each panel.
        for w in written {
            let times = ticks.iter().filter(|t| *t == w).count();
            assert!(
                times > 0 && times * written.len() == ticks.len(),
                "{name}: `{w}` labelled {times} times: {ticks:?}"
            );
        }
        let texts: Vec<&str> = axes.texts.iter().map(|t| t.text.as_str()).collect();
        assert!(texts.contains(&desc), "{name}: no `{desc}` among {texts:?}");
    }
    let (_dir, figures) = study("ticks-times", &sweep_rows());
    let texts: Vec<&str> = figure(&figures, "arch-axes-synthetic").texts.iter().map(|t| t.text.as_str()).collect();
    assert!(texts.contains(&"frame time, µs (log scale)"), "{texts:?}");
}

/// No text overlaps another, nor leaves the image, in any figure a study
/// draws — its Pareto plots and architecture-axes plot of a sweep like
/// the example's, of twelve architectures at six points each, of two at
/// three bandwidths — or in the extremes' precision plot.
#[test]
fn no_text_overlaps_another_in_any_study_figure() {
    let mut checked = 0;
    for (name, rows) in [("sweep", sweep_rows()), ("twelve", twelve_rows()), ("bandwidths", bandwidth_rows(&[1, 2, 4]))]
    {
        let (_dir, figures) = study(&format!("legible-{name}"), &rows);
        for (figure, record) in &figures {
            assert_legible(&format!("{name}: {figure}"), record);
            checked += 1;
        }
    }
    let (_dir, record) = precision("legible-precision");
    assert_legible("precision", &record);
    // Pareto plots of time and bytes and an architecture-axes plot each.
    assert!(checked >= 9, "{checked} figures");
}

/// Every line's markers show: after everything is drawn, at least half
/// of each marker's outline is in its series' colour in the PNG, in the
/// architecture-axes plot of the example-like sweep (own-tbdr's two
/// families take the same time at every size) and in the precision plot
/// (several curves on one value).
#[test]
fn every_line_shows_its_markers() {
    let (dir, figures) = study("markers", &sweep_rows());
    let (precision_dir, precision) = precision("markers-precision");
    let cases = [
        (dir.0.join("arch-axes-synthetic.png"), figure(&figures, "arch-axes-synthetic"), 4),
        (precision_dir.0.join("out").join("precision.png"), &precision, 8),
    ];
    for (path, record, n) in cases {
        let png = image::open(&path).expect("the PNG").to_rgb8();
        for k in 0..n {
            let c = colour(k, n);
            let rgb = (c.0, c.1, c.2);
            let markers = record.markers(rgb);
            // The legend's and at least one on the chart.
            assert!(markers.len() >= 2, "{}: series {k} has {} markers", path.display(), markers.len());
            for m in &markers {
                let shown = showing(&png, m, rgb);
                assert!(shown >= 0.5, "{}: series {k}'s marker near {:?} shows {shown:.2}", path.display(), m[0]);
            }
        }
    }
}

/// Each artifact budget's dashed line is labelled with its value at the
/// right of the plot, within it: a budget below the smallest error
/// (0.0001 %) extends the axis down to its line rather than fall off it.
#[test]
fn every_budget_is_labelled_on_the_plot() {
    use crate::experiment::study::budget::Budget;
    let dir = scratch_dir("umbra-figures", "budgets");
    let budgets = [1.0, 0.1, 0.0001].map(Budget::artifacts).to_vec();
    let _ = record::take();
    write_run(&dir.0, &sweep_rows(), &crate::experiment::study::Manifest { budgets, ..manifest() }).expect("written");
    let figures = record::take();
    let pareto = figure(&figures, "pareto-synthetic-time");
    assert_legible("pareto-synthetic-time", pareto);
    // The plot ends where the x axis's tick labels begin.
    let bottom = pareto.texts.iter().filter(|t| t.upright && t.anchor == "center top").map(|t| t.rect.y0).max();
    let bottom = bottom.expect("x ticks");
    for b in ["1 %", "0.1 %", "0.0001 %"] {
        let label = pareto.texts.iter().find(|t| t.text == b).unwrap_or_else(|| panic!("no `{b}`"));
        assert!(label.rect.y1 < bottom, "`{b}` at {:?} is below the plot (ticks from {bottom})", label.rect);
    }
}
