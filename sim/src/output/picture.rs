//! Pictures that explain themselves: a body of pixels framed by a caption
//! above it (what the picture is, its scene and configuration) and a key
//! below it (what each colour means: swatches, or a colour scale with its
//! ends labelled), so that a person reads the file without the code.

use std::path::PathBuf;

use super::OutputError;
use super::folder::OutputFolder;
use super::formats::{RawMap, font, save};
use crate::base::maps::{raw_depth, raw_far};

/// Rows of the caption band above the body, pixels: three lines of text.
pub const CAPTION_BAND: u32 = 58;
/// The narrowest a framed picture is, pixels: a caption line and a key
/// fit across it whatever the body's size.
pub const MIN_WIDTH: u32 = 640;
/// Where no surface is, in every picture of a render and every map: a
/// steel blue no shade of grey or class colour is.
pub const BACKGROUND: [u8; 3] = [70, 90, 130];

/// A colour scale: `colour(t)` for `t` from 0 to 1, with what each end
/// means.
pub struct Scale<'a> {
    /// The colour at `t`.
    pub colour: &'a dyn Fn(f64) -> [u8; 3],
    /// What `t = 0` means (`0.41 nearest`).
    pub low: String,
    /// What `t = 1` means.
    pub high: String,
}

/// What a picture says about itself.
pub struct Frame<'a> {
    /// The first line: what the picture is.
    pub title: String,
    /// Below it, wrapped to two lines: the scene and configuration.
    pub detail: String,
    /// A colour scale, when the body's colours run continuously.
    pub scale: Option<Scale<'a>>,
    /// Swatches: a colour and what it means.
    pub swatches: Vec<([u8; 3], String)>,
}

/// Characters a caption line holds at the caption's font across `width`.
fn line_chars(width: u32) -> usize {
    (width.saturating_sub(12) / 7) as usize
}

/// `text` in at most `lines` lines of at most `chars` characters, broken
/// at spaces; the last line cut with `…` when it does not fit.
fn wrap(text: &str, chars: usize, lines: usize) -> Vec<String> {
    let mut out = super::lines::lines(text, chars);
    if out.len() > lines {
        out.truncate(lines);
        if let Some(last) = out.last_mut() {
            let keep: String = last.chars().take(chars.saturating_sub(1)).collect();
            *last = format!("{keep}…");
        }
    }
    out.into_iter()
        .map(|l| {
            if l.chars().count() > chars { l.chars().take(chars.saturating_sub(1)).chain(['…']).collect() } else { l }
        })
        .collect()
}

/// Where the body sits in its framed picture: `(x, y)` of its top-left
/// pixel, under the caption at the canvas's left edge.
pub const BODY_ORIGIN: (u32, u32) = (0, CAPTION_BAND);

