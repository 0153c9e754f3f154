//! The format versions of the files users write: each kind of file
//! (architecture, scene, sweep) has a current version, a file may state
//! the one it was written for (`format = 2` at its top), and a file from
//! an earlier version keeps loading. `upgrade` rewrites a file's text for
//! the current version: the stated version, and any keys it lacks with
//! the values that keep what it meant, each with its meaning as a comment;
//! everything the user wrote, comments included, stays as it was.
//!
//! ```
//! use umbra_sim::input::format::{ARCH, SWEEP};
//! assert_eq!(ARCH.stated(None), Ok(1));
//! assert!(SWEEP.stated(Some(i64::from(SWEEP.current) + 1)).is_err());
//! assert!(SWEEP.stated(Some(-1)).unwrap_err().contains("format -1"));
//! let text = SWEEP.upgrade("name = \"mine\" # my sweep\n", &[]).expect("TOML");
//! assert_eq!(text, format!("format = {}  # upgraded from format 1\nname = \"mine\" # my sweep\n", SWEEP.current));
//! // A header comment stays first.
//! let text = SWEEP.upgrade("# my sweep\nname = \"mine\"\n", &[]).expect("TOML");
//! assert!(text.starts_with("# my sweep\nformat = "));
//! ```

use toml_edit::{DocumentMut, Item, Table, Value};

/// One kind of file and its current format version.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Format {
    /// What the files are (`architecture`), for messages.
    pub kind: &'static str,
    /// The version this build writes and reads up to.
    pub current: u32,
}

/// Architecture files. Version 2 added `front.frame_overhead_cycles`,
/// `depth.program_cycles`, `depth.peel_cycles`, `depth.combine_cycles`,
/// `shadow.cycles_per_sample`, `shadow.cycles_per_weights` and
/// `shade.per_fragment`; version 3 the `[technology]` table (node, SRAM
/// bit cell, array efficiency, gate, leakage).
pub const ARCH: Format = Format { kind: "architecture", current: 3 };
/// Scene files: one version so far.
pub const SCENE: Format = Format { kind: "scene", current: 1 };
/// Sweep files. Version 2 takes an architecture axis's values as numbers
/// and flags as well as text; version 3 takes budgets on any measure
/// (`"acne=0.01%"`) beside numbers for artifacts.
pub const SWEEP: Format = Format { kind: "sweep", current: 3 };

/// A key an upgrade adds: its dotted path, its value, and the comment
/// written after it.
pub struct Added {
    /// The dotted key (`depth.program_cycles`).
    pub key: &'static str,
    /// Its value.
    pub value: Value,
    /// What it means, and why this value.
    pub comment: String,
}

impl Format {
    /// The version a file states (`format`, as written), 1 when it
    /// states none.
    ///
    /// # Errors
    /// The problem, naming the version as written, for a version below 1
    /// or one newer than this build reads.
    pub fn stated(&self, format: Option<i64>) -> Result<u32, String> {
        match format.unwrap_or(1) {
            v if v < 1 => Err(format!("format {v}: format versions start at 1")),
            v if v > i64::from(self.current) => Err(format!(
                "the file is written for {} file format {v}; this umbra reads formats 1 to {} (a later release reads it)",
                self.kind, self.current
            )),
            v => Ok(u32::try_from(v).unwrap_or(u32::MAX)),
        }
    }

    /// `text` for the current version: `format` set (for a file that had
    /// none, after its header comment and before its first key), each of
    /// `added` that the file lacks put in its
    /// table with its comment; the rest of the text as it was. Applied to
    /// its own output it changes nothing.
    ///
    /// # Errors
    /// The TOML parser's message, for text that is not TOML.
    pub fn upgrade(&self, text: &str, added: &[Added]) -> Result<String, String> {
        let mut doc: DocumentMut = text.parse().map_err(|e: toml_edit::TomlError| e.to_string())?;
        let current = i64::from(self.current);
        let stated = doc.contains_key("format");
        if stated && doc.get("format").and_then(Item::as_integer) != Some(current) {
            doc["format"] = toml_edit::value(current);
        }
        for a in added {
            let (table, leaf) = match a.key.rsplit_once('.') {
                Some((t, leaf)) => (Some(t), leaf),
                None => (None, a.key),
            };
            let t: &mut Table = match table {
                Some(t) => {
                    let item = doc.entry(t).or_insert_with(toml_edit::table);
                    let Some(t) = item.as_table_mut() else { continue };
                    t
                }
                None => doc.as_table_mut(),
            };
            if t.contains_key(leaf) {
                continue;
            }
            let mut value = a.value.clone();
            value.decor_mut().set_suffix(format!("  # {}", a.comment));
            t.insert(leaf, Item::Value(value));
        }
        if stated {
            return Ok(doc.to_string());
        }
        // A key before every table, as TOML needs it; after the file's
        // header comment, which stays first, and saying what it was.
        let text = doc.to_string();
        let header: usize = text
            .split_inclusive('\n')
            .take_while(|l| l.trim().is_empty() || l.trim_start().starts_with('#'))
            .map(str::len)
            .sum();
        let (head, rest) = text.split_at(header);
        Ok(format!("{head}format = {current}  # upgraded from format 1\n{rest}"))
    }
}
