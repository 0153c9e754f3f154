//! The papers' claims at the papers' scale: 512×512 images or larger, the
//! papers' map sizes, each claim asserted in the metric it is argued in
//! (artifacts for acne and leaks, false light for self-unshadowing, area
//! error for filtering, wrong pixels and boundary displacement for
//! silhouette maps). Each threshold was set from a measurement on these
//! exact configurations and sits several pixels from it; the measured
//! figure and the margin are stated beside the assertion. A claim that does
//! not hold here is asserted as the measured failure.

use umbra::core::DepthFormatKind;
use umbra::core::shadow::{Filter, Jitter, MapCoord};
use umbra::sim::Algorithm;
use umbra::sim::experiment::study::{self, Row, RowMetrics, Shard, Spec, Status, Variant};
use umbra::sim::input::limits::Limits;
use umbra::sim::world::scene::{Light, Scene};

/// A metrics-only sweep of one bundled scene at `size` (width, height,
/// reference rays per pixel side), 24-bit maps.
fn sweep(scene: &str, variants: Vec<Variant>, maps: &[u32], filters: Vec<Filter>, size: (u32, u32, u32)) -> Vec<Row> {
    sweep_scene(Scene::bundled(scene).expect("a bundled scene"), variants, maps, filters, size)
}

/// `scene` with its first light moved to `position` (a variant).
fn lit_from(mut scene: Scene, position: [f32; 3]) -> Scene {
    let p = umbra::core::glam::Vec3::from_array(position);
    match &mut scene.lights[0] {
        Light::Spot(view) | Light::Cone(view) => view.position = p,
        Light::Directional(view, _) => view.position = p,
    }
    scene.name = format!("{} lit from {position:?}", scene.name);
    scene
}

/// [`sweep`] of a scene given whole (a variant of a bundled one).
fn sweep_scene(
    scene: Scene,
    variants: Vec<Variant>,
    maps: &[u32],
    filters: Vec<Filter>,
    size: (u32, u32, u32),
) -> Vec<Row> {
    let spec = Spec {
        scenes: vec![scene],
        variants,
        formats: vec![DepthFormatKind::D24],
        map_sizes: maps.to_vec(),
        filters,
        archs: Vec::new(),
        arch_points: Vec::new(),
        images: vec![[size.0, size.1]],
        reference_rays: size.2,
        budgets: Vec::new(),
        cost_limits: Default::default(),
        name: "claims".to_owned(),
        hash: String::new(),
        limits: Limits::DEFAULT,
    };
    let rows = study::run(&spec, Shard::ALL, &indicatif::ProgressBar::hidden()).expect("within the limits");
    for r in &rows {
        assert_eq!(r.status, Status::Ok, "{}: {}", r.label(), r.reason);
        let m = m(r);
        eprintln!(
            "{} {} map {}² {}: misclassified {:.4} % (aliasing {}, penumbra {}, acne {} ({} terminator), detachment {}, leaks {}), false light {} px, MAE {:.5}, displacement {}/{} px, {}×{} texels/px",
            r.config.scene,
            r.label(),
            r.config.map_side_texels,
            r.config.filter_name,
            m.misclassified_percent,
            m.aliasing_px,
            m.penumbra_px,
            m.acne_px,
            m.terminator_acne_px,
            m.detachment_px,
            m.leaks_px,
            m.false_light_px,
            m.mean_abs_error,
            m.displacement_mean_px,
            m.displacement_p95_px,
            m.footprint_x_texels_per_px,
            m.footprint_y_texels_per_px
        );
    }
    rows
}

fn filter(f: Filter) -> Vec<Filter> {
    vec![f]
}

/// A measured row's metrics.
fn m(r: &Row) -> RowMetrics {
    r.metrics.expect("measured")
}

fn artifacts(r: &Row) -> u64 {
    m(r).artifacts_px()
}

/// Pixels of false light.
fn false_light(r: &Row) -> u64 {
    m(r).false_light_px
}

