//! A frame of several shadow-casting lights against each light rendered
//! alone: the same maps, shading, references and metrics light by light;
//! the frame's picture the lights' sum; its cost the light passes added
//! and one camera pass testing each light's map.

use umbra::sim::Arch;
use umbra::sim::input::limits::Limits;
use umbra::sim::output::folder::OutputFolder;
use umbra::sim::output::picture::BODY_ORIGIN;
use umbra::sim::render::{Render, RenderConfig, TruthSource, cost, files::write_render, render};
use umbra::sim::world::scene::Scene;

use crate::common::scratch;

/// The bundled two-light city (a sun and a spot light).
fn city() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/city.glb");
    Scene::open(path, &Limits::DEFAULT).expect("the example opens")
}

const SMALL: RenderConfig =
    RenderConfig { width: 160, height: 90, map_size: 256, reference_rays: 1, ..RenderConfig::DEFAULT };

fn rendered(scene: &Scene, cfg: RenderConfig) -> Render {
    render(&cfg.check(scene, &Limits::DEFAULT).expect("fits"), TruthSource::Quiet).expect("renders")
}

/// Each light's part of the frame is that light rendered alone (the scene
/// with its other lights taken out): its map, its shading, its exact
/// reference, its verdicts and metrics, bit for bit; and the frame's
/// metrics count each (pixel, light) pair once.
#[test]
fn each_lights_part_is_that_light_alone() {
    let scene = city();
    assert_eq!(scene.lights.len(), 2);
    for algorithm in [
        umbra::sim::Algorithm::Second,
        umbra::sim::Algorithm::Silhouette { packed: true },
        umbra::sim::Algorithm::Volumes,
    ] {
        let cfg = RenderConfig { algorithm, ..SMALL };
        let frame = rendered(&scene, cfg);
        assert_eq!(frame.parts().count(), 2, "{algorithm}");
        let mut evaluated = 0;
        for (k, part) in frame.parts().enumerate() {
            let alone = rendered(&scene.lit_by(k), cfg);
            assert!(alone.more.is_empty());
            assert!(part.image.pixels == alone.image.pixels, "{algorithm}: lights[{k}]'s shading");
            assert!(
                part.maps.maps.z1 == alone.maps.maps.z1 && part.maps.maps.z2 == alone.maps.maps.z2,
                "{algorithm}: lights[{k}]'s map"
            );
            assert!(part.truth == alone.truth.as_slice(), "{algorithm}: lights[{k}]'s reference");
            assert!(part.verdicts == alone.verdicts.as_slice(), "{algorithm}: lights[{k}]'s verdicts");
            assert_eq!(*part.metrics, alone.metrics, "{algorithm}: lights[{k}]'s metrics");
            assert_eq!(part.light_events.totals, alone.light_events.totals, "{algorithm}: lights[{k}]'s pass");
            evaluated += alone.metrics.evaluated;
        }
        let m = frame.frame_metrics();
        assert_eq!(m.evaluated, evaluated, "{algorithm}: the frame counts (pixel, light) pairs");
        let wrong = frame.parts().map(|p| p.metrics.false_shadow + p.metrics.false_light).sum::<u64>();
        assert!((m.misclassified_percent - 100.0 * wrong as f64 / evaluated as f64).abs() < 1e-9, "{algorithm}");
    }
}

