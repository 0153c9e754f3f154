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
}

impl fmt::Display for UnknownName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "not a {} (", self.what)?;
        for (k, n) in self.names.iter().enumerate() {
            write!(f, "{}{n}", if k == 0 { "" } else { ", " })?;
        }
        f.write_str(")")
    }
}

impl core::error::Error for UnknownName {}

/// The name table of an enum of choices without data: `spelled!(Type,
/// "what it is", { Variant => "name", … })` writes `Type::ALL`, `Type::NAMES`,
/// `Type::name`, `Display` and `FromStr` (its error an [`UnknownName`]).
///
/// ```
/// #[derive(Clone, Copy, Debug, PartialEq)]
/// enum Side { Left, Right }
/// umbra_core::spelled!(Side, "side", { Left => "left", Right => "right" });
/// assert_eq!(Side::Left.to_string(), "left");
/// assert_eq!("right".parse(), Ok(Side::Right));
/// assert_eq!("up".parse::<Side>().unwrap_err().to_string(), "not a side (left, right)");
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
                match s {
                    $($s => Ok(Self::$v),)+
                    _ => Err($crate::spelling::UnknownName { what: $what, names: Self::NAMES }),
                }
            }
        }
    };
}
