//! Architecture files: the machine a render is costed on, as TOML a user
//! can write, bundled presets, `--set key=value` overrides with units, and
//! the effective architecture written back (as gem5's `config.ini` is).
//!
//! One table, [`PARAMS`], lists every key with its unit and meaning; it
//! drives parsing, overrides, validation and the written record alike, so
//! a key cannot be read without being recorded.

use std::fmt::Write as _;
use std::path::Path;

use crate::input::format::{ARCH, Added};
use crate::input::limits::Limits;

use super::keys::{PARAMS, Problem, SHOWN, Value, from_text, from_toml};
use super::machine::{Arch, Calibration};
use super::measure::Unit;
use super::presets::BUNDLED;

/// The largest cache an architecture may have, bytes: the model keeps a
/// tag per line, so a cache's model takes at most 64 MiB / 16 B × 25 B =
/// 100 MiB of memory.
pub(crate) const MAX_CACHE_BYTES: u64 = 64 << 20;
/// The smallest and largest cache line, bytes.
const MIN_LINE: u64 = 16;
const MAX_LINE: u64 = 4096;
/// The most ways of a cache.
const MAX_WAYS: u64 = 64;

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

/// Look up a dotted key in a table.
fn lookup<'t>(table: &'t toml::Table, key: &str) -> Option<&'t toml::Value> {
    let mut parts = key.split('.');
    let mut value = table.get(parts.next()?)?;
    for part in parts {
        value = value.as_table()?.get(part)?;
    }
    Some(value)
}

/// The `[calibration]` table: each key a parameter, each value the
/// `dataset/point` it was set from.
fn calibration(table: Option<toml::Value>) -> Result<Vec<Calibration>, (String, Problem)> {
    let Some(value) = table else { return Ok(Vec::new()) };
    let toml::Value::Table(t) = value else { return Err(("calibration".into(), Problem::Type("a table"))) };
    t.into_iter()
        .map(|(key, point)| {
            let name = format!("calibration.{key}");
            if !PARAMS.iter().any(|p| p.key == key && p.unit != Unit::Text) {
                return Err((name, Problem::unknown(&key)));
            }
            match point {
                toml::Value::String(point)
                    if point.split_once('/').is_some_and(|(d, p)| !d.is_empty() && !p.is_empty()) =>
                {
                    Ok(Calibration { key, point })
                }
                _ => Err((name, Problem::Type("a dataset point, `dataset/point`"))),
            }
        })
        .collect()
}

