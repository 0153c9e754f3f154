//! Architecture files: the machine a render is costed on, as TOML a user
//! can write, bundled presets, `--set key=value` overrides with units, and
//! the effective architecture written back (as gem5's `config.ini` is).
//!
//! One table, [`PARAMS`], lists every key with its unit and meaning; it
//! drives parsing, overrides, validation and the written record alike, so
//! a key cannot be read without being recorded.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

/// The bundled architecture files (presets), by name.
pub const BUNDLED: [(&str, &str); 6] = [
    ("pixelflow", include_str!("../../../../arch/pixelflow.toml")),
    ("talisman", include_str!("../../../../arch/talisman.toml")),
    ("immediate", include_str!("../../../../arch/immediate.toml")),
    ("mobile-tbdr", include_str!("../../../../arch/mobile-tbdr.toml")),
    ("desktop-imr", include_str!("../../../../arch/desktop-imr.toml")),
    ("r300", include_str!("../../../../arch/r300.toml")),
];

/// The front end: setup and binning.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Front {
    /// Cycles per triangle set up (the setup engine's issue interval).
    pub setup_cycles: f64,
    /// Setup and binning run concurrently with the tiles (a frame ahead on
    /// a tiler, pipelined on an immediate-mode machine).
    pub overlap: bool,
    /// Fixed cycles per pass spent waiting for the host.
    pub pass_overhead_cycles: f64,
}

/// Scan conversion.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Raster {
    /// Side of the tile (chunk, region) in pixels.
    pub tile: u32,
    /// Fragments scan-converted per clock (0: an evaluator instead).
    pub fragments_per_clock: f64,
    /// PixelFlow's linear-expression evaluator: cycles per triangle per
    /// tile it touches, whatever its fragment count.
    pub cycles_per_tile: f64,
}

/// The depth unit.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DepthRates {
    /// Fragments depth-tested per clock, per buffer (0: bit-serial).
    pub fragments_per_clock: f64,
    /// Bit-serial processors: cycles per depth bit per buffer per triangle
    /// per tile.
    pub cycles_per_bit: f64,
    /// The second depth takes a second light pass and a pass combining the
    /// two maps (a machine with one depth buffer per fragment), instead of
    /// a second buffer updated per fragment.
    pub second_depth_pass: bool,
}

/// Which buffers live on chip.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct OnChip {
    /// The light pass's depth buffers (else read-modify-written in DRAM per
    /// fragment).
    pub light_depth: bool,
    /// The camera pass's visibility depth and ids.
    pub camera_depth: bool,
    /// The stencil and the scene depth shadow-volume fragments test.
    pub stencil: bool,
    /// The resolve writes only the value the shadow test reads.
    pub resolve_test_value_only: bool,
}

/// Bins in memory (tilers).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Bins {
    /// Bytes of one bin entry.
    pub entry_bytes: u64,
    /// Bytes of one triangle's setup record, written at binning and read at
    /// each flush of a tile it is binned to.
    pub setup_record_bytes: u64,
}

/// The shadow unit.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ShadowRates {
    /// Map samples compared per clock.
    pub samples_per_clock: f64,
    /// Latency of one division (a tangent-plane setup), not pipelined.
    pub divider_cycles: f64,
    /// Dividers working in parallel.
    pub dividers: u64,
    /// Cycles per pixel looked up besides the samples: a programmable
    /// shadow test's own instructions (0 for fixed function).
    pub cycles_per_lookup: f64,
    /// The shadow test runs in the shading program on the same units: its
    /// cycles add to the shading's instead of overlapping them.
    pub in_shader: bool,
}

/// The shading work besides the shadow lookup.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Shade {
    /// Cycles per shaded pixel (throughput, whole chip; 0 for fixed function).
    pub cycles_per_pixel: f64,
}

/// DRAM.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DramParams {
    /// Bytes per second.
    pub bandwidth: f64,
    /// Seconds from request to data.
    pub latency: f64,
    /// Bytes of one access.
    pub burst: u64,
    /// Requests the memory system keeps in flight.
    pub requests_in_flight: u64,
}

