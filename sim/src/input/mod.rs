//! What the simulator reads in: the limits every input is read within
//! ([`limits`]), the files' format versions ([`format`](mod@format)), what kind of
//! file a user gave ([`kind`]), and fixed-length arrays read exactly
//! (`exact`).

pub(crate) mod exact;
pub mod format;
pub mod kind;
pub mod limits;

/// Where byte `offset` of a file's `text` is, as an error names it: the
/// line (from 1) and the line's text, so that a message names the key and
/// the value (`line 13, \`values = [180, 360]\``).
#[must_use]
pub(crate) fn at_line(text: &str, offset: usize) -> String {
    let before = text.get(..offset).unwrap_or(text);
    let number = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |k| k + 1);
    let line = text.get(start..).unwrap_or("").lines().next().unwrap_or("").trim();
    let shown: String = line.chars().take(80).collect();
    let more = if shown.len() < line.len() { "…" } else { "" };
    if shown.is_empty() { format!("line {number}") } else { format!("line {number}, `{shown}{more}`") }
}