/// Wang & Molnar §2 and Figure 4: on their table, lit from low to the side,
/// no first-depth bias is acceptable — a dense sweep of 31 biases from 0 to
/// 0.03 at 512×512 with a 512² 24-bit map (bilinear) leaves every bias with
/// acne or detachment, while second depth at bias 0 has almost none.
/// Artifacts are wrong pixels judged by their cause.
///
/// * Second depth: measured 5 artifacts (4 acne, 1 leak); asserted ≤ 15.
/// * First depth's best bias (0.015): 257 artifacts, 72 acne on the
///   sphere's terminator and 185 detachment at the legs; every bias leaves
///   at least that many (asserted ≥ 150). Acne falls and detachment rises
///   with the bias: no bias clears both.
/// * Below 0.022 acne dominates, and on the bundled table it is the
///   sphere's terminator, not the floor: from bias 0.005 on, at least 99 %
///   of the acne lies on a surface turning from the light (measured 738 of
///   743 at 0.005, all of it above); asserted at least 90 %. The floor's
///   own acne is gone by 0.005.
#[test]
fn wang_molnar_no_first_depth_bias_is_acceptable() {
    let biases: Vec<f64> = (0..=30).map(|k| f64::from(k) * 0.001).collect();
    let mut variants: Vec<Variant> = biases.iter().map(|&b| Variant::new(Algorithm::First, b)).collect();
    variants.push(Variant::new(Algorithm::Second, 0.0));
    let rows = sweep("table-and-sphere", variants, &[512], filter(Filter::Bilinear), (512, 512, 1));
    let second = rows.iter().find(|r| r.config.algorithm == "second").expect("second");
    let first: Vec<&Row> = rows.iter().filter(|r| r.config.algorithm == "first").collect();
    let best = first.iter().map(|r| artifacts(r)).min().expect("biases");
    eprintln!("second depth: {} artifacts; first depth's best bias: {best}", artifacts(second));
    assert!(artifacts(second) <= 15, "second depth: {} artifacts", artifacts(second));
    assert!(best >= 150, "a first-depth bias leaves only {best} artifacts");
    for r in first.iter().filter(|r| r.config.bias >= 0.005) {
        let (acne, terminator) = (m(r).acne_px, m(r).terminator_acne_px);
        assert!(terminator * 10 >= acne * 9, "bias {}: {terminator} of {acne} acne on terminators", r.config.bias);
    }
}

