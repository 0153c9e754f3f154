//! The timing model against published hardware (`umbra correlate`): the
//! statistics worked by hand, the datasets as their sources print them,
//! calibration kept apart from validation, Weiskopf & Ertl's Table 1
//! within the targets, and each bundled file's peak rates reproduced by
//! the quad microbenchmark as derived by hand from the file.

use umbra::core::DepthFormatKind;
use umbra::core::shadow::Filter;
use umbra::sim::Algorithm;
use umbra::sim::cost::arch::Arch;
use umbra::sim::experiment::correlation::{BUNDLED, Dataset, Kind, Role, run};
use umbra::sim::input::limits::Limits;
use umbra::sim::render::{RenderConfig, cost};
use umbra::sim::world::scene::Scene;

#[test]
fn the_datasets_hold_their_sources_numbers() {
    let limits = Limits::DEFAULT;
    let we = Dataset::open("weiskopf-ertl-2003", &limits).expect("bundled");
    // Weiskopf & Ertl 2003, Table 1, row by row.
    let table: Vec<f64> = vec![167.5, 106.2, 69.1, 85.3, 30.6, 44.8, 36.6, 40.6, 21.9, 27.2, 23.9, 25.5, 16.6];
    assert_eq!(we.points.iter().map(|p| p.measured).collect::<Vec<_>>(), table);
    assert_eq!((we.kind, we.scene.as_deref(), we.arch.as_deref()), (Kind::Validation, Some("factory"), Some("r300")));
    let arm = Dataset::open("arm-render-passes", &limits).expect("bundled");
    // 600.2 and 554.8 MiB/s.
    assert_eq!(arm.points.iter().map(|p| p.measured).collect::<Vec<_>>(), vec![600.2 * 1048576.0, 554.8 * 1048576.0]);
    assert_eq!(arm.kind, Kind::Sanity);
    let sen = Dataset::open("sen-cammarano-hanrahan-2003", &limits).expect("bundled");
    assert_eq!((sen.kind, sen.points.len()), (Kind::NotModelled, 0));
    assert_eq!(BUNDLED.len(), 4);
}

#[test]
fn a_bad_dataset_names_its_file_and_point() {
    let head = "name = \"x\"\nsource = \"s\"\nwhat = \"w\"\nkind = \"validation\"\nscene = \"quad\"\narch = \"r300\"\n";
    let bad = |points: &str| Dataset::parse(&format!("{head}{points}"), "mine.toml").expect_err("bad").to_string();
    let e = bad(
        "[[points]]\nid = \"p\"\nwhat = \"w\"\nmeasured = 1.0\nmeasure = \"frame\"\nconfig = { algo = \"first\", map = 256, filter = \"blur\" }\n",
    );
    assert!(e.starts_with("mine.toml: points.p.config: filter `blur`"), "{e}");
    let e = bad("[[points]]\nid = \"p\"\nwhat = \"w\"\nmeasured = -1.0\nmeasure = \"frame\"\n");
    assert!(e.starts_with("mine.toml: points.p: measured -1"), "{e}");
    let e = bad("[[points]]\nid = \"p\"\nwhat = \"w\"\nmeasured = 1.0\nmeasure = \"fill\"\n");
    assert!(e.contains("points.p: a Fill point needs a pass"), "{e}");
    let e = bad("colour = 1\n");
    assert!(e.starts_with("mine.toml: (file): unknown field `colour`"), "{e}");
    // A calibration that names no parameter, or no point.
    let r300 = include_str!("../../../arch/r300.toml");
    let e = Arch::parse(&r300.replace("\"front.pass_overhead_cycles\" =", "\"front.pass_overhead\" ="), "a.toml")
        .expect_err("unknown")
        .to_string();
    assert!(e.starts_with("a.toml: calibration.front.pass_overhead: unknown key"), "{e}");
    let e = Arch::parse(&r300.replace("= \"weiskopf-ertl-2003/no-shadow\"", "= \"no-shadow\""), "a.toml")
        .expect_err("no point")
        .to_string();
    assert!(e.contains("calibration.front.frame_overhead_cycles: expected a dataset point"), "{e}");
}

