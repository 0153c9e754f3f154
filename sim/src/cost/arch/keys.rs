//! The keys of an architecture file: one table, [`PARAMS`], of every key
//! with its unit ([`Unit`]) and meaning, and what can be wrong with a key,
//! its value or the file ([`Problem`]).

use super::machine::Arch;
use super::measure::{NotInUnit, Unit};
use super::presets::BUNDLED;

/// The kinds of problem with an architecture file, a key or its value.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Problem {
    /// The file cannot be read.
    #[error("cannot read: {0}")]
    Read(String),
    /// Not valid TOML.
    #[error("{0}")]
    Syntax(String),
    /// No such key; the one it is a slip of, if any.
    #[error("unknown key{}; `umbra arch show` lists every key", near.map_or_else(String::new, |n| format!(" (did you mean `{n}`?)")))]
    Unknown {
        /// The key it was nearly ([`umbra_core::spelling::closest`]).
        near: Option<&'static str>,
    },
    /// A key the file must give.
    #[error("missing")]
    Missing,
    /// Several keys wrong at once, each with its problem.
    #[error("{}", several(.0))]
    Several(Vec<(String, Problem)>),
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
    /// A number outside its key's range ([`Param::range`]).
    #[error("{value} is outside {min} ..= {max}")]
    Outside {
        /// The value, in the key's unit.
        value: String,
        /// The smallest allowed.
        min: String,
        /// The largest allowed.
        max: String,
    },
    /// An override not of the form `key=value`.
    #[error("expected key=value")]
    Override,
    /// A name that cannot be part of a file name.
    #[error("`{0}` is not a name: use 1 to 64 letters, digits, `-` and `_` (it names output files)")]
    Name(String),
    /// A file format version this build does not read.
    #[error("{0}")]
    Format(String),
    /// No bundled architecture of that name.
    #[error("no bundled architecture of that name (the bundled ones are: {})", BUNDLED.map(|b| b.0).join(", "))]
    NoSuchPreset,
}

/// The column a key's values take in a table of rows: `arch_`, the key
/// with `_` for `.`, and its SI unit (`dram.bandwidth` is
/// `arch_dram_bandwidth_bytes_per_second`).
#[must_use]
pub fn column(key: &str) -> String {
    let unit = PARAMS.iter().find(|p| p.key == key).map_or("", |p| p.unit.si_name());
    let base = format!("arch_{}", key.replace('.', "_"));
    if unit.is_empty() { base } else { format!("{base}_{unit}") }
}

impl Problem {
    /// `key` is no key: [`Problem::Unknown`], with the key it is a slip of.
    #[must_use]
    pub fn unknown(key: &str) -> Self {
        Self::Unknown { near: umbra_core::spelling::closest(key, PARAMS.iter().map(|p| p.key)) }
    }
}

/// The problems a message lists before it counts the rest.
pub(crate) const SHOWN: usize = 20;