/// Wang & Molnar §2, Figure 4 on their own set-up (`wang-molnar-4`: the
/// table on the floor, nothing else, lit from low to the side so that the
/// floor shadows itself) and on two variants with the light moved (higher,
/// above the table top, which then shadows itself too; and lower and
/// nearer), each at their 512² (4a) and 2048² (4b) maps, 512×512,
/// bilinear, 16 biases from 0 to 0.03, against second depth at bias 0.
/// Measured (set-up; higher; lower):
///
/// * Second depth: 7, 13 and 30 artifacts at 512² (acne on the legs'
///   terminators, a leak under a foot); asserted ≤ 45.
/// * A larger map needs a smaller bias (their §2): the acne clears at
///   0.002, 0.002, 0.004 with 2048² against 0.008, 0.008, 0.012 with 512²;
///   asserted smaller at 2048² on each.
/// * **No acceptable bias at 512²** (Figure 4a): the bias that clears the
///   floor's acne detaches the legs' shadows — 123, 144 and 273 pixels of
///   detachment there (asserted at least 80) — and no bias leaves fewer
///   artifacts than that (asserted at least 80, and at least 4× second
///   depth's). (With the edge band this release replaced, the detachment
///   lay within the texel's band and counted as edge placement: at most
///   1 artifact, and the claim did not reproduce.)
/// * Beyond that bias the shadows move further from the legs: aliasing,
///   detachment and leaks together grow to 0.03 by 1.9×, 1.9×, 1.55× at
///   512² and 6.1×, 5.9×, 5× at 2048² (asserted ≥ 1.3× and ≥ 3×).
#[test]
fn wang_molnar_figure_4_on_their_set_up_and_variants() {
    let biases =
        [0.0, 0.0005, 0.001, 0.0015, 0.002, 0.003, 0.004, 0.005, 0.006, 0.008, 0.01, 0.012, 0.015, 0.02, 0.025, 0.03];
    let set_up = Scene::bundled("wang-molnar-4").expect("bundled");
    for scene in [set_up.clone(), lit_from(set_up.clone(), [5.5, 1.6, 2.5]), lit_from(set_up, [6.0, 0.5, 1.0])] {
        let name = scene.name.clone();
        let mut variants: Vec<Variant> = biases.iter().map(|&b| Variant::new(Algorithm::First, b)).collect();
        variants.push(Variant::new(Algorithm::Second, 0.0));
        let rows = sweep_scene(scene, variants, &[512, 2048], filter(Filter::Bilinear), (512, 512, 1));
        let at = |map: u32| -> Vec<&Row> { rows.iter().filter(|r| r.config.map_side_texels == map).collect() };
        let first = |map: u32| -> Vec<&Row> { at(map).into_iter().filter(|r| r.config.algorithm == "first").collect() };
        let clears = |map: u32| first(map).into_iter().find(|r| m(r).acne_px == 0).expect("a bias clears the acne");
        let second = |map: u32| at(map).into_iter().find(|r| r.config.algorithm == "second").expect("second");
        let (small, large) = (clears(512).config.bias, clears(2048).config.bias);
        let detached = m(clears(512)).detachment_px;
        let best = first(512).iter().map(|r| artifacts(r)).min().expect("biases");
        let moved = |r: &Row| m(r).aliasing_px + m(r).detachment_px + m(r).leaks_px;
        let growth = |map: u32| moved(first(map).last().expect("biases")) as f64 / moved(clears(map)).max(1) as f64;
        eprintln!(
            "{name}: second depth {} artifacts; the acne clears at {small} (512²) and {large} (2048²); {detached} detached there; best 512² bias {best} artifacts; growth {:.2}× and {:.2}×",
            artifacts(second(512)),
            growth(512),
            growth(2048)
        );
        assert!(artifacts(second(512)) <= 45, "{name}: second depth {} artifacts", artifacts(second(512)));
        assert!(large < small, "{name}: the acne clears at {large} with 2048² against {small} with 512²");
        assert!(detached >= 80, "{name}: {detached} detached at the bias that clears the acne");
        assert!(best >= 80 && best >= 4 * artifacts(second(512)), "{name}: best first-depth bias {best} artifacts");
        assert!(growth(512) >= 1.3 && growth(2048) >= 3.0, "{name}: growth {} and {}", growth(512), growth(2048));
    }
}

