//! The trade study's own guarantees: the same bytes on any thread count,
//! shards that merge into exactly the whole run, a Pareto front checked by
//! hand, and the numerical extremes (near/far ratio, grazing light, guard
//! band, slivers, coincident surfaces) finite, without a panic, and
//! degrading monotonically with the near/far ratio.

use std::path::Path;

use crate::Algorithm;
use crate::cost::arch::Arch;
use crate::experiment::study::extremes::{self, RATIOS};
use crate::experiment::study::plot::pareto_front;
use crate::experiment::study::{self, Manifest, Row, Shard, Spec, Status, Variant};
use crate::input::limits::Limits;
use crate::world::scene::Scene;
use umbra_core::DepthFormatKind;

/// A scratch folder of this test process for `name`, removed when dropped.
fn dir(name: &str) -> super::scratch::Scratch {
    super::scratch_dir("umbra-study", name)
}

/// A small sweep with every preset: two scenes, two algorithms, two
/// formats, two filters, 64×36 images.
fn small() -> Spec {
    let scenes = study::load_scenes(&["table-and-sphere", "weiskopf-l"], &Limits::DEFAULT).expect("bundled");
    let mut spec = Spec::quick(scenes);
    spec.variants = vec![Variant::new(Algorithm::First, 0.002), Variant::new(Algorithm::Dual { offset: 0.005 }, 0.0)];
    spec.map_sizes = vec![128];
    spec.images = vec![[64, 36]];
    spec.reference_rays = 1;
    spec
}

/// The manifest of a whole run of `spec`.
fn whole(spec: &Spec, rows: &[Row]) -> Manifest {
    Manifest::new(spec, Shard::ALL, rows.len())
}

/// A sweep's limits hold for every configuration: a map above
/// `max_map_side` is a skipped row that names the limit, on every preset,
/// and the maps within it render as they do under the default limits.
#[test]
fn configurations_beyond_the_sweeps_limits_are_skipped_rows_naming_them() {
    let mut spec = small();
    spec.scenes.truncate(1);
    spec.variants.truncate(1);
    spec.formats.truncate(1);
    spec.map_sizes = vec![64, 128];
    let default = run_on(1, &spec, Shard::ALL);
    spec.limits = Limits { max_map_side: 64, ..Limits::DEFAULT };
    let limited = run_on(1, &spec, Shard::ALL);
    assert_eq!(limited.len(), default.len());
    let side = |r: &Row| r.config.map_side_texels;
    assert!(limited.iter().any(|r| side(r) == 64) && limited.iter().any(|r| side(r) == 128));
    for (l, d) in limited.iter().zip(&default) {
        if side(l) == 64 {
            assert_eq!(l.status, Status::Ok);
            assert_eq!(l, d);
        } else {
            assert_eq!(l.status, Status::Skipped);
            assert!(l.reason.contains("max_map_side") && l.reason.contains("128"), "{}", l.reason);
            assert_eq!(d.status, Status::Ok);
        }
    }
    // The scenes are loaded within limits too: the table has 2280 triangles.
    let few = Limits { max_triangles: 2279, ..Limits::DEFAULT };
    let err = study::load_scenes(&["table-and-sphere"], &few).expect_err("above the limit").to_string();
    assert!(err.contains("2280 triangles") && err.contains("max_triangles"), "{err}");
    assert!(study::load_scenes(&["table-and-sphere"], &Limits { max_triangles: 2280, ..few }).is_ok());
}

fn run_on(threads: usize, spec: &Spec, shard: Shard) -> Vec<Row> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| study::run(spec, shard, &indicatif::ProgressBar::hidden())).expect("within the limits")
}

/// Every file of a folder, sorted by name, with its bytes.
fn files(d: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(d)
        .expect("read dir")
        .map(|e| {
            let p = e.expect("entry").path();
            (p.file_name().expect("name").to_string_lossy().into_owned(), std::fs::read(&p).expect("read"))
        })
        .collect();
    v.sort();
    v
}

