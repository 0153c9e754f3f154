//! The summary from a synthetic results file whose answers are known: the
//! cheapest row under each budget in cycles, bytes and energy; ties and
//! how they were broken; a budget below one pixel flagged; the winner by
//! image size; the image size at which shadow volumes stop being the
//! cheapest; the bottleneck an architecture parameter moves.

use crate::cost::work::Bottleneck;
use crate::experiment::study::{Manifest, Row, RowConfig, RowCost, RowMetrics, Status, summary};

mod figures;

/// A row: `algorithm` of `family` at `image` on `arch` (`params`), with
/// `artifacts` percent of 10 000 evaluated pixels, and its costs: light and
/// camera cycles, bytes, energy, and the camera pass's bottleneck; at
/// 100 MHz.
#[allow(clippy::too_many_arguments, reason = "a synthetic row")]
fn row(
    index: usize,
    (algorithm, family): (&str, &str),
    image: [u32; 2],
    (arch, params): (&str, &str),
    artifacts: f64,
    (light, camera): (u64, u64),
    bytes: u64,
    energy_uj: f64,
    bottleneck: &str,
) -> Row {
    Row {
        config_index: index,
        arch_index: 0,
        config: RowConfig {
            scene: "synthetic".into(),
            algorithm: algorithm.into(),
            family: family.parse().expect("a family"),
            bias: 0.0,
            bias1: None,
            offset: None,
            virtual_samples: Some(true),
            culling: crate::Culling::ALGORITHM,
            depth_format: umbra_core::DepthFormatKind::D16,
            map_side_texels: 256,
            filter_name: umbra_core::shadow::Filter::Point,
            cascades: "scene".into(),
            arch: arch.into(),
            base_arch: arch.into(),
            arch_params: params.into(),
            arch_axes: std::collections::BTreeMap::new(),
            image_width_px: image[0],
            image_height_px: image[1],
            reference_rays: 1,
            command: String::new(),
            umbra_version: String::new(),
            sweep_hash: String::new(),
        },
        status: Status::Ok,
        reason: String::new(),
        metrics: Some(RowMetrics {
            evaluated_px: 10_000,
            misclassified_percent: artifacts + 0.5,
            artifact_percent: artifacts,
            ..RowMetrics::default()
        }),
        cost: Some(RowCost {
            light_cycles: light,
            camera_cycles: camera,
            total_cycles: light + camera,
            total_dram_bytes: bytes,
            energy_joules: energy_uj * 1e-6,
            #[allow(clippy::cast_precision_loss, reason = "small counts")]
            frame_seconds: (light + camera) as f64 / 1e8,
            clock_hertz: 1e8,
            light_bottleneck: Bottleneck::Depth,
            camera_bottleneck: bottleneck.parse().expect("a bottleneck"),
            ..RowCost::default()
        }),
    }
}

fn manifest() -> Manifest {
    Manifest {
        sweep: "synthetic".into(),
        sweep_hash: "0".into(),
        umbra_version: "test".into(),
        shard: "0/1".into(),
        configurations: 5,
        layout: crate::experiment::study::Layout { configurations: 5, variants: 5, formats: 1, maps: 1, filters: 1 },
        architectures: 1,
        rows: 6,
        budgets: [1.0, 0.1, 0.001].map(crate::experiment::study::budget::Budget::artifacts).to_vec(),
        cost_limits: crate::experiment::study::objective::CostLimits::default(),
        command: String::new(),
    }
}

/// The line of `md` for `budget` and cost `what`.
fn line<'a>(md: &'a str, budget: &str, what: &str) -> &'a str {
    md.lines().find(|l| l.starts_with(&format!("| {budget} ")) && l.contains(&format!("| {what} |"))).expect("a line")
}