/// Weiskopf & Ertl §3–§4 and Figure 5 on their L (one closed mesh, lit from
/// the right above so that the upright shadows the base), 512×512,
/// bilinear, at a heavily undersampled 128² map and at 512², and on the
/// variant a modeller builds: the L as two touching boxes
/// (`weiskopf-l-boxes`).
///
/// * Back-face culling removes dual depth's self-shadowing at the
///   silhouettes (Figure 2 (b), 5 (c) against (f)). Measured acne with
///   culling against without: closed L 77 against 2213 (128²) and 5
///   against 645 (512²); asserted at least 15× fewer. On the two boxes
///   culling leaves 545 and 132 acne pixels where the upright stands on
///   the base (each box's own back faces are in `z2` there, behind the
///   other's top, within the receiver's span), against 2673 and 771
///   without: asserted at least 300 and 50, and at most a third and a half
///   of the unculled count. (The edge band this release replaced counted
///   57 and 95 of them.)
/// * Midpoint maps with back-face culling self-unshadow near silhouettes
///   (Figure 4, 5 (e)), dual depth does not: leaks 117 against 0 at 128²
///   and 29 against 0 at 512² on the closed L (111 and 27 on the boxes);
///   asserted at least +60 and +15. The ½ verdict's false light shows it
///   too: 142 against 112 and 51 against 45 (asserted at least +15 and
///   +2). (With the edge band these leaks lay within it and counted none.)
/// * Not reproduced: Figure 5 (b)'s self-unshadowing of the midpoint
///   without culling — its false light equals dual depth's on every
///   variant, because without culling `z2` is the L's own back, close
///   behind `z1`, and the midpoint never passes a receiver (asserted as
///   measured, within 5 pixels).
#[test]
fn weiskopf_ertl_dual_depth_with_culling() {
    let variants = vec![
        Variant::new(Algorithm::Dual { offset: 0.05 }, 0.0),
        // Woo's midpoint by the dual test with an unlimited offset:
        // z1 + min((z2 − z1)/2, 1) = (z1 + z2)/2, so it runs with
        // Weiskopf & Ertl's per-object back-face culling.
        Variant::new(Algorithm::Dual { offset: 1.0 }, 0.0),
        Variant::new(Algorithm::Midpoint, 0.0),
        Variant::new(Algorithm::Dual { offset: 0.05 }, 0.0).without_culling(),
    ];
    for scene in ["weiskopf-l", "weiskopf-l-boxes"] {
        let rows = sweep(scene, variants.clone(), &[128, 512], filter(Filter::Bilinear), (512, 512, 1));
        for map in [128, 512] {
            // One row per variant, in the variants' order.
            let at: Vec<&Row> = rows.iter().filter(|r| r.config.map_side_texels == map).collect();
            let (dual, mid_bfc, midpoint, nocull) = (at[0], at[1], at[2], at[3]);
            let acne = |r: &Row| m(r).acne_px;
            let leaks = |r: &Row| m(r).leaks_px;
            let here = format!("{scene}, {map}²");
            eprintln!(
                "{here}: acne with culling {} against {} without; leaks midpoint-bfc {} against dual {}",
                acne(dual),
                acne(nocull),
                leaks(mid_bfc),
                leaks(dual)
            );
            assert!(acne(nocull) >= 400, "{here}: dual depth without culling: {} acne", acne(nocull));
            if scene == "weiskopf-l" {
                assert!(acne(dual) * 15 <= acne(nocull), "{here}: dual depth with culling: {} acne", acne(dual));
            } else {
                let (lo, hi) = if map == 128 { (300, 3) } else { (50, 2) };
                assert!(
                    acne(dual) >= lo && acne(dual) * hi <= acne(nocull),
                    "{here}: {} against {}",
                    acne(dual),
                    acne(nocull)
                );
            }
            let unshadowed = if map == 128 { 60 } else { 15 };
            assert!(
                leaks(mid_bfc) >= leaks(dual) + unshadowed,
                "{here}: leaks: midpoint-bfc {} against dual {}",
                leaks(mid_bfc),
                leaks(dual)
            );
            let gain = if map == 128 { 15 } else { 2 };
            assert!(
                false_light(mid_bfc) >= false_light(dual) + gain,
                "{here}: false light: midpoint-bfc {} against dual {}",
                false_light(mid_bfc),
                false_light(dual)
            );
            assert!(false_light(midpoint).abs_diff(false_light(dual)) <= 5, "{here}: midpoint without culling");
        }
    }
}

/// Reeves et al. §4 on their sphere, first depth at bias 0.01, 512² 24-bit,
/// 512×512 (the map magnified, 0.53 texels per pixel), the area-averaged
/// reference at 4×4 rays per pixel: the jittered filter's mean absolute
/// area error as `NumSamples` goes 1 → 4 → 16, with Reeves' own `ResFactor`
/// 3 and with 1.
///
/// Measured, ResFactor 3: 2.668, 1.995, 1.941 ×10⁻³ — more samples, less
/// error, asserted as a fall of at least 15 % from 1 to 4 samples (measured
/// 25 %) and no rise from 4 to 16 (measured −2.7 %). ResFactor 1: 1.656,
/// 1.582, 1.582 ×10⁻³ — a region under a texel wide takes no more than 4
/// samples, so 16 equals 4; and it is below ResFactor 3 at every count
/// (asserted at least 10 % below; measured 19–38 %): the wider region blurs
/// past the pixel's own area.
#[test]
fn reeves_more_samples_less_error() {
    let filters = [1.0, 3.0]
        .iter()
        .flat_map(|&res| {
            [1u16, 4, 16].map(|n| {
                let j = Jitter { num_samples: n, res_factor: MapCoord::from_num(res), ..Jitter::REEVES };
                Filter::Jittered(j)
            })
        })
        .collect();
    let rows = sweep("reeves-sphere", vec![Variant::new(Algorithm::First, 0.01)], &[512], filters, (512, 512, 4));
    let mae: Vec<f64> = rows.iter().map(|r| m(r).mean_abs_error).collect();
    eprintln!("mean absolute error, ResFactor 1 then 3, for 1, 4, 16 samples: {mae:?}");
    let (res1, res3) = (&mae[..3], &mae[3..]);
    assert!(res3[1] < 0.85 * res3[0], "ResFactor 3, 1 → 4 samples: {res3:?}");
    assert!(res3[2] <= res3[1], "ResFactor 3, 4 → 16 samples: {res3:?}");
    for k in 0..3 {
        assert!(res1[k] < 0.9 * res3[k], "ResFactor 1 against 3: {res1:?} {res3:?}");
    }
}

