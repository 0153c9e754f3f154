//! The planner: on two bundled scenes and a scene of shared meshes, under
//! one budget and under several at once, its pick is the cheapest of its
//! whole candidate set (algorithms with their biases and offsets, depth
//! formats, map sides, filters) meeting every budget — checked here by
//! rendering, measuring and costing every candidate on the direct path,
//! each measure counted from the metrics' pixel classes by hand. When no
//! candidate meets the budgets it says so and takes the nearest.

use std::path::Path;

use indicatif::ProgressBar;
use umbra::core::DepthFormatKind;
use umbra::core::shadow::Filter;
use umbra::sim::Algorithm;
use umbra::sim::experiment::plan::{Budget, Plan, PlanSpec, plan};
use umbra::sim::experiment::study::Variant;
use umbra::sim::input::limits::Limits;
use umbra::sim::render::{RenderConfig, TruthSource, cost, render, truth};
use umbra::sim::truth::metrics::Metrics;
use umbra::sim::world::scene::Scene;
use umbra::sim::world::scene_file::shared_meshes;

/// The image the tests plan at: at 192×108 one pixel is about 0.01 % of
/// those evaluated.
const IMAGE: [u32; 2] = [192, 108];

/// One candidate as measured here: its configuration, cycles, DRAM bytes,
/// and the budgeted measures in percent.
type Measured = (RenderConfig, u64, u64, Vec<f64>);

/// A measure of the metrics, percent of the evaluated pixels, counted
/// from the pixel classes (not through the planner's `Measure`).
#[allow(clippy::cast_precision_loss, reason = "pixel counts")]
fn percent(m: &Metrics, measure: &str) -> f64 {
    let px = match measure {
        "acne" => m.acne,
        "leaks" => m.leaks,
        "detachment" => m.detachment,
        "misclassified" => m.false_shadow + m.false_light,
        "artifacts" => m.acne + m.detachment + m.leaks,
        other => panic!("{other}"),
    };
    100.0 * px as f64 / m.evaluated as f64
}

/// Every candidate of `spec`, rendered and costed on the direct path.
fn every_candidate(scene: &Scene, spec: &PlanSpec) -> Vec<Measured> {
    let reference = truth(scene, IMAGE[0], IMAGE[1], 4, &ProgressBar::hidden()).expect("reference");
    let mut out = Vec::new();
    for v in &spec.variants {
        for &format in &spec.formats {
            for &map_size in &spec.map_sizes {
                for &filter in &spec.filters {
                    let cfg = RenderConfig {
                        algorithm: v.algorithm,
                        bias: v.bias,
                        virtual_samples: v.virtual_samples,
                        culling: v.culling,
                        format,
                        map_size,
                        filter,
                        width: IMAGE[0],
                        height: IMAGE[1],
                        reference_rays: 4,
                        cascades: v.cascades,
                    };
                    let job = cfg.check(scene, &Limits::DEFAULT).expect("valid");
                    let r = render(&job, TruthSource::Given(reference.clone())).expect("renders");
                    let c = cost(&job, &spec.arch).expect("costs");
                    let measures = spec.budgets.iter().map(|b| percent(&r.metrics, b.measure.name())).collect();
                    out.push((cfg, c.cycles().round() as u64, c.bytes(), measures));
                }
            }
        }
    }
    out
}

/// A space across the families: first depth at two biases, second depth
/// by front-face culling, the midpoint, dual depth at offset 1 and at a
/// small offset; 16- and 24-bit; two map sides; point and bilinear.
fn spec(scene: &Scene, budgets: &[&str]) -> PlanSpec {
    PlanSpec {
        variants: vec![
            Variant::new(Algorithm::First, 0.001),
            Variant::new(Algorithm::First, 0.005),
            Variant::new(Algorithm::SecondFrontCulled, 0.0),
            Variant::new(Algorithm::Midpoint, 0.0),
            Variant::new(Algorithm::Dual { offset: 1.0 }, 0.0),
            Variant::new(Algorithm::Dual { offset: 0.005 }, 0.0),
        ],
        formats: vec![DepthFormatKind::D16, DepthFormatKind::D24],
        map_sizes: vec![128, 512],
        filters: vec![Filter::Point, Filter::Bilinear],
        image: IMAGE,
        ..PlanSpec::new(scene, budgets.iter().map(|b| b.parse::<Budget>().expect("a budget")).collect())
    }
}

