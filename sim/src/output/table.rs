//! Every table Umbra writes, in Markdown or CSV, from one writer: a cell
//! holding a user's text (a folder, a scene, a description with `|`, a
//! newline, a quote or a comma) reads as itself and cannot add a column or
//! split a row.

use super::markdown::escape;

/// How a Markdown column is aligned: text left, numbers right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Align {
    /// Text.
    Left,
    /// Numbers.
    Right,
}

/// A table: its columns and its rows of text cells, written as Markdown
/// ([`Table::markdown`]) or CSV ([`Table::csv`]).
///
/// ```
/// use umbra_sim::output::table::{Align, Table};
/// let mut t = Table::new(&[("folder", Align::Left), ("rows", Align::Right)]);
/// t.row(["a|b\nc", "3"]);
/// assert_eq!(t.markdown(), "| folder | rows |\n|---|---:|\n| a\\|b\\u{a}c | 3 |\n");
/// assert_eq!(t.csv(), "folder,rows\n\"a|b\nc\",3\n");
/// ```
#[derive(Clone, Debug, Default)]
pub struct Table {
    columns: Vec<(String, Align)>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table of `columns` (heading, alignment) and no rows.
    #[must_use]
    pub fn new<S: AsRef<str>>(columns: &[(S, Align)]) -> Self {
        Self { columns: columns.iter().map(|(h, a)| (h.as_ref().to_owned(), *a)).collect(), rows: Vec::new() }
    }

    /// Add a row. Cells past the columns are dropped and missing ones left
    /// empty, so that every row has the table's width.
    pub fn row<I, S>(&mut self, cells: I)
    where
        I: IntoIterator<Item = S>,
        S: Into<String>,
    {
        let mut row: Vec<String> = cells.into_iter().take(self.columns.len()).map(Into::into).collect();
        row.resize(self.columns.len(), String::new());
        self.rows.push(row);
    }

    /// The rows added.
    #[must_use]
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// No row added.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The table in Markdown, each heading and cell escaped, one line per
    /// row, ending in a newline.
    #[must_use]
    pub fn markdown(&self) -> String {
        let line = |cells: &mut dyn Iterator<Item = String>| {
            let mut s = String::from("|");
            for c in cells {
                s.push(' ');
                s.push_str(&c);
                s.push_str(" |");
            }
            s.push('\n');
            s
        };
        let mut s = line(&mut self.columns.iter().map(|(h, _)| escape(h)));
        s.push('|');
        for (_, a) in &self.columns {
            s.push_str(match a {
                Align::Left => "---|",
                Align::Right => "---:|",
            });
        }
        s.push('\n');
        for r in &self.rows {
            s.push_str(&line(&mut r.iter().map(|c| escape(c))));
        }
        s
    }

    /// The table as CSV (RFC 4180: a cell with a comma, quote or newline
    /// quoted), its headings the first record.
    #[must_use]
    pub fn csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        // Writing to memory cannot fail, and every record has one width.
        let _ = w.write_record(self.columns.iter().map(|(h, _)| h.as_str()));
        for r in &self.rows {
            let _ = w.write_record(r);
        }
        String::from_utf8_lossy(&w.into_inner().unwrap_or_default()).into_owned()
    }
}