/// Reeves et al. §4 on variants of their sphere: the map at 256² and at
/// 1024², jittered with `ResFactor` 3, 512×512, the 4×4-ray reference.
/// Mean absolute area error for 1, 4 and 16 samples, measured ×10⁻³:
///
/// * 1024²: 2.535, 1.881, 1.779 — a fall of 26 % from 1 to 4 samples
///   (asserted at least 15 %) and 5 % more to 16 (asserted no rise beyond
///   0.5 %): the claim holds.
/// * 256²: 3.142, 3.007, 3.002 — it holds by only 4.3 % (asserted at least
///   2 %), then flat: the region of 3 texels spans about 6 pixels here, and
///   its blur past the pixel's own area, which no number of samples
///   removes, is most of the error.
#[test]
fn reeves_more_samples_less_error_on_variants() {
    let filters: Vec<Filter> = [1u16, 4, 16]
        .map(|n| Filter::Jittered(Jitter { num_samples: n, res_factor: MapCoord::from_num(3.0), ..Jitter::REEVES }))
        .to_vec();
    for map in [256, 1024] {
        let rows =
            sweep("reeves-sphere", vec![Variant::new(Algorithm::First, 0.01)], &[map], filters.clone(), (512, 512, 4));
        let mae: Vec<f64> = rows.iter().map(|r| m(r).mean_abs_error).collect();
        eprintln!("{map}²: mean absolute error for 1, 4, 16 samples: {mae:?}");
        let fall = if map == 1024 { 0.85 } else { 0.98 };
        assert!(mae[1] < fall * mae[0], "{map}², 1 → 4 samples: {mae:?}");
        assert!(mae[2] <= mae[1] * 1.005, "{map}², 4 → 16 samples: {mae:?}");
    }
}

