//! The rows' schema: every column of `results.csv` (and field of
//! `results.jsonl`) with its type, unit and meaning, written beside the
//! rows as `schema.csv` so that a script needs no documentation to read
//! them.

use crate::output::table::{Align, Table};

use super::RowCost;
use super::row::RowMetrics;
use crate::cost::arch::{PARAMS, column as arch_column};
use crate::render::params::RenderParam;

/// One column: name, type (`integer`, `number`, `text`, `boolean`), unit
/// (`-` for none) and meaning. An empty cell is a value that does not apply
/// to the row (or a skipped row's measurement).
pub(crate) use super::row::Column;

/// Where a column is declared: here; (a configuration's) as a render
/// parameter ([`PARAMS`](crate::render::params::PARAMS), by name), whose column,
/// type, unit and meaning it takes; or (a measurement's) in a row block,
/// [`RowMetrics`] or [`RowCost`], beside the value it holds.
enum Declared {
    Own(&'static str, &'static str, &'static str, &'static str),
    Param(&'static str),
    Block(&'static [Column]),
}

/// Every fixed column, in the order the rows hold them; the architecture
/// axes' columns (`arch_<key>_<unit>`) follow `arch_params`.
const DECLARED: &[Declared] = &[
    Declared::Own("config_index", "integer", "-", "the configuration's position in the sweep"),
    Declared::Own("arch_index", "integer", "-", "the architecture point's position in the sweep"),
    Declared::Own("scene", "text", "-", "the scene's name"),
    Declared::Param("algo"),
    Declared::Own(
        "family",
        "text",
        "-",
        "its family: first depth, second depth, midpoint and dual, silhouette map, shadow volumes",
    ),
    Declared::Param("bias"),
    Declared::Param("bias1"),
    Declared::Param("offset"),
    Declared::Param("virtual_samples"),
    Declared::Param("cull"),
    Declared::Param("depth"),
    Declared::Param("map"),
    Declared::Param("filter"),
    Declared::Param("cascades"),
    Declared::Own("arch", "text", "-", "the architecture point's name (- without architectures)"),
    Declared::Own("base_arch", "text", "-", "the architecture it was made from (- without architectures)"),
    Declared::Own("arch_params", "text", "-", "its axis assignments, key=value,… as the sweep file spells them"),
    Declared::Param("width"),
    Declared::Param("height"),
    Declared::Param("reference_rays"),
    Declared::Own("command", "text", "-", "the umbra render command that renders the row again"),
    Declared::Own("umbra_version", "text", "-", "the version that made the row"),
    Declared::Own("sweep_hash", "text", "-", "the sweep file's hash"),
    Declared::Own("status", "text", "-", "ok or skipped"),
    Declared::Own("reason", "text", "-", "why the row was skipped (empty when ok)"),
    Declared::Block(RowMetrics::COLUMNS),
    Declared::Block(RowCost::COLUMNS),
];

/// Every fixed column, in the order the rows hold them, each from its
/// one declaration.
#[must_use]
pub(crate) fn columns() -> Vec<Column> {
    let mut out = Vec::new();
    for d in DECLARED {
        match d {
            &Declared::Own(name, kind, unit, meaning) => out.push((name, kind, unit, meaning)),
            Declared::Param(name) => {
                out.extend(RenderParam::named(name).ok().map(|p| (p.column, p.kind.column_type(), p.unit, p.meaning)))
            }
            Declared::Block(columns) => out.extend_from_slice(columns),
        }
    }
    out
}

/// The unit of an architecture axis's column (`arch_<key>_<unit>`), as
/// its key declares it ([`PARAMS`](crate::cost::arch::PARAMS)); `-`
/// for a key without one, or a column of no key.
pub(crate) fn axis_unit(column: &str) -> &'static str {
    PARAMS.iter().find(|p| arch_column(p.key) == column).map_or("-", |p| p.unit.symbol())
}

/// The schema of rows whose columns are `header`, as `schema.csv`
/// (`column,type,unit,meaning`): each fixed column from `columns`, each
/// architecture axis's (a name starting `arch_` not in the table) as a
/// number in the SI unit its name ends in. A column that is neither has
/// an empty meaning.
#[must_use]
pub fn schema_csv(header: &[String]) -> String {
    let mut t = Table::new(&HEADINGS);
    let columns = columns();
    for h in header {
        match columns.iter().find(|c| c.0 == h) {
            Some(c) => t.row([c.0, c.1, c.2, c.3]),
            None if h.starts_with("arch_") => {
                let meaning = format!("the architecture axis {}, in SI base units (a flag or text as it is)", &h[5..]);
                t.row([h.clone(), "number".to_owned(), axis_unit(h).to_owned(), meaning]);
            }
            None => t.row([h.as_str(), "text", "-", ""]),
        }
    }
    t.csv()
}

/// The schema's headings, in `schema.csv` and the Markdown table alike.
const HEADINGS: [(&str, Align); 4] =
    [("column", Align::Left), ("type", Align::Left), ("unit", Align::Left), ("meaning", Align::Left)];

/// The fixed columns as a Markdown table.
#[must_use]
pub fn markdown() -> String {
    let mut t = Table::new(&HEADINGS);
    for (name, kind, unit, meaning) in columns() {
        t.row([format!("`{name}`"), kind.to_owned(), unit.to_owned(), meaning.to_owned()]);
    }
    t.markdown()
}

#[cfg(test)]
mod tests {
    use crate::render::params::PARAMS;

    /// Every parameter is a column of the study's schema with its unit and
    /// meaning, and the rows' schema holds no configuration column the table
    /// does not declare.
    #[test]
    fn every_parameter_is_a_schema_column() {
        let columns = super::columns();
        for p in PARAMS {
            let c = columns.iter().find(|c| c.0 == p.column).unwrap_or_else(|| panic!("{} has no column", p.name));
            assert_eq!((c.1, c.2, c.3), (p.kind.column_type(), p.unit, p.meaning), "{}", p.name);
        }
        assert_eq!(
            PARAMS.len(),
            13,
            "the parameters: algo, bias1, offset, depth, map, filter, bias, width, height, rays, virtual samples, cull, cascades"
        );
    }
}
