//! Labels set where they overlap nothing already placed: boxes on the
//! image (`Rect`), the size a text takes (`text_size`), and a `Placer` that
//! tries the positions it is given in turn, around a point (`around`) or
//! beside it (`beside`), and keeps the first that is free.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A box on the image, pixels: left and top inside, right and bottom
/// just outside.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rect {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl Rect {
    /// The box of `size` whose top-left corner is `at`.
    #[must_use]
    pub(crate) const fn at((x, y): (i32, i32), (w, h): (i32, i32)) -> Self {
        Self { x0: x, y0: y, x1: x + w, y1: y + h }
    }

    /// The square reaching `r` pixels from `centre` every way.
    #[must_use]
    pub(crate) const fn around((x, y): (i32, i32), r: i32) -> Self {
        Self { x0: x - r, y0: y - r, x1: x + r + 1, y1: y + r + 1 }
    }

    /// The box of a pixel range, as plotters gives a plotting area's.
    #[must_use]
    pub(crate) const fn of_ranges((x, y): (std::ops::Range<i32>, std::ops::Range<i32>)) -> Self {
        Self { x0: x.start, y0: y.start, x1: x.end, y1: y.end }
    }

    /// Whether the two share any area (boxes that only touch do not).
    #[must_use]
    pub(crate) const fn overlaps(&self, o: &Self) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Whether this box lies wholly inside `o`.
    #[must_use]
    pub(crate) const fn within(&self, o: &Self) -> bool {
        self.x0 >= o.x0 && self.y0 >= o.y0 && self.x1 <= o.x1 && self.y1 <= o.y1
    }

    /// The point of this box nearest `p`.
    #[must_use]
    pub(crate) fn nearest(&self, (x, y): (i32, i32)) -> (i32, i32) {
        (x.clamp(self.x0, self.x1), y.clamp(self.y0, self.y1))
    }
}

/// The room a placed label takes, pixels: its text and a pixel of margin
/// all round, so that labels placed side by side stay apart.
///
/// # Errors
/// The font cannot measure it.
pub(crate) fn label_size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    font: &TextStyle<'_>,
) -> Result<(i32, i32), String> {
    let (w, h) = text_size(area, text, font)?;
    Ok((w + 2, h + 2))
}

/// The pixel size of `text` drawn in `font`.
///
/// # Errors
/// The font cannot measure it.
pub(crate) fn text_size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    font: &TextStyle<'_>,
) -> Result<(i32, i32), String> {
    let (w, h) = area.estimate_text_size(text, font).map_err(|e| e.to_string())?;
    Ok((i32::try_from(w).unwrap_or(i32::MAX), i32::try_from(h).unwrap_or(i32::MAX)))
}

/// Boxes set one by one inside bounds, none over another or over what
/// was blocked out.
pub(crate) struct Placer {
    bounds: Rect,
    taken: Vec<Rect>,
}

impl Placer {
    /// Nothing taken yet inside `bounds`.
    #[must_use]
    pub(crate) const fn new(bounds: Rect) -> Self {
        Self { bounds, taken: Vec::new() }
    }

