//! One spelling per choice: [`spelled!`](crate::spelled) gives an enum of
//! choices its one name table — `name()`, the `Display` that writes it and
//! the `FromStr` that reads it back — so the command line, files and
//! records all spell a choice the same way.

use core::fmt;

/// Text that names none of a choice's values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownName {
    /// What was being named (`depth format`, `cull mode`, …).
    pub what: &'static str,
    /// Every spelling it takes.
    pub names: &'static [&'static str],
    /// The spelling the text was nearly, a slip of a letter or two
    /// ([`closest`]).
    pub near: Option<&'static str>,
}

impl fmt::Display for UnknownName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "not a {}", self.what)?;
        if let Some(near) = self.near {
            write!(f, ": did you mean `{near}`?")?;
        }
        f.write_str(" (")?;
        for (k, n) in self.names.iter().enumerate() {
            write!(f, "{}{n}", if k == 0 { "" } else { ", " })?;
        }
        f.write_str(")")
    }
}

impl core::error::Error for UnknownName {}

/// The one of `names` that `word` is a slip of, if any: the nearest by
/// edits (a letter inserted, dropped or changed; ASCII case aside), when
/// it is at most one edit away for a word of up to four letters, two up
/// to eight, three beyond. Ties go to the first.
///
/// ```
/// use umbra_core::spelling::closest;
/// let names = ["table-and-sphere", "reeves-sphere"];
/// assert_eq!(closest("tabel-and-sphere", names), Some("table-and-sphere"));
/// assert_eq!(closest("teapot", names), None);
/// ```
#[must_use]
pub fn closest<'n>(word: &str, names: impl IntoIterator<Item = &'n str>) -> Option<&'n str> {
    let limit = match word.chars().count() {
        0..=4 => 1,
        5..=8 => 2,
        _ => 3,
    };
    names.into_iter().map(|n| (edits(word, n), n)).filter(|&(d, _)| d <= limit).min_by_key(|&(d, _)| d).map(|(_, n)| n)
}

/// The edits between `a` and `b` (Levenshtein, by chars, ASCII case
/// aside); words longer than 64 chars are never near.
fn edits(a: &str, b: &str) -> usize {
    const LONGEST: usize = 64;
    let nb = b.chars().count();
    if a.chars().count() > LONGEST || nb > LONGEST {
        return usize::MAX;
    }
    let mut row = [0usize; LONGEST + 1];
    for (j, r) in row.iter_mut().enumerate() {
        *r = j;
    }
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.chars().enumerate() {
            let change = diagonal + usize::from(!ca.eq_ignore_ascii_case(&cb));
            diagonal = row[j + 1];
            row[j + 1] = change.min(row[j + 1] + 1).min(row[j] + 1);
        }
    }
    row[nb]
}

/// The name table of an enum of choices without data: `spelled!(Type,
/// "what it is", { Variant => "name", … })` writes `Type::ALL`, `Type::NAMES`,
/// `Type::name`, `Display` and `FromStr` (case aside; its error an
/// [`UnknownName`] that suggests the name the text was a slip of).
///
/// ```
/// #[derive(Clone, Copy, Debug, PartialEq)]
/// enum Side { Left, Right }
/// umbra_core::spelled!(Side, "side", { Left => "left", Right => "right" });
/// assert_eq!(Side::Left.to_string(), "left");
/// assert_eq!("right".parse(), Ok(Side::Right));
/// assert_eq!("Right".parse(), Ok(Side::Right)); // case aside
/// assert_eq!("up".parse::<Side>().unwrap_err().to_string(), "not a side (left, right)");
/// assert_eq!("rigth".parse::<Side>().unwrap_err().to_string(), "not a side: did you mean `right`? (left, right)");
/// ```
#[macro_export]
macro_rules! spelled {
    ($ty:ty, $what:literal, { $($v:ident => $s:literal),+ $(,)? }) => {
        impl $ty {
            /// Every value, in the table's order.
            pub const ALL: [Self; [$($s),+].len()] = [$(Self::$v),+];

            /// Every spelling, in the table's order.
            pub const NAMES: &'static [&'static str] = &[$($s),+];

            /// Its one spelling: its `Display`, and the only text its
            /// `FromStr` takes.
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self {
                    $(Self::$v => $s),+
                }
            }
        }

        impl ::core::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl ::core::str::FromStr for $ty {
            type Err = $crate::spelling::UnknownName;

            fn from_str(s: &str) -> ::core::result::Result<Self, Self::Err> {
                // Case aside: the help writes a name at a sentence's start.
                $(if s.eq_ignore_ascii_case($s) {
                    return Ok(Self::$v);
                })+
                let near = $crate::spelling::closest(s, Self::NAMES.iter().copied());
                Err($crate::spelling::UnknownName { what: $what, names: Self::NAMES, near })
            }
        }
    };
}
