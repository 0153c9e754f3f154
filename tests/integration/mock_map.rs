//! A mock map in the style of embedded-graphics' `MockDisplay`: what a unit
//! drew, as rows of ASCII a person can read, compared with the expected
//! picture. A texel drawn once is `#`, one never drawn is `.`, and one drawn
//! `n` times (overdraw) is the digit `n` (`+` beyond 9), so a picture of
//! `#`s fails on overdraw.

use std::fmt::Write as _;

use umbra::core::{Fragment, Probe};

/// Times each texel of a `width × height` map was drawn.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MockMap {
    width: u32,
    height: u32,
    counts: Vec<u32>,
}

impl MockMap {
    /// A map nothing has drawn on.
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, counts: vec![0; (width * height) as usize] }
    }

    /// The map of `texels` drawn once each, in any order.
    pub fn of(width: u32, height: u32, texels: impl IntoIterator<Item = (u32, u32)>) -> Self {
        let mut m = Self::new(width, height);
        texels.into_iter().for_each(|(x, y)| m.draw(x, y));
        m
    }

    /// Draw texel `(x, y)` once more; a texel off the map is a failure.
    pub fn draw(&mut self, x: u32, y: u32) {
        assert!(x < self.width && y < self.height, "({x}, {y}) is off the {}×{} map", self.width, self.height);
        self.counts[(y * self.width + x) as usize] += 1;
    }

    /// The map as rows of ASCII.
    pub fn rows(&self) -> Vec<String> {
        self.counts
            .chunks(self.width as usize)
            .map(|row| {
                row.iter()
                    .map(|&n| match n {
                        0 => '.',
                        1 => '#',
                        2..=9 => char::from_digit(n, 10).unwrap_or('+'),
                        _ => '+',
                    })
                    .collect()
            })
            .collect()
    }

    /// Fail, showing both pictures, unless the map is exactly `expected`
    /// (one row per string, `#` drawn once, `.` not drawn, digits for
    /// overdraw).
    #[track_caller]
    pub fn assert_pattern(&self, expected: &[&str]) {
        let got = self.rows();
        if got.iter().map(String::as_str).eq(expected.iter().copied()) {
            return;
        }
        let mut msg = String::from("the map differs from the expected picture\n  got        expected\n");
        for k in 0..got.len().max(expected.len()) {
            let g = got.get(k).map_or("", String::as_str);
            let e = expected.get(k).copied().unwrap_or("");
            let mark = if g == e { ' ' } else { '<' };
            let _ = writeln!(msg, "  {g:<w$} {e} {mark}", w = self.width as usize);
        }
        panic!("{msg}");
    }
}

/// The mock map as a probe: every fragment a pass reports is drawn.
impl Probe for MockMap {
    const FRAGMENTS: bool = true;

    fn fragment(&mut self, f: Fragment) {
        self.draw(f.x, f.y);
    }
}

/// The picture itself is checked: a texel drawn twice shows as `2`, so an
/// all-`#` picture fails; one never drawn as `.`.
#[test]
fn the_mock_map_fails_on_overdraw_and_on_gaps() {
    let m = MockMap::of(3, 2, [(0, 0), (1, 0), (1, 0), (2, 1)]);
    assert_eq!(m.rows(), ["#2.", "..#"]);
    m.assert_pattern(&["#2.", "..#"]);
    let overdraw = std::panic::catch_unwind(|| m.assert_pattern(&["##.", "..#"]));
    assert!(overdraw.is_err(), "overdraw must fail an all-# picture");
    let gap = std::panic::catch_unwind(|| MockMap::of(2, 1, [(0, 0)]).assert_pattern(&["##"]));
    assert!(gap.is_err(), "a texel not drawn must fail");
}