/// A scene lit twice by the same light: the camera pass sees once and
/// shades twice, the light passes cost twice one, and the second map's
/// reads do not hit the first's lines in the map cache (each light's map
/// has its own addresses). The shaded picture's body is the one light's:
/// each surface's two equal terms summed, exposed to the same white.
#[test]
fn the_same_light_twice_costs_two_passes_and_pictures_as_one() {
    let one = Scene::bundled("weiskopf-l").expect("bundled");
    let mut twice = one.clone();
    twice.lights.push(twice.lights[0]);
    let cfg = RenderConfig { width: 96, height: 72, map_size: 64, reference_rays: 1, ..RenderConfig::DEFAULT };
    let arch = Arch::open("talisman", &Limits::DEFAULT).expect("bundled");
    fn job(s: &Scene, cfg: RenderConfig) -> umbra::sim::Checked<'_> {
        cfg.check(s, &Limits::DEFAULT).expect("fits")
    }
    let (a, b) = (cost(&job(&one, cfg), &arch).expect("costs"), cost(&job(&twice, cfg), &arch).expect("costs"));
    assert_eq!(b.light_passes.len(), 2);
    assert_eq!(b.light.cycles(), 2.0 * a.light.cycles(), "the light passes add");
    assert_eq!(b.light_events.fragments, 2 * a.light_events.fragments);
    assert_eq!(b.camera_events.fragments, a.camera_events.fragments, "visibility runs once");
    assert_eq!(b.camera_events.pixels_shaded, 2 * a.camera_events.pixels_shaded, "shading runs per light");
    assert_eq!(b.pixels, a.pixels, "the covered pixels are the same pixels");
    assert_eq!(b.sen.model_map_bytes_per_pixel, 2.0 * a.sen.model_map_bytes_per_pixel, "a lookup per light");
    let (ma, mb) = (a.camera.map_cache.expect("a map cache"), b.camera.map_cache.expect("a map cache"));
    assert!(ma.misses > 0 && mb.misses >= 2 * ma.misses, "{} misses alone, {} twice", ma.misses, mb.misses);
    // The pictures: the shaded body alike, pixel for pixel.
    let base = scratch("lights-twice");
    let picture = |s: &Scene, name: &str| {
        let r = rendered(s, cfg);
        let dir = base.join(name);
        let mut folder = OutputFolder::create(
            &dir,
            umbra::sim::output::folder::Claim::new(umbra::sim::output::folder::RunKind::Render),
        )
        .expect("folder");
        write_render(&mut folder, &job(s, cfg), &r).expect("writes");
        folder.finish(None).expect("finishes");
        image::open(dir.join("shaded.png")).expect("a PNG").to_rgb8()
    };
    let (pa, pb) = (picture(&one, "one"), picture(&twice, "twice"));
    let body = |p: &image::RgbImage| {
        (0..cfg.height)
            .flat_map(|y| (0..cfg.width).map(move |x| (x, y)))
            .map(|(x, y)| *p.get_pixel(x + BODY_ORIGIN.0, y + BODY_ORIGIN.1))
            .collect::<Vec<_>>()
    };
    assert!(body(&pa) == body(&pb), "the summed picture differs from the one light's");
    assert!(body(&pa).iter().any(|p| p.0 != body(&pa)[0].0), "the body is not blank");
    let dir = base.join("twice");
    for name in ["shadow-light0.png", "shadow-light1.png", "z1-light1.npy", "verdict-light1.npy", "metrics.json"] {
        assert!(dir.join(name).is_file(), "{name}");
    }
    assert!(!dir.join("shadow.png").exists(), "a light's files are named for it");
    let metrics: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("metrics.json")).expect("json")).expect("json");
    assert_eq!(metrics["lights"].as_array().map(Vec::len), Some(2));
    assert_eq!(metrics["evaluated_px"], 2 * metrics["lights"][0]["evaluated_px"].as_u64().expect("a count"));
}

/// A light with `shadows = false` draws no pass and no lookup: the
/// render's metrics and events are those of the scene without it; it only
/// lights the picture, by its cosine at each surface, which is the cosine
/// the exact reference gives the same light when it casts shadows.
#[test]
fn a_light_without_shadows_only_lights_the_picture() {
    let text = crate::world::scenes::GOOD;
    let second = "\n[[lights]]\nkind = \"spot\"\nposition = [3.0, 4.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\nnear = 1.0\nfar = 20.0\n";
    let with = |extra: &str| {
        let at = text.find("[[objects]]").expect("objects");
        Scene::parse(
            &format!("{}{extra}\n{}", &text[..at], &text[at..]),
            std::path::Path::new("s.toml"),
            &Limits::DEFAULT,
        )
        .expect("parses")
    };
    let (alone, quiet, loud) = (with(""), with(&format!("{second}shadows = false\n")), with(second));
    assert_eq!((quiet.lights.len(), quiet.shadowless.len(), loud.lights.len()), (1, 1, 2));
    let (a, q, l) = (rendered(&alone, SMALL), rendered(&quiet, SMALL), rendered(&loud, SMALL));
    assert_eq!(q.metrics, a.metrics);
    assert_eq!((q.light_events.totals, q.camera_events.totals), (a.light_events.totals, a.camera_events.totals));
    assert!(q.more.is_empty() && q.shadowless.len() == 1);
    let cosines = &q.shadowless[0];
    let truth = l.more[0].truth.as_slice();
    let mut compared = 0;
    for (k, t) in truth.iter().enumerate() {
        if let Some(t) = t.filter(|t| t.faces_light) {
            assert!((cosines[k] - t.light_cos).abs() < 1e-9, "pixel {k}: {} against {}", cosines[k], t.light_cos);
            compared += 1;
        }
    }
    // 235 measured: the probe scene's ball at 160×90, on the lit side.
    assert!(compared > 100, "{compared}");
    // Every light `shadows = false` is a scene that casts none: refused.
    let none = text.replace("far = 10.0\n", "far = 10.0\nshadows = false\n");
    let e = Scene::parse(&none, std::path::Path::new("s.toml"), &Limits::DEFAULT).expect_err("no shadows");
    assert!(e.to_string().contains("casts shadows"), "{e}");
}