/// One and two threads write the same bytes, in every output file; the
/// rows are one per configuration and preset, in configuration order.
#[test]
fn same_bytes_on_one_and_two_threads() {
    let spec = small();
    let (a, b) = (dir("threads-1"), dir("threads-2"));
    let rows1 = run_on(1, &spec, Shard::ALL);
    let rows2 = run_on(2, &spec, Shard::ALL);
    study::write_run(&a, &rows1, &whole(&spec, &rows1)).expect("write");
    study::write_run(&b, &rows2, &whole(&spec, &rows2)).expect("write");
    let n = spec.configs().len();
    assert_eq!(n, 2 * 2 * 2 * 2);
    assert_eq!(rows1.len(), n * Arch::era_presets().len());
    assert!(rows1.windows(2).all(|w| (w[0].config_index, w[0].arch_index) < (w[1].config_index, w[1].arch_index)));
    let (fa, fb) = (files(&a), files(&b));
    let names: Vec<&str> = fa.iter().map(|f| f.0.as_str()).collect();
    for f in [
        "results.jsonl",
        "results.csv",
        "summary.md",
        "manifest.json",
        "pareto-table-and-sphere-time.png",
        "pareto-weiskopf-l-bytes.svg",
    ] {
        assert!(names.contains(&f), "{f} missing from {names:?}");
    }
    assert_eq!(fa.len(), fb.len());
    for (x, y) in fa.iter().zip(&fb) {
        assert!(x == y, "{} differs between 1 and 2 threads", x.0);
    }
}

/// The files of a folder but its manifest (which records the command
/// line that wrote it).
fn outputs(d: &Path) -> Vec<(String, Vec<u8>)> {
    files(d).into_iter().filter(|f| f.0 != "manifest.json").collect()
}

/// Three shards of `spec`, each in its folder with its manifest.
pub(crate) fn shards(spec: &Spec, tag: &str) -> Vec<super::scratch::Scratch> {
    (0..3)
        .map(|i| {
            let d = dir(&format!("{tag}-shard-{i}"));
            let shard = Shard::parse(&format!("{i}/3")).expect("valid");
            let rows = run_on(2, spec, shard);
            // Blocks of one scene, image, format and map side, numbered
            // scene-major, dealt out: block b to shard b mod 3.
            let block = |r: &Row| {
                let scene = spec.scenes.iter().position(|s| s.name == r.config.scene).expect("a scene of the sweep");
                let format = spec.formats.iter().position(|&f| f == r.config.depth_format).expect("a format");
                let map = spec.map_sizes.iter().position(|&m| m == r.config.map_side_texels).expect("a side");
                (scene * spec.formats.len() + format) * spec.map_sizes.len() + map
            };
            assert!(!rows.is_empty() && rows.iter().all(|r| block(r) % 3 == i), "shard {i}");
            study::write_run(&d, &rows, &Manifest::new(spec, shard, rows.len())).expect("write");
            d
        })
        .collect()
}

/// Three shards, merged (one given as a folder, two as files, out of
/// order), write exactly the bytes of the unsharded run, and a manifest
/// that says it is whole. (The refusals are in `merge.rs`.)
#[test]
fn shards_merge_into_the_whole_run() {
    let spec = small();
    let full = dir("whole");
    let rows = run_on(2, &spec, Shard::ALL);
    study::write_run(&full, &rows, &whole(&spec, &rows)).expect("write");
    let shards = shards(&spec, "merge");
    let merged = dir("merged");
    let inputs = vec![shards[2].join("results.jsonl"), shards[0].to_path_buf(), shards[1].join("results.jsonl")];
    let n = study::merge(&inputs, &merged, &Limits::DEFAULT).expect("merge");
    assert_eq!(n, spec.configs().len() * Arch::era_presets().len());
    assert_eq!(outputs(&full), outputs(&merged));
    let run = crate::output::folder::RunManifest::verify(&merged, u64::MAX).expect("a complete folder");
    let m: Manifest = serde_json::from_value(run.study.expect("the study's record")).expect("JSON");
    assert_eq!((m.shard.as_str(), m.rows), ("0/1", n));
    for bad in ["3/3", "1", "a/2", "0/0"] {
        assert!(Shard::parse(bad).is_err(), "{bad}");
    }
}

