//! The ledger's property: in every output of every algorithm on every
//! bundled architecture, the parts add up to the totals — the printed
//! report, `cost.json`, the stats file and the study's row — and shadow
//! volumes pay the lit pass's shading and colour as a map's camera pass
//! does, on the same pixels, and are described without a map.

use std::collections::BTreeMap;

use crate::cost::arch::{Arch, BUNDLED};
use crate::cost::dram::Purpose;
use crate::cost::report::CostReport;
use crate::cost::report::stats::{Figure, RowCost};
use crate::input::limits::Limits;
use crate::pass::algorithm::Algorithm;
use crate::render::{RenderConfig, TruthSource, render_costed};
use crate::world::scene::Scene;

/// Whole cycles as the stats file and the rows round each figure: a sum
/// of `n` rounded parts lies within `n / 2` of the rounded total.
fn near(total: f64, parts: f64, n: usize) -> bool {
    #[allow(clippy::cast_precision_loss, reason = "a handful of parts")]
    let slack = n as f64 / 2.0 + 1.0;
    (total - parts).abs() <= slack
}

/// The printed report's byte sentence: the frame's bytes, then each pass's
/// bytes and its parts (`light pass 123 (bins 100, map writes 23)`).
fn printed_bytes(md: &str) -> (u64, Vec<(u64, u64)>) {
    let line = md.lines().find_map(|l| l.strip_prefix("DRAM bytes, ")).expect("the bytes' sentence");
    let (total, rest) = line.split_once(" in all: ").expect("a total");
    let passes = rest
        .split("; ")
        .map(|pass| {
            let (head, parts) = pass.split_once(" (").expect("a pass's parts");
            let figure = head.rsplit(' ').next().and_then(|n| n.parse().ok()).expect("a pass's bytes");
            let parts = parts.split(')').next().unwrap_or_default();
            let sum = parts
                .split(", ")
                .filter(|p| *p != "none")
                .map(|p| p.rsplit(' ').next().and_then(|n| n.parse::<u64>().ok()).expect("a part's bytes"))
                .sum();
            (figure, sum)
        })
        .collect();
    (total.parse().expect("the frame's bytes"), passes)
}

/// Every ledger of `r` adds up, in every output.
fn check(r: &CostReport, what: &str) {
    // The report itself: each pass's purposes and causes.
    for (pass, t) in [("light", &r.light), ("camera", &r.camera)] {
        assert_eq!(t.dram.fields().map(|(_, b)| b).sum::<u64>(), t.bytes(), "{what}: {pass} bytes");
        let ledger = t.overhead + t.bound_cycles.iter().sum::<f64>();
        assert!((ledger - t.cycles()).abs() <= 1e-9 * ledger.max(1.0), "{what}: {pass} cycles");
    }
    assert_eq!(r.light.bytes() + r.camera.bytes(), r.bytes(), "{what}");
    // Independent of the ledger: four bytes of colour a pixel the shading
    // unit reported shaded, and no lookup's bytes on a pass without one.
    let colour = r.camera.dram.get(Purpose::Colour);
    assert_eq!(colour, 4 * r.camera_events.pixels_shaded, "{what}: colour");
    if r.camera_events.map_reads() == 0 {
        assert_eq!(r.camera.dram.get(Purpose::MapReads) + r.camera.dram.get(Purpose::MapCacheFills), 0, "{what}");
    }
    // The printed report.
    let md = r.markdown();
    let (total, passes) = printed_bytes(&md);
    assert_eq!(total, r.bytes(), "{what}: printed total");
    assert!(md.contains(&format!(", {} DRAM bytes,", r.bytes())), "{what}: the frame's line");
    assert_eq!(passes.len(), 2, "{what}");
    for (figure, sum) in &passes {
        assert_eq!(figure, sum, "{what}: a printed pass's parts\n{md}");
    }
    assert_eq!(passes.iter().map(|p| p.0).sum::<u64>(), total, "{what}");
    // cost.json.
    let json = serde_json::to_value(r).expect("JSON");
    let sum = |m: &serde_json::Value| -> u64 {
        m.as_object().expect("a map").values().filter_map(serde_json::Value::as_u64).sum()
    };
    assert_eq!(sum(&json["dram"]), json["dram_bytes"].as_u64().expect("bytes"), "{what}: cost.json");
    for pass in ["light", "camera"] {
        let p = &json[pass];
        assert_eq!(sum(&p["dram"]), p["dram_bytes"].as_u64().expect("bytes"), "{what}: cost.json {pass}");
        let bound: f64 =
            p["bound_cycles"].as_object().expect("a map").values().filter_map(serde_json::Value::as_f64).sum();
        let cycles = p["cycles"].as_f64().expect("cycles");
        assert!((bound + p["overhead_cycles"].as_f64().expect("overhead") - cycles).abs() <= 1e-6 * cycles.max(1.0));
    }
    let frame = json["host_cycles"].as_f64().unwrap_or(0.0)
        + json["light"]["cycles"].as_f64().unwrap_or(0.0)
        + json["camera"]["cycles"].as_f64().unwrap_or(0.0);
    assert!((frame - json["cycles"].as_f64().expect("cycles")).abs() <= 1e-6 * frame.max(1.0), "{what}");
    // The stats file's statistics.
    let stats: BTreeMap<String, f64> = r
        .statistics()
        .into_iter()
        .filter_map(|s| match s.value {
            Figure::Count(n) => Some((s.name, n as f64)),
            Figure::Real(x) => Some((s.name, x)),
            Figure::Bound(_) => None,
        })
        .collect();
    let family = |prefix: &str, suffix: &str| -> (f64, usize) {
        let parts: Vec<f64> =
            stats.iter().filter(|(k, _)| k.starts_with(prefix) && k.ends_with(suffix)).map(|(_, v)| *v).collect();
        (parts.iter().sum(), parts.len())
    };
    for pass in ["light", "camera"] {
        let (bytes, n) = family(&format!("{pass}.dram."), "_bytes");
        assert_eq!(n, Purpose::ALL.len(), "{what}: {pass}'s purposes");
        assert_eq!(bytes, stats[&format!("{pass}.dram_bytes")], "{what}: stats {pass}");
        let (bound, n) = family(&format!("{pass}.bound_cycles."), "");
        let cycles = stats[&format!("{pass}.cycles")];
        assert!(near(cycles, bound + stats[&format!("{pass}.overhead_cycles")], n + 1), "{what}: {pass} cycles");
    }
    let (frame_bytes, n) = family("frame.dram.", "_bytes");
    assert_eq!(n, Purpose::ALL.len(), "{what}: the frame's purposes");
    assert_eq!(frame_bytes, stats["frame.dram_bytes"], "{what}: stats frame");
    let passes = stats["frame.host_cycles"] + stats["light.cycles"] + stats["camera.cycles"];
    assert!(near(stats["frame.cycles"], passes, 3), "{what}: frame cycles");
    // The study's row.
    let row = serde_json::to_value(RowCost::new(r)).expect("a row");
    let row = row.as_object().expect("a map");
    let columns: Vec<u64> = row
        .iter()
        .filter(|(k, _)| k.starts_with("dram_") && k.ends_with("_bytes"))
        .filter_map(|(_, v)| v.as_u64())
        .collect();
    assert_eq!(columns.len(), Purpose::ALL.len(), "{what}: a column per purpose");
    assert_eq!(columns.iter().sum::<u64>(), row["total_dram_bytes"].as_u64().expect("bytes"), "{what}: the row");
}

