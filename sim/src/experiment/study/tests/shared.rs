//! Renders that share what does not change (`render::shared`) are the
//! renders of their own passes, bit for bit: for every algorithm, depth
//! format, map side and filter, on every bundled architecture, and a whole
//! study's files either way.

use std::path::Path;

use crate::Algorithm;
use crate::base::maps::with_format;
use crate::cost::arch::Arch;
use crate::experiment::study::{self, Manifest, Shard, Spec, Variant, jittered};
use crate::input::limits::Limits;
use crate::render::shared::{ImageShare, LightKey, LightShare, Scratch, render_shared, shares};
use crate::render::{RenderConfig, TruthSource, render_costed, truth};
use crate::world::scene::Scene;
use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;

/// Every algorithm of the full sweep, one parameter each, and the
/// variants that change only the shading (virtual samples off) or only
/// the light pass (culling off).
pub(super) fn variants() -> Vec<Variant> {
    vec![
        Variant::new(Algorithm::First, 0.002),
        Variant::new(Algorithm::First, 0.0),
        Variant::new(Algorithm::BiasRange { hi: 0.005 }, 0.001),
        Variant::new(Algorithm::Second, 0.0),
        Variant::new(Algorithm::Second, 0.0).without_virtual_samples(),
        Variant::new(Algorithm::SecondFrontCulled, 0.0),
        Variant::new(Algorithm::Midpoint, 0.0),
        Variant::new(Algorithm::Dual { offset: 0.005 }, 0.0),
        Variant::new(Algorithm::Dual { offset: 0.001 }, 0.0).without_culling(),
        Variant::new(Algorithm::Silhouette { packed: false }, 0.002),
        Variant::new(Algorithm::Silhouette { packed: true }, 0.002),
        Variant::new(Algorithm::Volumes, 0.0),
    ]
}

/// `table-and-sphere` with a second spot light, from the other side and
/// higher: a scene of two shadow-casting lights.
fn two_lights() -> Scene {
    let scene = Scene::open("table-and-sphere", &Limits::DEFAULT).expect("bundled");
    let other = scene.clone().with_light_from(glam::Vec3::new(-5.0, 7.0, 4.0)).expect("outside the scene");
    let mut two = scene;
    two.lights.push(other.lights[0]);
    two
}

/// Each configuration of `variants` in `formats` at each map side and
/// filter of `maps`, rendered from its shares of `scene` at 80×45, gives
/// on every bundled architecture that shares (all but the R300, which
/// shades per fragment) the frame's metrics and the cost report of a
/// render of its own passes; the R300 is left to be costed on its own.
/// The reports compared.
#[allow(clippy::needless_update, reason = "a parameter the study does not vary takes its default")]
fn compare_shared(scene: &Scene, variants: &[Variant], formats: &[DepthFormatKind], maps: &[(u32, Filter)]) -> usize {
    let limits = Limits::DEFAULT;
    let archs = Arch::presets().expect("bundled");
    assert!(archs.iter().any(|a| !shares(a)), "an architecture that keeps passes of its own");
    let (w, h) = (80, 45);
    let t = truth(scene, w, h, 2, &indicatif::ProgressBar::hidden()).expect("a reference");
    assert_eq!(t.len(), scene.lights.len(), "a reference a light");
    let image = ImageShare::new(scene, (w, h), &t, &archs, &limits).expect("the scene faces its lights");
    let mut scratch = Scratch::default();
    let mut compared = 0;
    for v in variants {
        for &format in formats {
            for &(map_size, filter) in maps {
                let cfg = RenderConfig {
                    algorithm: v.algorithm,
                    format,
                    map_size,
                    filter,
                    bias: v.bias,
                    virtual_samples: v.virtual_samples,
                    width: w,
                    height: h,
                    reference_rays: 2,
                    culling: v.culling,
                    ..RenderConfig::DEFAULT
                };
                let (own, own_costs) = cfg
                    .check(scene, &limits)
                    .and_then(|job| render_costed(&job, TruthSource::Given(t.clone()), &archs))
                    .expect("renders");
                let Some(_) = LightKey::of(&cfg) else {
                    assert_eq!(v.algorithm, Algorithm::Volumes, "only shadow volumes draw no map");
                    continue;
                };
                let (metrics, _, costs) = with_format!(format, F => {
                    let lights: Vec<LightShare<_>> = (0..scene.lights.len())
                        .map(|l| LightShare::new::<F>(&image, &cfg, l).expect("the light pass runs"))
                        .collect();
                    render_shared::<F>(&image, &lights, &cfg, &mut scratch).expect("a shared render")
                });
                assert_eq!(metrics, own.frame_metrics(), "{}", cfg.describe());
                for ((a, shared), own) in archs.iter().zip(&costs).zip(&own_costs) {
                    let own = serde_json::to_string(own.as_ref().expect("costed")).expect("serialises");
                    match shared {
                        Some(r) => {
                            let r = serde_json::to_string(r.as_ref().expect("costed")).expect("serialises");
                            assert_eq!(r, own, "{} on {}", cfg.describe(), a.name);
                            compared += 1;
                        }
                        None => assert!(!shares(a), "{} shares but was not costed", a.name),
                    }
                }
            }
        }
    }
    compared
}

