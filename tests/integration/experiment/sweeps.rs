//! Sweep files: the bundled ones load and round-trip through the copy a
//! study writes; a user's file with an architecture-parameter axis and a
//! scene beside it loads; a bad file is refused naming its key.

use umbra::sim::Algorithm;
use umbra::sim::Culling;
use umbra::sim::experiment::study::{SweepFile, Variant};
use umbra::sim::input::limits::Limits;

/// A scratch folder for `name`, removed when the test ends.
fn dir(name: &str) -> crate::common::Scratch {
    crate::common::scratch(name)
}

#[test]
fn bundled_sweeps_load_and_round_trip() {
    let l = Limits::DEFAULT;
    for name in ["quick", "full"] {
        let f = SweepFile::bundled(name).expect("bundled");
        let spec = f.spec(&l).expect("valid");
        let folder = dir(name);
        let copy = folder.join("sweep.toml");
        std::fs::write(&copy, &f.text).expect("write");
        let again = SweepFile::open(copy.to_str().expect("UTF-8"), &l).expect("opens").spec(&l).expect("valid");
        assert_eq!(again.hash, spec.hash);
        assert_eq!(again.configs(), spec.configs());
        assert_eq!(again.variants, spec.variants);
        assert_eq!(again.images, spec.images);
    }
    let quick = SweepFile::bundled("quick").and_then(|f| f.spec(&l)).expect("valid");
    assert!(quick.images.iter().all(|&[w, h]| w >= 640 && h >= 360), "{:?}", quick.images);
    // 3 first-depth biases, a bias range, second with and without virtual
    // samples, second-ffc, midpoint, dual unlimited, dual with and without
    // culling, two silhouette maps and volumes.
    assert_eq!(quick.variants.len(), 14);
    assert!(quick.variants.contains(&Variant::new(Algorithm::Dual { offset: 0.005 }, 0.0).without_culling()));
    let full = SweepFile::bundled("full").and_then(|f| f.spec(&l)).expect("valid");
    assert_eq!(full.images, vec![[1920, 1080]]);
}

#[test]
fn a_users_sweep_file_with_an_architecture_axis() {
    let d = dir("user");
    std::fs::write(
        d.join("plate.toml"),
        "name = \"plate\"\nimage = [64, 48]\n[camera]\nposition = [0.0, 3.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 50.0\nnear = 0.5\nfar = 20.0\n\
         [[lights]]\nkind = \"spot\"\nposition = [1.0, 5.0, 1.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\nnear = 1.0\nfar = 10.0\n\
         [[objects]]\nmesh = { box = { min = [-2.0, -0.1, -2.0], max = [2.0, 0.0, 2.0] } }\n",
    )
    .expect("write");
    let text = r#"
name = "mine"
scenes = ["plate.toml", "table-and-sphere"]
images = [[64, 36], [128, 72]]
reference_rays = 1
formats = ["d16"]
maps = [128]
filters = ["point", { name = "jitter8,res-factor=1", jitter = { num_samples = 8, res_factor = 1.0 } }]
archs = ["talisman"]
budgets = [1.0]

[[arch_axes]]
key = "map_cache.size"
values = ["0B", "16KiB"]

[[algorithms]]
algo = "dual"
offset = [0.005, 0.02]
cull = ["algorithm", "solids=none"]
"#;
    let f = d.join("mine.toml");
    std::fs::write(&f, text).expect("write");
    let spec =
        match SweepFile::open(f.to_str().expect("UTF-8"), &Limits::DEFAULT).and_then(|s| s.spec(&Limits::DEFAULT)) {
            Ok(s) => s,
            Err(e) => panic!("{e}"),
        };
    assert_eq!(spec.scenes[0].name, "plate");
    assert_eq!(spec.images.len(), 2);
    assert_eq!(spec.variants.len(), 4);
    assert_eq!(spec.variants[1].culling, "solids=none".parse::<Culling>().expect("valid"));
    assert_eq!(spec.archs.len(), 2);
    let params: Vec<String> = spec.arch_points.iter().map(umbra::sim::experiment::study::ArchPoint::params).collect();
    assert_eq!(params, ["map_cache.size=0B", "map_cache.size=16KiB"]);
    assert!(spec.arch_points.iter().all(|p| p.base == "talisman"), "{:?}", spec.arch_points);
    assert_eq!(spec.archs[1].map_cache.size, 16 * 1024);
    assert_eq!(spec.configs().len(), 2 * 2 * 4 * 2);
}