#[test]
fn summary_answers_what_wins_where() {
    let (small, large) = ([100, 100], [200, 100]);
    let (a, b) = (("talisman", "dram.bandwidth=1GB/s"), ("talisman", "dram.bandwidth=8GB/s"));
    let rows = vec![
        // At 100×100 (10 000 px): volumes 2 cycles a pixel, 20 000; the map
        // 10 000 + 1 a pixel, 20 000 too: a tie in cycles, broken by order.
        row(0, ("volumes", "shadow volumes"), small, a, 0.0, (0, 20_000), 900, 5.0, "depth"),
        row(1, ("second-ffc", "second depth"), small, a, 0.05, (10_000, 10_000), 500, 4.0, "dram-bandwidth"),
        // First depth: cheapest in energy but 0.5 % artifacts.
        row(2, ("first", "first depth"), small, a, 0.5, (9_000, 12_000), 700, 1.0, "dram-bandwidth"),
        // At 200×100: volumes 40 000, the map 30 000.
        row(3, ("volumes", "shadow volumes"), large, a, 0.0, (0, 40_000), 1_800, 9.0, "depth"),
        row(4, ("second-ffc", "second depth"), large, a, 0.05, (10_000, 20_000), 800, 6.0, "dram-bandwidth"),
        // The same map configuration on a faster DRAM: shadow-bound.
        Row {
            arch_index: 1,
            ..row(4, ("second-ffc", "second depth"), large, b, 0.05, (10_000, 15_000), 800, 6.0, "shadow")
        },
    ];
    let md = summary(&rows, &manifest());
    println!("{md}");
    // 1 %: cycles — rows 0 and 1 tie at 20 000, row 0 first in order.
    let l = line(&md, "1 %", "cycles");
    assert!(l.contains("volumes") && l.contains("| 20000 |") && l.contains("2 tie"), "{l}");
    // 1 %: bytes — the map at 500; energy — first depth at 1 µJ.
    assert!(line(&md, "1 %", "DRAM bytes").contains("second-ffc"), "{md}");
    assert!(line(&md, "1 %", "energy (µJ)").contains("first") && line(&md, "1 %", "energy (µJ)").contains("| 1.000 |"));
    // 0.1 %: first depth's 0.5 % no longer meets it: energy goes to the map.
    assert!(line(&md, "0.1 %", "energy (µJ)").contains("second-ffc"), "{md}");
    // 0.001 % is below one pixel of 10 000 (0.01 %): flagged, and met only
    // by the volumes' zero.
    let l = line(&md, "0.001 %", "cycles");
    assert!(l.contains("below one pixel") && l.contains("volumes"), "{l}");
    // Per family, in each cost: first depth meets only 1 %, at 1 µJ.
    // Every architecture runs at 100 MHz: cycles rank, and the summary says so.
    assert!(md.contains("every architecture runs at 100 MHz, so cycles rank as time does"), "{md}");
    // Each cell names the architecture point that won.
    assert!(md.contains("Cheapest per algorithm family in energy (µJ):"), "{md}");
    assert!(
        md.contains(
            "| first depth | first bias 0, d16, 256², point, talisman (dram.bandwidth=1GB/s) (1.000) | – | – |"
        ),
        "{md}"
    );
    // The winner by image size: volumes (first of the tie) at 100×100, the
    // map at 200×100.
    assert!(md.contains("by image size: 100×100: shadow volumes; 200×100: second depth"), "{md}");
    // Volumes cost 2 a pixel; the cheapest map 1 a pixel plus 10 000: they
    // cross at 10 000 pixels.
    assert!(md.contains("They cross at about 10000 pixels"), "{md}");
    // The DRAM bandwidth moves the map configuration's camera pass from
    // bound by the DRAM's bandwidth to bound by the shadow unit; 30 000
    // cycles at 100 MHz are 300 µs.
    let ffc = "second-ffc, d16, 256², point";
    let at = |params: &str, cycles: u64, us: &str, camera: &str| {
        format!("| {ffc} | talisman | {params} | {cycles} | {us} | 0.0 | 0.0 | depth | {camera} |")
    };
    assert!(md.contains(&at("dram.bandwidth=1GB/s", 30_000, "300.000", "dram-bandwidth")), "{md}");
    assert!(md.contains(&at("dram.bandwidth=8GB/s", 25_000, "250.000", "shadow")), "{md}");
    assert!(md.contains(&format!("| {ffc}: the parameters move its bottleneck |")), "{md}");
}