/// Plan `scene` under `budgets` and hold the pick to the exhaustive answer.
fn holds(scene: &Scene, budgets: &[&str]) -> Plan {
    let spec = spec(scene, budgets);
    let p = plan(scene, &spec, &ProgressBar::hidden()).expect("plans");
    let name = &scene.name;
    let all = every_candidate(scene, &spec);
    assert_eq!(p.candidates, all.len(), "{name}: every candidate measured");
    let meets = |c: &Measured| c.3.iter().zip(&spec.budgets).all(|(v, b)| *v <= b.percent);
    let meeting: Vec<&Measured> = all.iter().filter(|c| meets(c)).collect();
    assert_eq!(p.meeting, meeting.len(), "{name} under {budgets:?}");
    let cheapest = meeting.iter().min_by(|a, b| a.1.cmp(&b.1).then(a.2.cmp(&b.2)));
    match cheapest {
        Some(pick) => {
            assert!(p.meets, "{name} under {budgets:?}");
            assert_eq!((p.pick.cycles, p.pick.bytes), (pick.1, pick.2), "{name} under {budgets:?}: {:?}", p.pick);
            let same = |c: &RenderConfig| (c.algorithm, c.bias.to_bits(), c.format, c.map_size, c.filter);
            assert_eq!(same(&p.config), same(&pick.0), "{name} under {budgets:?}");
            for (b, v) in spec.budgets.iter().zip(&pick.3) {
                assert!((p.pick.measure(b.measure) - v).abs() < 1e-9, "{name}: {b}");
            }
        }
        None => {
            assert!(!p.meets && p.reasons.iter().any(|r| r.starts_with("no candidate meets")), "{name}");
        }
    }
    // Each cheaper runner-up misses a budget it names.
    for r in p.runners_up.iter().filter(|r| r.cheaper) {
        assert!(spec.budgets.iter().any(|b| r.lost.contains(b.measure.name())), "{name}: {}", r.lost);
    }
    p
}

/// Two bundled scenes (solids only; open surfaces beside solids), each
/// under one loose budget, under two at once, and under none it can meet.
#[test]
fn plans_pick_the_cheapest_candidate_meeting_every_budget() {
    let mut families = std::collections::BTreeSet::new();
    for name in ["table-and-sphere", "weiskopf-l"] {
        let scene = Scene::bundled(name).expect("bundled");
        // On table-and-sphere the cheapest candidate meeting the acne
        // budget misses the misclassified one (dual at offset 1, 128²:
        // acne 0.05 %, misclassified 1.18 %), so both must be read.
        for budgets in [&["artifacts=1%"][..], &["acne=0.1%", "misclassified=1.1%"], &["misclassified=0%"]] {
            let p = holds(&scene, budgets);
            families.insert(p.pick.algorithm.clone());
        }
    }
    // Not one family wins everywhere: the space matters.
    assert!(families.len() >= 2, "{families:?}");
}

/// A scene of shared meshes (the bunny and spot on a floor).
#[test]
#[ignore = "needs the shared meshes in ../shared/meshes (or UMBRA_MESHES): run with `cargo test --test integration shared_mesh -- --ignored`"]
fn plans_on_the_shared_meshes() {
    assert!(shared_meshes().join("bunny.obj").is_file(), "no shared meshes at {}", shared_meshes().display());
    let text = "name = \"bunny-and-spot\"\nimage = [192, 108]\n[camera]\nposition = [0.0, 1.5, 3.0]\n\
                target = [0.0, 0.3, 0.0]\nfov = 45.0\nnear = 0.3\nfar = 20.0\n[[lights]]\nkind = \"spot\"\n\
                position = [2.0, 3.0, 1.5]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\nnear = 1.0\nfar = 10.0\n\
                [[objects]]\nmesh = { box = { min = [-3.0, -0.1, -3.0], max = [3.0, 0.0, 3.0] } }\n\
                [[objects]]\nmesh = { shared = \"bunny\" }\ntranslate = [-0.6, 0.0, 0.0]\n\
                [[objects]]\nmesh = { shared = \"spot\" }\ntranslate = [0.6, 0.0, 0.0]\n";
    let scene = Scene::parse(text, Path::new("probe.toml"), &Limits::DEFAULT).expect("a scene");
    holds(&scene, &["acne=0.1%", "misclassified=1.1%"]);
}