/// An architecture axis takes numbers where the key means one, and the
/// names of the points it makes fit the 64 characters a name may have,
/// however long the base's name: cut, with a hash that keeps them apart.
#[test]
fn an_axis_of_numbers_and_long_generated_names() {
    let d = dir("numbers");
    let base = "a-mobile-tiler-of-our-own-with-a-rather-long-descriptive-name";
    let arch = umbra::sim::Arch::bundled("mobile-tbdr").expect("bundled").to_toml().replace("mobile-tbdr", base);
    // Named as its file: a file's own name is the architecture's.
    std::fs::write(d.join(format!("{base}.toml")), arch).expect("write");
    let text = r#"
format = 2
name = "numbers"
scenes = ["table-and-sphere"]
images = [[64, 36]]
reference_rays = 1
formats = ["d16"]
maps = [128]
filters = ["point"]
archs = ["a-mobile-tiler-of-our-own-with-a-rather-long-descriptive-name.toml"]
budgets = [1.0]

[[arch_axes]]
key = "dram.requests_in_flight"
values = [180, 360]

[[arch_axes]]
key = "map_cache.misses_in_flight"
values = [180, 360.0]

[[algorithms]]
algo = "first"
"#;
    let f = d.join("numbers.toml");
    std::fs::write(&f, text).expect("write");
    let l = Limits::DEFAULT;
    let spec =
        SweepFile::open(f.to_str().expect("UTF-8"), &l).and_then(|s| s.spec(&l)).unwrap_or_else(|e| panic!("{e}"));
    let got: Vec<(u64, u64)> =
        spec.archs.iter().map(|a| (a.dram.requests_in_flight, a.map_cache.misses_in_flight)).collect();
    assert_eq!(got, [(180, 180), (180, 360), (360, 180), (360, 360)]);
    let names: std::collections::BTreeSet<&str> = spec.archs.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names.len(), 4, "{names:?}");
    assert!(names.iter().all(|n| n.len() <= 64 && n.starts_with(&base[..40])), "{names:?}");
    // A format this build does not know is refused, naming it.
    std::fs::write(&f, text.replace("format = 2", "format = 4")).expect("write");
    let e = SweepFile::open(f.to_str().expect("UTF-8"), &l).and_then(|s| s.spec(&l)).expect_err("format 4");
    assert!(e.key == "format" && e.problem.contains("formats 1 to 3"), "{e}");
}

