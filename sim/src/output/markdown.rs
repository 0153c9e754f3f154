//! Text from users (scene names, skip reasons) as Markdown shows it: a name
//! with `|`, `*` or a newline is written so that it reads as itself and
//! cannot break the table or heading it is written into.

/// `text` escaped for a Markdown heading or table cell: `|` (which would
/// end a cell) behind a backslash everywhere, code spans included (a
/// table's cells are split before code spans are read); outside code
/// spans, a backslash and a `<` that could open HTML (before a letter, `/`,
/// `!` or `?`) behind one too; control characters (a newline would end the
/// heading or the row) as their `\u{…}` escapes. Emphasis and code spans
/// are left as written: they style a cell, they cannot break one. Text
/// with an unmatched backtick has no code span. (A backslash before a `|`
/// in a code span is doubled too, so the cell still splits where it
/// should.)
///
/// ```
/// use umbra_sim::output::markdown::escape;
/// assert_eq!(escape("table-and-sphere"), "table-and-sphere");
/// assert_eq!(escape("a|b\nc"), r"a\|b\u{a}c");
/// assert_eq!(escape("`box<N>` <b>0.2 > 0.1</b>"), r"`box<N>` \<b>0.2 > 0.1\</b>");
/// assert_eq!(escape(r"`a|b\c` d\e"), r"`a\|b\c` d\\e");
/// ```
#[must_use]
pub fn escape(text: &str) -> String {
    let spans = text.matches('`').count().is_multiple_of(2);
    let mut out = String::with_capacity(text.len());
    let mut code = false;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        let next = chars.peek().copied();
        let opens_html = next.is_some_and(|n| n.is_ascii_alphabetic() || matches!(n, '/' | '!' | '?'));
        match c {
            '`' if spans => {
                code = !code;
                out.push(c);
            }
            '|' => out.push_str("\\|"),
            // In a code span a backslash stays, but not where it would
            // escape the `\|` that keeps a cell's pipe from ending the cell.
            '\\' if !code || next == Some('|') => out.push_str("\\\\"),
            '<' if !code && opens_html => out.push_str("\\<"),
            c if c.is_control() => out.extend(c.escape_unicode()),
            c => out.push(c),
        }
    }
    out
}