/// A cache (size 0: none).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct CacheParams {
    /// Bytes.
    pub size: u64,
    /// Bytes of a line.
    pub line: u64,
    /// Associativity.
    pub ways: u64,
    /// Misses outstanding at once.
    pub misses_in_flight: u64,
}

/// Energy per access, joules.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Energy {
    /// Per DRAM byte.
    pub dram_byte: f64,
    /// Per on-chip buffer access.
    pub buffer_access: f64,
    /// Per cache access.
    pub cache_access: f64,
    /// Per fragment operation (a fragment scan-converted and depth-tested,
    /// a sample compared).
    pub fragment_op: f64,
}

/// An architecture: every parameter of the machine a render is costed on.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Arch {
    /// Name for reports and file names.
    pub name: String,
    /// What it models.
    pub description: String,
    /// Clock, hertz.
    pub clock: f64,
    /// Setup and binning.
    pub front: Front,
    /// Scan conversion.
    pub raster: Raster,
    /// The depth unit.
    pub depth: DepthRates,
    /// Buffers on chip.
    pub on_chip: OnChip,
    /// Bins.
    pub bins: Bins,
    /// The shadow unit.
    pub shadow: ShadowRates,
    /// Shading besides the shadow lookup.
    pub shade: Shade,
    /// DRAM.
    pub dram: DramParams,
    /// The shadow unit's map cache.
    pub map_cache: CacheParams,
    /// The cache for off-chip depth, ids and stencil.
    pub depth_cache: CacheParams,
    /// Energy per access.
    pub energy: Energy,
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
    /// Bytes: `B`, `KB`, `KiB`, `MB`, `MiB`, `GB`, `GiB`.
    Bytes,
    /// Bytes per second: `GB/s`, `MB/s`, `GiB/s`, ...
    Bandwidth,
    /// Hertz: `Hz`, `kHz`, `MHz`, `GHz`.
    Frequency,
    /// Seconds: `s`, `ms`, `us`, `ns`, `ps`.
    Time,
    /// Joules: `J`, `mJ`, `uJ`, `nJ`, `pJ`, `fJ`.
    Joules,
}

/// A key's value, read or to be written.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// Text.
    Text(String),
    /// A flag.
    Flag(bool),
    /// A number in the unit's base (bytes, B/s, Hz, s, J).
    Number(f64),
}

/// One key of an architecture file.
pub struct Param {
    /// The dotted key.
    pub key: &'static str,
    /// Its unit.
    pub unit: Unit,
    /// What it means.
    pub doc: &'static str,
    get: fn(&Arch) -> Value,
    set: fn(&mut Arch, Value) -> Result<(), Problem>,
}

impl core::fmt::Debug for Param {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Param").field("key", &self.key).field("unit", &self.unit).finish_non_exhaustive()
    }
}

/// A field a [`Param`] reads and writes.
trait Field {
    fn get(&self) -> Value;
    fn set(&mut self, v: Value) -> Result<(), Problem>;
}

impl Field for String {
    fn get(&self) -> Value {
        Value::Text(self.clone())
    }
    fn set(&mut self, v: Value) -> Result<(), Problem> {
        match v {
            Value::Text(t) => {
                *self = t;
                Ok(())
            }
            _ => Err(Problem::Type("text")),
        }
    }
}

impl Field for bool {
    fn get(&self) -> Value {
        Value::Flag(*self)
    }
    fn set(&mut self, v: Value) -> Result<(), Problem> {
        match v {
            Value::Flag(b) => {
                *self = b;
                Ok(())
            }
            _ => Err(Problem::Type("true or false")),
        }
    }
}

impl Field for f64 {
    fn get(&self) -> Value {
        Value::Number(*self)
    }
    fn set(&mut self, v: Value) -> Result<(), Problem> {
        match v {
            Value::Number(x) if (0.0..1e30).contains(&x) => {
                *self = x;
                Ok(())
            }
            Value::Number(x) => Err(Problem::Range { value: x, what: "a finite, non-negative number below 1e30" }),
            _ => Err(Problem::Type("a number")),
        }
    }
}

