//! The papers' claims, measured through the study's sweep (metrics only, no
//! presets) on small images. Each threshold was set from a measurement on
//! these exact configurations and is stated beside the assertion with the
//! measured figure.

use umbra::core::DepthFormatKind;
use umbra::core::shadow::{Filter, Jitter, MapCoord};
use umbra::sim::experiment::study::{self, FIRST_BIASES, Row, Shard, Spec, UNLIMITED_OFFSET, Variant};
use umbra::sim::io::limits::Limits;
use umbra::sim::pass::render::Algorithm;
use umbra::sim::world::scene::Scene;

/// A metrics-only sweep of one scene.
fn sweep(
    scene: &str,
    variants: Vec<Variant>,
    maps: &[u32],
    filters: Vec<(String, Filter)>,
    size: (u32, u32, u32),
) -> Vec<Row> {
    let spec = Spec {
        scenes: vec![Scene::bundled(scene).expect("a bundled scene")],
        variants,
        formats: vec![DepthFormatKind::D24],
        map_sizes: maps.to_vec(),
        filters,
        archs: Vec::new(),
        width: size.0,
        height: size.1,
        reference_samples: size.2,
        limits: Limits::DEFAULT,
    };
    let rows = study::run(&spec, Shard::ALL, &indicatif::ProgressBar::hidden());
    for r in &rows {
        assert_eq!(r.status, "ok", "{}: {}", r.label(), r.reason);
    }
    rows
}

fn bilinear() -> Vec<(String, Filter)> {
    vec![("bilinear".to_owned(), Filter::Bilinear)]
}

fn err(r: &Row) -> f64 {
    r.misclassified_percent.expect("measured")
}

/// Wang & Molnar §1–§3 on their table (legs touching the floor), 240×135,
/// one reference ray per pixel, 24-bit bilinear.
///
/// * No bias of the sweep (0 … 0.01) brings first depth below 0.07 %
///   misclassified at 512² (measured best 0.0715 % at 0.005 and 0.01; bias 0
///   gives 45.9 % acne), while second depth with virtual samples at bias 0
///   stays below 0.07 % (measured 0.0660 %). The margins are thin: on this
///   scene a large bias costs only the few pixels where the legs meet the
///   floor.
/// * No bias is free of both errors: at every bias first depth has more
///   false shadow or more false light than second depth.
/// * At the same map size (256²) second depth beats first depth at its best
///   bias (measured 0.099 % against 0.115 %). Across sizes the claim does
///   not hold here: second depth at 256² (0.099 %) is less accurate than
///   first depth's best at 512² (0.0715 %).
#[test]
fn wang_molnar_table_second_depth_needs_no_bias() {
    let mut variants: Vec<Variant> = FIRST_BIASES.iter().map(|&b| Variant::new("first", Algorithm::First, b)).collect();
    variants.push(Variant::new("second", Algorithm::Second, 0.0));
    let rows = sweep("table", variants, &[256, 512], bilinear(), (240, 135, 1));
    let first = |map: u32| rows.iter().filter(move |r| r.algorithm == "first" && r.map == map);
    let best = |map: u32| first(map).map(err).fold(f64::INFINITY, f64::min);
    let second = |map: u32| rows.iter().find(|r| r.algorithm == "second" && r.map == map).expect("second");
    for r in &rows {
        eprintln!("{} at {}²: {:.4} %", r.label(), r.map, err(r));
    }
    assert!(best(512) > 0.07, "first depth's best bias reached {} %", best(512));
    assert!(err(second(512)) < 0.07, "second depth at bias 0: {} %", err(second(512)));
    let s = second(512);
    for r in first(512) {
        assert!(
            r.false_shadow_rate > s.false_shadow_rate || r.false_light_rate > s.false_light_rate,
            "bias {} is no worse than second depth in either error",
            r.bias
        );
    }
    assert!(err(second(256)) < best(256), "second {} % vs first's best {} % at 256²", err(second(256)), best(256));
}

/// Weiskopf & Ertl §3 on their L-shaped object, 320×180, 512² 24-bit:
/// dual depth with back-face culled solids has fewer self-shadowing errors
/// (false shadow) than dual depth without culling (measured 0.148 % against
/// 0.240 % of the pixels), and no more self-unshadowing (false light) than
/// the midpoint with the same culling (measured 0.023 % for both: here every
/// false-light pixel lies on the L's silhouette, where both references take
/// the same texels; the strict difference needs a receiver between
/// `z1 + offset` and the midpoint, which this scene does not have).
#[test]
fn weiskopf_ertl_dual_depth_with_culling() {
    let variants = vec![
        Variant::new("dual", Algorithm::Dual { offset: 0.005 }, 0.0),
        Variant::new("midpoint-bfc", Algorithm::Dual { offset: UNLIMITED_OFFSET }, 0.0),
        Variant::new("dual-nocull", Algorithm::Dual { offset: 0.005 }, 0.0).without_culling(),
    ];
    let rows = sweep("weiskopf-l", variants, &[512], bilinear(), (320, 180, 1));
    let get = |name: &str| rows.iter().find(|r| r.algorithm == name).expect("row");
    let (dual, mid, nocull) = (get("dual"), get("midpoint-bfc"), get("dual-nocull"));
    let rate = |x: Option<f64>| x.expect("measured");
    assert!(
        rate(dual.false_shadow_rate) < rate(nocull.false_shadow_rate),
        "false shadow: dual {:?} vs no culling {:?}",
        dual.false_shadow_rate,
        nocull.false_shadow_rate
    );
    assert!(
        rate(dual.false_light_rate) <= rate(mid.false_light_rate),
        "false light: dual {:?} vs midpoint {:?}",
        dual.false_light_rate,
        mid.false_light_rate
    );
    // The culling is what removes the self-shadowing: without it the dual
    // map's z2 is the L's own back face.
    assert!(rate(nocull.false_shadow_rate) > 1.5 * rate(dual.false_shadow_rate));
}

/// Reeves et al. §4: the jittered filter's error against the area-averaged
/// reference (4×4 rays per pixel) falls as `NumSamples` goes 1 → 4 → 16, on
/// their sphere, first depth at bias 0.01, 512² 24-bit, 240×135, with
/// `ResFactor` 1 so that the filter's footprint is the pixel's own (Reeves'
/// `ResFactor` 3 blurs past the pixel, and then the blur, not the sampling
/// noise, dominates the error against the pixel's own area). Measured mean
/// absolute error 0.00389, 0.00246, 0.00219.
#[test]
fn reeves_more_samples_less_error() {
    let filters = [1u16, 4, 16]
        .iter()
        .map(|&n| {
            let j = Jitter { num_samples: n, res_factor: MapCoord::ONE, ..Jitter::REEVES };
            (format!("jitter{n}"), Filter::Jittered(j))
        })
        .collect();
    let rows =
        sweep("reeves-sphere", vec![Variant::new("first", Algorithm::First, 0.01)], &[512], filters, (240, 135, 4));
    let mae: Vec<f64> = rows.iter().map(|r| r.mean_abs_error.expect("measured")).collect();
    eprintln!("mean absolute error for 1, 4, 16 samples: {mae:?}");
    assert!(mae[1] < 0.9 * mae[0] && mae[2] < mae[1], "{mae:?}");
}