/// Sen, Cammarano & Hanrahan §6 on CROWD, first depth at bias 0.002 under
/// both, point sampled: the silhouette map's wrong pixels against the
/// shadow map's with the map magnified on screen (`crowd-zoom`, 600×512,
/// 512² map, 0.031 texels per pixel along x) and minified (`crowd` at
/// 512×512 with a 2048² map, 3.2 texels per pixel).
///
/// * Magnified, the silhouette map's edges are where the exact ones are:
///   measured 0.061 % misclassified against 1.452 % (24×; asserted at least
///   10×), 48 edge-placement pixels against 1141 (asserted at least 10×
///   fewer), mean boundary displacement 0.009 against 0.405 pixels
///   (asserted below 0.1 and above 0.2). Neither has an artifact (a
///   magnified texel's staircase is aliasing, not acne): measured 0 and
///   0, asserted ≤ 5.
/// * Minified, the gain shrinks to 1.7× (0.063 % against 0.106 %; asserted
///   below 3×): a texel is smaller than a pixel, so the shadow map's
///   staircase is already under a pixel. At the same bias the silhouette
///   map adds acne on the figures' terminators: measured 95 (84 of them
///   terminator) against the shadow map's 22, asserted ≥ 60 (≥ 50
///   terminator) and at least twice the shadow map's. (The edge band this
///   release replaced excused most of both: 35 against 1.)
#[test]
fn sen_silhouette_maps_sharpen_magnified_edges() {
    let variants =
        vec![Variant::new(Algorithm::First, 0.002), Variant::new(Algorithm::Silhouette { packed: false }, 0.002)];
    let zoom = sweep("crowd-zoom", variants.clone(), &[512], filter(Filter::Point), (600, 512, 1));
    let wide = sweep("crowd", variants, &[2048], filter(Filter::Point), (512, 512, 1));
    let err = |r: &Row| m(r).misclassified_percent;
    let (map, sil) = (&zoom[0], &zoom[1]);
    assert!(
        m(map).footprint_x_texels_per_px < 1.0 && m(&wide[0]).footprint_x_texels_per_px > 1.0,
        "magnified, then minified"
    );
    assert!(err(sil) * 10.0 < err(map), "magnified: silhouette {} % against {} %", err(sil), err(map));
    let edge = |r: &Row| m(r).aliasing_px;
    assert!(edge(sil) * 10 < edge(map), "edge placement {} against {}", edge(sil), edge(map));
    assert!(artifacts(sil) <= 5 && artifacts(map) <= 5, "artifacts {} and {}", artifacts(sil), artifacts(map));
    let shift = |r: &Row| m(r).displacement_mean_px;
    assert!(shift(sil) < 0.1 && shift(map) > 0.2, "displacement {} against {}", shift(sil), shift(map));
    assert!(err(&wide[1]) * 3.0 > err(&wide[0]), "minified: {} % against {} %", err(&wide[1]), err(&wide[0]));
    let (acne, terminator) = (m(&wide[1]).acne_px, m(&wide[1]).terminator_acne_px);
    assert!(acne >= 60 && terminator >= 50, "silhouette map, minified: {acne} acne, {terminator} terminator");
    assert!(m(&wide[0]).acne_px * 2 <= acne, "shadow map, minified: {} acne against {acne}", m(&wide[0]).acne_px);
}

/// Sen et al. §6 on the crowd seen from above its shadows
/// (`crowd-overhead`, the 512² map magnified along both axes, 0.26 and
/// 0.05 texels a pixel) and on variants of `crowd-zoom`: a 256² map, and
/// `crowd-grazing` (the light lowered from 3 to 1.2 above the floor so that
/// the floor is lit near grazing), at 512² and 256². Misclassified, shadow map against
/// silhouette map, measured: overhead 1.781 % against 0.679 % (2.6×;
/// asserted at least 2×); 256² 2.589 % against 0.639 % (4.1×); grazing 512²
/// 1.480 % against 0.252 % (5.9×); asserted at least 3× on both. **Not
/// on the grazing floor at 256²**: 12.62 % against 11.34 % (1.1×;
/// asserted below 1.5×): a texel there spans so much of the floor that
/// one silhouette point per texel cannot place the edge of the figures'
/// thin, overlapping shadows.
#[test]
fn sen_silhouette_maps_on_variants_of_the_zoomed_crowd() {
    let variants =
        vec![Variant::new(Algorithm::First, 0.002), Variant::new(Algorithm::Silhouette { packed: false }, 0.002)];
    let set_up = Scene::bundled("crowd-zoom").expect("bundled");
    let gain = |rows: &[Row], map: u32| {
        let at: Vec<&Row> = rows.iter().filter(|r| r.config.map_side_texels == map).collect();
        m(at[0]).misclassified_percent / m(at[1]).misclassified_percent.max(1e-9)
    };
    let zoom = sweep_scene(set_up, variants.clone(), &[256], filter(Filter::Point), (600, 512, 1));
    let low = sweep("crowd-grazing", variants.clone(), &[256, 512], filter(Filter::Point), (600, 512, 1));
    let overhead = sweep("crowd-overhead", variants, &[512], filter(Filter::Point), (512, 512, 1));
    let m0 = m(&overhead[0]);
    assert!(m0.footprint_x_texels_per_px < 1.0 && m0.footprint_y_texels_per_px < 1.0, "magnified both ways");
    assert!(gain(&overhead, 512) >= 2.0, "overhead: {}×", gain(&overhead, 512));
    assert!(gain(&zoom, 256) >= 3.0, "256²: {}×", gain(&zoom, 256));
    assert!(gain(&low, 512) >= 3.0, "grazing, 512²: {}×", gain(&low, 512));
    assert!(gain(&low, 256) < 1.5, "grazing, 256²: {}×", gain(&low, 256));
}