/// Two architectures whose frames take the same cycles at different clocks:
/// the faster clock wins, ranked by time, and the summary says time ranks.
/// Cycles would tie (and the tie would go to the first in sweep order).
#[test]
fn different_clocks_rank_by_time() {
    let at = |k: usize, arch: &str, clock: f64| {
        let r =
            row(k, ("second-ffc", "second depth"), [100, 100], (arch, ""), 0.05, (10_000, 10_000), 500, 4.0, "depth");
        let cost = r.cost.clone().map(|c| RowCost { clock_hertz: clock, frame_seconds: 20_000.0 / clock, ..c });
        Row { arch_index: k, cost, ..r }
    };
    // 20 000 cycles: 200 µs at 100 MHz, 100 µs at 200 MHz.
    let rows = vec![at(0, "slow", 1e8), Row { config_index: 0, ..at(1, "fast", 2e8) }];
    let md = summary(&rows, &manifest());
    assert!(md.contains("the architectures' clocks differ, so time ranks, not cycles"), "{md}");
    let l = line(&md, "1 %", "time (µs)");
    assert!(l.contains(", fast |") && l.contains("| 100.000 |") && !l.contains("tie"), "{l}");
    assert!(!md.contains("| cycles |"), "{md}");
}

/// Scene names become file names only as slugs: a name that climbs out of
/// the folder writes inside it, a dot does not turn one plot into another,
/// and two names with one slug are refused rather than overwrite each other.
#[test]
fn scene_names_never_become_paths() {
    let base = super::scratch_dir("umbra-summary", "slug");
    let _ = std::fs::remove_dir_all(&base);
    let out = base.join("inside").join("out");
    let named = |name: &str, k: usize| {
        let r = row(k, ("second-ffc", "second depth"), [100, 100], ("talisman", ""), 0.05, (1, 1), 1, 1.0, "depth");
        Row { config: RowConfig { scene: name.into(), ..r.config }, ..r }
    };
    let rows = vec![named("/../../../ESCAPED", 0), named("table.v2", 1)];
    crate::experiment::study::write_run(&out, &rows, &manifest()).expect("written");
    let mut names: Vec<String> =
        std::fs::read_dir(&out).expect("out").map(|e| e.expect("entry").file_name().to_string_lossy().into()).collect();
    names.sort();
    for f in ["pareto-__________ESCAPED-time.png", "pareto-table_v2-bytes.svg", "pareto-table_v2-time.svg"] {
        assert!(names.iter().any(|n| n == f), "{f} not in {names:?}");
    }
    // Nothing beside or above the output folder.
    let above: Vec<_> = std::fs::read_dir(base.join("inside")).expect("dir").collect();
    assert_eq!(above.len(), 1, "only out/ inside {}", base.display());
    assert!(!base.join("ESCAPED-time.png").exists() && std::fs::read_dir(&base).expect("dir").count() == 1);
    let clash = vec![named("a.b", 0), named("a/b", 1)];
    let e = crate::experiment::study::write_run(&base.join("clash"), &clash, &manifest()).expect_err("clash");
    assert!(e.to_string().contains("`a.b` and `a/b`"), "{e}");
    let _ = std::fs::remove_dir_all(&base);
}

