//! The legend beside a plot: entries (a swatch and its label), headings
//! over the entries they group, and keys (a short code and what it
//! stands for, in two columns), with the plot's footnote below. It takes
//! at most a third of the image's width: laid out in the largest font
//! that fits above the footnote, in one column or two, every line wrapped
//! to its column as the font measures it; what fits in none is counted
//! on a last line, never drawn over something else.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::experiment::plot::place::text_size;
use crate::experiment::plot::{SIZE, footnote};

/// Draws a legend entry's swatch centred at a point of the legend's area.
pub(super) type Swatch<'a, DB> = dyn Fn(&DrawingArea<DB, Shift>, (i32, i32)) -> Result<(), String> + 'a;

/// One thing a legend lists.
pub(super) enum Item<'a, DB: DrawingBackend> {
    /// A swatch and its label.
    Entry(String, Box<Swatch<'a, DB>>),
    /// A line of text over the entries it groups.
    Heading(String),
    /// A short code and what it stands for (`LAT`, `DRAM latency`).
    Key(String, String),
}

impl<'a, DB: DrawingBackend> Item<'a, DB> {
    /// An entry of `label` drawn with `swatch`.
    pub(super) fn entry(
        label: impl Into<String>,
        swatch: impl Fn(&DrawingArea<DB, Shift>, (i32, i32)) -> Result<(), String> + 'a,
    ) -> Self {
        Self::Entry(label.into(), Box::new(swatch))
    }
}

/// The widest a legend is, pixels: under a third of the image.
#[allow(clippy::cast_possible_wrap, reason = "a small image")]
const MAX_WIDTH: i32 = SIZE.0 as i32 / 3 - 10;
/// The legend's first line, pixels from the top of its area.
const TOP: i32 = 30;
/// The legend's last line ends this far above the image's bottom, where
/// the footnote begins.
const FOOT: i32 = 70;
/// Where an entry's label begins, right of its swatch.
const INDENT: i32 = 28;
/// The font sizes tried, largest first.
const FONT_SIZES: [i32; 6] = [13, 12, 11, 10, 9, 8];

/// Where everything goes.
struct Layout {
    font: i32,
    columns: i32,
    width: i32,
    /// The width of a key's code column.
    codes: i32,
    /// Each item's lines, wrapped to its column.
    lines: Vec<Vec<String>>,
    /// How many items are drawn; the rest are counted on a last line.
    shown: usize,
}

impl Layout {
    /// Pixels from one line to the next.
    const fn step(&self) -> i32 {
        self.font + 4
    }

    /// The lines a column holds.
    const fn rows(&self) -> i32 {
        (SIZE.1.cast_signed() - TOP - FOOT) / self.step()
    }

    /// Where `item`'s text begins in its column.
    const fn indent<DB: DrawingBackend>(&self, item: &Item<'_, DB>) -> i32 {
        match item {
            Item::Entry(..) => INDENT,
            Item::Heading(_) => 2,
            Item::Key(..) => 4 + self.codes,
        }
    }
}

/// A legend laid out, ready to split its area from the chart's and draw.
pub(super) struct Legend<'a, DB: DrawingBackend> {
    items: Vec<Item<'a, DB>>,
    foot: Vec<String>,
    layout: Layout,
}

/// `text` cut after each of the characters `at`, every piece kept.
fn pieces(text: &str, at: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    for c in text.chars() {
        if let Some(p) = out.last_mut() {
            p.push(c);
        }
        if at.contains(c) {
            out.push(String::new());
        }
    }
    out.retain(|p| !p.is_empty());
    out
}

/// `text` in lines that `measure` finds at most `width` wide: broken
/// between words where it can be, a word too long for a line after its
/// punctuation (`,:=;._-/`), else within it.
fn wrap(text: &str, width: i32, measure: &dyn Fn(&str) -> i32) -> Vec<String> {
    let fits = |s: &str| measure(s.trim_end()) <= width;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in pieces(text, " ") {
        // A word too long for a line alone comes in its pieces, the
        // pieces too long in characters.
        let parts = if fits(&word) { vec![word] } else { pieces(&word, ",:=;._-/") };
        let parts =
            parts.into_iter().flat_map(|p| if fits(&p) { vec![p] } else { p.chars().map(String::from).collect() });
        for part in parts {
            if !line.is_empty() && !fits(&format!("{line}{part}")) {
                lines.push(line.trim_end().to_owned());
                line.clear();
            }
            line.push_str(&part);
        }
    }
    if !line.trim().is_empty() || lines.is_empty() {
        lines.push(line.trim_end().to_owned());
    }
    lines
}