#[test]
fn a_bad_sweep_file_names_its_key() {
    let d = dir("bad");
    let base = "name = \"b\"\nscenes = [\"table-and-sphere\"]\nimages = [[64, 36]]\nreference_rays = 1\nformats = [\"d16\"]\n\
                maps = [128]\nfilters = [\"point\"]\narchs = [\"talisman\"]\nbudgets = [1.0]\n";
    let sides = (1..=2048).map(|k| (8 * k).to_string()).collect::<Vec<_>>().join(", ");
    let maps = format!("maps = [{sides}]");
    let biases = (0..513).map(|k| format!("{}", f64::from(k) / 1e4)).collect::<Vec<_>>().join(", ");
    let big = format!("[[algorithms]]\nalgo = \"first\"\nbias = [{biases}]\n");
    for (extra, replace, key) in [
        ("[[algorithms]]\nalgo = \"fourth\"\n", None, "algorithms[0].algo"),
        ("[[algorithms]]\nalgo = \"dual\"\n", None, "algorithms[0].offset"),
        ("[[algorithms]]\nalgo = \"first\"\nbias = [2.0]\n", None, "algorithms[0].bias"),
        ("[[algorithms]]\nalgo = \"first\"\ncull = [\"walls=none\"]\n", None, "algorithms[0].cull"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("\"d16\"", "\"d12\"")), "formats[0]"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("maps = [128]", "maps = [0]")), "maps[0]"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("\"point\"", "\"blur\"")), "filters[0]"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("\"talisman\"", "\"cray\"")), "archs[0]"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("[\"table-and-sphere\"]", "[\"nowhere\"]")), "scenes[0]"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("budgets = [1.0]", "budgets = [-1.0]")), "budgets[0]"),
        (
            "[[algorithms]]\nalgo = \"first\"\n[[arch_axes]]\nkey = \"clock\"\nvalues = [\"fast\"]\n",
            None,
            "arch_axes[0]",
        ),
        ("[[algorithms]]\nalgo = \"first\"\nspeed = 3\n", None, "(line 12, `speed = 3`)"),
        // Repeats would run every configuration twice; sizes are whole.
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("maps = [128]", "maps = [128, 128]")), "maps[1]"),
        (
            "[[algorithms]]\nalgo = \"first\"\n",
            Some(("[\"table-and-sphere\"]", "[\"table-and-sphere\", \"table-and-sphere\"]")),
            "scenes[1]",
        ),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("budgets = [1.0]", "budgets = [1.0, 1.0]")), "budgets[1]"),
        (
            "[[algorithms]]\nalgo = \"first\"\n",
            Some(("budgets = [1.0]", "budgets = [1.0, \"glare=1%\"]")),
            "budgets[1]",
        ),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("budgets = [1.0]", "budgets = [\"acne=0%\"]")), "budgets[0]"),
        ("[[algorithms]]\nalgo = \"first\"\nbias = [0.0, 0.0]\n", None, "algorithms"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("[[64, 36]]", "[[64, 36, 2]]")), "(line"),
        ("[[algorithms]]\nalgo = \"first\"\n", Some(("[[64, 36]]", "[[64.5, 36]]")), "(line"),
        // A sweep too large to run (2048 maps × 513 biases) is refused
        // before it starts.
        (&big, Some(("maps = [128]", &maps as &str)), "(axes)"),
    ] {
        let mut text = format!("{base}{extra}");
        if let Some((a, b)) = replace {
            text = text.replace(a, b);
        }
        let f = d.join("bad.toml");
        std::fs::write(&f, &text).expect("write");
        let Err(e) =
            SweepFile::open(f.to_str().expect("UTF-8"), &Limits::DEFAULT).and_then(|s| s.spec(&Limits::DEFAULT))
        else {
            panic!("{key}: accepted");
        };
        assert!(e.key.starts_with(key) && e.to_string().contains("bad.toml"), "{key}: {e}");
    }
    assert!(SweepFile::bundled("huge").is_err_and(|e| e.key == "(name)"));
}

