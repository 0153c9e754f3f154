//! The public surface is the documented API: every item `umbra-sim` makes
//! public (declared `pub` in a `pub` module, or re-exported with
//! `pub use`) is listed in `docs/api.md`'s table of public items, and
//! every item that table lists is public. Everything else is
//! crate-private, its tests beside it.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// One public item: the module it is public in (`umbra_sim::render`) and
/// its name there.
type Item = (String, String);

/// The kinds of item a `pub` declaration at a module's top level makes.
const KINDS: &[&str] = &["fn", "const fn", "struct", "enum", "trait", "type", "const", "static", "mod"];

/// The name a `pub` declaration on `line` makes public, with its kind.
fn declared(line: &str) -> Option<(&str, String)> {
    let rest = line.strip_prefix("pub ")?;
    KINDS.iter().find_map(|kind| {
        let name = rest.strip_prefix(kind)?.strip_prefix(' ')?;
        let end = name.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(name.len());
        (end > 0).then(|| (*kind, name[..end].to_owned()))
    })
}

/// The names a `use` tree (`a::{b, c::d as e, f::{self, g}}`) brings in.
fn use_leaves(tree: &str) -> Vec<String> {
    let tree: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = Vec::new();
    leaves(&tree, None, &mut out);
    out
}

fn leaves(tree: &str, parent: Option<&str>, out: &mut Vec<String>) {
    let tree = tree.trim();
    if let Some(open) = tree.find('{') {
        let prefix = tree[..open].trim_end_matches("::");
        let inner = &tree[open + 1..tree.rfind('}').expect("a closed group")];
        let last = prefix.rsplit("::").next().filter(|s| !s.is_empty());
        let mut depth = 0;
        let mut start = 0;
        for (i, c) in inner.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    leaves(&inner[start..i], last, out);
                    start = i + 1;
                }
                _ => {}
            }
        }
        leaves(&inner[start..], last, out);
    } else if !tree.is_empty() {
        let name = match tree.split_once(" as ") {
            Some((_, alias)) => alias.trim(),
            None => tree.rsplit("::").next().expect("a segment"),
        };
        out.push(if name == "self" { parent.expect("self in a group").to_owned() } else { name.to_owned() });
    }
}

/// The file a module `name` declared in `file` lives in.
fn module_file(file: &Path, name: &str) -> PathBuf {
    let stem = file.file_stem().and_then(|s| s.to_str()).expect("a file name");
    let dir = file.parent().expect("a folder");
    let dir = if stem == "mod" || stem == "lib" { dir.to_path_buf() } else { dir.join(stem) };
    let flat = dir.join(format!("{name}.rs"));
    if flat.exists() { flat } else { dir.join(name).join("mod.rs") }
}

/// Every item public in the module of `file`, path `module`, and in its
/// public modules. Only top-level lines count (rustfmt leaves items in
/// impls and inline modules indented), but for blocks a declaring macro
/// makes (`pub struct Name from (…)`).
fn public_items(file: &Path, module: &str, out: &mut BTreeSet<Item>) {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let top = line.trim_start();
        let macro_block = line.starts_with("    pub struct ") && top.contains(" from (");
        if let Some(tree) = line.strip_prefix("pub use ") {
            let mut statement = String::from(tree);
            while !statement.contains(';') {
                i += 1;
                statement.push(' ');
                statement.push_str(lines[i]);
            }
            for name in use_leaves(statement.trim_end_matches(';')) {
                out.insert((module.to_owned(), name));
            }
        } else if let Some((kind, name)) = declared(if macro_block { top } else { line }) {
            if kind == "mod" {
                assert!(line.ends_with(';'), "{}: inline public module `{name}`", file.display());
                public_items(&module_file(file, &name), &format!("{module}::{name}"), out);
            }
            out.insert((module.to_owned(), name));
        }
        i += 1;
    }
}

/// The items `docs/api.md`'s table of public items lists: each row a
/// module and its items, each in backticks.
fn documented(api: &str) -> BTreeSet<Item> {
    let table = api.split("## Every public item").nth(1).expect("docs/api.md has `## Every public item`");
    let table = table.split("\n## ").next().unwrap_or(table);
    let mut out = BTreeSet::new();
    for row in table.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let module = cells[1].trim_matches('`');
        for name in cells[2].split(", ") {
            out.insert((module.to_owned(), name.trim().trim_matches('`').to_owned()));
        }
    }
    out
}

#[test]
fn the_public_items_are_the_documented_ones() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut public = BTreeSet::new();
    public_items(&root.join("sim/src/lib.rs"), "umbra_sim", &mut public);
    let api = std::fs::read_to_string(root.join("docs/api.md")).expect("docs/api.md");
    let listed = documented(&api);
    let undocumented: Vec<_> = public.difference(&listed).map(|(m, n)| format!("{m}::{n}")).collect();
    let stale: Vec<_> = listed.difference(&public).map(|(m, n)| format!("{m}::{n}")).collect();
    assert!(
        undocumented.is_empty() && stale.is_empty(),
        "public but not in docs/api.md's table: {undocumented:?}\nin the table but not public: {stale:?}"
    );
    // 20 names at the root and about 190 in the modules; a scanner that
    // stopped reading would find far fewer.
    assert!(public.len() > 150, "{} public items", public.len());
}

#[test]
fn use_trees_are_read_leaf_by_leaf() {
    assert_eq!(use_leaves("a::{B, c::D as E, f::{self, G}}"), ["B", "E", "f", "G"]);
    assert_eq!(use_leaves("umbra_core as core"), ["core"]);
    assert_eq!(declared("pub const fn name(self)"), Some(("const fn", "name".to_owned())));
    assert_eq!(declared("pub(crate) fn hidden()"), None);
}