impl<'a, DB: DrawingBackend> Legend<'a, DB> {
    /// `items` laid out above the footnote `foot`, measured on `area`
    /// (any area of the image's backend): in one column in the largest
    /// font that fits from 13 down to 9 pixels, else in two columns down
    /// to 8, else as many as fit and a count of the rest.
    ///
    /// # Errors
    /// A text cannot be measured.
    pub(super) fn new(
        area: &DrawingArea<DB, Shift>,
        items: Vec<Item<'a, DB>>,
        foot: &[String],
    ) -> Result<Self, String> {
        let tries = FONT_SIZES[..5].iter().map(|&f| (f, 1)).chain(FONT_SIZES[1..].iter().map(|&f| (f, 2)));
        let mut last = None;
        for (font, columns) in tries {
            let layout = Self::lay_out(area, &items, foot, font, columns)?;
            if layout.shown == items.len() {
                return Ok(Self { items, foot: foot.to_vec(), layout });
            }
            last = Some(layout);
        }
        let layout = last.ok_or("no layout")?;
        Ok(Self { items, foot: foot.to_vec(), layout })
    }

    /// Whether every item fits, in a font of at least `font` pixels.
    pub(super) fn fits(&self, font: i32) -> bool {
        self.layout.shown == self.items.len() && self.layout.font >= font
    }

    /// `items` in `columns` in a font of `font` pixels.
    fn lay_out(
        area: &DrawingArea<DB, Shift>,
        items: &[Item<'a, DB>],
        foot: &[String],
        font: i32,
        columns: i32,
    ) -> Result<Layout, String> {
        let style = TextStyle::from(("sans-serif", font));
        let measure = |s: &str| text_size(area, s, &style).map_or(i32::MAX, |m| m.0);
        let note = TextStyle::from(("sans-serif", 11));
        let mut foot_width = 0;
        for l in foot {
            foot_width = foot_width.max(text_size(area, l, &note)?.0 + 12);
        }
        let codes = items.iter().map(|i| if let Item::Key(k, _) = i { measure(k) + 10 } else { 0 }).max().unwrap_or(0);
        let mut layout = Layout { font, columns, width: MAX_WIDTH, codes, lines: Vec::new(), shown: 0 };
        let text = |i: &'_ Item<'a, DB>| match i {
            Item::Entry(l, _) | Item::Heading(l) | Item::Key(_, l) => l.clone(),
        };
        if columns == 1 {
            let natural = items.iter().map(|i| layout.indent(i) + measure(&text(i)) + 4).max().unwrap_or(0);
            layout.width = natural.max(foot_width).min(MAX_WIDTH);
        }
        let column = layout.width / columns;
        layout.lines = items.iter().map(|i| wrap(&text(i), column - layout.indent(i) - 4, &measure)).collect();
        let rows = layout.rows();
        let (mut col, mut used) = (1, 0);
        for (k, l) in layout.lines.iter().enumerate() {
            let n = i32::try_from(l.len()).unwrap_or(i32::MAX);
            if used + n > rows && used > 0 {
                (col, used) = (col + 1, 0);
            }
            // The last column keeps a line for the count of what is left.
            let spare = i32::from(col == columns && k + 1 < items.len());
            if col > columns || used + n + spare > rows {
                break;
            }
            used += n;
            layout.shown = k + 1;
        }
        Ok(layout)
    }

    /// How wide the legend is, pixels.
    pub(super) fn width(&self) -> u32 {
        self.layout.width.unsigned_abs()
    }

    /// `area` split into the chart's area and, at its right, the legend's.
    pub(super) fn split(&self, area: &DrawingArea<DB, Shift>) -> (DrawingArea<DB, Shift>, DrawingArea<DB, Shift>) {
        area.split_horizontally(SIZE.0 - self.width())
    }

    /// Draw the legend and its footnote on `area` (from [`Legend::split`]).
    ///
    /// # Errors
    /// Drawing failed.
    pub(super) fn draw(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let l = &self.layout;
        let (step, column, rows) = (l.step(), l.width / l.columns, l.rows());
        let style = TextStyle::from(("sans-serif", l.font)).color(&BLACK);
        let text = |s: &str, at: (i32, i32)| area.draw(&Text::new(s.to_owned(), at, &style)).map_err(|e| e.to_string());
        let (mut x, mut y) = (0, TOP);
        for (item, lines) in self.items.iter().zip(&l.lines).take(l.shown) {
            let n = i32::try_from(lines.len()).unwrap_or(i32::MAX);
            if y + n * step > TOP + rows * step && y > TOP {
                (x, y) = (x + column, TOP);
            }
            match item {
                Item::Entry(_, swatch) => swatch(area, (x + 14, y + step / 2 - 2))?,
                Item::Key(code, _) => text(code, (x + 4, y))?,
                Item::Heading(_) => {}
            }
            for line in lines {
                text(line, (x + l.indent(item), y))?;
                y += step;
            }
        }
        if l.shown < self.items.len() {
            if y + step > TOP + rows * step {
                (x, y) = (x + column, TOP);
            }
            text(&format!("… and {} more", self.items.len() - l.shown), (x + 2, y))?;
        }
        footnote(area, &self.foot)
    }
}

#[cfg(test)]
mod tests {
    use plotters::coord::Shift;
    use plotters::prelude::*;

