//! Text from users (scene names, skip reasons) as Markdown shows it: a name
//! with `|`, `*` or a newline is written so that it reads as itself and
//! cannot break the table or heading it is written into.

/// `text` escaped for a Markdown heading or table cell: the characters
/// that would end a cell or start HTML (`\ | < >`) behind a backslash, and
/// control characters (a newline would end the heading or the row) as
/// their `\u{…}` escapes. Emphasis and code spans are left as written:
/// they style a cell, they cannot break one.
///
/// ```
/// use umbra_sim::output::markdown::escape;
/// assert_eq!(escape("table-and-sphere"), "table-and-sphere");
/// assert_eq!(escape("a|b\nc"), r"a\|b\u{a}c");
/// ```
#[must_use]
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\\' | '|' | '<' | '>' => {
                out.push('\\');
                out.push(c);
            }
            c if c.is_control() => out.extend(c.escape_unicode()),
            c => out.push(c),
        }
    }
    out
}