    /// Keep `r` free of every box placed from now on.
    pub(crate) fn block(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// The first of `corners` (top-left corners) where a box of `size`
    /// lies inside the bounds and over nothing taken, taken from then on;
    /// `None` when every one is taken.
    pub(crate) fn place(&mut self, size: (i32, i32), corners: impl IntoIterator<Item = (i32, i32)>) -> Option<Rect> {
        let free = corners
            .into_iter()
            .map(|c| Rect::at(c, size))
            .find(|r| r.within(&self.bounds) && !self.taken.iter().any(|t| t.overlaps(r)))?;
        self.taken.push(free);
        Some(free)
    }
}

/// Top-left corners for a box of `size` around the point `at`: `gap`
/// pixels from it to the right, left, above, below and at the four
/// corners, then the same ever `step` pixels farther out, `rings` times.
#[must_use]
pub(crate) fn around((x, y): (i32, i32), (w, h): (i32, i32), gap: i32, step: i32, rings: i32) -> Vec<(i32, i32)> {
    let mut out = Vec::new();
    for ring in 0..=rings {
        let d = gap + ring * step;
        out.extend([
            (x + d, y - h / 2),
            (x - d - w, y - h / 2),
            (x - w / 2, y - d - h),
            (x - w / 2, y + d),
            (x + d, y - d - h),
            (x + d, y + d),
            (x - d - w, y - d - h),
            (x - d - w, y + d),
        ]);
    }
    out
}

/// Top-left corners for a box of `size` to the right of the point `at`,
/// `gap` pixels from it: centred on its row first, then `step` pixels
/// lower and higher in turn, out to `reach` pixels either way.
#[must_use]
pub(crate) fn beside((x, y): (i32, i32), (_, h): (i32, i32), gap: i32, step: i32, reach: i32) -> Vec<(i32, i32)> {
    let top = y - h / 2;
    let mut out = vec![(x + gap, top)];
    let mut d = step.max(1);
    while d <= reach {
        out.extend([(x + gap, top + d), (x + gap, top - d)]);
        d += step.max(1);
    }
    out
}

/// Draw `text` in `font` inside the room `placed` (from [`label_size`],
/// in `area`'s pixels), over a veil of white that keeps it
/// legible across lines, and, when the box lies farther than `near`
/// pixels from the point `of` it labels, a thin line from the point to
/// the box in `leader`'s colour.
///
/// # Errors
/// Drawing failed.
pub(crate) fn draw_placed<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    font: &TextStyle<'_>,
    placed: Rect,
    (of, near): ((i32, i32), i32),
    leader: RGBAColor,
) -> Result<(), String> {
    let (nx, ny) = placed.nearest(of);
    let (dx, dy) = (nx - of.0, ny - of.1);
    let far = f64::from(dx).hypot(f64::from(dy));
    if far > f64::from(near) {
        // From just outside the point's marker to the box.
        #[allow(clippy::cast_possible_truncation, reason = "pixels on a small plot")]
        let from = (of.0 + (f64::from(dx) * 6.0 / far) as i32, of.1 + (f64::from(dy) * 6.0 / far) as i32);
        area.draw(&PathElement::new(vec![from, (nx, ny)], leader.stroke_width(1))).map_err(|e| e.to_string())?;
    }
    let veil = Rectangle::new([(placed.x0, placed.y0), (placed.x1 - 1, placed.y1 - 1)], WHITE.mix(0.8).filled());
    area.draw(&veil).map_err(|e| e.to_string())?;
    let font = font.pos(Pos::new(HPos::Left, VPos::Top));
    area.draw(&Text::new(text.to_owned(), (placed.x0 + 1, placed.y0 + 1), font)).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::{Placer, Rect, around, beside};

    /// A box goes to the first free place: past what is blocked and what
    /// was placed before it, never out of bounds; with no place left,
    /// nowhere.
    #[test]
    fn a_box_goes_where_nothing_is() {
        let mut p = Placer::new(Rect::at((0, 0), (100, 100)));
        p.block(Rect::around((50, 50), 5));
        let size = (20, 10);
        let first = p.place(size, around((50, 50), size, 8, 8, 3)).expect("room");
        assert_eq!(first, Rect::at((58, 45), size), "right of the point, clear of its marker");
        let second = p.place(size, around((50, 50), size, 8, 8, 3)).expect("room");
        assert!(!second.overlaps(&first) && !second.overlaps(&Rect::around((50, 50), 5)), "{second:?}");
        // Against the right edge: the right is out of bounds, the left free.
        let edge = p.place(size, around((95, 20), size, 3, 8, 0)).expect("room");
        assert!(edge.x1 <= 100 && edge.x0 < 95, "{edge:?}");
        let mut full = Placer::new(Rect::at((0, 0), (10, 10)));
        assert_eq!(full.place(size, beside((0, 5), size, 2, 4, 20)), None);
        // Touching is not overlapping.
        assert!(!Rect::at((0, 0), (10, 10)).overlaps(&Rect::at((10, 0), (10, 10))));
    }
}
