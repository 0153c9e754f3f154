//! The units an architecture file's values are written in (`16KiB`,
//! `25.6GB/s`, `800MHz`, `2ns`, `20pJ`, `0.021um2`, `10mW/mm2`): each
//! one's suffixes, how a value is read and written back to the same
//! bits, and its SI name for columns.

/// Text that is not a value of its unit: the text, and what the unit
/// expects.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{value}` is not {unit}")]
pub struct NotInUnit {
    /// The text.
    pub value: String,
    /// What was expected.
    pub unit: &'static str,
}

/// The unit a key's value is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Free text.
    Text,
    /// `true` or `false`.
    Flag,
    /// A whole number.
    Count,
    /// A non-negative number (cycles, rates).
    Number,
    /// Bytes: `B`, `KB`, `KiB`, `MB`, `MiB`, `GB`, `GiB`, `TB`, `TiB`.
    Bytes,
    /// Bytes per second: `GB/s`, `MB/s`, `GiB/s`, ...
    Bandwidth,
    /// Hertz: `Hz`, `kHz`, `MHz`, `GHz`.
    Frequency,
    /// Seconds: `s`, `ms`, `us`, `ns`, `ps`.
    Time,
    /// Joules: `J`, `mJ`, `uJ`, `nJ`, `pJ`, `fJ`.
    Joules,
    /// Square metres: `mm2`, `um2` (or `mm²`, `µm²`).
    Area,
    /// Watts per square metre: `W/mm2`, `mW/mm2`, `uW/mm2`.
    PowerDensity,
}

impl Unit {
    /// The SI base unit a value is held in, as a column's name ends
    /// (`bytes`, `bytes_per_second`, `hertz`, `seconds`, `joules`); empty
    /// for counts, numbers, flags and text.
    #[must_use]
    pub(crate) const fn si_name(self) -> &'static str {
        match self {
            Self::Text | Self::Flag | Self::Count | Self::Number => "",
            Self::Bytes => "bytes",
            Self::Bandwidth => "bytes_per_second",
            Self::Frequency => "hertz",
            Self::Time => "seconds",
            Self::Joules => "joules",
            Self::Area => "square_metres",
            Self::PowerDensity => "watts_per_square_metre",
        }
    }

    /// The symbol of the SI base unit a value is held in (`B`, `B/s`,
    /// `Hz`, `s`, `J`); `-` for counts, numbers, flags and text.
    #[must_use]
    pub(crate) const fn symbol(self) -> &'static str {
        match self {
            Self::Text | Self::Flag | Self::Count | Self::Number => "-",
            Self::Bytes => "B",
            Self::Bandwidth => "B/s",
            Self::Frequency => "Hz",
            Self::Time => "s",
            Self::Joules => "J",
            Self::Area => "m²",
            Self::PowerDensity => "W/m²",
        }
    }
}