impl Field for u64 {
    #[allow(clippy::cast_precision_loss, reason = "sizes below 2^53, checked on the way in")]
    fn get(&self) -> Value {
        Value::Number(*self as f64)
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "checked whole and in range")]
    fn set(&mut self, v: Value) -> Result<(), Problem> {
        match v {
            Value::Number(x) if x.fract() == 0.0 && (0.0..=9.0e15).contains(&x) => {
                *self = x as Self;
                Ok(())
            }
            Value::Number(x) => Err(Problem::Range { value: x, what: "a whole number from 0 to 9e15" }),
            _ => Err(Problem::Type("a whole number")),
        }
    }
}

impl Field for u32 {
    fn get(&self) -> Value {
        Value::Number(f64::from(*self))
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "checked whole and in range")]
    fn set(&mut self, v: Value) -> Result<(), Problem> {
        match v {
            Value::Number(x) if x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x) => {
                *self = x as Self;
                Ok(())
            }
            Value::Number(x) => Err(Problem::Range { value: x, what: "a whole number below 2^32" }),
            _ => Err(Problem::Type("a whole number")),
        }
    }
}

/// Declares [`PARAMS`] from one list: key, unit, field path, meaning.
macro_rules! params {
    ($($key:literal, $unit:ident, $($field:ident).+, $doc:literal;)+) => {
        /// Every key of an architecture file, in file order.
        pub const PARAMS: &[Param] = &[$(Param {
            key: $key,
            unit: Unit::$unit,
            doc: $doc,
            get: |a: &Arch| Field::get(&a.$($field).+),
            set: |a: &mut Arch, v: Value| Field::set(&mut a.$($field).+, v),
        }),+];
    };
}

params! {
    "name", Text, name, "name for reports and file names";
    "description", Text, description, "what the file models";
    "clock", Frequency, clock, "core clock";
    "front.setup_cycles", Number, front.setup_cycles, "cycles per triangle set up";
    "front.overlap", Flag, front.overlap, "setup and binning overlap the tiles";
    "front.pass_overhead_cycles", Number, front.pass_overhead_cycles, "fixed cycles per pass waiting for the host";
    "raster.tile", Count, raster.tile, "tile (chunk, region) side in pixels";
    "raster.fragments_per_clock", Number, raster.fragments_per_clock, "fragments scan-converted per clock (0: evaluator)";
    "raster.cycles_per_tile", Number, raster.cycles_per_tile, "evaluator cycles per triangle per tile touched";
    "depth.fragments_per_clock", Number, depth.fragments_per_clock, "fragments depth-tested per clock per buffer (0: bit-serial)";
    "depth.cycles_per_bit", Number, depth.cycles_per_bit, "bit-serial cycles per depth bit per buffer per triangle per tile";
    "depth.second_depth_pass", Flag, depth.second_depth_pass, "second depth by a second light pass and a combining pass";
    "on_chip.light_depth", Flag, on_chip.light_depth, "light-pass depth buffers on chip";
    "on_chip.camera_depth", Flag, on_chip.camera_depth, "camera visibility depth and ids on chip";
    "on_chip.stencil", Flag, on_chip.stencil, "stencil and volume-tested depth on chip";
    "on_chip.resolve_test_value_only", Flag, on_chip.resolve_test_value_only, "the resolve writes only the value the test reads";
    "bins.entry_bytes", Count, bins.entry_bytes, "bytes of one bin entry in DRAM";
    "bins.setup_record_bytes", Count, bins.setup_record_bytes, "bytes of one setup record in DRAM";
    "shadow.samples_per_clock", Number, shadow.samples_per_clock, "map samples compared per clock";
    "shadow.divider_cycles", Number, shadow.divider_cycles, "latency of one tangent-plane division";
    "shadow.dividers", Count, shadow.dividers, "dividers working in parallel";
    "shadow.cycles_per_lookup", Number, shadow.cycles_per_lookup, "shadow-test cycles per pixel besides the samples";
    "shadow.in_shader", Flag, shadow.in_shader, "the shadow test runs in the shading program";
    "shade.cycles_per_pixel", Number, shade.cycles_per_pixel, "shading cycles per pixel besides the shadow lookup";
    "dram.bandwidth", Bandwidth, dram.bandwidth, "DRAM bandwidth";
    "dram.latency", Time, dram.latency, "DRAM latency, request to data";
    "dram.burst", Bytes, dram.burst, "bytes of one DRAM access";
    "dram.requests_in_flight", Count, dram.requests_in_flight, "DRAM requests kept in flight";
    "map_cache.size", Bytes, map_cache.size, "map cache size (0: none)";
    "map_cache.line", Bytes, map_cache.line, "map cache line";
    "map_cache.ways", Count, map_cache.ways, "map cache associativity";
    "map_cache.misses_in_flight", Count, map_cache.misses_in_flight, "map cache misses outstanding";
    "depth_cache.size", Bytes, depth_cache.size, "off-chip depth and stencil cache size (0: none)";
    "depth_cache.line", Bytes, depth_cache.line, "depth cache line";
    "depth_cache.ways", Count, depth_cache.ways, "depth cache associativity";
    "depth_cache.misses_in_flight", Count, depth_cache.misses_in_flight, "depth cache misses outstanding";
    "energy.dram_byte", Joules, energy.dram_byte, "energy per DRAM byte";
    "energy.buffer_access", Joules, energy.buffer_access, "energy per on-chip buffer access";
    "energy.cache_access", Joules, energy.cache_access, "energy per cache access";
    "energy.fragment_op", Joules, energy.fragment_op, "energy per fragment operation";
}