/// A configuration the renderer refuses becomes a skipped row per preset
/// that says why, not a missing row.
#[test]
fn refused_configurations_are_skipped_rows() {
    let mut spec = small();
    spec.scenes.truncate(1);
    spec.variants.truncate(1);
    spec.formats = vec![DepthFormatKind::D16];
    spec.filters.truncate(1);
    spec.map_sizes = vec![128, 20_000];
    let rows = run_on(1, &spec, Shard::ALL);
    assert_eq!(rows.len(), 2 * Arch::era_presets().len());
    let (ok, skipped): (Vec<&Row>, Vec<&Row>) = rows.iter().partition(|r| r.config.map_side_texels == 128);
    assert!(ok.iter().all(|r| r.status == Status::Ok && r.complete()));
    for r in skipped {
        assert_eq!(r.status, Status::Skipped);
        assert!(r.reason.contains("map"), "{}", r.reason);
        assert!(r.metrics.is_none() && r.cost.is_none());
    }
    let md = study::summary(&rows, &whole(&spec, &rows));
    assert!(md.contains("## Skipped") && md.contains("20000"), "{md}");
}

/// The front of a hand-made set: (1, 5) (2, 3) (2, 4) (3, 3) (4, 1) (5, 2)
/// keeps (1, 5), (2, 3) and (4, 1).
#[test]
fn pareto_front_by_hand() {
    let pts = [(2.0, 4.0), (5.0, 2.0), (1.0, 5.0), (3.0, 3.0), (4.0, 1.0), (2.0, 3.0)];
    assert_eq!(pareto_front(&pts), vec![2, 5, 4]);
}

fn finite(r: &Row) -> bool {
    r.status == Status::Ok
        && r.metrics.is_some_and(|m| {
            m.evaluated_px > 0 && [m.misclassified_percent, m.mean_abs_error].iter().all(|v| v.is_finite())
        })
}

fn misclassified(r: &Row) -> Option<f64> {
    r.metrics.map(|m| m.misclassified_percent)
}

/// The light's near/far ratio from 10 to 10⁶ (table, 160×90, 512² map):
/// second depth, midpoint and dual in d16 and d24 misclassify no fewer
/// pixels as the ratio grows, within 0.05 points (4 pixels of the ~8000
/// evaluated: the map's texel centres move with the projection, so a
/// handful of edge pixels may flip either way). Measured, d16: second
/// 0.025 → 5.5 %, breaking down (1 point over its ratio-10 error) at 10⁵;
/// d24: second stays at 0.22 % and dual at 0.06 % at 10⁶; d24 and f32
/// (standard z, whose steps near 1 are 2⁻²⁴ too) agree.
#[test]
fn near_far_ratio_degrades_monotonically() {
    let scenes: Vec<Scene> = RATIOS.iter().map(|&r| extremes::near_far_scene(r)).collect();
    let rows = run_on(2, &extremes::spec(scenes, 160, 90), Shard::ALL);
    assert!(rows.iter().all(finite));
    for a in ["second", "midpoint", "dual"] {
        for f in [DepthFormatKind::D16, DepthFormatKind::D24] {
            let e: Vec<f64> = rows
                .iter()
                .filter(|r| r.config.algorithm == a && r.config.depth_format == f)
                .map(|r| misclassified(r).expect("finite"))
                .collect();
            assert_eq!(e.len(), RATIOS.len());
            assert!(e.windows(2).all(|w| w[1] >= w[0] - 0.05), "{a} {f}: {e:?}");
        }
    }
    let d16 = extremes::breakdown(&rows, "second", DepthFormatKind::D16).expect("d16 breaks down");
    let d24 = extremes::breakdown(&rows, "second", DepthFormatKind::D24);
    assert!(d24.is_none_or(|r| r > d16), "d24 breaks down at {d24:?}, d16 at {d16}");
    let at = |f: DepthFormatKind, ratio: f64| {
        rows.iter()
            .find(|r| {
                r.config.algorithm == "second"
                    && r.config.depth_format == f
                    && r.config.scene == extremes::near_far_scene(ratio).name
            })
            .and_then(misclassified)
            .expect("row")
    };
    // 16 bits have run out at 10⁶ (every surface within a few steps of 1);
    // 24 bits have not.
    let (d16, d24) = (DepthFormatKind::D16, DepthFormatKind::D24);
    assert!(at(d16, 1e6) > 10.0 * at(d24, 1e6), "{} vs {}", at(d16, 1e6), at(d24, 1e6));
}