impl Unit {
    /// What a value of this unit looks like, for errors.
    pub(super) const fn expected(self) -> &'static str {
        match self {
            Self::Text => "text",
            Self::Flag => "true or false",
            Self::Count => "a whole number",
            Self::Number => "a number",
            Self::Bytes => "a size such as 64B, 16KiB, 2MB or 1TiB",
            Self::Bandwidth => "a bandwidth such as 25.6GB/s",
            Self::Frequency => "a frequency such as 800MHz",
            Self::Time => "a time such as 2ns",
            Self::Joules => "an energy such as 20pJ",
            Self::Area => "an area such as 0.021um2 or 2mm2",
            Self::PowerDensity => "a power per area such as 20mW/mm2",
        }
    }

    /// The suffixes of this unit and their scale, the preferred one for
    /// writing first.
    const fn suffixes(self) -> &'static [(&'static str, f64)] {
        match self {
            Self::Bytes => &[
                ("TiB", 1_099_511_627_776.0),
                ("GiB", 1_073_741_824.0),
                ("MiB", 1_048_576.0),
                ("KiB", 1024.0),
                ("TB", 1e12),
                ("GB", 1e9),
                ("MB", 1e6),
                ("KB", 1e3),
                ("kB", 1e3),
                ("B", 1.0),
            ],
            Self::Bandwidth => &[
                ("TB/s", 1e12),
                ("GB/s", 1e9),
                ("MB/s", 1e6),
                ("KB/s", 1e3),
                ("kB/s", 1e3),
                ("GiB/s", 1_073_741_824.0),
                ("MiB/s", 1_048_576.0),
                ("B/s", 1.0),
            ],
            Self::Frequency => &[("GHz", 1e9), ("MHz", 1e6), ("kHz", 1e3), ("Hz", 1.0)],
            Self::Time => &[("ns", 1e-9), ("us", 1e-6), ("µs", 1e-6), ("ms", 1e-3), ("ps", 1e-12), ("s", 1.0)],
            Self::Joules => &[("pJ", 1e-12), ("nJ", 1e-9), ("fJ", 1e-15), ("uJ", 1e-6), ("mJ", 1e-3), ("J", 1.0)],
            Self::Area => &[("mm2", 1e-6), ("um2", 1e-12), ("mm²", 1e-6), ("µm²", 1e-12), ("m2", 1.0)],
            // A longer suffix before the one it ends with.
            Self::PowerDensity => &[
                ("mW/mm2", 1e3),
                ("uW/mm2", 1.0),
                ("mW/mm²", 1e3),
                ("µW/mm²", 1.0),
                ("W/mm2", 1e6),
                ("W/mm²", 1e6),
                ("W/m2", 1.0),
            ],
            Self::Text | Self::Flag | Self::Count | Self::Number => &[],
        }
    }

    /// The smallest scaled number a value is written with before a
    /// smaller suffix is tried: areas read best in the unit of the
    /// figure (`0.021um2`, `0.25mm2`).
    fn smallest(self) -> f64 {
        if self == Self::Area { 1e-3 } else { 1.0 }
    }

    /// Read `text` (a number and a suffix) in this unit, to its base: the
    /// one reader of sizes, rates, frequencies, times and energies, for
    /// architecture files and command-line flags alike.
    ///
    /// # Errors
    /// [`NotInUnit`] naming the text and what the unit expects.
    pub fn parse(self, text: &str) -> Result<f64, NotInUnit> {
        let bad = || NotInUnit { value: text.to_owned(), unit: self.expected() };
        let t = text.trim();
        let (number, scale) = self
            .suffixes()
            .iter()
            .find_map(|&(s, scale)| t.strip_suffix(s).map(|n| (n.trim(), scale)))
            .ok_or_else(bad)?;
        let x: f64 = number.parse().map_err(|_| bad())?;
        let v = x * scale;
        if v.is_finite() { Ok(v) } else { Err(bad()) }
    }

    /// Show a figure worked out from a file's values (`v`, in the base) as a
    /// person writes it: in each suffix it reaches (at least the unit's
    /// smallest, 1 or 0.001), rounded to 12 significant digits so that
    /// the float noise of its arithmetic goes, and of those the shortest
    /// (`760GB/s`, not `759.9999999999999GB/s`; `10KB`, not `9.765625KiB`).
    ///
    /// ```
    /// use umbra_sim::cost::arch::Unit;
    /// assert_eq!(Unit::Bandwidth.show(760e9 * (1.0 - 1e-16)), "760GB/s");
    /// assert_eq!(Unit::Time.show(225.0 * 1e-9), "225ns");
    /// assert_eq!(Unit::Bytes.show(10_000.0), "10KB");
    /// assert_eq!(Unit::Bytes.show(65_536.0), "64KiB");
    /// ```
    #[must_use]
    pub fn show(self, v: f64) -> String {
        let round = |x: f64| format!("{x:.11e}").parse().unwrap_or(x);
        self.suffixes()
            .iter()
            .map(|&(s, scale)| (round(v / scale), s))
            .filter(|&(x, _)| x.abs() >= self.smallest())
            .map(|(x, s)| format!("{x}{s}"))
            .min_by_key(String::len)
            .unwrap_or_else(|| self.write(v))
    }

    /// Write `v` (in the base) with the largest suffix that reads back to
    /// the same bits.
    #[must_use]
    pub(crate) fn write(self, v: f64) -> String {
        for &(s, scale) in self.suffixes() {
            let scaled = v / scale;
            let text = format!("{scaled}{s}");
            if scaled.abs() >= self.smallest() && self.parse(&text).is_ok_and(|back| back.to_bits() == v.to_bits()) {
                return text;
            }
        }
        let base = self.suffixes().last().map_or("", |s| s.0);
        if v != 0.0 && !(1e-3..1e15).contains(&v.abs()) { format!("{v:e}{base}") } else { format!("{v}{base}") }
    }
}