/// Every leaf key of a table, dotted, and every empty table no key lies
/// under (`[cache_tweaks]` alone): a table the model does not know is
/// named as an unknown key is.
fn leaves(table: &toml::Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in table {
        let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match v {
            toml::Value::Table(t) if t.is_empty() => {
                let known = PARAMS.iter().any(|p| p.key.strip_prefix(key.as_str()).is_some_and(|r| r.starts_with('.')));
                if !known {
                    out.push(key);
                }
            }
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
    /// machine that cannot be modelled (see `Arch::check`).
    pub fn parse(text: &str, file: &str) -> Result<Self, ArchError> {
        let err = |key: &str, problem| ArchError { file: file.to_owned(), key: key.to_owned(), problem };
        let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let at = e.span().map_or_else(|| "(file)".to_owned(), |s| crate::input::at_line(text, s.start));
            err(&at, Problem::Syntax(e.message().trim().to_owned()))
        })?;
        let format = match table.remove("format") {
            None => None,
            Some(toml::Value::Integer(v)) => Some(v),
            Some(_) => return Err(err("format", Problem::Type("a whole number, the file format version"))),
        };
        let format = ARCH.stated(format).map_err(|e| err("format", Problem::Format(e)))?;
        let calibration = calibration(table.remove("calibration")).map_err(|(key, problem)| err(&key, problem))?;
        let mut keys = Vec::new();
        leaves(&table, "", &mut keys);
        // Every unknown, missing or malformed key, all at once; a
        // suggestion only for the unknown keys the message lists (a file
        // of a million would otherwise be spelt against every key).
        let mut problems: Vec<(String, Problem)> = keys
            .into_iter()
            .filter(|k| !PARAMS.iter().any(|p| p.key == k.as_str()))
            .enumerate()
            .map(|(i, k)| {
                let p = if i < SHOWN { Problem::unknown(&k) } else { Problem::Unknown { near: None } };
                (k, p)
            })
            .collect();
        let mut arch = Self { calibration, ..Self::default() };
        for p in PARAMS {
            let value = match (lookup(&table, p.key), &p.default) {
                (Some(v), _) => from_toml(p.unit, v),
                // A key added since the file's format: the earlier behaviour.
                (None, Some(default)) if format < p.since => Ok(default.clone()),
                (None, _) => Err(Problem::Missing),
            };
            if let Err(problem) = value.and_then(|v| p.assign(&mut arch, v)) {
                problems.push((p.key.to_owned(), problem));
            }
        }
        if problems.len() == 1 {
            let (key, problem) = problems.remove(0);
            return Err(err(&key, problem));
        }
        if !problems.is_empty() {
            return Err(err("(file)", Problem::Several(problems)));
        }
        arch.check().map_err(|(key, problem)| err(key, problem))?;
        Ok(arch)
    }

    /// An architecture file's text for the current format: `format`
    /// stated, and every key added since the file's format written into
    /// its table with the value that keeps the earlier behaviour, its
    /// meaning and its unit as a comment; everything else as it was. The
    /// upgraded text loads to the same architecture, and upgrading it
    /// again changes nothing.
    ///
    /// ```
    /// use umbra_sim::Arch;
    /// let old = Arch::bundled("talisman")?.to_toml().replace("depth.peel_cycles = 0", "");
    /// let old = old.lines().filter(|l| !l.starts_with("format")).collect::<Vec<_>>().join("\n");
    /// let new = Arch::upgrade(&old, "old.toml")?;
    /// assert!(new.contains("format = 3  # upgraded from format 1\n"));
    /// assert!(new.contains("peel_cycles = 0  # second light pass"));
    /// assert_eq!(Arch::parse(&new, "new.toml")?, Arch::parse(&old, "old.toml")?);
    /// assert_eq!(Arch::upgrade(&new, "new.toml")?, new);
    /// # Ok::<(), umbra_sim::cost::arch::ArchError>(())
    /// ```
    ///
    /// # Errors
    /// [`ArchError`] for a file that does not load: the upgrade is of a
    /// file that does.
    pub fn upgrade(text: &str, file: &str) -> Result<String, ArchError> {
        Self::parse(text, file)?;
        let added: Vec<Added> = PARAMS
            .iter()
            .filter_map(|p| {
                let value = match p.default.as_ref()? {
                    // A quantity with a unit as text with its unit (`"0mm2"`).
                    Value::Number(x) if !matches!(p.unit, Unit::Count | Unit::Number) => {
                        toml_edit::Value::from(p.unit.write(*x))
                    }
                    // Whole numbers as integers, as the bundled files write them.
                    #[allow(clippy::cast_possible_truncation, reason = "whole and far below 2^53")]
                    Value::Number(x) if x.fract() == 0.0 && x.abs() < 1e15 => toml_edit::Value::from(*x as i64),
                    Value::Number(x) => toml_edit::Value::from(*x),
                    Value::Flag(b) => toml_edit::Value::from(*b),
                    Value::Text(t) => toml_edit::Value::from(t.as_str()),
                };
                let unit = match p.unit.symbol() {
                    "-" => String::new(),
                    u => format!(" ({u})"),
                };
                let comment =
                    format!("{}{unit}; added in format {}, this value keeps the earlier behaviour", p.doc, p.since);
                Some(Added { key: p.key, value, comment })
            })
            .collect();
        ARCH.upgrade(text, &added).map_err(|e| ArchError {
            file: file.to_owned(),
            key: "(file)".into(),
            problem: Problem::Syntax(e),
        })
    }

    /// Load an architecture file (a regular file within `limits`).
    ///
    /// # Errors
    /// [`ArchError`] naming the file, the key and the problem.
    pub fn load(path: &Path, limits: &Limits) -> Result<Self, ArchError> {
        let name = path.display().to_string();
        let read =
            |problem: String| ArchError { file: name.clone(), key: "(file)".into(), problem: Problem::Read(problem) };
        let bytes = limits.read_text_file(path).map_err(|e| read(e.to_string()))?;
        let text = String::from_utf8(bytes).map_err(|_| read("not UTF-8 text".into()))?;
        let mut arch = Self::parse(&text, &name)?;
        arch.name = Self::file_name(path, arch.name);
        Ok(arch)
    }

    /// The name an architecture loaded from `path` goes by: the file's
    /// own (its stem), so that a copy (`cp arch/mobile-tbdr.toml
    /// my-gpu.toml`) reports as `my-gpu`, not as what it was copied from;
    /// `declared`, its `name` key, where the stem is that name or is
    /// `arch-<name>` (the files Umbra writes beside its results), or is not
    /// a name an architecture may have.
    fn file_name(path: &Path, declared: String) -> String {
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let written = stem == declared || stem.strip_prefix("arch-") == Some(declared.as_str());
        let valid = !stem.is_empty()
            && stem.len() <= 64
            && stem.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
        if written || !valid { declared } else { stem }
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
    /// ```
    /// use umbra_sim::{Arch, Limits};
    /// let mut arch = Arch::open("mobile-tbdr", &Limits::DEFAULT)?;
    /// arch.set("dram.bandwidth=25.6GB/s")?;
    /// assert!(arch.set("dram.bandwidth=fast").is_err());
    /// # Ok::<(), umbra_sim::cost::arch::ArchError>(())
    /// ```
    ///
    /// # Errors
    /// [`ArchError`] naming the file, the key and the problem.
    pub fn open(name: &str, limits: &Limits) -> Result<Self, ArchError> {
        let path = Path::new(name);
        let names_a_file = path.extension().is_some_and(|e| e == "toml") || path.components().count() > 1;
        if names_a_file || path.exists() { Self::load(path, limits) } else { Self::bundled(name) }
    }

    /// Apply one `key=value` override (`dram.bandwidth=25.6GB/s`,
    /// `clock=800MHz`, `map_cache.size=32KiB`), then check the machine.
    /// The architecture keeps its name: [`Arch::set_named`] renames it.
    ///
    /// # Errors
    /// [`ArchError`] with file `--set` naming the key and the problem.
    pub fn set(&mut self, assignment: &str) -> Result<(), ArchError> {
        let err = |key: &str, problem| ArchError { file: "--set".into(), key: key.to_owned(), problem };
        let (key, value) = assignment.split_once('=').ok_or_else(|| err(assignment, Problem::Override))?;
        let key = key.trim();
        self.assign(key, value).map_err(|problem| err(key, problem))?;
        self.check().map_err(|(key, problem)| err(key, problem))
    }

    /// [`Arch::set`], the change then named wherever the architecture is:
    /// its name [`Arch::name_with`] it (`talisman-dram_bandwidth-2_4GB_s`),
    /// its description ends with it as written (`--set dram.bandwidth=2.4GB/s`).
    ///
    /// ```
    /// use umbra_sim::{Arch, Limits};
    /// let mut arch = Arch::open("talisman", &Limits::DEFAULT)?;
    /// arch.set_named("dram.bandwidth=2.4GB/s")?;
    /// assert_eq!(arch.name, "talisman-dram_bandwidth-2_4GB_s");
    /// assert!(arch.description.ends_with("; --set dram.bandwidth=2.4GB/s"));
    /// # Ok::<(), umbra_sim::cost::arch::ArchError>(())
    /// ```
    ///
    /// # Errors
    /// As [`Arch::set`].
    pub fn set_named(&mut self, assignment: &str) -> Result<(), ArchError> {
        self.set(assignment)?;
        let (key, value) = assignment.split_once('=').unwrap_or((assignment, ""));
        self.name = Self::name_with(&self.name, key.trim(), value.trim());
        self.description = format!("{}; --set {}={}", self.description, key.trim(), value.trim());
        Ok(())
    }

    /// The name of architecture `name` with `key` set to `value`:
    /// `<name>-<key>-<value>`, every character but letters and digits
    /// written `_`, within the 64 characters a name may have (past them,
    /// its first 55 characters, `-` and 8 hexadecimal digits of its hash,
    /// so that two long names stay apart).
    #[must_use]
    pub fn name_with(name: &str, key: &str, value: &str) -> String {
        const MAX: usize = 64;
        let word = |s: &str| s.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect::<String>();
        let long = format!("{name}-{}-{}", word(key), word(value));
        if long.len() <= MAX {
            return long;
        }
        let hash = crate::output::provenance::hash(long.as_bytes());
        let head: String = long.chars().take(MAX - 9).collect();
        format!("{head}-{}", &hash[..8])
    }

    /// Set one key to a value written as `--set` takes it, checked against
    /// the key's range but not yet against the rest of the machine
    /// ([`Arch::check`]): the caller names the source in its errors.
    ///
    /// # Errors
    /// The problem: an unknown key, or a value of the wrong unit or range.
    pub(crate) fn assign(&mut self, key: &str, value: &str) -> Result<(), Problem> {
        let p = PARAMS.iter().find(|p| p.key == key).ok_or_else(|| Problem::unknown(key))?;
        from_text(p.unit, value).and_then(|v| p.assign(self, v))
    }

    /// The value `text` means for `key`, in the key's base unit: `1GB/s`,
    /// `1 GB/s` and `1e9B/s` are one value. Not checked against the key's
    /// range ([`Arch::assign`] checks that).
    ///
    /// # Errors
    /// An unknown key, or text that is not a value of the key's unit.
    pub(crate) fn value_of(key: &str, text: &str) -> Result<Value, Problem> {
        let p = PARAMS.iter().find(|p| p.key == key).ok_or_else(|| Problem::unknown(key))?;
        from_text(p.unit, text)
    }

    /// Take `keys`' values from `other`, then check the machine: a
    /// coalition of keys changed, as an attribution changes them.
    ///
    /// # Errors
    /// An unknown key, or the machine the change makes that cannot run:
    /// the key and the problem.
    pub(crate) fn take(&mut self, keys: &[&str], other: &Self) -> Result<(), (String, Problem)> {
        for &key in keys {
            let p = PARAMS.iter().find(|p| p.key == key).ok_or_else(|| (key.to_owned(), Problem::unknown(key)))?;
            p.assign(self, (p.get)(other)).map_err(|e| (key.to_owned(), e))?;
        }
        self.check().map_err(|(k, e)| (k.to_owned(), e))
    }

    /// When this machine calls itself by a bundled architecture's name but
    /// is not that machine (a copied file, edited): the keys that differ.
    /// `None` for a name of its own, or the bundled machine itself.
    ///
    /// ```
    /// use umbra_sim::Arch;
    /// let mut copy = Arch::bundled("mobile-tbdr")?;
    /// assert_eq!(copy.namesake_differences(), None);
    /// copy.set("dram.bandwidth=10GB/s")?;
    /// assert_eq!(copy.namesake_differences(), Some(vec!["dram.bandwidth"]));
    /// # Ok::<(), umbra_sim::cost::arch::ArchError>(())
    /// ```
    #[must_use]
    pub fn namesake_differences(&self) -> Option<Vec<&'static str>> {
        let original = Self::bundled(&self.name).ok()?;
        let keys: Vec<&'static str> = super::derived::diff(&original, self).0.into_iter().map(|d| d.0).collect();
        (!keys.is_empty()).then_some(keys)
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
    pub(crate) fn check(&self) -> Result<(), (&'static str, Problem)> {
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
        for (keys, c) in [
            (["map_cache.size", "map_cache.line", "map_cache.ways", "map_cache.misses_in_flight"], &self.map_cache),
            (
                ["depth_cache.size", "depth_cache.line", "depth_cache.ways", "depth_cache.misses_in_flight"],
                &self.depth_cache,
            ),
        ] {
            if c.size == 0 {
                continue;
            }
            let [size, line, ways, misses] = keys;
            let range = |key, value: u64, what| Err((key, Problem::Range { value: value as f64, what }));
            #[allow(clippy::cast_precision_loss, reason = "sizes and counts, for the message")]
            {
                if c.size > MAX_CACHE_BYTES {
                    return range(size, c.size, "at most 64 MiB (the model keeps a tag per line)");
                }
                if !c.line.is_power_of_two() || !(MIN_LINE..=MAX_LINE).contains(&c.line) {
                    return range(line, c.line, "a power of two from 16 B to 4 KiB");
                }
                if !(1..=MAX_WAYS).contains(&c.ways) {
                    return range(ways, c.ways, "from 1 to 64");
                }
                if c.misses_in_flight == 0 {
                    return range(misses, c.misses_in_flight, "at least 1");
                }
                if !c.size.is_multiple_of(c.line * c.ways) {
                    return range(size, c.size, "a whole number of sets of `ways` lines");
                }
            }
        }
        Ok(())
    }

    /// The effective architecture as an architecture file: every key with
    /// its value, its meaning and its unit (the record every output
    /// carries; it parses back to the same architecture).
    #[must_use]
    pub fn to_toml(&self) -> String {
        let mut s = format!("format = {}  # the architecture file format this is written for\n", ARCH.current);
        for p in PARAMS {
            let w = p.written(self);
            let value = match p.unit {
                Unit::Text => toml::Value::String(w).to_string(),
                Unit::Flag | Unit::Count | Unit::Number => w,
                _ => format!("\"{w}\""),
            };
            let _ = writeln!(s, "{} = {value}  # {}", p.key, p.doc);
        }
        for c in &self.calibration {
            let _ = writeln!(s, "calibration.\"{}\" = \"{}\"  # fitted to this point", c.key, c.point);
        }
        s
    }
}