/// Several keys' problems in one line, an unknown key without the list of
/// every key; past the first [`SHOWN`], only how many more.
fn several(problems: &[(String, Problem)]) -> String {
    let each = problems.iter().take(SHOWN).map(|(key, problem)| match problem {
        Problem::Unknown { near: Some(near) } => format!("{key}: unknown key (did you mean `{near}`?)"),
        Problem::Unknown { near: None } => format!("{key}: unknown key"),
        _ => format!("{key}: {problem}"),
    });
    let more = match problems.len().saturating_sub(SHOWN) {
        0 => String::new(),
        n => format!("; and {n} more"),
    };
    format!("{} keys: {}{more}", problems.len(), each.collect::<Vec<_>>().join("; "))
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
    /// The smallest and largest value a number may take, in the unit's
    /// base (none for text and flags): the model's counters (bytes in
    /// `u64`, cycles in `f64`) cannot overflow inside these ranges and the
    /// [`Limits`](crate::input::limits::Limits), and its times stay finite.
    pub range: Option<(f64, f64)>,
    /// The value a file that lacks the key gets: the behaviour of the
    /// releases before the key existed (none: every file must give it).
    pub default: Option<Value>,
    /// The file format the key was added in (1: the first): a file of an
    /// earlier format that lacks it gets [`Param::default`].
    pub since: u32,
    pub(super) get: fn(&Arch) -> Value,
    pub(super) set: fn(&mut Arch, Value) -> Result<(), Problem>,
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

impl From<NotInUnit> for Problem {
    fn from(e: NotInUnit) -> Self {
        Self::Unit { value: e.value, unit: e.unit }
    }
}

impl Param {
    /// This key's value in `arch` as a file writes it, with its unit
    /// (`25.6GB/s`, `true`, `4`).
    #[must_use]
    pub fn written(&self, arch: &Arch) -> String {
        match (self.get)(arch) {
            Value::Text(t) => t,
            Value::Flag(f) => f.to_string(),
            Value::Number(x) => match self.unit {
                Unit::Count | Unit::Number => format!("{x}"),
                u => u.write(x),
            },
        }
    }

    /// Set this key of `arch` to `v`, checked against [`Param::range`].
    ///
    /// # Errors
    /// [`Problem::Outside`] out of range, or the field's own problem.
    pub(super) fn assign(&self, arch: &mut Arch, v: Value) -> Result<(), Problem> {
        if let (Some((min, max)), Value::Number(x)) = (self.range, &v)
            && !(min..=max).contains(x)
        {
            return Err(Problem::Outside {
                value: self.unit.write(*x),
                min: self.unit.write(min),
                max: self.unit.write(max),
            });
        }
        (self.set)(arch, v)
    }
}

/// Declares [`PARAMS`] from one list: key, unit, field path, range (for
/// numbers), for a key added after the first release the format it came
/// in and its default (the value that keeps the earlier behaviour),
/// meaning.
macro_rules! params {
    ($($key:literal, $unit:ident, $($field:ident).+, $([$min:expr, $max:expr],)? $(since $since:literal default $default:expr,)? $doc:literal;)+) => {
        /// Every key of an architecture file, in file order.
        pub const PARAMS: &[Param] = &[$(Param {
            key: $key,
            unit: Unit::$unit,
            doc: $doc,
            range: params!(@range $([$min, $max])?),
            default: params!(@default $($default)?),
            since: params!(@since $($since)?),
            get: |a: &Arch| Field::get(&a.$($field).+),
            set: |a: &mut Arch, v: Value| Field::set(&mut a.$($field).+, v),
        }),+];
    };
    (@range [$min:expr, $max:expr]) => { Some(($min, $max)) };
    (@range) => { None };
    (@default $default:expr) => { Some($default) };
    (@default) => { None };
    (@since $since:literal) => { $since };
    (@since) => { 1 };
}

/// Largest cycle count of one unit event (setup, tile, division), cycles.
const CYCLES: f64 = 1e6;
/// Most units or requests working in parallel.
const PARALLEL: f64 = 65_536.0;
/// Largest rate, per clock.
const RATE: f64 = 65_536.0;
/// Largest record (bin entry, setup record, burst), bytes.
const RECORD: f64 = 4096.0;

params! {
    "name", Text, name, "name for reports and file names";
    "description", Text, description, "what the file models";
    "clock", Frequency, clock, [1e3, 1e11], "core clock";
    "front.setup_cycles", Number, front.setup_cycles, [0.0, CYCLES], "cycles per triangle set up";
    "front.overlap", Flag, front.overlap, "setup and binning overlap the tiles";
    "front.pass_overhead_cycles", Number, front.pass_overhead_cycles, [0.0, 1e9], "fixed cycles per pass waiting for the host";
    "front.frame_overhead_cycles", Number, front.frame_overhead_cycles, [0.0, 1e10], since 2 default Value::Number(0.0), "fixed cycles per frame in the host and driver";
    "raster.tile", Count, raster.tile, [8.0, 128.0], "tile (chunk, region) side in pixels";
    "raster.fragments_per_clock", Number, raster.fragments_per_clock, [0.0, RATE], "fragments scan-converted per clock (0: evaluator)";
    "raster.cycles_per_tile", Number, raster.cycles_per_tile, [0.0, CYCLES], "evaluator cycles per triangle per tile touched";
    "depth.fragments_per_clock", Number, depth.fragments_per_clock, [0.0, RATE], "fragments depth-tested per clock per buffer (0: bit-serial)";
    "depth.cycles_per_bit", Number, depth.cycles_per_bit, [0.0, CYCLES], "bit-serial cycles per depth bit per buffer per triangle per tile";
    "depth.second_depth_pass", Flag, depth.second_depth_pass, "second depth by a second light pass and a combining pass";
    "depth.program_cycles", Number, depth.program_cycles, [0.0, CYCLES], since 2 default Value::Number(0.0), "map-writing fragment program cycles per light fragment passing depth (0: fixed function)";
    "depth.peel_cycles", Number, depth.peel_cycles, [0.0, CYCLES], since 2 default Value::Number(0.0), "second light pass's further program cycles per fragment passing depth";
    "depth.combine_cycles", Number, depth.combine_cycles, [0.0, CYCLES], since 2 default Value::Number(0.0), "combining pass program cycles per texel";
    "on_chip.light_depth", Flag, on_chip.light_depth, "light-pass depth buffers on chip";
    "on_chip.camera_depth", Flag, on_chip.camera_depth, "camera visibility depth and ids on chip";
    "on_chip.stencil", Flag, on_chip.stencil, "stencil and volume-tested depth on chip";
    "on_chip.resolve_test_value_only", Flag, on_chip.resolve_test_value_only, "the resolve writes only the value the test reads";
    "bins.entry_bytes", Count, bins.entry_bytes, [0.0, RECORD], "bytes of one bin entry in DRAM";
    "bins.setup_record_bytes", Count, bins.setup_record_bytes, [0.0, RECORD], "bytes of one setup record in DRAM";
    "shadow.samples_per_clock", Number, shadow.samples_per_clock, [1e-3, RATE], "map samples compared per clock";
    "shadow.divider_cycles", Number, shadow.divider_cycles, [0.0, CYCLES], "latency of one tangent-plane division";
    "shadow.dividers", Count, shadow.dividers, [1.0, PARALLEL], "dividers working in parallel";
    "shadow.cycles_per_lookup", Number, shadow.cycles_per_lookup, [0.0, CYCLES], "shadow-test cycles per pixel besides the samples";
    "shadow.cycles_per_sample", Number, shadow.cycles_per_sample, [0.0, CYCLES], since 2 default Value::Number(0.0), "filter program cycles per sample besides its fetch";
    "shadow.cycles_per_weights", Number, shadow.cycles_per_weights, [0.0, CYCLES], since 2 default Value::Number(0.0), "bilinear weights program cycles per lookup";
    "shadow.in_shader", Flag, shadow.in_shader, "the shadow test runs in the shading program";
    "shade.cycles_per_pixel", Number, shade.cycles_per_pixel, [0.0, CYCLES], "shading cycles per pixel besides the shadow lookup";
    "shade.per_fragment", Flag, shade.per_fragment, since 2 default Value::Flag(false), "shading runs per camera fragment passing depth, not per covered pixel";
    "dram.bandwidth", Bandwidth, dram.bandwidth, [1e6, 1e14], "DRAM bandwidth";
    "dram.latency", Time, dram.latency, [0.0, 1e-3], "DRAM latency, request to data";
    "dram.burst", Bytes, dram.burst, [1.0, RECORD], "bytes of one DRAM access";
    "dram.requests_in_flight", Count, dram.requests_in_flight, [1.0, PARALLEL], "DRAM requests kept in flight";
    "map_cache.size", Bytes, map_cache.size, [0.0, 67_108_864.0], "map cache size (0: none)";
    "map_cache.line", Bytes, map_cache.line, [16.0, RECORD], "map cache line";
    "map_cache.ways", Count, map_cache.ways, [1.0, 64.0], "map cache associativity";
    "map_cache.misses_in_flight", Count, map_cache.misses_in_flight, [1.0, PARALLEL], "map cache misses outstanding";
    "depth_cache.size", Bytes, depth_cache.size, [0.0, 67_108_864.0], "off-chip depth and stencil cache size (0: none)";
    "depth_cache.line", Bytes, depth_cache.line, [16.0, RECORD], "depth cache line";
    "depth_cache.ways", Count, depth_cache.ways, [1.0, 64.0], "depth cache associativity";
    "depth_cache.misses_in_flight", Count, depth_cache.misses_in_flight, [1.0, PARALLEL], "depth cache misses outstanding";
    "energy.dram_byte", Joules, energy.dram_byte, [0.0, 1e-6], "energy per DRAM byte";
    "energy.buffer_access", Joules, energy.buffer_access, [0.0, 1e-6], "energy per on-chip buffer access";
    "energy.cache_access", Joules, energy.cache_access, [0.0, 1e-6], "energy per cache access";
    "energy.fragment_op", Joules, energy.fragment_op, [0.0, 1e-6], "energy per fragment operation";
    "technology.node", Text, technology.node, since 3 default Value::Text(String::new()), "process node the area and leakage figures are for (empty: no silicon modelled)";
    "technology.sram_bit", Area, technology.sram_bit, [0.0, 1e-9], since 3 default Value::Number(0.0), "area of one SRAM bit cell";
    "technology.array_efficiency", Number, technology.array_efficiency, [0.01, 1.0], since 3 default Value::Number(0.7), "bit cells' share of an SRAM array's area";
    "technology.gate", Area, technology.gate, [0.0, 1e-9], since 3 default Value::Number(0.0), "area of one NAND2 gate equivalent of logic, placed and routed";
    "technology.leakage", PowerDensity, technology.leakage, [0.0, 1e6], since 3 default Value::Number(0.0), "leakage power per area of the units";
}

/// A TOML value as a [`Value`] for a key of `unit`.
pub(super) fn from_toml(unit: Unit, v: &toml::Value) -> Result<Value, Problem> {
    #[allow(clippy::cast_precision_loss, reason = "integers in a file, checked by the field")]
    match (unit, v) {
        (Unit::Text, toml::Value::String(s)) => Ok(Value::Text(s.clone())),
        (Unit::Flag, toml::Value::Boolean(b)) => Ok(Value::Flag(*b)),
        (Unit::Count | Unit::Number, toml::Value::Integer(i)) => Ok(Value::Number(*i as f64)),
        (Unit::Number, toml::Value::Float(x)) => Ok(Value::Number(*x)),
        (Unit::Count, toml::Value::Float(x)) => Err(Problem::Range { value: *x, what: "a whole number" }),
        (
            Unit::Bytes
            | Unit::Bandwidth
            | Unit::Frequency
            | Unit::Time
            | Unit::Joules
            | Unit::Area
            | Unit::PowerDensity,
            toml::Value::String(s),
        ) => unit.parse(s).map(Value::Number).map_err(Problem::from),
        _ => Err(Problem::Type(unit.expected())),
    }
}

/// An override's text as a [`Value`] for a key of `unit`.
pub(super) fn from_text(unit: Unit, text: &str) -> Result<Value, Problem> {
    let t = text.trim();
    match unit {
        Unit::Text => Ok(Value::Text(t.to_owned())),
        Unit::Flag => t.parse().map(Value::Flag).map_err(|_| Problem::Type(unit.expected())),
        Unit::Count | Unit::Number => t.parse().map(Value::Number).map_err(|_| Problem::Type(unit.expected())),
        _ => unit.parse(t).map(Value::Number).map_err(Problem::from),
    }
}