/// `--objective area` ranks by the silicon of the units each candidate
/// uses: under a budget every candidate meets, one 16-bit buffer is the
/// least, then one 24-bit buffer, two 16-bit buffers, two 24-bit ones,
/// and last a silhouette map's points and evaluator beside its buffer;
/// each candidate's area is its
/// units' at the architecture's technology, computed here from the
/// configuration alone. The reasons set the pick beside the fastest and
/// name the units that differ.
#[test]
fn an_area_objective_picks_by_the_units_silicon() {
    use umbra::sim::cost::silicon::Silicon;
    use umbra::sim::experiment::plan::Objective;
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let arch = umbra::sim::Arch::bundled("talisman").expect("bundled");
    let spec = PlanSpec {
        variants: vec![
            Variant::new(Algorithm::Silhouette { packed: false }, 0.005),
            Variant::new(Algorithm::Second, 0.0),
            Variant::new(Algorithm::First, 0.005),
            Variant::new(Algorithm::Volumes, 0.0),
        ],
        formats: vec![DepthFormatKind::D24, DepthFormatKind::D16],
        map_sizes: vec![256],
        filters: vec![Filter::Point],
        image: [320, 180],
        objective: Objective::Area,
        arch: arch.clone(),
        ..PlanSpec::new(&scene, vec!["artifacts=100%".parse::<Budget>().expect("a budget")])
    };
    let p = plan(&scene, &spec, &ProgressBar::hidden()).expect("plans");
    assert_eq!(p.candidates, 8);
    let order: Vec<(String, f64)> = std::iter::once(&p.pick)
        .chain(p.runners_up.iter().filter(|r| !r.cheaper).map(|r| &r.candidate))
        .map(|c| (format!("{} {}", c.algorithm, c.format.name()), c.square_metres))
        .collect();
    let names: Vec<&str> = order.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names[1..], ["first d16", "first d24", "second d16"], "{order:?}");
    assert!(names[0].starts_with("volumes"), "{order:?}");
    assert!(order.windows(2).all(|w| w[0].1 < w[1].1), "{order:?}");
    // Each area is the units' of its configuration, from the file.
    let area = |algorithm, format| {
        let v = spec.variants.iter().find(|v| v.algorithm == algorithm).expect("a variant");
        let (virtual_samples, filter) = (v.virtual_samples, Filter::Point);
        let (width, height) = (320, 180);
        let cfg = RenderConfig {
            algorithm,
            format,
            filter,
            virtual_samples,
            map_size: 256,
            width,
            height,
            ..RenderConfig::DEFAULT
        };
        Silicon::of(&arch, &cfg.demand()).square_metres()
    };
    assert_eq!(order[0].1, area(Algorithm::Volumes, DepthFormatKind::D16));
    assert_eq!(order[1].1, area(Algorithm::First, DepthFormatKind::D16));
    assert_eq!(order[3].1, area(Algorithm::Second, DepthFormatKind::D16));
    let (sil, two) = (Algorithm::Silhouette { packed: false }, area(Algorithm::Second, DepthFormatKind::D24));
    assert!(area(sil, DepthFormatKind::D16) > two && two > order[3].1);
    let why = p.reasons.iter().find(|r| r.starts_with("against the fastest"));
    let why = why.unwrap_or_else(|| panic!("{}", p.reasons.join("\n")));
    assert!(why.contains("map cache 0 against") && why.contains("stencil"), "{why}");
    // By cycles the same space picks otherwise: area is a trade, not a tie.
    let fastest = plan(&scene, &PlanSpec { objective: Objective::Cycles, ..spec.clone() }, &ProgressBar::hidden())
        .expect("plans");
    assert!(fastest.pick.label != p.pick.label, "{}", fastest.pick.label);
}