/// Write `body` (RGB, `width × height`) framed by `frame` as the PNG
/// `name`: the caption above, the key below, the canvas at least
/// [`MIN_WIDTH`] wide (the body at its left, the rest white).
///
/// # Errors
/// `OutputError::Font` when the text cannot be drawn, `OutputError::Image`
/// or `OutputError::Io` naming the file.
pub fn write_framed(
    folder: &mut OutputFolder,
    name: &str,
    body: &[u8],
    (width, height): (u32, u32),
    frame: &Frame<'_>,
) -> Result<PathBuf, OutputError> {
    use plotters::prelude::*;
    let canvas = width.max(MIN_WIDTH);
    let as_i32 = |v: u32| i32::try_from(v).unwrap_or(i32::MAX);
    // The key: a scale row when there is one, then swatches in rows that
    // wrap at the canvas's width.
    let mut placed = Vec::new();
    let first_row = u32::from(frame.scale.is_some());
    let (mut x, mut row) = (8, first_row);
    for (rgb, text) in &frame.swatches {
        #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap, reason = "a short label")]
        let advance = 7 * text.chars().count() as i32 + 34;
        if x > 8 && x + advance > as_i32(canvas) {
            (x, row) = (8, row + 1);
        }
        placed.push((*rgb, text.clone(), x, row));
        x += advance;
    }
    let rows = placed.last().map_or(first_row, |p| p.3 + 1).max(1);
    let key_band = 10 + 26 * rows;
    let total = CAPTION_BAND + height + key_band;
    let mut rgb = vec![255u8; canvas as usize * total as usize * 3];
    let (x0, y0) = BODY_ORIGIN;
    for y in 0..height as usize {
        let from = &body[3 * width as usize * y..3 * width as usize * (y + 1)];
        let at = 3 * (canvas as usize * (y + y0 as usize) + x0 as usize);
        rgb[at..at + from.len()].copy_from_slice(from);
    }
    let path = folder.dir().join(name);
    font().map_err(|problem| OutputError::Font { path: path.clone(), problem })?;
    let drawn = {
        let root = BitMapBackend::with_buffer(&mut rgb, (canvas, total)).into_drawing_area();
        let bold = ("sans-serif", 15).into_font().color(&BLACK);
        let plain = ("sans-serif", 12).into_font().color(&RGBColor(60, 60, 60));
        let chars = line_chars(canvas);
        let mut lines = vec![(wrap(&frame.title, chars, 1), bold)];
        lines.push((wrap(&frame.detail, chars + chars / 6, 2), plain.clone()));
        let mut y = 4;
        let mut result = Ok(());
        for (texts, style) in lines {
            for t in texts {
                result = result.and_then(|()| root.draw(&Text::new(t, (8, y), style.clone())));
                y += 18;
            }
        }
        let top = as_i32(CAPTION_BAND + height) + 8;
        if let Some(scale) = &frame.scale {
            let (bar, left) = (256, 8 + 7 * as_i32(u32::try_from(scale.low.chars().count()).unwrap_or(0)) + 8);
            result = result.and_then(|()| root.draw(&Text::new(scale.low.clone(), (8, top), plain.clone())));
            for k in 0..bar {
                let [r, g, b] = (scale.colour)(f64::from(k) / f64::from(bar - 1));
                let x = left + k;
                result = result.and_then(|()| {
                    root.draw(&Rectangle::new([(x, top), (x + 1, top + 14)], RGBColor(r, g, b).filled()))
                });
            }
            result = result.and_then(|()| {
                root.draw(&Rectangle::new([(left - 1, top - 1), (left + bar, top + 15)], BLACK.stroke_width(1)))
            });
            result =
                result.and_then(|()| root.draw(&Text::new(scale.high.clone(), (left + bar + 8, top), plain.clone())));
        }
        for ([r, g, b], text, x, row) in &placed {
            let y = top + 26 * as_i32(*row);
            result = result
                .and_then(|()| root.draw(&Rectangle::new([(*x, y), (x + 14, y + 14)], RGBColor(*r, *g, *b).filled())))
                .and_then(|()| {
                    root.draw(&Rectangle::new([(*x, y), (x + 14, y + 14)], RGBColor(90, 90, 90).stroke_width(1)))
                })
                .and_then(|()| root.draw(&Text::new(text.clone(), (x + 20, y), plain.clone())));
        }
        result.and_then(|()| root.present())
    };
    drawn.map_err(|e| OutputError::Font { path, problem: e.to_string() })?;
    save(folder, name, &rgb, canvas, total, image::ColorType::Rgb8)
}

/// Write a PNG preview of a map as `name` in `folder`: the depths present
/// stretched over black (nearest) to light grey (farthest), the clear
/// value (no surface) [`BACKGROUND`]; framed
/// with `title` and `detail` and a depth scale whose ends are the nearest
/// and farthest depths drawn.
///
/// # Errors
/// `OutputError::Image`, `OutputError::Font` or `OutputError::Io` naming
/// the file.
pub fn write_preview(
    folder: &mut OutputFolder,
    name: &str,
    map: &RawMap<'_>,
    (title, detail): (&str, &str),
) -> Result<PathBuf, OutputError> {
    let RawMap { format, width, height, raw } = *map;
    let far = raw_far(format);
    let depths = raw.iter().filter(|&&v| v != far).map(|&v| raw_depth(format, v));
    let (lo, hi) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
    let span = if hi > lo { hi - lo } else { 1.0 };
    let grey = |t: f64| {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to 0..=230")]
        let g = (t * 230.0).round().clamp(0.0, 230.0) as u8;
        [g; 3]
    };
    let pixels: Vec<u8> = raw
        .iter()
        .flat_map(|&v| if v == far { BACKGROUND } else { grey((raw_depth(format, v) - lo) / span) })
        .collect();
    let (low, high) = if lo <= hi {
        (format!("depth {lo:.4} (nearest)"), format!("{hi:.4} (farthest)"))
    } else {
        ("no depth drawn".to_owned(), String::new())
    };
    let frame = Frame {
        title: title.to_owned(),
        detail: detail.to_owned(),
        scale: Some(Scale { colour: &grey, low, high }),
        swatches: vec![(BACKGROUND, "clear: no surface".into())],
    };
    write_framed(folder, name, &pixels, (width, height), &frame)
}

#[cfg(test)]
mod tests {
    /// Captions break at spaces and never run past their width.
    #[test]
    fn captions_wrap_at_spaces_within_their_width() {
        let lines = super::wrap("second, d24, map 1024², filter bilinear, bias 0", 20, 2);
        assert_eq!(lines, ["second, d24, map", "1024², filter…"]);
        assert!(super::wrap("a b c", 20, 2) == ["a b c"]);
        assert!(super::wrap(&"x".repeat(50), 10, 1)[0].chars().count() <= 10);
    }
}