/// Two base architectures, talisman and immediate, each swept over the
/// DRAM bandwidths `gbs` (GB/s): a frame of second depth on each, its
/// camera pass the faster the more bandwidth.
fn bandwidth_rows(gbs: &[u32]) -> Vec<Row> {
    let mut rows = Vec::new();
    for arch in ["talisman", "immediate"] {
        for gb in gbs {
            let params = format!("dram.bandwidth={gb}GB/s");
            let name = format!("{arch}-dram_bandwidth-{gb}GB_s");
            let camera = 10_000 / u64::from(*gb);
            let r = row(
                0,
                ("second-ffc", "second depth"),
                [100, 100],
                (&name, &params),
                0.05,
                (10_000, camera),
                1,
                1.0,
                "depth",
            );
            let mut axes = std::collections::BTreeMap::new();
            axes.insert("arch_dram_bandwidth_bytes_per_second".to_owned(), serde_json::json!(f64::from(*gb) * 1e9));
            let config = RowConfig { base_arch: arch.to_owned(), arch_axes: axes, ..r.config };
            rows.push(Row { arch_index: rows.len(), config, ..r });
        }
    }
    rows
}

/// Two base architectures swept over DRAM bandwidths: the
/// architecture-axes plot draws one line for each, a point a bandwidth,
/// on a numeric axis ticked at the bandwidths as written (read from the
/// SVG's polylines and text) — 1, 2 and 4 GB/s, within ten times of each
/// other, linearly; 1 to 64 GB/s on a log scale — and the palette keeps
/// twelve architectures apart.
#[test]
fn the_arch_axes_plot_is_numeric_with_a_line_per_base() {
    use crate::experiment::plot::{colour, log_ticks, tick_label};
    for (gbs, desc) in [(&[1u32, 2, 4][..], "dram.bandwidth"), (&[1, 4, 16, 64], "dram.bandwidth (log scale)")] {
        let base = super::scratch_dir("umbra-summary", &format!("axes-{}", gbs.len()));
        let _ = std::fs::remove_dir_all(&base);
        crate::experiment::study::write_run(&base, &bandwidth_rows(gbs), &manifest()).expect("written");
        let svg = std::fs::read_to_string(base.join("arch-axes-synthetic.svg")).expect("the plot");
        // Each base's line: a point a bandwidth, in its colour.
        for k in 0..2 {
            let c = colour(k, 2);
            let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
            let lines: Vec<&str> = svg
                .split("<polyline")
                .skip(1)
                .filter(|p| p.contains(&stroke))
                .filter_map(|p| p.split("points=\"").nth(1)?.split('"').next())
                .filter(|pts| pts.split_whitespace().count() == gbs.len())
                // Not a marker: a marker's outline closes on itself.
                .filter(|pts| pts.split_whitespace().next() != pts.split_whitespace().last())
                .collect();
            assert_eq!(lines.len(), 1, "base {k}: {lines:?}");
        }
        let texts: Vec<&str> =
            svg.split("<text").skip(1).filter_map(|t| Some(t.split('>').nth(1)?.split('<').next()?.trim())).collect();
        for gb in gbs {
            let tick = format!("{gb}GB/s");
            assert!(texts.contains(&tick.as_str()), "{tick} not among {texts:?}");
        }
        // The ticks carry the unit: the axis names only the key.
        assert!(texts.contains(&desc), "{desc} not among {texts:?}");
        let _ = std::fs::remove_dir_all(&base);
    }
    // Twelve colours, no two alike (each channel apart by more than a
    // rounding, summed over the channels).
    let twelve: Vec<_> = (0..12).map(|k| colour(k, 12)).collect();
    for (i, a) in twelve.iter().enumerate() {
        for b in &twelve[i + 1..] {
            let d = (i32::from(a.0) - i32::from(b.0)).abs()
                + (i32::from(a.1) - i32::from(b.1)).abs()
                + (i32::from(a.2) - i32::from(b.2)).abs();
            assert!(d > 40, "{a:?} and {b:?} are too close");
        }
    }
    // A log axis within one decade still has labelled ticks.
    let (bold, light) = log_ticks(&(8e5..3e6));
    assert_eq!(bold, [1e6, 2e6]);
    assert!(light.len() > bold.len());
    assert_eq!(bold.iter().map(|&v| tick_label(v)).collect::<Vec<_>>(), ["1e6", "2e6"]);
}

