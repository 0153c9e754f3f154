//! Every study row carries the `umbra render` command line that renders it
//! again: run, that command gives the row's metrics exactly, for an
//! algorithm with its own parameter, a culling override and Reeves'
//! jittered filter. A culling the command cannot read is refused by name.

mod common;
use common::{dir, umbra};
use umbra_core::DepthFormatKind;
use umbra_sim::experiment::study::{self, Shard, Spec, Variant, jittered};
use umbra_sim::io::limits::Limits;
use umbra_sim::pass::render::Algorithm;
use umbra_sim::world::scene::Scene;

#[test]
fn each_row_renders_again_from_its_command_line() {
    let spec = Spec {
        scenes: vec![Scene::bundled("weiskopf-l").expect("bundled")],
        variants: vec![
            Variant::new("dual", Algorithm::Dual { offset: 0.05 }, 0.0),
            Variant::new("dual-nocull", Algorithm::Dual { offset: 0.05 }, 0.0).without_culling(),
            Variant::new("first-range", Algorithm::BiasRange { hi: 0.004 }, 0.001),
        ],
        formats: vec![DepthFormatKind::D16],
        map_sizes: vec![128],
        filters: vec![
            ("jitter4".to_owned(), jittered(4)),
            ("bilinear".to_owned(), umbra_core::shadow::Filter::Bilinear),
        ],
        archs: Vec::new(),
        width: 128,
        height: 96,
        reference_samples: 2,
        limits: Limits::DEFAULT,
    };
    let rows = study::run(&spec, Shard::ALL, &indicatif::ProgressBar::hidden());
    assert_eq!(rows.len(), 6);
    let nocull = rows.iter().find(|r| r.algorithm == "dual-nocull").expect("row");
    assert!(nocull.command.contains("--cull solids=none,open=none"), "{}", nocull.command);
    for (k, row) in rows.iter().enumerate() {
        let out = dir(&format!("row{k}"));
        let mut args: Vec<&str> = row.command.split_whitespace().skip(1).collect();
        let o = out.to_str().expect("UTF-8");
        args.extend(["--out", o]);
        let r = umbra(&args);
        assert!(r.status.success(), "{}: {}", row.command, String::from_utf8_lossy(&r.stderr));
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("metrics.json")).expect("metrics")).expect("JSON");
        let _ = std::fs::remove_dir_all(&out);
        let field = |name: &str| m[name].as_u64();
        assert_eq!(field("evaluated"), row.evaluated, "{}", row.command);
        assert_eq!(field("edge_placement"), row.edge_placement, "{}", row.command);
        assert_eq!(field("acne"), row.acne, "{}", row.command);
        assert_eq!(field("leaks"), row.leaks, "{}", row.command);
        assert_eq!(m["mean_abs_error"].as_f64(), row.mean_abs_error, "{}", row.command);
    }
    // The culling changes the result: the rows differ.
    let dual = rows.iter().find(|r| r.algorithm == "dual" && r.filter == "bilinear").expect("row");
    let nocull = rows.iter().find(|r| r.algorithm == "dual-nocull" && r.filter == "bilinear").expect("row");
    assert_ne!(dual.acne, nocull.acne);
}

#[test]
fn a_culling_the_command_cannot_read_is_refused() {
    let out = dir("badcull");
    for (bad, named) in [("solids=sideways", "sideways"), ("walls=none", "walls"), ("solids", "solids")] {
        let r = umbra(&["render", "weiskopf-l", "--cull", bad, "--out", out.to_str().expect("UTF-8")]);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success() && err.contains(named) && err.contains("--cull"), "{bad}: {err}");
    }
    assert!(!out.exists(), "nothing is written");
}
