//! Files a person or another tool can open: NumPy arrays of raw texels, PNG
//! previews, Markdown tables.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use umbra_core::DepthFormatKind;

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
    /// Encoding the image failed.
    #[error("{path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The encoder's error.
        source: image::ImageError,
    },
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

/// Write a `height × width` map of raw texels as a C-order `.npy` array:
/// `<u2` for 16-bit depth, `<u4` for 24-bit depth and for the f32 format's bits.
///
/// # Errors
/// [`OutputError::Io`].
pub fn write_npy(path: &Path, map: &RawMap<'_>) -> Result<(), OutputError> {
    let RawMap { format, width, height, raw } = *map;
    let file = File::create(path).map_err(io(path))?;
    let mut w = BufWriter::new(file);
    let shape = [u64::from(height), u64::from(width)];
    match format {
        DepthFormatKind::D16 => npy_body(&mut w, &shape, raw.iter().map(|&v| u16::try_from(v).unwrap_or(u16::MAX))),
        DepthFormatKind::D24 | DepthFormatKind::F32 => npy_body(&mut w, &shape, raw.iter().copied()),
    }
    .map_err(io(path))?;
    w.flush().map_err(io(path))
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

/// Write a greyscale PNG preview of a map: the depths present are stretched
/// over black (nearest) to light grey, and the clear value is white.
///
/// # Errors
/// [`OutputError::Image`].
pub fn write_preview(path: &Path, map: &RawMap<'_>) -> Result<(), OutputError> {
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
    image::save_buffer(path, &pixels, width, height, image::ColorType::L8)
        .map_err(|source| OutputError::Image { path: path.to_owned(), source })
}

/// Write text to a file, creating its folder.
///
/// # Errors
/// [`OutputError::Io`].
pub fn write_text(path: &Path, text: &str) -> Result<(), OutputError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(io(path))?;
    }
    std::fs::write(path, text).map_err(io(path))
}

/// Write the camera pass as a picture a person can read: surfaces grey by
/// their facing to the light (`light_dir`, from the light into the scene;
/// faces turned away are dark), shadowed parts dark in proportion to the
/// shadow fraction, the background black.
///
/// # Errors
/// [`OutputError::Image`].
pub fn write_shadow_image(
    path: &Path,
    image: &crate::pass::camera::CameraImage,
    light_dir: umbra_core::glam::Vec3,
) -> Result<(), OutputError> {
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
    save(path, &pixels, image.width, image.height, image::ColorType::L8)
}

fn save(path: &Path, pixels: &[u8], width: u32, height: u32, color: image::ColorType) -> Result<(), OutputError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(io(path))?;
    }
    image::save_buffer(path, pixels, width, height, color)
        .map_err(|source| OutputError::Image { path: path.to_owned(), source })
}

/// Write the shadow term alone: white lit, black fully shadowed, the
/// background a dark grey (24).
///
/// # Errors
/// [`OutputError::Image`].
pub fn write_shadow_term(path: &Path, image: &crate::pass::camera::CameraImage) -> Result<(), OutputError> {
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
    save(path, &pixels, image.width, image.height, image::ColorType::L8)
}

/// Write the error map: pixels the metrics evaluate in mid grey, false
/// shadows in red, false lights in blue; surfaces facing away from the
/// light in dark grey, the background black.
///
/// # Errors
/// [`OutputError::Image`].
pub fn write_error_image(
    path: &Path,
    image: &crate::pass::camera::CameraImage,
    truth: &[Option<crate::truth::reference::PixelTruth>],
) -> Result<(), OutputError> {
    let half = umbra_core::shadow::Shadow::from_bits(1 << 15);
    let pixels: Vec<u8> = image
        .pixels
        .iter()
        .zip(truth)
        .flat_map(|(p, t)| match t {
            None => [0, 0, 0],
            Some(t) if !t.faces_light => [60, 60, 60],
            Some(t) => match (p.shadow > half, t.lit) {
                (true, true) => [220, 40, 40],
                (false, false) => [40, 90, 230],
                _ => [150, 150, 150],
            },
        })
        .collect();
    save(path, &pixels, image.width, image.height, image::ColorType::Rgb8)
}