/// Every algorithm on every bundled architecture, three scenes: every
/// output's parts add up to its totals; shadow volumes shade the pixels a
/// map's camera pass shades and write their colour.
#[test]
fn every_ledger_adds_up_and_volumes_pay_the_lit_pass() {
    let limits = Limits::DEFAULT;
    let archs: Vec<Arch> = BUNDLED.iter().map(|(name, _)| Arch::open(name, &limits).expect("bundled")).collect();
    for name in ["table-and-sphere", "weiskopf-l", "factory"] {
        let scene = Scene::open(name, &limits).expect("bundled");
        let mut colour: BTreeMap<&str, (u64, u64)> = BTreeMap::new();
        for algorithm in Algorithm::every(Algorithm::DEFAULT_BIAS1, Algorithm::DEFAULT_OFFSET) {
            let cfg = RenderConfig {
                algorithm,
                width: 80,
                height: 48,
                map_size: 64,
                reference_rays: 1,
                ..RenderConfig::DEFAULT
            };
            let job = cfg.check(&scene, &limits).expect("a valid configuration");
            let (_, costs) = render_costed(&job, TruthSource::Quiet, &archs).expect("renders");
            for (arch, r) in archs.iter().zip(costs) {
                let r = r.expect("costs");
                check(&r, &format!("{name}, {}, {}", algorithm.name(), arch.name));
                // Shadow volumes name no map's side, format, filter or bias.
                if algorithm == Algorithm::Volumes {
                    for word in ["map", "filter", "bias", "d24", "d16"] {
                        assert!(!r.config.contains(word), "{}: {word}", r.config);
                    }
                    assert_eq!(r.light.bottleneck().name(), "none", "{name} on {}: an empty light pass", arch.name);
                }
                let pixels = (r.camera_events.pixels_shaded, r.camera.dram.get(Purpose::Colour));
                let first = *colour.entry(arch.name.as_str()).or_insert(pixels);
                assert_eq!(
                    pixels,
                    first,
                    "{name}, {} on {}: the lit pass's pixels and colour",
                    algorithm.name(),
                    arch.name
                );
            }
        }
    }
}

/// The row's byte columns are the purposes, each named and explained as
/// the ledger declares it, in its order: a purpose added to the ledger
/// without its column (or a column out of step) fails here.
#[test]
fn the_rows_byte_columns_are_the_ledgers_purposes() {
    let columns: Vec<(&str, &str)> = RowCost::COLUMNS
        .iter()
        .filter(|c| c.0.starts_with("dram_") && c.0.ends_with("_bytes"))
        .map(|c| (c.0, c.3))
        .collect();
    let purposes: Vec<(String, &str)> =
        Purpose::ALL.iter().map(|p| (format!("dram_{}_bytes", p.name()), p.meaning())).collect();
    assert_eq!(columns.len(), purposes.len(), "{columns:?}");
    for ((name, meaning), (want, doc)) in columns.iter().zip(&purposes) {
        assert_eq!((*name, *meaning), (want.as_str(), *doc));
    }
}
