//! The exact f64 reference against closed-form shadows, and the metrics on
//! verdict images worked by hand.

use umbra::core::NO_TRIANGLE;
use umbra::core::glam::{DVec3, Vec3};
use umbra::core::shade::Shaded;
use umbra::core::shadow::Shadow;
use umbra::sim::pass::camera::{CameraFrame, visibility};
use umbra::sim::truth::cause::Cause;
use umbra::sim::truth::metrics::{Fields, compare};
use umbra::sim::truth::reference::{PixelTruth, Reference};
use umbra::sim::world::mesh::Mesh;
use umbra::sim::world::scene::LightSource;
use umbra::sim::world::scene::{Camera, Light, Object, Perspective, Scene};

/// A sphere of radius ½ centred 1 above the plane y = 0, under a light
/// straight down: its shadow is the disc x² + z² < ¼. Every plane pixel
/// farther than the tessellation's reach (2·10⁻³) from the circle agrees.
#[test]
fn a_sphere_casts_a_disc_under_a_directional_light() {
    let (r, slices) = (0.5f64, 96u32);
    let plane = Mesh::quad(Vec3::new(-3.0, 0.0, 3.0), Vec3::new(6.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -6.0));
    let sphere = Mesh::sphere(Vec3::new(0.0, 1.0, 0.0), r as f32, 48, slices);
    let view = Perspective {
        position: Vec3::new(0.4, 4.0, 1.5),
        target: Vec3::ZERO,
        fov_degrees: 50.0,
        near: 0.5,
        far: 20.0,
        up: Vec3::Y,
    };
    let scene = Scene {
        name: "disc".into(),
        objects: vec![
            Object { name: "plane".into(), mesh: plane, solid: false },
            Object { name: "sphere".into(), mesh: sphere, solid: true },
        ],
        lights: vec![Light::Spot(view)],
        camera: Camera::Perspective(view),
        image: [160, 120],
        source: String::new(),
        camera_choice: None,
        light_from: None,
        shadowless: Vec::new(),
        notes: Vec::new(),
    };
    let (w, h) = (160u32, 120u32);
    let mut frame = CameraFrame::default();
    let camera =
        visibility(&mut frame, &scene, (w, h), umbra::sim::base::maps::Tiling::DEFAULT, &mut umbra::core::NoProbe)
            .expect("renders")
            .camera;
    let ids = frame.ids();
    let reference = Reference::new(&scene.triangles()).expect("builds");
    let light = LightSource::Directional(DVec3::NEG_Y);
    let truth = reference.image(ids, &camera, w, h, &light, 1, &indicatif::ProgressBar::hidden());
    let inverse = camera.as_dmat4().inverse();
    let (mut inside, mut outside, mut checked) = (0, 0, 0);
    for (i, (&id, t)) in ids.iter().zip(&truth).enumerate() {
        if id >= 2 {
            continue; // not the plane
        }
        let (px, py) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
        let p = crate::common::ground_point(&inverse, w, h, i);
        let d = (p.x * p.x + p.z * p.z).sqrt();
        if (d - r).abs() < 2e-3 {
            continue;
        }
        let t = t.expect("a plane pixel has a truth");
        assert!(t.faces_light, "the plane faces the light at ({px}, {py})");
        assert_eq!(t.lit, d > r, "pixel ({px}, {py}) at distance {d} from the axis");
        checked += 1;
        if d < r { inside += 1 } else { outside += 1 }
    }
    assert!(inside > 200 && outside > 2000 && checked == inside + outside, "inside {inside}, outside {outside}");
}

