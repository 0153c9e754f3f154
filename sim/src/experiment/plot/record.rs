//! A drawing backend for tests that draws nothing and keeps what was
//! drawn: each text with the box it takes (measured as every backend
//! measures it, from the font's layout and the anchor), each stroke with
//! its colour; and every figure [`both`](super::both) drew on this
//! thread, kept by name, so that a test can ask where things landed.

use std::cell::RefCell;
use std::rc::Rc;

use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind};

use super::place::Rect;
use super::{Figure, SIZE};

/// What a stroke drew.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Mark {
    /// A circle: its centre and radius.
    Circle((i32, i32), i32),
    /// A rectangle: two opposite corners.
    Rect((i32, i32), (i32, i32)),
    /// A path through its points.
    Path(Vec<(i32, i32)>),
    /// One line from one point to another.
    Line((i32, i32), (i32, i32)),
}

/// A shape drawn, with its colour.
#[derive(Clone, Debug)]
pub(crate) struct Stroke {
    pub mark: Mark,
    pub rgb: (u8, u8, u8),
    /// Opacity, 0 to 1.
    pub alpha: f64,
}

/// A text drawn, with the box it takes.
#[derive(Clone, Debug)]
pub(crate) struct Label {
    pub text: String,
    pub rect: Rect,
    /// Where the anchor is on the text: `left`, `center` or `right`, then
    /// `top`, `center` or `bottom` (`center top` for an x axis's ticks).
    pub anchor: String,
    /// Whether it reads left to right (not turned).
    pub upright: bool,
}

/// Everything one figure drew.
#[derive(Clone, Debug, Default)]
pub(crate) struct Record {
    pub texts: Vec<Label>,
    pub strokes: Vec<Stroke>,
}

/// A backend of [`SIZE`] that keeps what is drawn on it in a shared
/// [`Record`].
pub(crate) struct Recorder(Rc<RefCell<Record>>);

impl Recorder {
    fn keep(&self, mark: Mark, color: BackendColor) {
        self.0.borrow_mut().strokes.push(Stroke { mark, rgb: color.rgb, alpha: color.alpha });
    }
}

type Drawn = Result<(), DrawingErrorKind<std::fmt::Error>>;

impl DrawingBackend for Recorder {
    type ErrorType = std::fmt::Error;

    fn get_size(&self) -> (u32, u32) {
        SIZE
    }

    fn ensure_prepared(&mut self) -> Drawn {
        Ok(())
    }

    fn present(&mut self) -> Drawn {
        Ok(())
    }

    fn draw_pixel(&mut self, _: BackendCoord, _: BackendColor) -> Drawn {
        Ok(())
    }

    fn draw_line<S: BackendStyle>(&mut self, from: BackendCoord, to: BackendCoord, style: &S) -> Drawn {
        self.keep(Mark::Line(from, to), style.color());
        Ok(())
    }

