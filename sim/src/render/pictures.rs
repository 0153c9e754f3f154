//! The pictures of a render a person reads at a glance: the shaded scene,
//! the shadow term, and the error map of its verdicts against the exact
//! reference.

use std::path::PathBuf;

use crate::io::folder::OutputFolder;
use crate::io::output::{OutputError, font, save};
use crate::pass::camera::CameraImage;
use crate::truth::metrics::{Verdict, verdicts};
use crate::truth::reference::PixelTruth;

/// Write the camera pass as a picture a person can read: surfaces grey by
/// their facing to the light (`light_dir`, from the light into the scene;
/// faces turned away are dark), shadowed parts dark in proportion to the
/// shadow fraction, the background black.
///
/// # Errors
/// [`OutputError::Image`].
pub fn write_shadow_image(
    folder: &mut OutputFolder,
    name: &str,
    image: &CameraImage,
    light_dir: umbra_core::glam::Vec3,
) -> Result<PathBuf, OutputError> {
    let to_light = -light_dir.normalize_or_zero();
    let pixels: Vec<u8> = image
        .pixels
        .iter()
        .map(|p| {
            if p.triangle == umbra_core::NO_TRIANGLE {
                return 0;
            }
            let lambert = f64::from(p.normal.normalize_or_zero().dot(to_light).max(0.0));
            let lit = 1.0 - p.shadow.to_num::<f64>();
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 40..=255")]
            let g = (40.0 + 215.0 * lit * lambert).round().clamp(40.0, 255.0) as u8;
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
pub fn write_shadow_term(folder: &mut OutputFolder, name: &str, image: &CameraImage) -> Result<PathBuf, OutputError> {
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

/// The error map's colours: edge placement, acne, leaks.
pub const ERROR_COLOURS: [[u8; 3]; 3] = [[235, 170, 0], [220, 30, 30], [30, 100, 235]];

/// Acne and leak pixels ringed on the error map when there are at most
/// this many.
pub const RINGS: usize = 2000;

/// Write the error map: every pixel's [`Verdict`](crate::truth::metrics::Verdict) over a faint shading of
/// the scene (light greys, lit surfaces lighter, so the geometry stays
/// readable), edge placement amber, acne red, leaks blue, each acne and
/// leak pixel ringed in its colour (up to [`RINGS`] of them), with a
/// legend band below the image giving each colour's meaning and count.
///
/// # Errors
/// [`OutputError::Image`] or [`OutputError::Io`] naming the file.
pub fn write_error_image(
    folder: &mut OutputFolder,
    name: &str,
    image: &CameraImage,
    truth: &[Option<PixelTruth>],
    light_dir: umbra_core::glam::Vec3,
) -> Result<PathBuf, OutputError> {
    use plotters::prelude::*;
    let to_light = -light_dir.normalize_or_zero();
    let verdicts = verdicts(&image.pixels, truth, image.width);
    let count = |v: Verdict| verdicts.iter().filter(|&&x| x == v).count();
    let (w, h) = (image.width, image.height);
    let band = 30;
    let mut rgb = vec![255u8; (w as usize) * (h as usize + band as usize) * 3];
    for (k, (p, v)) in image.pixels.iter().zip(&verdicts).enumerate() {
        let colour = match v {
            Verdict::EdgePlacement => ERROR_COLOURS[0],
            Verdict::Acne => ERROR_COLOURS[1],
            Verdict::Leak => ERROR_COLOURS[2],
            _ if p.triangle == umbra_core::NO_TRIANGLE => [255, 255, 255],
            _ => {
                let lambert = f64::from(p.normal.normalize_or_zero().dot(to_light).max(0.0));
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
        // A ring round each acne and leak pixel, so that a few on a large
        // image show at a glance; past RINGS of them they show unaided.
        let rings: Vec<(usize, [u8; 3])> = verdicts
            .iter()
            .enumerate()
            .filter_map(|(k, v)| match v {
                Verdict::Acne => Some((k, ERROR_COLOURS[1])),
                Verdict::Leak => Some((k, ERROR_COLOURS[2])),
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
        let legend = [
            ("edge placement", count(Verdict::EdgePlacement), ERROR_COLOURS[0]),
            ("acne", count(Verdict::Acne), ERROR_COLOURS[1]),
            ("leaks", count(Verdict::Leak), ERROR_COLOURS[2]),
        ];
        let style = ("sans-serif", 14).into_font().color(&BLACK);
        let y = i32::try_from(h).unwrap_or(i32::MAX).saturating_add(8);
        let mut x = 6;
        legend
            .iter()
            .try_for_each(|(name, n, [r, g, b])| {
                root.draw(&Rectangle::new([(x, y), (x + 14, y + 14)], RGBColor(*r, *g, *b).filled()))?;
                let text = format!("{name} {n}");
                root.draw(&Text::new(text.clone(), (x + 20, y), style.clone()))?;
                #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a short label")]
                let advance = 8 * text.len() as i32 + 34;
                x += advance;
                Ok::<(), DrawingAreaErrorKind<_>>(())
            })
            .and_then(|()| root.present())
    };
    drawn.map_err(|e| OutputError::Font { path, problem: e.to_string() })?;
    save(folder, name, &rgb, w, h + band, image::ColorType::Rgb8)
}
