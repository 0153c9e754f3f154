//! The pictures of a render a person reads at a glance: the shaded scene,
//! the shadow term, and the error map of its verdicts against the exact
//! reference.

use std::path::PathBuf;

use crate::output::OutputError;
use crate::output::folder::OutputFolder;
use crate::output::picture::{BACKGROUND, Frame, Scale, write_framed};
use crate::pass::camera::CameraImage;
use crate::truth::cause::Cause;
use crate::truth::metrics::Verdict;
use crate::truth::reference::PixelTruth;

/// Pixel `k`'s cosine to the light from the exact reference, 0 for the
/// background and for surfaces facing away.
fn lambert(truth: &[Option<PixelTruth>], k: usize) -> f64 {
    truth.get(k).copied().flatten().map_or(0.0, |t| t.light_cos.max(0.0))
}

/// One light's shading of the camera image and its exact reference.
pub(crate) type LitBy<'a> = (&'a CameraImage, &'a [Option<PixelTruth>]);

/// Write the camera pass as a picture a person can read: surfaces grey by
/// their facing to each light (the cosine to the light at each pixel's
/// surface point, from that light's exact reference; faces turned away
/// are dark), shadowed parts dark in proportion to that light's shadow
/// fraction, the lights' contributions summed; where there is no surface
/// [`BACKGROUND`]. `image` is the camera pass (its size and which pixels
/// hold a surface), `lights` each shadow-casting light's shading and
/// reference, `shadowless` each other light's cosine per pixel (it lights
/// without shadows). The
/// picture is exposed so that the brightest tenth of the surfaces facing
/// a light is white: a scene lit at grazing (every surface's cosine a few
/// hundredths) still shows its lit surfaces apart from its shadows. Framed
/// with `detail` (the scene and configuration) and its key.
///
/// # Errors
/// [`OutputError::Image`] or [`OutputError::Font`].
pub(crate) fn write_shadow_image(
    folder: &mut OutputFolder,
    name: &str,
    (image, lights, shadowless): (&CameraImage, &[LitBy<'_>], &[Vec<f64>]),
    detail: &str,
) -> Result<PathBuf, OutputError> {
    let unshadowed = |k: usize| shadowless.iter().map(|c| c.get(k).copied().unwrap_or(0.0)).sum::<f64>();
    let lambert = |k: usize| lights.iter().map(|(_, truth)| lambert(truth, k)).sum::<f64>() + unshadowed(k);
    let mut facing: Vec<f64> = (0..image.pixels.len()).map(lambert).filter(|&l| l > 0.0).collect();
    let brightest = if facing.is_empty() {
        1.0
    } else {
        let at = facing.len() * 9 / 10;
        *facing.select_nth_unstable_by(at, f64::total_cmp).1
    };
    // Within the sum's range: each light's cosine at most 1.
    #[allow(clippy::cast_precision_loss, reason = "a few lights")]
    let most = (lights.len() + shadowless.len()).max(1) as f64;
    let exposure = 1.0 / brightest.clamp(0.02 * most, most);
    let grey = |t: f64| {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 40..=255")]
        let g = (40.0 + 215.0 * t.clamp(0.0, 1.0)).round() as u8;
        [g; 3]
    };
    let pixels: Vec<u8> = image
        .pixels
        .iter()
        .enumerate()
        .flat_map(|(k, p)| {
            if p.triangle == umbra_core::NO_TRIANGLE {
                return BACKGROUND;
            }
            let shaded: f64 = lights
                .iter()
                .map(|(light, truth)| {
                    let lit = light.pixels.get(k).map_or(0.0, |q| 1.0 - q.shadow.to_num::<f64>());
                    lit * self::lambert(truth, k)
                })
                .sum::<f64>()
                + unshadowed(k);
            grey((shaded * exposure).min(1.0))
        })
        .collect();
    let title = if lights.len() + shadowless.len() == 1 {
        "shaded: grey by each surface's facing to the light, darker where the render shadows it".to_owned()
    } else {
        format!(
            "shaded: {} lights, each surface grey by its facing to each, darker where the render shadows it, summed",
            lights.len() + shadowless.len()
        )
    };
    let frame = Frame {
        title,
        detail: detail.to_owned(),
        scale: Some(Scale {
            colour: &grey,
            low: "in shadow, or facing away".into(),
            high: "lit, facing the light".into(),
        }),
        swatches: vec![(BACKGROUND, "no surface".into())],
    };
    write_framed(folder, name, &pixels, (image.width, image.height), &frame)
}

/// The colour of a surface the light does not reach on the shadow term:
/// one dark grey, apart from the scale (the shading leaves it unlit,
/// whatever the shadow unit would say).
pub const UNLIT: [u8; 3] = [48, 48, 56];

/// Write the shadow term alone: white lit, black fully shadowed, greys
/// between; [`UNLIT`] where the surface faces away from the light or lies
/// outside a spot light's frustum (the shading lights none of it: the
/// test's result there is no shadow's), [`BACKGROUND`] where there is no
/// surface; framed with `detail` and its key.
///
/// # Errors
/// [`OutputError::Image`] or [`OutputError::Font`].
pub(crate) fn write_shadow_term(
    folder: &mut OutputFolder,
    name: &str,
    (image, truth): (&CameraImage, &[Option<PixelTruth>]),
    detail: &str,
) -> Result<PathBuf, OutputError> {
    let grey = |lit: f64| {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 0..=255")]
        let g = (255.0 * lit.clamp(0.0, 1.0)).round() as u8;
        [g; 3]
    };
    let pixels: Vec<u8> = image
        .pixels
        .iter()
        .zip(truth.iter().chain(core::iter::repeat(&None)))
        .flat_map(|(p, t)| match t {
            _ if p.triangle == umbra_core::NO_TRIANGLE => BACKGROUND,
            Some(t) if !t.faces_light => UNLIT,
            _ => grey(1.0 - p.shadow.to_num::<f64>()),
        })
        .collect();
    let frame = Frame {
        title: "shadow term: the fraction of light the shadow unit lets through".into(),
        detail: detail.to_owned(),
        scale: Some(Scale { colour: &grey, low: "0 (shadowed)".into(), high: "1 (lit)".into() }),
        swatches: vec![
            (UNLIT, "faces away from the light, or out of its reach".into()),
            (BACKGROUND, "no surface".into()),
        ],
    };
    write_framed(folder, name, &pixels, (image.width, image.height), &frame)
}

/// The error map's classes in legend order, each with its colour: the
/// two that are the map and the filter at work, then the four artifacts.
pub const ERROR_COLOURS: [(Cause, &str, [u8; 3]); 6] = [
    (Cause::Aliasing, "aliasing", [235, 170, 0]),
    (Cause::Penumbra, "penumbra", [150, 205, 220]),
    (Cause::Acne, "acne", [220, 30, 30]),
    (Cause::Detachment, "detachment", [150, 40, 190]),
    (Cause::Leak, "leaks", [30, 100, 235]),
    (Cause::Clipped, "clipped occluder", [20, 150, 70]),
];

/// The colour of a class on the error map.
fn colour_of(cause: Cause) -> [u8; 3] {
    ERROR_COLOURS.iter().find(|(c, _, _)| *c == cause).map_or([0; 3], |&(_, _, rgb)| rgb)
}

/// The colour of a cascade boundary on the error map: where a pixel's
/// right or lower neighbour reads another cascade.
pub const CASCADE_BOUNDARY: [u8; 3] = [230, 0, 160];

/// Whether pixel `k` of a `width`-wide image whose pixels read the
/// cascades `cascade_of` lies on a boundary between two.
fn on_boundary(cascade_of: &[u8], k: usize, width: usize) -> bool {
    let here = cascade_of.get(k);
    let differs = |n: usize| cascade_of.get(n).is_some_and(|c| Some(c) != here);
    (k % width + 1 < width && differs(k + 1)) || differs(k + width)
}

/// Artifact pixels (acne, detachment, leaks, clipped occluders) ringed on the error map when
/// there are at most this many.
pub(crate) const RINGS: usize = 2000;

/// Write the error map: every pixel's [`Verdict`] over a faint shading of
/// the scene (light greys, lit surfaces lighter by their exact cosine to
/// the light from `truth`, so the geometry stays readable; [`BACKGROUND`]
/// where there is no surface), each wrong pixel in its class's colour
/// ([`ERROR_COLOURS`]), each artifact pixel ringed in its colour (up to
/// `RINGS` of them), for a cascaded light each boundary between two
/// cascades of `cascade_of` (each pixel's; empty for one map) where no
/// wrong pixel is, in [`CASCADE_BOUNDARY`], framed with `detail` and a
/// key giving each class and its count. The body's pixel `(x, y)` is at
/// [`BODY_ORIGIN`](crate::output::picture::BODY_ORIGIN) + `(x, y)`.
///
/// # Errors
/// `OutputError::Image`, `OutputError::Font` or `OutputError::Io` naming
/// the file.
pub fn write_error_image(
    folder: &mut OutputFolder,
    name: &str,
    image: &CameraImage,
    verdicts: &[Verdict],
    (truth, cascade_of, detail): (&[Option<PixelTruth>], &[u8], &str),
) -> Result<PathBuf, OutputError> {
    use plotters::prelude::*;
    let count = |v: Verdict| verdicts.iter().filter(|&&x| x == v).count();
    let (w, h) = (image.width, image.height);
    let mut rgb = vec![255u8; (w as usize) * (h as usize) * 3];
    for (k, (p, v)) in image.pixels.iter().zip(verdicts).enumerate() {
        let colour = match v {
            Verdict::Wrong(cause) => colour_of(*cause),
            _ if p.triangle == umbra_core::NO_TRIANGLE => BACKGROUND,
            _ if on_boundary(cascade_of, k, w as usize) => CASCADE_BOUNDARY,
            _ => {
                let lambert = lambert(truth, k);
                let lit = if *v == Verdict::Right { 1.0 - p.shadow.to_num::<f64>() } else { 0.0 };
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "within 170..=240")]
                let g = (170.0 + 70.0 * lit * lambert).round() as u8;
                [g; 3]
            }
        };
        rgb[3 * k..3 * k + 3].copy_from_slice(&colour);
    }
    // A ring round each artifact pixel, so that a few on a large image
    // show at a glance; past RINGS of them they show unaided.
    let rings: Vec<(usize, [u8; 3])> = verdicts
        .iter()
        .enumerate()
        .filter_map(|(k, v)| match v {
            Verdict::Wrong(cause) if cause.is_artifact() => Some((k, colour_of(*cause))),
            _ => None,
        })
        .collect();
    if !rings.is_empty() && rings.len() <= RINGS {
        let path = folder.dir().join(name);
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        for (k, [r, g, b]) in &rings {
            let (x, y) = (k % w as usize, k / w as usize);
            let at = (i32::try_from(x).unwrap_or(i32::MAX), i32::try_from(y).unwrap_or(i32::MAX));
            root.draw(&Circle::new(at, 8, RGBColor(*r, *g, *b).stroke_width(3)))
                .and_then(|()| root.present())
                .map_err(|e| OutputError::Font { path: path.clone(), problem: e.to_string() })?;
        }
    }
    let mut swatches: Vec<([u8; 3], String)> = ERROR_COLOURS
        .iter()
        .map(|&(cause, name, rgb)| (rgb, format!("{name} {}", count(Verdict::Wrong(cause)))))
        .collect();
    if !cascade_of.is_empty() {
        let n = cascade_of.iter().max().map_or(1, |&c| usize::from(c) + 1);
        swatches.push((CASCADE_BOUNDARY, format!("cascade boundary ({n} read)")));
    }
    swatches.push(([225; 3], "right".into()));
    swatches.push((BACKGROUND, "no surface".into()));
    let frame = Frame {
        title: "error map: each wrong pixel by its cause, each artifact ringed".into(),
        detail: detail.to_owned(),
        scale: None,
        swatches,
    };
    write_framed(folder, name, &rgb, (w, h), &frame)
}