/// What is wrong with an architecture file or an override.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {key}: {problem}")]
pub struct ArchError {
    /// The file (or `--set`, or the bundled preset's name).
    pub file: String,
    /// The dotted key.
    pub key: String,
    /// What is wrong.
    pub problem: Problem,
}

/// The kinds of problem.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Problem {
    /// The file cannot be read.
    #[error("cannot read: {0}")]
    Read(String),
    /// Not valid TOML.
    #[error("{0}")]
    Syntax(String),
    /// No such key.
    #[error("unknown key (the keys are: {})", PARAMS.iter().map(|p| p.key).collect::<Vec<_>>().join(", "))]
    Unknown,
    /// A key the file must give.
    #[error("missing")]
    Missing,
    /// A value of the wrong kind.
    #[error("expected {0}")]
    Type(&'static str),
    /// A number with a unit that cannot be read.
    #[error("`{value}` is not {unit}")]
    Unit {
        /// The text.
        value: String,
        /// What was expected.
        unit: &'static str,
    },
    /// A value outside its range.
    #[error("{value} is not {what}")]
    Range {
        /// The value.
        value: f64,
        /// What it must be.
        what: &'static str,
    },
    /// An override not of the form `key=value`.
    #[error("expected key=value")]
    Override,
    /// A name that cannot be part of a file name.
    #[error("`{0}` is not a name: use 1 to 64 letters, digits, `-` and `_` (it names output files)")]
    Name(String),
    /// No bundled architecture of that name.
    #[error("no bundled architecture of that name (the bundled ones are: {})", BUNDLED.map(|b| b.0).join(", "))]
    NoSuchPreset,
}

