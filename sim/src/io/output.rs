//! Files a person or another tool can open: NumPy arrays of raw texels, PNG
//! previews, Markdown tables.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::style::FontStyle;
use umbra_core::DepthFormatKind;

use super::folder::OutputFolder;
use crate::pass::light::{raw_depth, raw_far};

/// Why an output file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// Creating or writing the file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// Drawing a picture's text failed (no usable font).
    #[error("{path}: {problem}")]
    Font {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        problem: String,
    },
    /// The folder cannot take the file: a name outside it, a folder that
    /// is a file, a manifest that does not match.
    #[error("{path}: {problem}")]
    Folder {
        /// The file or folder.
        path: PathBuf,
        /// What is wrong.
        problem: String,
    },
    /// Encoding the image failed.
    #[error("{path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The encoder's error.
        source: image::ImageError,
    },
}

/// The pictures' font, DejaVu Sans (Bitstream Vera licence, `assets/DejaVuSans.LICENSE`), bundled so that
/// no system font is needed.
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Register the pictures' font once (text needs it for its metrics).
pub(crate) fn font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
                .map_err(|_| "the bundled font is not a TrueType font".to_owned())
        })
        .clone()
}

/// `pixels` as a PNG file's bytes; an error names `path`.
///
/// # Errors
/// [`OutputError::Image`].
pub fn png(
    path: &Path,
    pixels: &[u8],
    width: u32,
    height: u32,
    color: image::ColorType,
) -> Result<Vec<u8>, OutputError> {
    use image::ImageEncoder;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(pixels, width, height, color.into())
        .map_err(|source| OutputError::Image { path: path.to_owned(), source })?;
    Ok(bytes)
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io { path: path.to_owned(), source }
}

/// One depth map as raw texel bits, row-major.
#[derive(Clone, Copy, Debug)]
pub struct RawMap<'a> {
    /// The depth format the bits belong to.
    pub format: DepthFormatKind,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width × height` raw texels.
    pub raw: &'a [u32],
}

/// Write a `height × width` map of raw texels as a C-order `.npy` array
/// named `name` in `folder`: `<u2` for 16-bit depth, `<u4` for 24-bit depth
/// and for the f32 format's bits.
///
/// # Errors
/// [`OutputError::Io`] naming the file.
pub fn write_npy(folder: &mut OutputFolder, name: &str, map: &RawMap<'_>) -> Result<PathBuf, OutputError> {
    let RawMap { format, width, height, raw } = *map;
    let mut bytes = Vec::new();
    let shape = [u64::from(height), u64::from(width)];
    match format {
        DepthFormatKind::D16 => npy_body(&mut bytes, &shape, raw.iter().map(|&v| u16::try_from(v).unwrap_or(u16::MAX))),
        DepthFormatKind::D24 | DepthFormatKind::F32 => npy_body(&mut bytes, &shape, raw.iter().copied()),
    }
    .map_err(io(&folder.dir().join(name)))?;
    folder.write(name, &bytes)
}

fn npy_body<T: npyz::AutoSerialize>(
    w: &mut impl Write,
    shape: &[u64],
    data: impl Iterator<Item = T>,
) -> std::io::Result<()> {
    use npyz::WriterBuilder;
    let mut out = npyz::WriteOptions::<T>::new().default_dtype().shape(shape).writer(w).begin_nd()?;
    out.extend(data)?;
    out.finish()
}

/// Write a greyscale PNG preview of a map as `name` in `folder`: the
/// depths present are stretched over black (nearest) to light grey, and
/// the clear value is white.
///
/// # Errors
/// [`OutputError::Image`] or [`OutputError::Io`] naming the file.
pub fn write_preview(folder: &mut OutputFolder, name: &str, map: &RawMap<'_>) -> Result<PathBuf, OutputError> {
    let RawMap { format, width, height, raw } = *map;
    let far = raw_far(format);
    let depths = raw.iter().filter(|&&v| v != far).map(|&v| raw_depth(format, v));
    let (lo, hi) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
    let span = if hi > lo { hi - lo } else { 1.0 };
    let pixels: Vec<u8> = raw
        .iter()
        .map(|&v| {
            if v == far {
                255
            } else {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 0..=230")]
                let g = (((raw_depth(format, v) - lo) / span) * 230.0).round().clamp(0.0, 230.0) as u8;
                g
            }
        })
        .collect();
    save(folder, name, &pixels, width, height, image::ColorType::L8)
}

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
    image: &crate::pass::camera::CameraImage,
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

fn save(
    folder: &mut OutputFolder,
    name: &str,
    pixels: &[u8],
    width: u32,
    height: u32,
    color: image::ColorType,
) -> Result<PathBuf, OutputError> {
    let bytes = png(&folder.dir().join(name), pixels, width, height, color)?;
    folder.write(name, &bytes)
}

/// Write the shadow term alone: white lit, black fully shadowed, the
/// background a dark grey (24).
///
/// # Errors
/// [`OutputError::Image`].
pub fn write_shadow_term(
    folder: &mut OutputFolder,
    name: &str,
    image: &crate::pass::camera::CameraImage,
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

/// The error map's colours: edge placement, acne, leaks.
pub const ERROR_COLOURS: [[u8; 3]; 3] = [[235, 170, 0], [220, 30, 30], [30, 100, 235]];

/// Write the error map: every pixel's [`Verdict`](crate::truth::metrics::Verdict) over a faint shading of
/// the scene (light greys, lit surfaces lighter, so the geometry stays
/// readable), edge placement amber, acne red, leaks blue, with a legend
/// band below the image giving each colour's meaning and count.
///
/// # Errors
/// [`OutputError::Image`] or [`OutputError::Io`] naming the file.
pub fn write_error_image(
    folder: &mut OutputFolder,
    name: &str,
    image: &crate::pass::camera::CameraImage,
    truth: &[Option<crate::truth::reference::PixelTruth>],
    light_dir: umbra_core::glam::Vec3,
) -> Result<PathBuf, OutputError> {
    use crate::truth::metrics::{Verdict, verdicts};
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
