//! An attribution as a person reads it: a row per key's share, ranked,
//! and the whole difference, in Markdown.

use std::fmt::Write as _;

use super::{Attribution, Delta, Method};
use crate::output::table::{Align, Table};

/// Bytes with their sign, as few digits as they need (a share of two
/// keys is a whole or half byte); no sign for none.
fn signed(bytes: f64) -> String {
    if bytes == 0.0 { "0".to_owned() } else { format!("{bytes:+}") }
}

impl Attribution {
    /// The attribution as a Markdown table: a row per player (ranked) and
    /// the total; time in µs and percent of `a`'s, energy in µJ, DRAM bytes
    /// in all and by every purpose that changes.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let purposes: Vec<(usize, &'static str)> = self
            .total
            .bytes_by_purpose
            .iter()
            .enumerate()
            .filter(|(k, _)| {
                self.shares.iter().map(|x| &x.share).chain([&self.total]).any(|d| d.bytes_by_purpose[*k].1 != 0.0)
            })
            .map(|(k, &(n, _))| (k, n))
            .collect();
        let how = match self.method {
            Method::Exact { players, coalitions } => format!(
                "each key's Shapley share, its effect averaged over every order of changing the {players} key(s) ({coalitions} costings)"
            ),
            Method::Sampled { players, permutations, coalitions } => format!(
                "each key's Shapley share, its effect averaged over {permutations} random orders of changing the {players} keys ({coalitions} costings; ± one standard error)"
            ),
        };
        let _ = writeln!(
            s,
            "From `{}` ({:.3} ms) to `{}` ({:.3} ms) on {}, {how}:\n",
            self.a,
            self.a_seconds * 1e3,
            self.b,
            self.b_seconds * 1e3,
            self.config
        );
        let mut columns = vec![
            ("change".to_owned(), Align::Left),
            ("time (µs)".to_owned(), Align::Right),
            ("time".to_owned(), Align::Right),
            ("alone (µs)".to_owned(), Align::Right),
            ("energy (µJ)".to_owned(), Align::Right),
            ("area (µm²)".to_owned(), Align::Right),
            ("DRAM bytes".to_owned(), Align::Right),
        ];
        columns.extend(purposes.iter().map(|(_, n)| (format!("{n} bytes"), Align::Right)));
        let mut t = Table::new(&columns);
        let cells = |what: String, d: &Delta, alone: Option<&Delta>, error: Option<f64>| {
            let time = match error {
                Some(e) => format!("{:+.3} ± {:.3}", d.seconds * 1e6, e * 1e6),
                None => format!("{:+.3}", d.seconds * 1e6),
            };
            let mut cells = vec![
                what,
                time,
                format!("{:+.1} %", 100.0 * d.seconds / self.a_seconds.max(f64::MIN_POSITIVE)),
                alone.map_or_else(String::new, |a| format!("{:+.3}", a.seconds * 1e6)),
                format!("{:+.3}", d.joules * 1e6),
                format!("{:+.0}", d.square_metres * 1e12),
                signed(d.bytes),
            ];
            cells.extend(purposes.iter().map(|&(k, _)| signed(d.bytes_by_purpose[k].1)));
            cells
        };
        for share in &self.shares {
            let what: Vec<String> =
                share.keys.iter().map(|k| format!("`{}` {} → {}", k.key, k.values.0, k.values.1)).collect();
            t.row(cells(what.join(" with "), &share.share, Some(&share.alone), share.standard_error_seconds));
        }
        t.row(cells("**all of them**".to_owned(), &self.total, None, None));
        s.push_str(&t.markdown());
        s
    }
}