impl Unit {
    /// What a value of this unit looks like, for errors.
    const fn expected(self) -> &'static str {
        match self {
            Self::Text => "text",
            Self::Flag => "true or false",
            Self::Count => "a whole number",
            Self::Number => "a number",
            Self::Bytes => "a size such as 64B, 16KiB or 2MB",
            Self::Bandwidth => "a bandwidth such as 25.6GB/s",
            Self::Frequency => "a frequency such as 800MHz",
            Self::Time => "a time such as 2ns",
            Self::Joules => "an energy such as 20pJ",
        }
    }

    /// The suffixes of this unit and their scale, the preferred one for
    /// writing first.
    const fn suffixes(self) -> &'static [(&'static str, f64)] {
        match self {
            Self::Bytes => &[
                ("GiB", 1_073_741_824.0),
                ("MiB", 1_048_576.0),
                ("KiB", 1024.0),
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
            Self::Text | Self::Flag | Self::Count | Self::Number => &[],
        }
    }

    /// Read `text` (a number and a suffix) in this unit, to its base.
    fn parse(self, text: &str) -> Result<f64, Problem> {
        let bad = || Problem::Unit { value: text.to_owned(), unit: self.expected() };
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

    /// Write `v` (in the base) with the largest suffix that reads back to
    /// the same bits.
    fn write(self, v: f64) -> String {
        for &(s, scale) in self.suffixes() {
            let scaled = v / scale;
            let text = format!("{scaled}{s}");
            if scaled.abs() >= 1.0 && self.parse(&text).is_ok_and(|back| back.to_bits() == v.to_bits()) {
                return text;
            }
        }
        let base = self.suffixes().last().map_or("", |s| s.0);
        format!("{v}{base}")
    }
}

/// A TOML value as a [`Value`] for a key of `unit`.
fn from_toml(unit: Unit, v: &toml::Value) -> Result<Value, Problem> {
    #[allow(clippy::cast_precision_loss, reason = "integers in a file, checked by the field")]
    match (unit, v) {
        (Unit::Text, toml::Value::String(s)) => Ok(Value::Text(s.clone())),
        (Unit::Flag, toml::Value::Boolean(b)) => Ok(Value::Flag(*b)),
        (Unit::Count | Unit::Number, toml::Value::Integer(i)) => Ok(Value::Number(*i as f64)),
        (Unit::Number, toml::Value::Float(x)) => Ok(Value::Number(*x)),
        (Unit::Count, toml::Value::Float(x)) => Err(Problem::Range { value: *x, what: "a whole number" }),
        (Unit::Bytes | Unit::Bandwidth | Unit::Frequency | Unit::Time | Unit::Joules, toml::Value::String(s)) => {
            unit.parse(s).map(Value::Number)
        }
        _ => Err(Problem::Type(unit.expected())),
    }
}

/// An override's text as a [`Value`] for a key of `unit`.
fn from_text(unit: Unit, text: &str) -> Result<Value, Problem> {
    let t = text.trim();
    match unit {
        Unit::Text => Ok(Value::Text(t.to_owned())),
        Unit::Flag => t.parse().map(Value::Flag).map_err(|_| Problem::Type(unit.expected())),
        Unit::Count | Unit::Number => t.parse().map(Value::Number).map_err(|_| Problem::Type(unit.expected())),
        _ => unit.parse(t).map(Value::Number),
    }
}

/// Look up a dotted key in a table.
fn lookup<'t>(table: &'t toml::Table, key: &str) -> Option<&'t toml::Value> {
    let mut parts = key.split('.');
    let mut value = table.get(parts.next()?)?;
    for part in parts {
        value = value.as_table()?.get(part)?;
    }
    Some(value)
}

/// Every leaf key of a table, dotted.
fn leaves(table: &toml::Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in table {
        let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match v {
            toml::Value::Table(t) => leaves(t, &key, out),
            _ => out.push(key),
        }
    }
}