/// Grazing light within 0.1° and 0.02°, vertices either side of the guard
/// band and 10⁵ units out, slivers and sub-pixel triangles, coincident
/// surfaces: every algorithm in every format renders without a panic and
/// gives finite metrics over pixels that face the light.
#[test]
fn extremes_give_finite_metrics() {
    let mut scenes: Vec<Scene> = extremes::GRAZING_DEGREES.iter().map(|&d| extremes::grazing_scene(d)).collect();
    scenes.extend([extremes::guard_band_scene(), extremes::sliver_scene(), extremes::coincident_scene()]);
    let rows = run_on(2, &extremes::spec(scenes, 96, 54), Shard::ALL);
    assert_eq!(rows.len(), 5 * extremes::variants().len() * 3);
    for r in &rows {
        assert!(finite(r), "{} {}: {r:?}", r.config.scene, r.label());
    }
    let md = extremes::markdown(&rows);
    assert!(md.contains("| guard-band | dual |") && !md.contains("NaN"), "{md}");
}

/// The extremes' sweep keeps to the limits it runs under: with maps capped
/// below its 512² every row is skipped and names the limit, the table says
/// no curve was measured (not that none broke down), and the files are
/// still written.
#[test]
fn extremes_keep_to_their_limits() {
    let out = dir("extremes-limits");
    let limits = Limits { max_map_side: 256, ..Limits::DEFAULT };
    let mut folder = crate::output::folder::OutputFolder::create(
        &out,
        crate::output::folder::Claim::new(crate::output::folder::RunKind::Study),
    )
    .expect("folder");
    let md = extremes::run_all(&mut folder, &limits).expect("runs");
    folder.finish(None).expect("finished");
    let rows = study::read_rows(&out.join("extremes.jsonl"), &Limits::DEFAULT).expect("written");
    assert_eq!(rows.len(), extremes::scenes().len() * extremes::variants().len() * 3);
    for r in &rows {
        assert!(r.metrics.is_none() && r.status == Status::Skipped, "{r:?}");
        assert!(r.reason.contains("max_map_side"), "{}", r.reason);
    }
    assert!(md.contains("not measured") && !md.contains("never"), "{md}");
    assert!(out.join("extremes.md").is_file() && out.join("precision.png").is_file());
}