    fn draw_rect<S: BackendStyle>(&mut self, a: BackendCoord, b: BackendCoord, style: &S, _: bool) -> Drawn {
        self.keep(Mark::Rect(a, b), style.color());
        Ok(())
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(&mut self, path: I, style: &S) -> Drawn {
        self.keep(Mark::Path(path.into_iter().collect()), style.color());
        Ok(())
    }

    fn draw_circle<S: BackendStyle>(&mut self, centre: BackendCoord, radius: u32, style: &S, _: bool) -> Drawn {
        self.keep(Mark::Circle(centre, i32::try_from(radius).unwrap_or(i32::MAX)), style.color());
        Ok(())
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(&mut self, _: I, _: &S) -> Drawn {
        Ok(())
    }

    fn draw_text<S: BackendTextStyle>(&mut self, text: &str, style: &S, (x, y): BackendCoord) -> Drawn {
        // As plotters' own backends lay a text out: its layout box moved
        // by the anchor, then turned by the style's transform about the
        // anchor point.
        let ((x0, y0), (x1, y1)) = style.layout_box(text).map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let (w, h) = (x1 - x0, y1 - y0);
        let anchor = style.anchor();
        let (dx, h_name) = match anchor.h_pos {
            HPos::Left => (0, "left"),
            HPos::Center => (-w / 2, "center"),
            HPos::Right => (-w, "right"),
        };
        let (dy, v_name) = match anchor.v_pos {
            VPos::Top => (0, "top"),
            VPos::Center => (-h / 2, "center"),
            VPos::Bottom => (-h, "bottom"),
        };
        let t = style.transform();
        let (ax, ay) = t.transform(dx, dy);
        let (bx, by) = t.transform(dx + w, dy + h);
        let rect = Rect { x0: x + ax.min(bx), y0: y + ay.min(by), x1: x + ax.max(bx), y1: y + ay.max(by) };
        let upright = matches!(t, plotters_backend::FontTransform::None);
        let anchor = format!("{h_name} {v_name}");
        let label = Label { text: text.to_owned(), rect, anchor, upright };
        self.0.borrow_mut().texts.push(label);
        Ok(())
    }
}

thread_local! {
    /// The figures drawn on this thread, by file name without extension.
    static KEPT: RefCell<Vec<(String, Record)>> = const { RefCell::new(Vec::new()) };
}

/// Draw `f` once more into a [`Recorder`] and keep what it drew as `base`.
///
/// # Errors
/// Drawing failed.
pub(crate) fn keep(base: &str, f: &impl Figure) -> Result<(), String> {
    let record = Rc::new(RefCell::new(Record::default()));
    f.draw(&Recorder(Rc::clone(&record)).into_drawing_area())?;
    let record = record.borrow().clone();
    KEPT.with(|k| k.borrow_mut().push((base.to_owned(), record)));
    Ok(())
}

/// The figures drawn on this thread since the last call, in order.
#[must_use]
pub(crate) fn take() -> Vec<(String, Record)> {
    KEPT.with(|k| std::mem::take(&mut *k.borrow_mut()))
}

/// Whether the pixel `p` lies within half a pixel of the segment `a`–`b`.
fn on_segment(p: (i32, i32), a: (i32, i32), b: (i32, i32)) -> bool {
    let (px, py) = (f64::from(p.0 - a.0), f64::from(p.1 - a.1));
    let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
    let len = dx.mul_add(dx, dy * dy);
    let t = if len > 0.0 { (px.mul_add(dx, py * dy) / len).clamp(0.0, 1.0) } else { 0.0 };
    (px - t * dx).hypot(py - t * dy) <= 0.5
}

/// The pixels within reach `r` of `centre` that `on` says are on a
/// shape's outline.
fn outline(centre: (i32, i32), r: i32, on: impl Fn((i32, i32)) -> bool) -> Vec<(i32, i32)> {
    let (cx, cy) = centre;
    (cy - r..=cy + r).flat_map(|y| (cx - r..=cx + r).map(move |x| (x, y))).filter(|&p| on(p)).collect()
}

/// The widest a marker is, pixels: anything larger is a line or a frame.
const MARKER: i32 = 16;

impl Record {
    /// Every pair of texts (not empty) whose boxes share area: boxes that
    /// only touch do not.
    #[must_use]
    pub(crate) fn overlapping_texts(&self) -> Vec<(&Label, &Label)> {
        let texts: Vec<&Label> = self.texts.iter().filter(|t| !t.text.trim().is_empty()).collect();
        let mut out = Vec::new();
        for (i, a) in texts.iter().enumerate() {
            out.extend(texts[i + 1..].iter().filter(|b| a.rect.overlaps(&b.rect)).map(|b| (*a, *b)));
        }
        out
    }

    /// The texts (not empty) that reach outside the image.
    #[must_use]
    pub(crate) fn texts_outside(&self) -> Vec<&Label> {
        let image = Rect::at((0, 0), (SIZE.0.cast_signed(), SIZE.1.cast_signed()));
        self.texts.iter().filter(|t| !t.text.trim().is_empty() && !t.rect.within(&image)).collect()
    }

    /// The markers drawn opaque in `rgb` (circles, rectangles and closed
    /// paths no wider than a marker, and crosses: two such lines through
    /// one middle, one after the other), each as the pixels of its outline.
    #[must_use]
    pub(crate) fn markers(&self, rgb: (u8, u8, u8)) -> Vec<Vec<(i32, i32)>> {
        let mine: Vec<&Mark> =
            self.strokes.iter().filter(|s| s.rgb == rgb && s.alpha >= 1.0).map(|s| &s.mark).collect();
        let small = |a: (i32, i32), b: (i32, i32)| (a.0 - b.0).abs() <= MARKER && (a.1 - b.1).abs() <= MARKER;
        let mut out = Vec::new();
        for (k, mark) in mine.iter().enumerate() {
            match mark {
                Mark::Circle(c, r) if *r <= MARKER / 2 => {
                    out.push(outline(*c, r + 1, |(x, y)| {
                        (f64::from(x - c.0).hypot(f64::from(y - c.1)) - f64::from(*r)).abs() <= 0.5
                    }));
                }
                Mark::Rect(a, b) if small(*a, *b) => {
                    let (x0, x1, y0, y1) = (a.0.min(b.0), a.0.max(b.0), a.1.min(b.1), a.1.max(b.1));
                    let centre = ((x0 + x1) / 2, (y0 + y1) / 2);
                    out.push(outline(centre, MARKER, |(x, y)| {
                        ((x == x0 || x == x1) && (y0..=y1).contains(&y))
                            || ((y == y0 || y == y1) && (x0..=x1).contains(&x))
                    }));
                }
                Mark::Path(p) if p.len() >= 4 && p.first() == p.last() && p.iter().all(|q| small(*q, p[0])) => {
                    out.push(outline(p[0], MARKER, |q| p.windows(2).any(|w| on_segment(q, w[0], w[1]))));
                }
                Mark::Line(a, b) if small(*a, *b) => {
                    // A cross: this line and the next through one middle.
                    let middle = |a: (i32, i32), b: (i32, i32)| (a.0 + b.0, a.1 + b.1);
                    if let Some(Mark::Line(c, d)) = mine.get(k + 1)
                        && middle(*a, *b) == middle(*c, *d)
                        && (a, b) != (c, d)
                    {
                        let (a, b, c, d) = (*a, *b, *c, *d);
                        out.push(outline(a, MARKER, |q| on_segment(q, a, b) || on_segment(q, c, d)));
                    }
                }
                _ => {}
            }
        }
        out
    }
}

/// Fail naming `figure` and the texts, if any text of `record` overlaps
/// another or leaves the image.
///
/// # Panics
/// When one does.
pub(crate) fn assert_legible(figure: &str, record: &Record) {
    let clashes: Vec<String> = record
        .overlapping_texts()
        .iter()
        .map(|(a, b)| format!("`{}` {:?} over `{}` {:?}", a.text, a.rect, b.text, b.rect))
        .collect();
    assert!(clashes.is_empty(), "{figure}: {}", clashes.join("; "));
    let outside: Vec<String> = record.texts_outside().iter().map(|t| format!("`{}` {:?}", t.text, t.rect)).collect();
    assert!(outside.is_empty(), "{figure}: outside the image: {}", outside.join("; "));
}

/// The share of `outline`'s pixels at which `png` shows `rgb` (at the
/// pixel or one beside it, each channel within 8), after everything was
/// drawn over it.
#[must_use]
pub(crate) fn showing(png: &image::RgbImage, outline: &[(i32, i32)], rgb: (u8, u8, u8)) -> f64 {
    let is = |x: i32, y: i32| {
        let (Ok(x), Ok(y)) = (u32::try_from(x), u32::try_from(y)) else { return false };
        png.get_pixel_checked(x, y)
            .is_some_and(|p| [(p[0], rgb.0), (p[1], rgb.1), (p[2], rgb.2)].iter().all(|&(a, b)| a.abs_diff(b) <= 8))
    };
    let shown = outline
        .iter()
        .filter(|&&(x, y)| [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|(dx, dy)| is(x + dx, y + dy)))
        .count();
    #[allow(clippy::cast_precision_loss, reason = "a few pixels")]
    let share = shown as f64 / outline.len().max(1) as f64;
    share
}