/// Sen et al.'s Table 1 on CROWD zoomed in on the shadow (`crowd-zoom` at
/// its 600×512, on `talisman`): the overdraw `O` of the shadow volumes and
/// the silhouette fill `P`, beside theirs (O = 154.2, P = 13.3 %).
/// Measured O = 70.6 on `crowd-zoom` against 4.96 on the wide `crowd`
/// (asserted above 40 and at least 10× the wide view's), P = 8.95 %
/// (asserted between 5 % and 16 %, Sen's bound for silhouette maps to cost
/// less than twice a shadow map's bandwidth). Zoomed in from above
/// (`crowd-overhead`), where the volumes are seen end-on, O = 6.4 and
/// P = 2.7 % (asserted below 10 and 16 %): the overdraw is a property of
/// looking across the volumes, not of zooming in. The figures
/// `docs/claims.md` quotes (what `umbra cost` prints for these renders)
/// are held to the measurement as written there.
#[test]
fn sen_table_one_overdraw_and_silhouette_fill() {
    use umbra::sim::cost::arch::Arch;
    use umbra::sim::render::{RenderConfig, cost};
    let arch = Arch::bundled("talisman").expect("bundled");
    let figures = |scene: &str, algorithm| {
        let s = Scene::bundled(scene).expect("bundled");
        let cfg = RenderConfig {
            algorithm,
            format: DepthFormatKind::D24,
            map_size: 512,
            filter: Filter::Point,
            bias: 0.002,
            virtual_samples: true,
            width: s.image[0],
            height: s.image[1],
            reference_rays: 1,
            ..RenderConfig::DEFAULT
        };
        cfg.check(&s, &Limits::DEFAULT).and_then(|job| cost(&job, &arch)).expect("costed").sen
    };
    let zoom = figures("crowd-zoom", Algorithm::Volumes);
    let wide = figures("crowd", Algorithm::Volumes);
    let sil = figures("crowd-zoom", Algorithm::Silhouette { packed: false });
    eprintln!("O = {} (zoom), {} (wide); P = {}", zoom.overdraw, wide.overdraw, sil.p_fill);
    assert!(
        zoom.overdraw > 40.0 && zoom.overdraw > 10.0 * wide.overdraw,
        "O {} against {}",
        zoom.overdraw,
        wide.overdraw
    );
    assert!((0.05..0.16).contains(&sil.p_fill), "P = {}", sil.p_fill);
    // Variants: the crowd seen from above its shadows, where the volumes
    // are seen end-on rather than across.
    let over = figures("crowd-overhead", Algorithm::Volumes);
    let over_sil = figures("crowd-overhead", Algorithm::Silhouette { packed: false });
    eprintln!("overhead: O = {}, P = {}", over.overdraw, over_sil.p_fill);
    assert!(over.overdraw < 10.0 && over_sil.p_fill < 0.16, "overhead: O {}, P {}", over.overdraw, over_sil.p_fill);
    // docs/claims.md: "O = 70.6 against 4.96 wide, P = 8.95 %", "O = 6.4 (P = 2.7 %)".
    let quoted = [(zoom.overdraw, 70.6, 0.05), (wide.overdraw, 4.96, 0.005), (100.0 * sil.p_fill, 8.95, 0.005)];
    let quoted = quoted.into_iter().chain([(over.overdraw, 6.4, 0.05), (100.0 * over_sil.p_fill, 2.7, 0.05)]);
    for (measured, written, half) in quoted {
        assert!((measured - written).abs() <= half, "docs/claims.md says {written}, the model gives {measured}");
    }
}
