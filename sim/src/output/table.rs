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

#[cfg(test)]
mod tests {
    use super::{Align, Table};

    /// The cell separators of a Markdown line: `|` not behind a backslash
    /// (a backslash itself escaped counts as text).
    fn separators(line: &str) -> usize {
        let (mut n, mut escaped) = (0, false);
        for c in line.chars() {
            match (c, escaped) {
                ('\\', false) => escaped = true,
                ('|', false) => n += 1,
                _ => escaped = false,
            }
        }
        n
    }

    /// Cells of every troublesome character: each Markdown row is one line
    /// of as many cells as the table has columns, and the CSV reads back,
    /// through an independent reader, to the very cells written.
    #[test]
    fn no_cell_breaks_a_row_or_a_record() {
        let parts = ["a", "|", "\n", "\r\n", "\"", ",", "\\", "<b>", "`x|y`", "`", " ", "é", "\\|", "\t"];
        let mut x: u32 = 12_345;
        let mut next = || {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (x >> 16) as usize
        };
        let mut t = Table::new(&[("name | of\nit", Align::Left), ("b", Align::Right), ("c,\"", Align::Left)]);
        let mut rows = Vec::new();
        for _ in 0..2000 {
            let cell = |next: &mut dyn FnMut() -> usize| -> String {
                (0..next() % 5).map(|_| parts[next() % parts.len()]).collect()
            };
            let row = vec![cell(&mut next), cell(&mut next), cell(&mut next)];
            t.row(row.clone());
            rows.push(row);
        }
        let md = t.markdown();
        let lines: Vec<&str> = md.lines().collect();
        assert_eq!(lines.len(), rows.len() + 2, "one line per row");
        assert!(lines.iter().all(|l| separators(l) == 4), "four separators a line");
        let csv = t.csv();
        let mut r = csv::ReaderBuilder::new().has_headers(true).from_reader(csv.as_bytes());
        assert_eq!(r.headers().expect("headers").iter().collect::<Vec<_>>(), ["name | of\nit", "b", "c,\""]);
        let read: Vec<Vec<String>> =
            r.records().map(|rec| rec.expect("a record").iter().map(str::to_owned).collect()).collect();
        assert_eq!(read, rows);
    }

    /// A row too short is filled, one too long cut to the table's width.
    #[test]
    fn every_row_has_the_tables_width() {
        let mut t = Table::new(&[("a", Align::Left), ("b", Align::Left)]);
        t.row(["1"]);
        t.row(["1", "2", "3"]);
        assert_eq!(t.markdown(), "| a | b |\n|---|---|\n| 1 |  |\n| 1 | 2 |\n");
    }
}