/// Configurations that render alike are rendered once: shadow volumes draw
/// no map, so their rows for every map format, side and filter come from
/// one render, and a silhouette map's rows for every filter. Every file
/// the run writes is byte for byte the unshared run's, a map beyond the
/// limits still its own skipped row.
#[test]
fn configurations_that_render_alike_write_the_unshared_files() {
    let mut spec = small();
    spec.scenes.truncate(1);
    spec.variants = vec![
        Variant::new(Algorithm::First, 0.002),
        Variant::new(Algorithm::Volumes, 0.0),
        Variant::new(Algorithm::Silhouette { packed: true }, 0.002),
    ];
    spec.map_sizes = vec![64, 128, 256];
    spec.limits = Limits { max_map_side: 128, ..Limits::DEFAULT };
    let hidden = indicatif::ProgressBar::hidden();
    let shared = study::run(&spec, Shard::ALL, &hidden).expect("runs");
    let unshared = study::run_unshared(&spec, Shard::ALL, &hidden).expect("runs");
    assert_eq!(shared.len(), unshared.len());
    let volumes: Vec<&Row> = shared.iter().filter(|r| r.config.algorithm == "volumes").collect();
    // 2 formats × 3 sides × 2 filters, on each preset; the 256² ones
    // beyond the limit.
    assert_eq!(volumes.len(), 12 * Arch::era_presets().len());
    assert!(volumes.iter().any(|r| r.status == Status::Skipped && r.reason.contains("max_map_side")));
    // What lets them share: rendered each on its own, a silhouette map's
    // two filters give the same numbers.
    let silhouettes: Vec<&Row> =
        unshared.iter().filter(|r| r.config.algorithm == "silhouette-packed" && r.complete()).collect();
    assert_eq!(silhouettes.len(), 8 * Arch::era_presets().len());
    for r in &silhouettes {
        let twin = silhouettes.iter().find(|o| {
            let key = |x: &Row| (x.config.depth_format, x.config.map_side_texels, x.arch_index);
            o.config.filter_name != r.config.filter_name && key(o) == key(r)
        });
        let twin = twin.expect("the other filter's row");
        assert_eq!((r.metrics, &r.cost), (twin.metrics, &twin.cost), "{:?}", r.config);
    }
    let (a, b) = (dir("alike-shared"), dir("alike-unshared"));
    study::write_run(&a, &shared, &whole(&spec, &shared)).expect("write");
    study::write_run(&b, &unshared, &whole(&spec, &unshared)).expect("write");
    assert_eq!(outputs(&a), outputs(&b));
}

/// Shards partition any sweep, keep its blocks whole while there are no
/// more shards than blocks (so each draws a block's passes once), give
/// every shard work when there are more, and stay within a block's size
/// of one another.
#[test]
fn shards_partition_by_whole_blocks() {
    use crate::experiment::study::Layout;
    for (scenes, variants, formats, maps, filters) in
        [(9, 22, 3, 6, 5), (3, 14, 2, 2, 2), (1, 3, 1, 1, 4), (2, 5, 3, 2, 1)]
    {
        let configurations = scenes * variants * formats * maps * filters;
        let layout = Layout { configurations, variants, formats, maps, filters };
        let blocks = scenes * formats * maps;
        for count in [1, 2, 3, 8, 64, blocks, blocks + 1, 3 * blocks + 2] {
            let mut sizes = vec![0usize; count];
            let mut held: Vec<Vec<usize>> = vec![Vec::new(); count];
            for c in 0..configurations {
                let mine: Vec<usize> = (0..count).filter(|&i| Shard { index: i, count }.contains(&layout, c)).collect();
                assert_eq!(mine.len(), 1, "configuration {c} of {count} shards");
                sizes[mine[0]] += 1;
                // The block by hand: scene, format and map of the index.
                let (map, format) = ((c / filters) % maps, (c / filters / maps) % formats);
                let scene = c / filters / maps / formats / variants;
                let block = (scene * formats + format) * maps + map;
                if !held[mine[0]].contains(&block) {
                    held[mine[0]].push(block);
                }
            }
            let (least, most) = (sizes.iter().min().copied(), sizes.iter().max().copied());
            let block = variants * filters;
            assert!(most.zip(least).is_some_and(|(m, l)| m - l <= block), "{count} shards: {sizes:?}");
            if count <= blocks {
                // Whole blocks: a shard holds at most its share of them.
                assert!(held.iter().all(|h| h.len() <= blocks.div_ceil(count)), "{count} shards: {held:?}");
            } else if configurations >= count {
                assert!(sizes.iter().all(|&n| n > 0), "{count} shards, one without work: {sizes:?}");
            }
        }
    }
}