#[test]
fn table_1_within_the_targets_calibration_apart() {
    let limits = Limits::DEFAULT;
    let we = Dataset::open("weiskopf-ertl-2003", &limits).expect("bundled");
    let arch = |name: &str, set: &[String]| {
        let mut a = Arch::open(name, &limits).map_err(|e| e.to_string())?;
        set.iter().try_for_each(|s| a.set(s).map_err(|e| e.to_string()))?;
        Ok(a)
    };
    let c = run(std::slice::from_ref(&we), &arch, &limits).expect("runs");
    let points = &c.datasets[0].points;
    // The two fitted parameters' points reproduce their measurements (to
    // the fit's rounding to whole cycles) and validate nothing.
    let calibrated: Vec<&str> = points.iter().filter(|p| p.role == Role::Calibration).map(|p| p.id.as_str()).collect();
    assert_eq!(calibrated, ["no-shadow", "point-dual-256"]);
    for p in points.iter().filter(|p| p.role == Role::Calibration) {
        assert!(p.error().abs() < 1e-3, "{}: {:+.4}", p.id, p.error());
    }
    let s = c.validation;
    assert_eq!(s.points, 11);
    // The targets, against the measured 10.5 % and 0.968: the
    // error has 1.5 points of room, r 0.07. Shading once a covered pixel
    // instead of once a fragment (shade.per_fragment = false) gives 58.4 %
    // and fails; so do programs without filter instructions (63.8 %).
    assert!(s.mean_absolute_error_percent <= 12.0, "{s:?}");
    assert!(s.pearson_r.expect("one unit") >= 0.9, "{s:?}");
    // Two cells outside 25 % (bilinear at 256², the measured reason in
    // docs/correlation.md), nine inside.
    assert!(s.within_25_percent >= 9, "{s:?}");
    // And the table's order: a second depth costs more than a first, a
    // bigger map and more samples more.
    let fps = |id: &str| points.iter().find(|p| p.id == id).expect(id).predicted;
    for f in ["point", "bilinear", "4x4"] {
        for m in ["256", "2048"] {
            assert!(fps(&format!("{f}-dual-{m}")) < fps(&format!("{f}-bias-{m}")));
        }
        for a in ["bias", "dual"] {
            assert!(fps(&format!("{f}-{a}-2048")) < fps(&format!("{f}-{a}-256")));
        }
    }
    assert!(fps("4x4-bias-256") < fps("bilinear-bias-256") && fps("bilinear-bias-256") < fps("point-bias-256"));
}

/// The quad's depth-only fill (its light pass, one 4-byte buffer, each
/// texel drawn once) against each bundled file's rates worked by hand:
/// its fragments a clock, or its DRAM bandwidth over the bytes a texel
/// moves — a line fetched and written back through the depth cache (8 B)
/// off chip, the resolve's store (4 B) on chip — whichever is lower.
/// The desktop file is left out: its depth unit also reduces each 16²
/// tile's maximum at its fragment rate, which the pass's time includes and
/// this formula does not (the model gives 88 Gpixel/s against 95).
/// PixelFlow's evaluator does a 128² region's triangle in 128 cycles, far
/// faster than its memory takes the resolve, and its memory is latency-
/// bound: 2 requests of 32 B in flight over 100 ns is 640 MB/s, below its
/// 800 MB/s (every other file's latency ceiling is at or above its
/// bandwidth).
#[test]
fn each_files_depth_only_fill_as_derived_by_hand() {
    let limits = Limits::DEFAULT;
    let scene = Scene::bundled("quad").expect("bundled");
    let cfg = RenderConfig {
        algorithm: Algorithm::First,
        format: DepthFormatKind::F32,
        map_size: 256,
        filter: Filter::Point,
        width: 64,
        height: 64,
        reference_rays: 1,
        ..RenderConfig::DEFAULT
    };
    let expected = [
        ("pixelflow", (2.0 * 32.0 / 100e-9f64).min(800e6) / 4.0),
        ("talisman", (2.0 * 75e6f64).min(1.2e9 / 4.0)),
        ("immediate", (2.0 * 75e6f64).min(1.2e9 / 8.0)),
        ("mobile-tbdr", (40.0 * 850e6f64).min(51.2e9 / 4.0)),
        ("r300", (8.0 * 275e6f64).min(17.28e9 / 8.0)),
    ];
    for (name, rate) in expected {
        let mut arch = Arch::open(name, &limits).expect("bundled");
        // The R300's map-writing program is not depth-only fill.
        arch.set("depth.program_cycles=0").expect("a key");
        let r = cfg.check(&scene, &limits).and_then(|job| cost(&job, &arch)).expect("costs");
        assert_eq!(r.light_events.fragments, 256 * 256, "{name}: the quad fills the map once");
        #[allow(clippy::cast_precision_loss, reason = "a count")]
        let fill = r.light_events.fragments as f64 / ((r.light.cycles() - r.light.overhead) / arch.clock);
        assert!((fill / rate - 1.0).abs() < 0.05, "{name}: {fill:.4e} pixels/s against {rate:.4e} by hand");
    }
}
