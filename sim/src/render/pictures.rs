//! The pictures of a render a person reads at a glance: the shaded scene,
//! the shadow term, and the error map of its verdicts against the exact
//! reference.

use std::path::PathBuf;

use crate::output::OutputError;
use crate::output::folder::OutputFolder;
use crate::output::formats::{font, save};
use crate::pass::camera::CameraImage;
use crate::truth::cause::Cause;
use crate::truth::metrics::Verdict;
use crate::truth::reference::PixelTruth;

/// Pixel `k`'s cosine to the light from the exact reference, 0 for the
/// background and for surfaces facing away.
fn lambert(truth: &[Option<PixelTruth>], k: usize) -> f64 {
    truth.get(k).copied().flatten().map_or(0.0, |t| t.light_cos.max(0.0))
}

/// Write the camera pass as a picture a person can read: surfaces grey by
/// their facing to the light (the cosine to the light at each pixel's
/// surface point, from the exact reference `truth`; faces turned away are
/// dark), shadowed parts dark in proportion to the shadow fraction, the
/// background black. The picture is exposed so that
/// the brightest tenth of the surfaces facing the light is white: a scene
/// lit at grazing (every surface's cosine a few hundredths) still shows
/// its lit surfaces apart from its shadows.
///
/// # Errors
/// [`OutputError::Image`].
pub(crate) fn write_shadow_image(
    folder: &mut OutputFolder,
    name: &str,
    image: &CameraImage,
    truth: &[Option<PixelTruth>],
) -> Result<PathBuf, OutputError> {
    let lambert = |k: usize| lambert(truth, k);
    let mut facing: Vec<f64> = (0..image.pixels.len()).map(lambert).filter(|&l| l > 0.0).collect();
    let brightest = if facing.is_empty() {
        1.0
    } else {
        let at = facing.len() * 9 / 10;
        *facing.select_nth_unstable_by(at, f64::total_cmp).1
    };
    let exposure = 1.0 / brightest.clamp(0.02, 1.0);
    let pixels: Vec<u8> = image
        .pixels
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if p.triangle == umbra_core::NO_TRIANGLE {
                return 0;
            }
            let lit = 1.0 - p.shadow.to_num::<f64>();
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 40..=255")]
            let g = (40.0 + 215.0 * (lit * lambert(k) * exposure).min(1.0)).round().clamp(40.0, 255.0) as u8;
            g
        })
        .collect();
    save(folder, name, &pixels, image.width, image.height, image::ColorType::L8)
}

/// Write the shadow term alone: white lit, black fully shadowed, the
/// background a dark grey (24).
///
/// # Errors
/// [`OutputError::Image`].
pub(crate) fn write_shadow_term(
    folder: &mut OutputFolder,
    name: &str,
    image: &CameraImage,
) -> Result<PathBuf, OutputError> {
    let pixels: Vec<u8> = image
        .pixels
        .iter()
        .map(|p| {
            if p.triangle == umbra_core::NO_TRIANGLE {
                return 24;
            }
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 0..=255")]
            let g = (255.0 * (1.0 - p.shadow.to_num::<f64>())).round().clamp(0.0, 255.0) as u8;
            g
        })
        .collect();
    save(folder, name, &pixels, image.width, image.height, image::ColorType::L8)
}

/// The error map's classes in legend order, each with its colour: the
/// two that are the map and the filter at work, then the three artifacts.
pub const ERROR_COLOURS: [(Cause, &str, [u8; 3]); 5] = [
    (Cause::Aliasing, "aliasing", [235, 170, 0]),
    (Cause::Penumbra, "penumbra", [150, 205, 220]),
    (Cause::Acne, "acne", [220, 30, 30]),
    (Cause::Detachment, "detachment", [150, 40, 190]),
    (Cause::Leak, "leaks", [30, 100, 235]),
];