impl Arch {
    /// Parse an architecture file's text; `file` names it in errors.
    ///
    /// # Errors
    /// [`ArchError`] naming the file, the key and the problem: TOML syntax,
    /// an unknown or missing key, a value of the wrong type or unit, or a
    /// machine that cannot be modelled (see [`Arch::check`]).
    pub fn parse(text: &str, file: &str) -> Result<Self, ArchError> {
        let err = |key: &str, problem| ArchError { file: file.to_owned(), key: key.to_owned(), problem };
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let line = e.span().map_or(0, |s| text[..s.start.min(text.len())].lines().count().max(1));
            err(&format!("line {line}"), Problem::Syntax(e.message().to_owned()))
        })?;
        let mut keys = Vec::new();
        leaves(&table, "", &mut keys);
        if let Some(unknown) = keys.iter().find(|k| !PARAMS.iter().any(|p| p.key == k.as_str())) {
            return Err(err(unknown, Problem::Unknown));
        }
        let mut arch = Self::default();
        for p in PARAMS {
            let v = lookup(&table, p.key).ok_or_else(|| err(p.key, Problem::Missing))?;
            from_toml(p.unit, v).and_then(|v| (p.set)(&mut arch, v)).map_err(|e| err(p.key, e))?;
        }
        arch.check().map_err(|(key, problem)| err(key, problem))?;
        Ok(arch)
    }

    /// Load an architecture file.
    ///
    /// # Errors
    /// [`ArchError`] naming the file, the key and the problem.
    pub fn load(path: &Path) -> Result<Self, ArchError> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ArchError {
            file: name.clone(),
            key: "(file)".into(),
            problem: Problem::Read(e.to_string()),
        })?;
        Self::parse(&text, &name)
    }

    /// A bundled architecture by name.
    ///
    /// # Errors
    /// [`Problem::NoSuchPreset`] for an unknown name.
    pub fn bundled(name: &str) -> Result<Self, ArchError> {
        let (_, text) = BUNDLED.iter().find(|(n, _)| *n == name).ok_or_else(|| ArchError {
            file: name.to_owned(),
            key: "(name)".into(),
            problem: Problem::NoSuchPreset,
        })?;
        Self::parse(text, &format!("arch/{name}.toml (bundled)"))
    }

    /// Every bundled architecture, in [`BUNDLED`] order.
    ///
    /// # Errors
    /// [`ArchError`] if a bundled file is broken (a test guards this).
    pub fn presets() -> Result<Vec<Self>, ArchError> {
        BUNDLED.iter().map(|(n, _)| Self::bundled(n)).collect()
    }

    /// The presets of the papers' era the study compares by default:
    /// PixelFlow, Talisman and the immediate-mode baseline.
    #[must_use]
    pub fn era_presets() -> Vec<Self> {
        ["pixelflow", "talisman", "immediate"].iter().filter_map(|n| Self::bundled(n).ok()).collect()
    }

    /// The file `name` when it is one (a path with a folder or a `.toml`
    /// extension, which then must exist), else the bundled architecture of
    /// that name.
    ///
    /// # Errors
    /// [`ArchError`] naming the file, the key and the problem.
    pub fn open(name: &str) -> Result<Self, ArchError> {
        let path = Path::new(name);
        let names_a_file = path.extension().is_some_and(|e| e == "toml") || path.components().count() > 1;
        if names_a_file || path.is_file() { Self::load(path) } else { Self::bundled(name) }
    }

    /// Apply one `key=value` override (`dram.bandwidth=25.6GB/s`,
    /// `clock=800MHz`, `map_cache.size=32KiB`), then check the machine.
    ///
    /// # Errors
    /// [`ArchError`] with file `--set` naming the key and the problem.
    pub fn set(&mut self, assignment: &str) -> Result<(), ArchError> {
        let err = |key: &str, problem| ArchError { file: "--set".into(), key: key.to_owned(), problem };
        let (key, value) = assignment.split_once('=').ok_or_else(|| err(assignment, Problem::Override))?;
        let key = key.trim();
        let p = PARAMS.iter().find(|p| p.key == key).ok_or_else(|| err(key, Problem::Unknown))?;
        from_text(p.unit, value).and_then(|v| (p.set)(self, v)).map_err(|e| err(key, e))?;
        self.check().map_err(|(key, problem)| err(key, problem))
    }

    /// The value of one key.
    #[must_use]
    pub fn get(&self, key: &str) -> Option<Value> {
        PARAMS.iter().find(|p| p.key == key).map(|p| (p.get)(self))
    }

    /// Check what the model needs: positive clock, bandwidth and rates, a
    /// tile side the raster can draw, cache geometries that can be built.
    ///
    /// # Errors
    /// The key and the problem.
    pub fn check(&self) -> Result<(), (&'static str, Problem)> {
        let positive = |key: &'static str, v: f64| {
            if v > 0.0 { Ok(()) } else { Err((key, Problem::Range { value: v, what: "positive" })) }
        };
        let n = &self.name;
        if n.is_empty() || n.len() > 64 || !n.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
            return Err(("name", Problem::Name(n.clone())));
        }
        positive("clock", self.clock)?;
        positive("dram.bandwidth", self.dram.bandwidth)?;
        positive("shadow.samples_per_clock", self.shadow.samples_per_clock)?;
        #[allow(clippy::cast_precision_loss, reason = "small counts")]
        {
            positive("dram.burst", self.dram.burst as f64)?;
            positive("dram.requests_in_flight", self.dram.requests_in_flight as f64)?;
            positive("shadow.dividers", self.shadow.dividers as f64)?;
        }
        let tile = self.raster.tile;
        if !tile.is_power_of_two() || !umbra_core::budget::TILE_SIZES.contains(&tile) {
            return Err((
                "raster.tile",
                Problem::Range { value: f64::from(tile), what: "a power of two from 8 to 128" },
            ));
        }
        if self.raster.fragments_per_clock == 0.0 {
            positive("raster.cycles_per_tile", self.raster.cycles_per_tile)?;
        }
        if self.depth.fragments_per_clock == 0.0 {
            positive("depth.cycles_per_bit", self.depth.cycles_per_bit)?;
        }
        for (prefix, c) in [("map_cache", &self.map_cache), ("depth_cache", &self.depth_cache)] {
            if c.size == 0 {
                continue;
            }
            let key = if prefix == "map_cache" { "map_cache.size" } else { "depth_cache.size" };
            let set = c.line.saturating_mul(c.ways);
            #[allow(clippy::cast_precision_loss, reason = "a size")]
            if !c.line.is_power_of_two() || c.ways == 0 || c.misses_in_flight == 0 || !c.size.is_multiple_of(set) {
                return Err((
                    key,
                    Problem::Range {
                        value: c.size as f64,
                        what: "a whole number of sets of `ways` power-of-two lines, with misses_in_flight at least 1",
                    },
                ));
            }
        }
        Ok(())
    }

    /// The effective architecture as an architecture file: every key with
    /// its value, its meaning and its unit (the record every output
    /// carries; it parses back to the same architecture).
    #[must_use]
    pub fn to_toml(&self) -> String {
        let mut s = String::new();
        for p in PARAMS {
            let value = match (p.get)(self) {
                Value::Text(t) => toml::Value::String(t).to_string(),
                Value::Flag(b) => b.to_string(),
                Value::Number(x) => match p.unit {
                    Unit::Count | Unit::Number => format!("{x}"),
                    _ => format!("\"{}\"", p.unit.write(x)),
                },
            };
            let _ = writeln!(s, "{} = {value}  # {}", p.key, p.doc);
        }
        s
    }

    /// An immediate-mode machine: no bins, so each draw is finished before
    /// the next and timed as one unit.
    #[must_use]
    pub const fn immediate(&self) -> bool {
        self.bins.entry_bytes == 0 && self.bins.setup_record_bytes == 0
    }

    /// How the passes walk the target on this machine: its tiles, and draw
    /// by draw when it is immediate-mode.
    #[must_use]
    pub const fn tiling(&self) -> crate::pass::camera::Tiling {
        crate::pass::camera::Tiling { tile: self.raster.tile, per_draw: self.immediate() }
    }

    /// Bytes DRAM moves per clock.
    #[must_use]
    pub fn bytes_per_cycle(&self) -> f64 {
        self.dram.bandwidth / self.clock
    }

    /// DRAM latency in clocks.
    #[must_use]
    pub fn latency_cycles(&self) -> f64 {
        self.dram.latency * self.clock
    }
}
