//! Every study row carries the `umbra render` command line that renders it
//! again: run, that command gives the row's metrics exactly — for a user's
//! sweep file with a 5×5 box, a jitter table, an algorithm with its own
//! parameter, a culling override and an architecture axis, and for every
//! spelling the bundled sweeps produce. A culling the command cannot read
//! is refused by name.

mod common;
use std::collections::BTreeMap;

use common::{dir, umbra};
use umbra_sim::Culling;
use umbra_sim::experiment::study::{self, Row, Shard, SweepFile, render_config};
use umbra_sim::input::limits::Limits;
use umbra_sim::render::TruthSource;

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
    assert_eq!(field("evaluated_px"), Some(want.evaluated_px), "{c}");
    assert_eq!(field("aliasing_px"), Some(want.aliasing_px), "{c}");
    assert_eq!(field("penumbra_px"), Some(want.penumbra_px), "{c}");
    assert_eq!(field("acne_px"), Some(want.acne_px), "{c}");
    assert_eq!(field("detachment_px"), Some(want.detachment_px), "{c}");
    assert_eq!(field("leaks_px"), Some(want.leaks_px), "{c}");
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
/// one `umbra render` reads: every flag's every value is run at least once
/// (the first command that spells one not yet run is run), on its row's
/// scene at a small image and map, and gives the metrics the library
/// renders for the same configuration.
#[test]
fn every_bundled_sweep_spells_commands_the_cli_reads() {
    let limits = Limits::DEFAULT;
    for name in ["quick", "full"] {
        let spec = SweepFile::bundled(name).and_then(|f| f.spec(&limits)).expect("bundled sweep");
        let mut seen = std::collections::BTreeSet::new();
        for c in spec.configs() {
            let scene = &spec.scenes[c.scene];
            let small = umbra_sim::render::RenderConfig {
                width: 64,
                height: 36,
                map_size: 64,
                reference_rays: 1,
                ..render_config(&spec, &c)
            };
            let command = small.command(scene);
            // Each `--flag value` (or lone switch) of the command after
            // `umbra render <scene>`: a command none of whose words is new
            // spells nothing not yet read.
            let words: Vec<&str> = command.split_whitespace().skip(3).collect();
            let mut spelt = Vec::new();
            for (k, w) in words.iter().enumerate() {
                if w.starts_with("--") {
                    let value = words.get(k + 1).filter(|v| !v.starts_with("--")).copied().unwrap_or("");
                    spelt.push(format!("{w} {value}"));
                }
            }
            let new: Vec<String> = spelt.into_iter().filter(|p| !seen.contains(p)).collect();
            if new.is_empty() {
                continue;
            }
            seen.extend(new);
            let m = render_again(&command, &format!("{name}-{}", seen.len()));
            let want = small
                .check(scene, &limits)
                .and_then(|job| umbra_sim::render::render(&job, TruthSource::Build(&indicatif::ProgressBar::hidden())));
            match want {
                Ok(r) => assert_eq!(m["acne_px"].as_u64(), Some(r.metrics.acne), "{command}"),
                Err(e) => panic!("{command}: {e}"),
            }
        }
        assert!(seen.len() > 10, "{name}: {} distinct spellings", seen.len());
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

/// A sweep with a numeric architecture axis, first and second depth:
/// `results.csv` carries the axis as a number column in SI units equal to
/// the swept values, the base architecture, null where a field does not
/// apply (first depth's virtual samples), frame time in seconds; and
/// `schema.csv` lists every column, each with a type, a unit and a
/// meaning.
#[test]
fn rows_a_script_reads_as_they_are() {
    let folder = dir("script-rows");
    std::fs::create_dir_all(&folder).expect("folder");
    let file = folder.join("axis.toml");
    std::fs::write(
        &file,
        r#"
name = "axis"
scenes = ["weiskopf-l"]
images = [[64, 48]]
reference_rays = 1
formats = ["d16"]
maps = [64]
filters = ["point"]
archs = ["talisman"]
budgets = [1.0]

[[arch_axes]]
key = "dram.bandwidth"
values = ["1.2GB/s", "2400MB/s"]

[[algorithms]]
algo = "first"
bias = [0.01]

[[algorithms]]
algo = "second"
"#,
    )
    .expect("written");
    let out = folder.join("out");
    let o = umbra(&["study", "--sweep", file.to_str().expect("UTF-8"), "--out", out.to_str().expect("UTF-8")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut reader = csv::Reader::from_path(out.join("results.csv")).expect("results.csv");
    let header: Vec<String> = reader.headers().expect("a header").iter().map(str::to_owned).collect();
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name} in {header:?}"));
    let (axis, base, vs, algo, seconds, cycles, clock) = (
        column("arch_dram_bandwidth_bytes_per_second"),
        column("base_arch"),
        column("virtual_samples"),
        column("algorithm"),
        column("frame_seconds"),
        column("total_cycles"),
        column("clock_hertz"),
    );
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.expect("a record")).collect();
    assert_eq!(rows.len(), 4, "2 algorithms × 2 bandwidths");
    let mut bandwidths: Vec<f64> = rows.iter().map(|r| r[axis].parse().expect("a number")).collect();
    bandwidths.sort_by(f64::total_cmp);
    assert_eq!(bandwidths, [1.2e9, 1.2e9, 2.4e9, 2.4e9]);
    for r in &rows {
        assert_eq!(&r[base], "talisman");
        assert_eq!(&r[vs], if &r[algo] == "first" { "" } else { "true" }, "{r:?}");
        let (s, c, hz): (f64, f64, f64) =
            (r[seconds].parse().expect("s"), r[cycles].parse().expect("cycles"), r[clock].parse().expect("Hz"));
        // The cycles column is rounded to a whole cycle.
        assert!((s * hz - c).abs() <= 0.5, "{s} s against {c} cycles at {hz} Hz");
    }
    let mut schema = csv::Reader::from_path(out.join("schema.csv")).expect("schema.csv");
    assert_eq!(schema.headers().expect("header").iter().collect::<Vec<_>>(), ["column", "type", "unit", "meaning"]);
    let described: Vec<csv::StringRecord> = schema.records().map(|r| r.expect("a record")).collect();
    assert_eq!(described.iter().map(|r| r[0].to_owned()).collect::<Vec<_>>(), header, "one line a column, in order");
    for r in &described {
        assert!(
            ["integer", "number", "text", "boolean"].contains(&&r[1]) && !r[2].is_empty() && !r[3].is_empty(),
            "{r:?}"
        );
    }
    let unit = |name: &str| described.iter().find(|r| &r[0] == name).map(|r| r[2].to_owned()).expect("described");
    assert_eq!(unit("arch_dram_bandwidth_bytes_per_second"), "B/s");
    assert_eq!((unit("frame_seconds"), unit("total_dram_bytes")), ("s".to_owned(), "B".to_owned()));
    // The JSON rows hold the axis as a dict of numbers.
    let jsonl = std::fs::read_to_string(out.join("results.jsonl")).expect("results.jsonl");
    let first: serde_json::Value = serde_json::from_str(jsonl.lines().next().expect("a row")).expect("JSON");
    assert!(first["config"]["arch_axes"]["arch_dram_bandwidth_bytes_per_second"].is_f64(), "{first}");
    let _ = std::fs::remove_dir_all(&folder);
}
