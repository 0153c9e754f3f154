//! The `umbra` command's architectures: a bad file or override ends in an
//! error naming the file (or `--set`), the key and the problem, before
//! anything is written; a good file and overrides are recorded beside the
//! report.

mod common;
use common::{dir, umbra};

#[test]
fn a_bad_architecture_names_its_file_and_key_and_writes_nothing() {
    let input = dir("input");
    std::fs::create_dir_all(&input).expect("temp dir");
    let talisman = include_str!("../../../arch/talisman.toml");
    let bad = input.join("bad.toml");
    std::fs::write(&bad, talisman.replacen("tile = 32", "tile = 48", 1)).expect("write");
    let out = dir("out");
    let o = umbra(&[
        "cost",
        "table-and-sphere",
        "--width",
        "64",
        "--height",
        "36",
        "--arch",
        bad.to_str().expect("UTF-8"),
        "--out",
        out.to_str().expect("UTF-8"),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("bad.toml: raster.tile: 48"), "{err}");
    let o = umbra(&[
        "cost",
        "table-and-sphere",
        "--arch",
        "talisman",
        "--set",
        "dram.bandwidth=fast",
        "--out",
        out.to_str().expect("UTF-8"),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--set: dram.bandwidth: `fast` is not a bandwidth"), "{err}");
    assert!(!out.exists(), "nothing is written");

    let good = input.join("mine.toml");
    std::fs::write(&good, talisman.replacen("name = \"talisman\"", "name = \"mine\"", 1)).expect("write");
    let o = umbra(&[
        "cost",
        "table-and-sphere",
        "--width",
        "64",
        "--height",
        "36",
        "--arch",
        good.to_str().expect("UTF-8"),
        "--set",
        "clock=150MHz",
        "--out",
        out.to_str().expect("UTF-8"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Named for its file and the change: `--set` is said in every output.
    let record = std::fs::read_to_string(out.join("arch-mine-clock-150MHz.toml")).expect("the effective architecture");
    assert!(record.contains("clock = \"150MHz\"") && record.contains("; --set clock=150MHz"), "{record}");
    let stats = std::fs::read_to_string(out.join("stats-mine-clock-150MHz.txt")).expect("stats");
    assert!(stats.contains("# arch.clock = \"150MHz\"") && stats.contains("frame.cycles"), "{stats}");
    let _ = std::fs::remove_dir_all(&input);
    let _ = std::fs::remove_dir_all(&out);
}

/// A copied file reports under its own file's name (`cp
/// arch/mobile-tbdr.toml copy.toml` costs as `copy`), edited or not; a
/// file named as a bundled machine but differing from it is said to
/// differ, naming the keys, since its outputs take that machine's name.
#[test]
fn a_copy_reports_under_its_own_name_and_a_namesake_is_said() {
    let d = dir("namesake");
    std::fs::create_dir_all(&d).expect("temp dir");
    let original = include_str!("../../../arch/mobile-tbdr.toml");
    let line = original.lines().find(|l| l.starts_with("bandwidth = ")).expect("a bandwidth");
    let edited = original.replace(line, "bandwidth = \"10GB/s\"");
    let (copy, namesake) = (d.join("copy.toml"), d.join("mobile-tbdr.toml"));
    std::fs::write(&copy, &edited).expect("write");
    std::fs::write(&namesake, &edited).expect("write");
    let run = |file: &std::path::Path, out: &str| {
        let out = d.join(out);
        let args = ["cost", "table-and-sphere", "--width", "64", "--height", "36", "--arch"];
        let o = umbra(&[&args[..], &[file.to_str().expect("UTF-8"), "--out", out.to_str().expect("UTF-8")]].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        (String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
    };
    let (printed, said) = run(&copy, "copy-out");
    assert!(!said.contains("warning") && printed.contains("### copy — "), "{printed}{said}");
    assert!(d.join("copy-out/arch-copy.toml").is_file() && d.join("copy-out/stats-copy.txt").is_file());
    let (_, said) = run(&namesake, "namesake-out");
    assert!(said.contains("calls itself `mobile-tbdr`") && said.contains("(dram.bandwidth)"), "{said}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A study with a map-cache axis names a best design per objective in its
/// summary: the fastest takes a large cache, but under area (and energy ×
/// time × area) the best is not simply the largest cache, since a cache's
/// bits are silicon; a Pareto front against area is drawn.
#[test]
fn a_map_cache_axis_has_a_best_per_objective() {
    let d = dir("cache-axis");
    std::fs::create_dir_all(&d).expect("temp dir");
    let sweep = d.join("caches.toml");
    std::fs::write(
        &sweep,
        r#"
format = 2
name = "caches"
scenes = ["table-and-sphere"]
images = [[160, 90]]
reference_rays = 1
formats = ["d24"]
maps = [1024]
filters = ["bilinear"]
archs = ["talisman"]
budgets = [100.0]

[[arch_axes]]
key = "map_cache.size"
values = ["1KiB", "16KiB", "256KiB"]

[[algorithms]]
algo = "second"
"#,
    )
    .expect("write");
    let out = d.join("out");
    let o = umbra(&["study", "--sweep", sweep.to_str().expect("UTF-8"), "--out", out.to_str().expect("UTF-8")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("summary.md")).expect("summary");
    // The best-per-objective table's row: budget, objective, best, …, why.
    let best = |objective: &str| {
        let line = md
            .lines()
            .find(|l| l.starts_with("| 100 % |") && l.contains(&format!("| {objective} |")) && l.contains("map_cache"))
            .unwrap_or_else(|| panic!("{objective}:\n{md}"));
        let cells: Vec<&str> = line.split(" | ").collect();
        (cells[2].to_owned(), cells[cells.len() - 1].to_owned())
    };
    assert!(best("cycles").0.contains("map_cache.size=256KiB"), "{:?}", best("cycles"));
    for objective in ["area (mm²)", "energy × time × area (J·s·mm²)"] {
        let (pick, why) = best(objective);
        assert!(!pick.contains("map_cache.size=256KiB"), "{pick}");
        assert!(why.contains("of the fastest's"), "says why: {why}");
    }
    assert!(out.join("pareto-table-and-sphere-area.svg").is_file());
    std::fs::remove_dir_all(&d).expect("clean up");
}
