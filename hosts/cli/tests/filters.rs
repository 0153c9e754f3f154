//! Reeves et al.'s parameters from the command line: `--filter
//! jitter<NumSamples>` with `,res-factor=`, `,min-samples=` and
//! `,min-size=` draws what the study's presets draw with the same values,
//! other values draw something else, and values the filter cannot take are
//! refused by name before anything is written.

mod common;
use common::{dir, umbra};

/// Render `reeves-sphere` small with `filter` flags; its metrics.json.
fn metrics(name: &str, filter: &[&str]) -> String {
    let out = dir(name);
    let o = out.to_str().expect("UTF-8");
    let mut args = vec!["render", "reeves-sphere", "--algo", "first", "--bias", "0.002", "--map", "128"];
    args.extend(["--width", "96", "--height", "64", "--reference-rays", "1", "--out", o]);
    args.extend(filter);
    let r = umbra(&args);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let text = std::fs::read_to_string(out.join("metrics.json")).expect("metrics");
    let _ = std::fs::remove_dir_all(&out);
    // Everything but the command line that made it.
    let mut m: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    m.as_object_mut().expect("an object").remove("command");
    m.to_string()
}

#[test]
fn reeves_parameters_reach_the_filter() {
    // Reeves' Figure 4 values with 4 samples are the study's `jitter4`.
    let preset = metrics("preset", &["--filter", "jitter4"]);
    let flags = metrics("flags", &["--filter", "jitter4,res-factor=3,min-samples=1,min-size=0"]);
    assert_eq!(preset, flags);
    // A smaller ResFactor samples a smaller region: another result.
    let smaller = metrics("smaller", &["--filter", "jitter4,res-factor=1"]);
    assert_ne!(preset, smaller);
    let out = dir("bad");
    for (bad, named) in [
        ("jitter4,res-factor=-1", "res-factor"),
        ("jitter4,min-size=1e9", "min-size"),
        ("jitter0", "num-samples"),
        ("jitter4,min-samples=0", "min-samples"),
        ("jitter4,blur=2", "res-factor, min-samples and min-size"),
        ("box17", "1 to 16"),
        ("gauss", "not a filter"),
    ] {
        let r = umbra(&["render", "reeves-sphere", "--filter", bad, "--out", out.to_str().expect("UTF-8")]);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success() && err.contains(named), "{bad}: {err}");
    }
    assert!(!out.exists(), "nothing is written");
}