/// Every text element of an SVG: its x, y and content.
fn texts(svg: &str) -> Vec<(f64, f64, String)> {
    let attr = |t: &str, name: &str| -> f64 {
        t.split(&format!(" {name}=\""))
            .nth(1)
            .and_then(|v| v.split('"').next())
            .and_then(|v| v.parse().ok())
            .expect("a coordinate")
    };
    svg.split("<text")
        .skip(1)
        .map(|t| {
            let content = t.split('>').nth(1).and_then(|c| c.split('<').next()).unwrap_or("").trim().to_owned();
            (attr(t, "x"), attr(t, "y"), content)
        })
        .collect()
}

/// Twelve base architectures (names as long as a sweep makes them), each
/// at three DRAM bandwidths and two map-cache sizes.
fn twelve_rows() -> Vec<Row> {
    let mut rows = Vec::new();
    for b in 0..12u64 {
        for gb in &[1u64, 2, 4] {
            for (c, kib) in [16u64, 64].iter().enumerate() {
                let arch = format!("an-architecture-of-our-own-number-{b}");
                let params = format!("dram.bandwidth={gb}GB/s,map_cache.size={kib}KiB");
                let name = format!("{arch}-dram_bandwidth-{gb}GB_s-map_cache_size-{kib}KiB");
                let r = row(
                    0,
                    ("second-ffc", "second depth"),
                    [100, 100],
                    (&name, &params),
                    0.01 * (1.0 + b as f64),
                    (10_000 + 100 * b, 10_000 / gb + 10 * c as u64),
                    1,
                    1.0,
                    "dram-bandwidth",
                );
                let mut axes = std::collections::BTreeMap::new();
                axes.insert("arch_dram_bandwidth_bytes_per_second".to_owned(), serde_json::json!(*gb as f64 * 1e9));
                axes.insert("arch_map_cache_size_bytes".to_owned(), serde_json::json!(*kib as f64 * 1024.0));
                let config = RowConfig { base_arch: arch, arch_axes: axes, ..r.config };
                rows.push(Row { arch_index: rows.len(), config, ..r });
            }
        }
    }
    rows
}

/// Twelve base architectures (names as long as a sweep makes them), each
/// at three DRAM bandwidths, in two panels of map-cache size: every plot
/// a study writes keeps its legend inside the image and above its
/// footnote (every text's coordinates read from the SVG), and each
/// panel's title gives its value as a number with a prefix, as the key's
/// files write it (`16KiB`), which reads back as the value.
#[test]
fn plots_of_twelve_architectures_keep_their_legends_and_read_in_si() {
    let base = super::scratch_dir("umbra-summary", "twelve");
    let _ = std::fs::remove_dir_all(&base);
    let rows = twelve_rows();
    crate::experiment::study::write_run(&base, &rows, &manifest()).expect("written");
    let (w, h) = (f64::from(crate::experiment::plot::SIZE.0), f64::from(crate::experiment::plot::SIZE.1));
    let mut plots = 0;
    for entry in std::fs::read_dir(&base).expect("the folder") {
        let path = entry.expect("an entry").path();
        if path.extension().is_none_or(|e| e != "svg") {
            continue;
        }
        plots += 1;
        let all = texts(&std::fs::read_to_string(&path).expect("the plot"));
        let footnote = all.iter().filter(|t| t.2.starts_with("sweep ")).map(|t| t.1).fold(h, f64::min);
        for (x, y, text) in &all {
            assert!((0.0..=w).contains(x) && (0.0..=h).contains(y), "{}: `{text}` at ({x}, {y})", path.display());
        }
        // The legend's last lines end above the footnote's.
        let legend: Vec<&(f64, f64, String)> = all.iter().filter(|t| t.2.starts_with("an-architecture")).collect();
        assert!(!legend.is_empty(), "{}: no legend", path.display());
        for (_, y, text) in &legend {
            assert!(*y < footnote - 20.0, "{}: `{text}` at {y} runs into the footnote at {footnote}", path.display());
        }
        if path.file_name().is_some_and(|n| n.to_string_lossy().starts_with("arch-axes")) {
            let titles: Vec<&String> =
                all.iter().map(|t| &t.2).filter(|t| t.starts_with("map_cache.size = ")).collect();
            assert_eq!(titles.len(), 2, "{titles:?}");
            // Each reads back, through the key's own unit, as its value.
            let mut read: Vec<f64> = titles
                .iter()
                .map(|t| crate::cost::arch::Unit::Bytes.parse(t.trim_start_matches("map_cache.size = ")).expect(t))
                .collect();
            read.sort_by(f64::total_cmp);
            assert_eq!(read, [16384.0, 65536.0], "{titles:?}");
        }
    }
    assert!(plots >= 2, "{plots} plots");
    let _ = std::fs::remove_dir_all(&base);
}

