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
            Variant::new(Algorithm::Dual { offset: 0.05 }, 0.0),
            Variant::new(Algorithm::Dual { offset: 0.05 }, 0.0).without_culling(),
            Variant::new(Algorithm::BiasRange { hi: 0.004 }, 0.001),
        ],
        formats: vec![DepthFormatKind::D16],
        map_sizes: vec![128],
        filters: vec![
            ("jitter4".to_owned(), jittered(4)),
            ("bilinear".to_owned(), umbra_core::shadow::Filter::Bilinear),
        ],
        archs: Vec::new(),
        arch_params: Vec::new(),
        images: vec![[128, 96]],
        reference_samples: 2,
        budgets: vec![1.0],
        name: "rows".to_owned(),
        hash: String::new(),
        limits: Limits::DEFAULT,
    };
    let rows = study::run(&spec, Shard::ALL, &indicatif::ProgressBar::hidden());
    assert_eq!(rows.len(), 6);
    let nocull = |r: &&umbra_sim::experiment::study::Row| r.config.culling != "algorithm";
    let c = &rows.iter().find(nocull).expect("row").config.command;
    assert!(c.contains("--cull solids=none,open=none"), "{c}");
    for (k, row) in rows.iter().enumerate() {
        let out = dir(&format!("row{k}"));
        let mut args: Vec<&str> = row.config.command.split_whitespace().skip(1).collect();
        let o = out.to_str().expect("UTF-8");
        args.extend(["--out", o]);
        let r = umbra(&args);
        assert!(r.status.success(), "{}: {}", row.config.command, String::from_utf8_lossy(&r.stderr));
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("metrics.json")).expect("metrics")).expect("JSON");
        let _ = std::fs::remove_dir_all(&out);
        let (field, want, c) = (|name: &str| m[name].as_u64(), row.metrics.expect("measured"), &row.config.command);
        assert_eq!(field("evaluated"), Some(want.evaluated_px), "{c}");
        assert_eq!(field("edge_placement"), Some(want.edge_placement_px), "{c}");
        assert_eq!(field("acne"), Some(want.acne_px), "{c}");
        assert_eq!(field("leaks"), Some(want.leaks_px), "{c}");
        assert_eq!(m["mean_abs_error"].as_f64(), Some(want.mean_abs_error), "{c}");
    }
    // The culling changes the result: the rows differ.
    let bilinear = |cull: bool| {
        rows.iter()
            .find(|r| r.config.algorithm == "dual" && r.config.filter_name == "bilinear" && nocull(r) == cull)
            .and_then(|r| r.metrics)
            .expect("row")
    };
    assert_ne!(bilinear(false).acne_px, bilinear(true).acne_px);
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