    use super::{Item, Legend, wrap};
    use crate::experiment::plot::record::{self, assert_legible};
    use crate::experiment::plot::{Figure, SIZE};

    /// A legend of `0` entries with long names, alone on the image.
    struct Many(usize);

    impl Figure for Many {
        fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
            let items = (0..self.0)
                .map(|k| {
                    let label = format!("base-architecture-{k}: dram.bandwidth=25.6GB/s, map_cache.size=16KiB");
                    Item::entry(label, |l: &DrawingArea<DB, Shift>, c| {
                        l.draw(&Circle::new(c, 5, BLACK.filled())).map_err(|e| e.to_string())
                    })
                })
                .collect();
            let legend = Legend::new(area, items, &["umbra 0.1.0 (git 06d3658c59fa)".to_owned()])?;
            let (_, right) = legend.split(area);
            legend.draw(&right)
        }
    }

    /// However many entries, the legend keeps within the image's right
    /// third, its texts apart and above the footnote: in a smaller font,
    /// in two columns, and past what fits, a count of the rest.
    #[test]
    fn a_legend_keeps_to_a_third_of_the_image() {
        crate::output::formats::font().expect("the bundled font");
        for n in [3, 12, 30, 400] {
            let _ = record::take();
            record::keep("legend", &Many(n)).expect("drawn");
            let (_, drawn) = record::take().remove(0);
            assert_legible(&format!("{n} entries"), &drawn);
            let third = (SIZE.0 - SIZE.0 / 3).cast_signed();
            for t in &drawn.texts {
                assert!(t.rect.x0 >= third, "{n} entries: `{}` at {:?} left of the right third", t.text, t.rect);
            }
            // Every entry while they fit, else a count of the rest.
            let more = drawn.texts.iter().any(|t| t.text.starts_with("… and "));
            let all =
                (0..n).all(|k| drawn.texts.iter().any(|t| t.text.starts_with(&format!("base-architecture-{k}:"))));
            assert!(more != all, "{n} entries");
            assert!(all || n > 12, "{n} entries");
        }
    }

    /// Lines break between words within the width, a word too long for a
    /// line after its punctuation, else within it; every character is
    /// kept.
    #[test]
    fn labels_wrap_to_their_column() {
        // One pixel a character.
        let measure = |s: &str| i32::try_from(s.chars().count()).unwrap_or(i32::MAX);
        assert_eq!(wrap("talisman, first depth", 12, &measure), ["talisman,", "first depth"]);
        assert_eq!(wrap("map_cache.size=16KiB", 15, &measure), ["map_cache.size=", "16KiB"]);
        assert_eq!(wrap("a=1GB/s, m.s=16KiB", 12, &measure), ["a=1GB/s,", "m.s=16KiB"]);
        assert_eq!(wrap("abcdefghij", 4, &measure), ["abcd", "efgh", "ij"]);
        assert_eq!(wrap("short", 40, &measure), ["short"]);
    }
}