/// Axis values are compared as the values they mean: two spellings of one
/// value are refused naming both, and one key is one axis. Each case ran
/// twice (two identical rows per configuration) before.
#[test]
fn one_value_under_two_spellings_is_refused() {
    let d = dir("spellings");
    let base = "name = \"s\"\nscenes = [\"table-and-sphere\"]\nimages = [[64, 36]]\nreference_rays = 1\nformats = [\"d16\"]\n\
                maps = [128]\nfilters = [\"point\"]\narchs = [\"talisman\"]\nbudgets = [1.0]\n[[algorithms]]\nalgo = \"first\"\n";
    let axis = |key: &str, values: &str| format!("[[arch_axes]]\nkey = \"{key}\"\nvalues = {values}\n");
    for (extra, replace, key, both) in [
        // The issue's examples: a bandwidth spelt with and without a space,
        // and a count written whole and as a real.
        (axis("dram.bandwidth", r#"["1GB/s", "1 GB/s"]"#), None, "arch_axes[0].values[1]", ["`1 GB/s`", "`1GB/s`"]),
        (axis("dram.requests_in_flight", "[1, 1.0, 2]"), None, "arch_axes[0].values[1]", ["`1`", "repeats"]),
        // Ours: one size in two units; one key as two axes; one filter as
        // a name and as a table.
        (axis("map_cache.size", r#"["16KiB", "16384B"]"#), None, "arch_axes[0].values[1]", ["`16384B`", "`16KiB`"]),
        (
            axis("dram.bandwidth", r#"["1GB/s"]"#) + &axis("dram.bandwidth", r#"["2GB/s"]"#),
            None,
            "arch_axes[1].key",
            ["also arch_axes[0].key", "dram.bandwidth"],
        ),
        (String::new(), Some(("[\"point\"]", "[\"box3\", { box = 3 }]")), "filters[1]", ["box3", "repeats"]),
    ] {
        let mut text = format!("{base}{extra}");
        if let Some((a, b)) = replace {
            text = text.replace(a, b);
        }
        let f = d.join("spelt.toml");
        std::fs::write(&f, &text).expect("write");
        let e = SweepFile::open(f.to_str().expect("UTF-8"), &Limits::DEFAULT)
            .and_then(|s| s.spec(&Limits::DEFAULT))
            .expect_err(key);
        assert!(e.key == key && both.iter().all(|w| e.problem.contains(w)), "{key}: {e}");
    }
    // Distinct values on one axis still load: 1 GB/s and 2 GB/s.
    let f = d.join("fine.toml");
    std::fs::write(&f, format!("{base}{}", axis("dram.bandwidth", r#"["1GB/s", "2 GB/s"]"#))).expect("write");
    let spec = SweepFile::open(f.to_str().expect("UTF-8"), &Limits::DEFAULT)
        .and_then(|s| s.spec(&Limits::DEFAULT))
        .expect("two values");
    assert_eq!(spec.archs.len(), 2);
    // A `--set` of the key the axis varies would run one value while each
    // row records another.
    let request = |sets: Vec<String>| umbra::sim::experiment::study::Request {
        sweep: f.to_str().expect("UTF-8").into(),
        overrides: umbra::sim::experiment::study::Overrides { sets, ..Default::default() },
        shard: None,
        extremes: false,
        out: "target/unused".into(),
        replace: false,
    };
    let e = request(vec!["dram.bandwidth=3GB/s".into()]).prepare(&Limits::DEFAULT, 1).expect_err("swept key");
    assert!(e.to_string().contains("arch_axes vary `dram.bandwidth`"), "{e}");
    request(vec!["clock=2GHz".into()]).prepare(&Limits::DEFAULT, 1).expect("another key");
}

/// A sweep's budgets bound any measure the planner's do: a number is
/// artifacts, as every earlier file meant; `MEASURE=PERCENT` another; and
/// the summary judges each row by the measure its budget names.
#[test]
fn budgets_on_any_measure() {
    use umbra::sim::experiment::study::budget::{Budget, Measure};
    let d = dir("measures");
    let text = "format = 3\nname = \"m\"\nscenes = [\"table-and-sphere\"]\nimages = [[64, 36]]\nreference_rays = 1\n\
                formats = [\"d16\"]\nmaps = [128]\nfilters = [\"point\"]\narchs = [\"talisman\"]\n\
                budgets = [1.0, \"acne=0.01%\", \"misclassified=5%\"]\n[[algorithms]]\nalgo = \"first\"\n";
    let f = d.join("m.toml");
    std::fs::write(&f, text).expect("write");
    let l = Limits::DEFAULT;
    let spec = SweepFile::open(f.to_str().expect("UTF-8"), &l).and_then(|s| s.spec(&l)).expect("loads");
    let want = [(Measure::Artifacts, 1.0), (Measure::Acne, 0.01), (Measure::Misclassified, 5.0)];
    assert_eq!(spec.budgets, want.map(|(measure, percent)| Budget { measure, percent }));
    assert_eq!(spec.budgets.iter().map(Budget::short).collect::<Vec<_>>(), ["1 %", "acne 0.01 %", "misclassified 5 %"]);
}
