//! Every study row carries the `umbra render` command line that renders it
//! again: run, that command gives the row's metrics exactly — for a user's
//! sweep file with a 5×5 box, a jitter table, an algorithm with its own
//! parameter, a culling override and an architecture axis, and for every
//! spelling the bundled sweeps produce. A culling the command cannot read
//! is refused by name.

mod common;
use std::collections::BTreeMap;

use common::{dir, umbra};
use umbra_sim::experiment::study::{self, Row, Shard, SweepFile, render_config};
use umbra_sim::io::limits::Limits;
use umbra_sim::render::{Culling, TruthSource};

/// A user's sweep: every kind of choice a row's command must spell.
const MINE: &str = r#"
name = "mine"
scenes = ["weiskopf-l"]
images = [[128, 96]]
reference_rays = 2
formats = ["d16"]
maps = [128]
filters = ["box5", { jitter = { num_samples = 4, res_factor = 1.5, min_size = 0.25 } }, { name = "box3", box = 3 }]
archs = ["talisman"]
budgets = [1.0]

[[arch_axes]]
key = "map_cache.size"
values = ["0B", "16KiB"]

[[algorithms]]
algo = "dual"
offset = [0.05]
cull = ["algorithm", "solids=none,open=none"]

[[algorithms]]
algo = "bias-range"
bias = [0.001]
bias1 = 0.004
"#;

/// Run `command` (a row's, without `umbra`) into a fresh folder and read
/// back its `metrics.json`.
fn render_again(command: &str, name: &str) -> serde_json::Value {
    let out = dir(name);
    let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
    let o = out.to_str().expect("UTF-8");
    args.extend(["--out", o]);
    let r = umbra(&args);
    assert!(r.status.success(), "{command}: {}", String::from_utf8_lossy(&r.stderr));
    let m = serde_json::from_str(&std::fs::read_to_string(out.join("metrics.json")).expect("metrics")).expect("JSON");
    let _ = std::fs::remove_dir_all(&out);
    m
}

/// The metrics a command printed are the row's, exactly.
fn assert_same(m: &serde_json::Value, row: &Row) {
    let (field, want, c) = (|name: &str| m[name].as_u64(), row.metrics.expect("measured"), &row.config.command);
    assert_eq!(field("evaluated"), Some(want.evaluated_px), "{c}");
    assert_eq!(field("edge_placement"), Some(want.edge_placement_px), "{c}");
    assert_eq!(field("acne"), Some(want.acne_px), "{c}");
    assert_eq!(field("leaks"), Some(want.leaks_px), "{c}");
    assert_eq!(m["mean_abs_error"].as_f64(), Some(want.mean_abs_error), "{c}");
}

#[test]
fn each_row_of_a_users_sweep_renders_again_from_its_command_line() {
    let folder = dir("mine-sweep");
    std::fs::create_dir_all(&folder).expect("folder");
    let file = folder.join("mine.toml");
    std::fs::write(&file, MINE).expect("written");
    let spec = SweepFile::open(file.to_str().expect("UTF-8"), &Limits::DEFAULT)
        .and_then(|f| f.spec(&Limits::DEFAULT))
        .expect("the sweep loads");
    let rows = study::run(&spec, Shard::ALL, &indicatif::ProgressBar::hidden()).expect("within the limits");
    // 3 filters × 3 variants × 2 architecture points.
    assert_eq!(rows.len(), 18);
    let filters: Vec<String> = rows.iter().map(|r| r.config.filter_name.to_string()).collect();
    for f in ["box5", "jitter4,res-factor=1.5,min-size=0.25", "box3"] {
        assert!(filters.iter().any(|g| g == f), "{f} in {filters:?}");
    }
    let nocull = |r: &&Row| r.config.culling != Culling::ALGORITHM;
    let c = &rows.iter().find(nocull).expect("row").config.command;
    assert!(c.contains("--cull solids=none,open=none") && c.contains("--offset 0.05"), "{c}");
    // Rows that differ only in the architecture share a command.
    let mut commands: BTreeMap<&str, Vec<&Row>> = BTreeMap::new();
    for r in &rows {
        assert_eq!(r.status, study::Status::Ok, "{}: {}", r.config.command, r.reason);
        commands.entry(r.config.command.as_str()).or_default().push(r);
    }
    assert_eq!(commands.len(), 9);
    for (k, (command, rows)) in commands.iter().enumerate() {
        let m = render_again(command, &format!("mine{k}"));
        rows.iter().for_each(|r| assert_same(&m, r));
    }
    // The culling changes the result: the rows differ.
    let box5 = |cull: bool| {
        rows.iter()
            .find(|r| r.config.algorithm == "dual" && r.config.filter_name.to_string() == "box5" && nocull(r) == cull)
            .and_then(|r| r.metrics)
            .expect("row")
    };
    assert_ne!(box5(false).acne_px, box5(true).acne_px);
    let _ = std::fs::remove_dir_all(&folder);
}

/// Every spelling a bundled sweep writes into a row's command (algorithm
/// and its parameters, depth format, filter, culling, virtual samples) is
/// one `umbra render` reads: each distinct one, run on its row's scene at
/// a small image and map, gives the metrics the library renders for the
/// same configuration.
#[test]
fn every_bundled_sweep_spells_commands_the_cli_reads() {
    let limits = Limits::DEFAULT;
    for name in ["quick", "full"] {
        let spec = SweepFile::bundled(name).and_then(|f| f.spec(&limits)).expect("bundled sweep");
        let mut seen = BTreeMap::new();
        for c in spec.configs() {
            let scene = &spec.scenes[c.scene];
            let small = umbra_sim::render::RenderConfig {
                width: 64,
                height: 36,
                map_size: 64,
                reference_rays: 1,
                ..render_config(&spec, &c)
            };
            let command = small.command(&scene.source);
            let key = command.split_whitespace().skip(3).collect::<Vec<_>>().join(" ");
            if seen.insert(key, ()).is_some() {
                continue;
            }
            let m = render_again(&command, &format!("{name}-{}", seen.len()));
            let want = umbra_sim::render::render(
                scene,
                &small,
                &limits,
                TruthSource::Build(&indicatif::ProgressBar::hidden()),
            );
            match want {
                Ok(r) => assert_eq!(m["acne"].as_u64(), Some(r.metrics.acne), "{command}"),
                Err(e) => panic!("{command}: {e}"),
            }
        }
        assert!(seen.len() > 10, "{name}: {} distinct commands", seen.len());
    }
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