/// A budget on another measure judges rows by it: misclassified pixels
/// are artifacts + 0.5 % in these rows, so `misclassified=0.52%` admits
/// only the rows with at most 0.02 % artifacts (the volumes' 0), and
/// `acne=0.01%` every row (none has acne).
#[test]
fn a_budget_on_another_measure_judges_by_it() {
    use crate::experiment::study::budget::Budget;
    let small = [100, 100];
    let a = ("talisman", "");
    let rows = vec![
        row(0, ("volumes", "shadow volumes"), small, a, 0.0, (0, 30_000), 900, 5.0, "depth"),
        row(1, ("second-ffc", "second depth"), small, a, 0.05, (10_000, 10_000), 500, 4.0, "depth"),
    ];
    let budgets: Vec<Budget> = ["misclassified=0.52%", "acne=0.01%"].map(|b| b.parse().expect("a budget")).to_vec();
    let md = summary(&rows, &Manifest { budgets, ..manifest() });
    let l = line(&md, "misclassified 0.52 %", "cycles");
    assert!(l.contains("volumes") && l.contains("| 30000 |"), "{l}");
    let l = line(&md, "acne 0.01 %", "cycles");
    assert!(l.contains("second-ffc") && l.contains("| 20000 |"), "{l}");
}

/// The best per objective stays within the cost limits: the volumes'
/// 9 µJ row is left out under `--max-energy 8uJ`, so the fastest within
/// the limit is the map's; without a limit, volumes are the fastest.
#[test]
fn the_best_per_objective_keeps_within_the_cost_limits() {
    use crate::experiment::study::objective::CostLimits;
    let (small, a) = ([100, 100], ("talisman", ""));
    let rows = vec![
        row(0, ("volumes", "shadow volumes"), small, a, 0.0, (0, 15_000), 900, 9.0, "depth"),
        row(1, ("second-ffc", "second depth"), small, a, 0.05, (10_000, 10_000), 500, 4.0, "depth"),
    ];
    let best = |md: &str| {
        md.lines().find(|l| l.starts_with("| 1 % | cycles |") && l.contains("the fastest too")).map(str::to_owned)
    };
    let free = summary(&rows, &manifest());
    assert!(best(&free).is_some_and(|l| l.contains("volumes")), "{free}");
    let limits = CostLimits::parse(None, Some("8uJ")).expect("a limit");
    let md = summary(&rows, &Manifest { cost_limits: limits, ..manifest() });
    assert!(md.contains("within energy ≤ 8 µJ"), "{md}");
    assert!(best(&md).is_some_and(|l| l.contains("second-ffc")), "{md}");
}