/// Ten pixels by hand: background and a surface facing away are not
/// evaluated; of the eight others two are false shadows and two false lights.
#[test]
fn metrics_count_what_they_should() {
    let px = |shadow: f64| Shaded { triangle: 0, light: None, normal: Vec3::Y, shadow: Shadow::from_num(shadow) };
    let truth = |lit: bool, visibility: f64| Some(PixelTruth { faces_light: true, lit, visibility, light_cos: 1.0 });
    let render =
        [Shaded::BACKGROUND, px(1.0), px(0.0), px(1.0), px(0.75), px(0.0), px(0.25), px(1.0), px(0.5), px(0.0)];
    let truths = [
        None,
        Some(PixelTruth { faces_light: false, lit: false, visibility: 0.0, light_cos: -1.0 }),
        truth(true, 1.0),   // lit, lit
        truth(true, 1.0),   // false shadow: |1 − 0| = 1
        truth(true, 0.5),   // false shadow (0.75 > ½): |0.75 − 0.5| = 0.25
        truth(false, 0.0),  // false light: |0 − 1| = 1
        truth(false, 0.75), // lit by the pipeline (0.25 ≤ ½) but shadowed at the centre: false light
        truth(false, 0.0),  // shadowed, shadowed
        truth(true, 0.5),   // ½ is not above ½: lit, lit
        truth(true, 1.0),   // lit, lit
    ];
    let fields = Fields::new(&truths, 10);
    let (m, _) = compare(&render, &truths, &fields, &mut |_, _: &_, _| Cause::Aliasing);
    assert_eq!(render[0].triangle, NO_TRIANGLE);
    assert_eq!((m.evaluated, m.false_shadow, m.false_light), (8, 2, 2));
    assert!((m.misclassified_percent - 50.0).abs() < 1e-12);
    // |errors|: 0, 1, 0.25, 1, 0, 0, 0, 0 → 2.25 / 8
    assert!((m.mean_abs_error - 2.25 / 8.0).abs() < 1e-9, "{}", m.mean_abs_error);
}

/// The reference is the same on one thread and on several: each pixel is a
/// pure function of the scene.
#[test]
fn the_reference_does_not_depend_on_the_thread_count() {
    let scene = Scene::bundled("crowd").expect("bundled");
    let (w, h) = (96u32, 64u32);
    let mut frame = CameraFrame::default();
    let camera =
        visibility(&mut frame, &scene, (w, h), umbra::sim::base::maps::Tiling::DEFAULT, &mut umbra::core::NoProbe)
            .expect("renders")
            .camera;
    let ids = frame.ids();
    let reference = Reference::new(&scene.triangles()).expect("builds");
    let light = scene.light().source();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        pool.install(|| reference.image(ids, &camera, w, h, &light, 3, &indicatif::ProgressBar::hidden()))
    };
    let one = on(1);
    assert_eq!(one, on(2));
    assert_eq!(one, on(4));
    assert!(one.iter().flatten().any(|t| !t.lit) && one.iter().flatten().any(|t| t.lit));
}

/// A render's own reference, cast through the triangles its camera pass
/// saw, is the reference `render::truth` builds with a visibility pass of
/// its own (which the study shares between configurations), for every
/// kind of camera pass: a depth map, front-face culling, a silhouette map
/// and shadow volumes.
#[test]
fn a_renders_own_reference_is_the_shared_one() {
    use umbra::sim::Algorithm;
    use umbra::sim::input::limits::Limits;
    use umbra::sim::render::{RenderConfig, TruthSource, render, truth};
    let scene = Scene::bundled("weiskopf-l").expect("bundled");
    let shared = truth(&scene, 96, 72, 2, &indicatif::ProgressBar::hidden()).expect("a reference");
    assert_eq!(shared.len(), 1, "one reference for one light");
    assert!(shared[0].iter().flatten().any(|t| t.faces_light));
    for algorithm in [
        Algorithm::First,
        Algorithm::SecondFrontCulled,
        Algorithm::Dual { offset: 0.01 },
        Algorithm::Silhouette { packed: true },
        Algorithm::Volumes,
    ] {
        let cfg = RenderConfig {
            algorithm,
            width: 96,
            height: 72,
            map_size: 128,
            reference_rays: 2,
            ..RenderConfig::DEFAULT
        };
        let own =
            cfg.check(&scene, &Limits::DEFAULT).and_then(|job| render(&job, TruthSource::Quiet)).expect("renders");
        assert!(own.truth == shared[0], "{algorithm}: the references differ");
        let given = cfg
            .check(&scene, &Limits::DEFAULT)
            .and_then(|job| render(&job, TruthSource::Given(shared.clone())))
            .expect("renders");
        assert_eq!(own.metrics, given.metrics, "{algorithm}");
    }
}
