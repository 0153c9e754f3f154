//! The pictures a render writes explain themselves: decoded, each carries
//! its caption inside the canvas, and the shadow term's background, shadow
//! and lit values are three different colours, where they were two greys
//! a reader could not tell apart (24 and 0).

use umbra::core::shade::Shaded;
use umbra::sim::input::limits::Limits;
use umbra::sim::output::folder::OutputFolder;
use umbra::sim::output::picture::{BACKGROUND, BODY_ORIGIN, CAPTION_BAND};
use umbra::sim::render::files::write_render;
use umbra::sim::render::pictures::UNLIT;
use umbra::sim::render::{RenderConfig, TruthSource, render};
use umbra::sim::world::scene::Scene;

#[test]
fn every_picture_carries_its_caption_and_key_and_tells_its_values_apart() {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let cfg = RenderConfig { width: 160, height: 90, map_size: 256, reference_rays: 1, ..RenderConfig::DEFAULT };
    let job = cfg.check(&scene, &Limits::DEFAULT).expect("valid");
    let r = render(&job, TruthSource::Build(&indicatif::ProgressBar::hidden())).expect("renders");
    let dir = std::env::temp_dir().join(format!("umbra-pictures-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut folder =
        OutputFolder::create(&dir, umbra::sim::output::folder::Claim::new(umbra::sim::output::folder::RunKind::Render))
            .expect("folder");
    write_render(&mut folder, &job, &r).expect("written");
    folder.finish(None).expect("finished");
    for name in ["shaded.png", "shadow.png", "error.png", "z1.png", "z2.png"] {
        let png = image::open(dir.join(name)).expect("a PNG").to_rgb8();
        let (w, h) = (png.width(), png.height());
        let dark = |x: u32, y: u32| png.get_pixel(x, y).0.iter().all(|&c| c < 128);
        // The caption's text is drawn, and ends inside the canvas: the
        // band's last columns are blank.
        let inked = (0..CAPTION_BAND).flat_map(|y| (0..w).map(move |x| (x, y))).filter(|&(x, y)| dark(x, y)).count();
        assert!(inked > 200, "{name}: the caption has {inked} dark pixels");
        let edge = (0..CAPTION_BAND).flat_map(|y| (w - 3..w).map(move |x| (x, y))).any(|(x, y)| dark(x, y));
        assert!(!edge, "{name}: the caption runs off the right edge");
        // The key below the body holds the background's swatch.
        let body_end = CAPTION_BAND + if name.starts_with('z') { 256 } else { 90 };
        let keyed =
            (body_end..h).flat_map(|y| (0..w).map(move |x| (x, y))).any(|(x, y)| png.get_pixel(x, y).0 == BACKGROUND);
        assert!(keyed, "{name}: no background swatch in the key");
    }
    // The shadow term: where there is no surface, where the unit shadows
    // fully and where it lights fully, three different colours, read back
    // at the render's own pixels.
    let png = image::open(dir.join("shadow.png")).expect("a PNG").to_rgb8();
    let (x0, y0) = BODY_ORIGIN;
    let at = |k: usize| png.get_pixel(x0 + (k as u32 % r.image.width), y0 + (k as u32 / r.image.width)).0;
    let facing = |k: usize| r.truth[k].is_some_and(|t| t.faces_light);
    let find = |f: &dyn Fn(&Shaded) -> bool| {
        (0..r.image.pixels.len()).find(|&k| facing(k) && f(&r.image.pixels[k])).expect("such a pixel")
    };
    let none = at(r.image.pixels.iter().position(|p| p.triangle == umbra::core::NO_TRIANGLE).expect("background"));
    let shadowed = at(find(&|p| p.shadow.to_num::<f64>() == 1.0));
    let lit = at(find(&|p| p.shadow.to_num::<f64>() == 0.0));
    assert_eq!((none, shadowed, lit), (BACKGROUND, [0; 3], [255; 3]));
    // A surface the light does not reach (the sphere's far side, the
    // floor beyond the spot's frustum) is one colour, apart from the
    // scale, whatever the unit's test said there: no grid of its taps.
    let away: Vec<usize> = (0..r.image.pixels.len()).filter(|&k| r.truth[k].is_some_and(|t| !t.faces_light)).collect();
    assert!(away.len() >= 100, "only {} pixels face away", away.len());
    assert!(away.iter().all(|&k| at(k) == UNLIT), "a pixel facing away is not the unlit colour");
    assert!(![BACKGROUND, [0; 3], [255; 3]].contains(&UNLIT));
    let _ = std::fs::remove_dir_all(&dir);
}