/// Every algorithm, format and a point filter, a bilinear one and a
/// jittered one, on a scene of one light. If a share handed a probe the
/// wrong events (a map of the wrong tiling, a camera probe that had not
/// seen the visibility, the wrong filter's reading), a report would differ.
#[test]
fn a_shared_render_is_its_own_render() {
    let scene = Scene::open("table-and-sphere", &Limits::DEFAULT).expect("bundled");
    let formats = [DepthFormatKind::D16, DepthFormatKind::D24, DepthFormatKind::F32];
    let maps = [(64, Filter::Point), (128, Filter::Bilinear), (128, jittered(4))];
    // 11 algorithms with maps × 3 formats × 3 maps, on the five that share.
    assert_eq!(compare_shared(&scene, &variants(), &formats, &maps), 11 * 3 * 3 * 5);
}

/// The same of a scene of two lights: each light's pass shared, the
/// camera probes told which light's map they read before each light's
/// shading, the frame's metrics from the lights' parts. If the second
/// light's shading read the first's map or reference, or an
/// architecture's report lost a light's pass, a report or the metrics
/// would differ.
#[test]
fn a_shared_render_of_two_lights_is_its_own_render() {
    let scene = two_lights();
    assert_eq!(scene.lights.len(), 2);
    let variants: Vec<Variant> = variants()
        .into_iter()
        .filter(|v| {
            matches!(v.algorithm, Algorithm::First | Algorithm::Dual { .. } | Algorithm::Silhouette { packed: true })
        })
        .collect();
    let maps = [(64, Filter::Point), (128, jittered(4))];
    // 5 variants (first depth at two biases, two dual depths, the packed
    // silhouette map) × 2 maps, on the five that share.
    assert_eq!(compare_shared(&scene, &variants, &[DepthFormatKind::D16], &maps), 5 * 2 * 5);
}

/// A scratch folder of this test process for `name`, removed when dropped.
fn dir(name: &str) -> super::scratch::Scratch {
    super::scratch_dir("umbra-shared", name)
}

/// Every file of `d` but the manifest (which names the command), by name.
fn outputs(d: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<(String, Vec<u8>)> = std::fs::read_dir(d)
        .expect("written")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.file_name().is_some_and(|n| n != "manifest.json"))
        .map(|p| (p.file_name().expect("named").to_string_lossy().into_owned(), std::fs::read(&p).expect("read")))
        .collect();
    out.sort();
    out
}

/// A study run from its shares writes every file byte for byte as the run
/// that renders each configuration on its own passes: every algorithm,
/// two formats, two map sides (one beyond the limits: its own skipped
/// row), two filters, every bundled architecture, on a scene of one light
/// and one of two.
#[test]
fn a_shared_study_writes_the_unshared_files() {
    let limits = Limits::DEFAULT;
    let mut scenes = study::load_scenes(&["weiskopf-l"], &limits).expect("bundled");
    let mut two = two_lights();
    two.name = "two-lights".into();
    scenes.push(two);
    let mut spec = Spec::quick(scenes);
    spec.variants = variants();
    spec.formats = vec![DepthFormatKind::D16, DepthFormatKind::F32];
    spec.map_sizes = vec![64, 256];
    spec.filters = vec![Filter::Bilinear, Filter::Box { size: 3 }];
    spec.images = vec![[64, 36]];
    spec.reference_rays = 1;
    spec.archs = Arch::presets().expect("bundled");
    spec.arch_points = vec![Default::default(); spec.archs.len()];
    spec.limits = Limits { max_map_side: 128, ..limits };
    let hidden = indicatif::ProgressBar::hidden();
    let shared = study::run(&spec, Shard::ALL, &hidden).expect("runs");
    let unshared = study::run_unshared(&spec, Shard::ALL, &hidden).expect("runs");
    assert_eq!(shared.len(), 2 * 12 * 2 * 2 * 2 * spec.archs.len());
    assert!(shared.iter().any(|r| r.reason.contains("max_map_side")), "a map beyond the limits is skipped");
    let (a, b) = (dir("shared"), dir("unshared"));
    study::write_run(&a, &shared, &Manifest::new(&spec, Shard::ALL, shared.len())).expect("write");
    study::write_run(&b, &unshared, &Manifest::new(&spec, Shard::ALL, unshared.len())).expect("write");
    let (x, y) = (outputs(&a), outputs(&b));
    assert_eq!(x.iter().map(|f| &f.0).collect::<Vec<_>>(), y.iter().map(|f| &f.0).collect::<Vec<_>>());
    for (f, g) in x.iter().zip(&y) {
        assert!(f.1 == g.1, "{} differs", f.0);
    }
}
