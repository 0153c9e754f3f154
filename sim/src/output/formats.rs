//! The formats maps and pictures are written in, files a person or another
//! tool can open: NumPy arrays of raw texels, PNG images, and
//! the pictures' bundled font.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::style::FontStyle;
use umbra_core::DepthFormatKind;

use super::error::OutputError;
use super::folder::OutputFolder;

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
pub(crate) fn png(
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
/// `OutputError::Io` naming the file.
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

/// Write a `height × width` array of `values` (row-major) as a C-order
/// `.npy` file named `name` in `folder`: `<f4` for `f32`, `|u1` for `u8`.
///
/// # Errors
/// [`OutputError::Io`] naming the file.
pub(crate) fn write_array<T: npyz::AutoSerialize + Copy>(
    folder: &mut OutputFolder,
    name: &str,
    (width, height): (u32, u32),
    values: &[T],
) -> Result<PathBuf, OutputError> {
    let mut bytes = Vec::new();
    npy_body(&mut bytes, &[u64::from(height), u64::from(width)], values.iter().copied())
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

pub(crate) fn save(
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