/// The colour of a class on the error map.
fn colour_of(cause: Cause) -> [u8; 3] {
    ERROR_COLOURS.iter().find(|(c, _, _)| *c == cause).map_or([0; 3], |&(_, _, rgb)| rgb)
}

/// Artifact pixels (acne, detachment, leaks) ringed on the error map when
/// there are at most this many.
pub(crate) const RINGS: usize = 2000;

/// Write the error map: every pixel's [`Verdict`] over a faint shading of
/// the scene (light greys, lit surfaces lighter by their exact cosine to
/// the light from `truth`, so the geometry stays readable), each wrong pixel in its class's colour ([`ERROR_COLOURS`]),
/// each artifact pixel ringed in its colour (up to `RINGS` of them),
/// with a legend band below the image giving each class and its count.
///
/// # Errors
/// `OutputError::Image` or `OutputError::Io` naming the file.
pub fn write_error_image(
    folder: &mut OutputFolder,
    name: &str,
    image: &CameraImage,
    verdicts: &[Verdict],
    truth: &[Option<PixelTruth>],
) -> Result<PathBuf, OutputError> {
    use plotters::prelude::*;
    let count = |v: Verdict| verdicts.iter().filter(|&&x| x == v).count();
    let (w, h) = (image.width, image.height);
    // The legend's entries, placed in rows that wrap at the image's width.
    let legend: Vec<(String, [u8; 3], (i32, i32))> = {
        let (mut x, mut row) = (6, 0);
        let width = i32::try_from(w).unwrap_or(i32::MAX);
        ERROR_COLOURS
            .iter()
            .map(|&(cause, name, rgb)| {
                let text = format!("{name} {}", count(Verdict::Wrong(cause)));
                #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a short label")]
                let advance = 8 * text.len() as i32 + 34;
                if x > 6 && x + advance > width {
                    (x, row) = (6, row + 1);
                }
                let at = (x, row);
                x += advance;
                (text, rgb, at)
            })
            .collect()
    };
    let rows = legend.last().map_or(1, |l| l.2.1 + 1);
    let band = 30 * u32::try_from(rows).unwrap_or(1);
    let mut rgb = vec![255u8; (w as usize) * (h as usize + band as usize) * 3];
    for (k, (p, v)) in image.pixels.iter().zip(verdicts).enumerate() {
        let colour = match v {
            Verdict::Wrong(cause) => colour_of(*cause),
            _ if p.triangle == umbra_core::NO_TRIANGLE => [255, 255, 255],
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
    let path = folder.dir().join(name);
    font().map_err(|problem| OutputError::Font { path: path.clone(), problem })?;
    let drawn = {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h + band)).into_drawing_area();
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
        if rings.len() <= RINGS {
            for (k, [r, g, b]) in &rings {
                let (x, y) = (k % w as usize, k / w as usize);
                let at = (i32::try_from(x).unwrap_or(i32::MAX), i32::try_from(y).unwrap_or(i32::MAX));
                let _ = root.draw(&Circle::new(at, 7, RGBColor(*r, *g, *b).stroke_width(2)));
            }
        }
        let style = ("sans-serif", 14).into_font().color(&BLACK);
        let top = i32::try_from(h).unwrap_or(i32::MAX).saturating_add(8);
        legend
            .iter()
            .try_for_each(|(text, [r, g, b], (x, row))| {
                let (x, y) = (*x, top + 30 * row);
                root.draw(&Rectangle::new([(x, y), (x + 14, y + 14)], RGBColor(*r, *g, *b).filled()))?;
                root.draw(&Text::new(text.clone(), (x + 20, y), style.clone()))?;
                Ok::<(), DrawingAreaErrorKind<_>>(())
            })
            .and_then(|()| root.present())
    };
    drawn.map_err(|e| OutputError::Font { path, problem: e.to_string() })?;
    save(folder, name, &rgb, w, h + band, image::ColorType::Rgb8)
}
