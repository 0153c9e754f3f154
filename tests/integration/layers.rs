//! Layers that point one way: every `crate::` or `super::` path in
//! `umbra-core` and `umbra-sim` names a module of a lower layer than its
//! own (or its own), and no two sibling modules (files or folders) import
//! each other, however deep.
//! The layers are those `ARCHITECTURE.md` states.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// `umbra-core`'s layers, bottom first.
const CORE: &[&[&str]] = &[
    &["budget", "grid", "spelling"],
    &["round", "probe", "config"],
    &["depth"],
    &["front"],
    &["raster"],
    &["light_pass"],
    &["shadow"],
    &["silhouette", "stencil"],
    &["shade"],
];

/// `umbra-sim`'s layers, bottom first.
const SIM: &[&[&str]] =
    &[&["base"], &["input", "output"], &["world"], &["pass", "cost", "truth"], &["render"], &["experiment"]];

/// One import: the importing file's module path and the imported path.
#[derive(Clone, Debug)]
struct Import {
    file: PathBuf,
    from: Vec<String>,
    to: Vec<String>,
}

/// What the crate root re-exports (`pub use module::…::{A, B}` in
/// `lib.rs`): each name and the module it comes from.
fn root_exports(src: &Path) -> BTreeMap<String, String> {
    let lib = std::fs::read_to_string(src.join("lib.rs")).expect("lib.rs");
    let mut names = BTreeMap::new();
    for item in lib.split(';') {
        let Some(path) = item.trim().strip_prefix("pub use ") else { continue };
        let module = path.split("::").next().unwrap_or_default().trim().to_owned();
        let tail = path.rsplit("::").next().unwrap_or_default();
        for name in tail.trim_matches(|c| c == '{' || c == '}').split([',', '{', '}']) {
            let name = name.split(" as ").last().unwrap_or_default().trim();
            if !name.is_empty() {
                names.insert(name.to_owned(), module.clone());
            }
        }
    }
    names
}

/// The module path of `file` under `src` (`a/b/mod.rs` is `[a, b]`).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).expect("under src");
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap_or_default();
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_owned());
    }
    parts
}

/// The paths `text` (one source file, comments removed) names through
/// `crate::` or `super::`, resolved against `module`; groups
/// (`crate::{a, b::c}`) give one path per item.
fn imports(module: &[String], text: &str) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let rest = &text[i..];
        let (base, skip) = if rest.starts_with("crate::") && !text[..i].ends_with("::") && !ident_before(text, i) {
            (vec!["crate".to_owned()], "crate::".len())
        } else if rest.starts_with("super::") && !text[..i].ends_with("::") && !ident_before(text, i) {
            let mut base = [&["super".to_owned()], module].concat();
            let mut j = i;
            while text[j..].starts_with("super::") {
                if base.len() > 1 {
                    base.pop();
                }
                j += "super::".len();
            }
            (base, j - i)
        } else {
            i += rest.chars().next().map_or(1, char::len_utf8);
            continue;
        };
        i += skip;
        let tail = &text[i..];
        for item in path_items(tail) {
            let mut path = base.clone();
            path.extend(item.split("::").map(str::trim).filter(|s| !s.is_empty() && *s != "self").map(str::to_owned));
            found.push(path);
        }
    }
    found
}

fn ident_before(text: &str, i: usize) -> bool {
    text[..i].chars().next_back().is_some_and(|c| c.is_alphanumeric() || c == '_')
}

/// The items of the path that starts `tail`: one path, or a group's items.
fn path_items(tail: &str) -> Vec<String> {
    let head: String = tail.chars().take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':').collect();
    let after = &tail[head.len()..];
    if !after.starts_with('{') {
        return vec![head];
    }
    let (mut depth, mut items, mut current) = (0, Vec::new(), String::new());
    for c in after.chars() {
        match c {
            '{' => {
                depth += 1;
                if depth == 1 {
                    continue;
                }
            }
            '}' => {
                depth -= 1;
                if depth == 0 {
                    items.push(format!("{head}{}", current.trim()));
                    break;
                }
                continue;
            }
            ',' if depth == 1 => {
                items.push(format!("{head}{}", current.trim()));
                current.clear();
                continue;
            }
            _ => {}
        }
        if depth >= 2 {
            continue;
        }
        current.push(c);
    }
    items.into_iter().map(|s| s.split('{').next().unwrap_or_default().to_owned()).collect()
}

/// Every import of every `.rs` file under `src`, comments left out.
fn scan(src: &Path) -> Vec<Import> {
    let exports = root_exports(src);
    let mut out = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("a source folder") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path).expect("a source file");
                let code: String =
                    text.lines().map(|l| l.split("//").next().unwrap_or_default()).collect::<Vec<_>>().join("\n");
                let from = module_of(src, &path);
                for mut to in imports(&from, &code) {
                    let how = to.remove(0);
                    let first = to.first().cloned().unwrap_or_default();
                    if src.join(&first).is_dir() || src.join(format!("{first}.rs")).is_file() {
                        out.push(Import { file: path.clone(), from: from.clone(), to });
                    } else if let Some(module) = exports.get(&first).filter(|_| how == "crate") {
                        out.push(Import { file: path.clone(), from: from.clone(), to: vec![module.clone(), first] });
                    }
                    // Otherwise `super::` from an inline module (`mod tests`)
                    // names its own file's items.
                }
            }
        }
    }
    out
}

/// The imports that reach a top-level module of the same or a higher layer.
fn upward(imports: &[Import], layers: &[&[&str]]) -> Vec<String> {
    let layer = |m: &str| layers.iter().position(|l| l.contains(&m));
    let mut bad = Vec::new();
    for i in imports {
        let (Some(a), Some(b)) = (i.from.first(), i.to.first()) else { continue };
        if a == b {
            continue;
        }
        match (layer(a), layer(b)) {
            (Some(la), Some(lb)) if lb < la => {}
            (Some(_), Some(_)) => bad.push(format!("{}: {a} imports {}", i.file.display(), i.to.join("::"))),
            _ => bad.push(format!("{}: {a} → {b}: a module missing from the layer table", i.file.display())),
        }
    }
    bad
}

/// Pairs of sibling modules (files or folders, at any depth, under one
/// parent) that import each other. A module naming its parent's own items
/// (`super::Item` from a child of `mod.rs`) imports no sibling.
fn module_cycles(src: &Path, imports: &[Import]) -> Vec<String> {
    let is_module = |m: &[String]| {
        let path = src.join(m.iter().collect::<PathBuf>());
        path.is_dir() || path.with_extension("rs").is_file()
    };
    let mut edges: BTreeMap<Vec<String>, BTreeMap<Vec<String>, PathBuf>> = BTreeMap::new();
    for i in imports {
        let common = i.from.iter().zip(&i.to).take_while(|(a, b)| a == b).count();
        if common >= i.from.len() || common >= i.to.len() {
            continue;
        }
        let (a, b) = (i.from[..=common].to_vec(), i.to[..=common].to_vec());
        if is_module(&a) && is_module(&b) {
            edges.entry(a).or_default().entry(b).or_insert_with(|| i.file.clone());
        }
    }
    let mut cycles = Vec::new();
    for (a, tos) in &edges {
        for (b, file) in tos {
            if let Some(back) = edges.get(b).and_then(|t| t.get(a))
                && a < b
            {
                let shown = |f: &Path| f.strip_prefix(src).unwrap_or(f).display().to_string();
                cycles.push(format!("{} ⇄ {} ({} and {})", a.join("::"), b.join("::"), shown(file), shown(back)));
            }
        }
    }
    cycles
}

fn src(krate: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(krate).join("src")
}

/// No upward import and no two modules importing each other in `krate`'s
/// source.
fn assert_layered(krate: &str, layers: &[&[&str]]) {
    let found = scan(&src(krate));
    assert!(found.len() > 100, "the scan found {} imports: it is not reading {krate}", found.len());
    assert_eq!(upward(&found, layers), Vec::<String>::new());
    assert_eq!(module_cycles(&src(krate), &found), Vec::<String>::new(), "modules that import each other");
}

#[test]
fn the_core_imports_only_downwards() {
    assert_layered("core", CORE);
}

#[test]
fn the_simulator_imports_only_downwards() {
    assert_layered("sim", SIM);
}

/// The checker itself: an upward import, a group, `super::` and a comment.
#[test]
fn the_check_sees_an_upward_import() {
    let pass = vec!["pass".to_owned(), "light".to_owned()];
    let text =
        "use crate::{world::scene::Draw, render::{a, b}};\nuse super::super::cost::x;\nlet y = crate::input::f();";
    let paths = imports(&pass, text);
    let names: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(names, ["crate::world::scene::Draw", "crate::render", "super::cost::x", "crate::input::f"]);
    let found: Vec<Import> =
        paths.into_iter().map(|to| Import { file: "x.rs".into(), from: pass.clone(), to: to[1..].to_vec() }).collect();
    let bad = upward(&found, SIM);
    assert_eq!(bad.len(), 2, "render and cost sit above pass: {bad:?}");
    // A comment naming an upper layer is not an import.
    let code: String = "// crate::render::x".split("//").next().unwrap_or_default().to_owned();
    assert!(imports(&pass, &code).is_empty());
}

/// The checker itself: two files that import each other are a cycle, a
/// file naming its parent's items is not.
#[test]
fn the_check_sees_two_modules_importing_each_other() {
    let path = |p: &[&str]| p.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
    let import = |from: &[&str], to: &[&str]| Import { file: "x.rs".into(), from: path(from), to: path(to) };
    let sim = src("sim");
    let one_way = [import(&["world", "scene"], &["world", "occluders", "Occluders"])];
    assert_eq!(module_cycles(&sim, &one_way), Vec::<String>::new());
    let parent = [import(&["world", "scene"], &["world", "Scene"]), import(&["world"], &["world", "scene", "Scene"])];
    assert_eq!(module_cycles(&sim, &parent), Vec::<String>::new(), "a child naming its parent's items");
    let both = [one_way[0].clone(), import(&["world", "occluders"], &["world", "scene", "Scene"])];
    assert_eq!(module_cycles(&sim, &both).len(), 1, "two files importing each other");
}

/// Every `.rs` file under `root`'s folders `within` (their `src/` folders
/// when `src`), relative to `root`.
fn rust_files(root: &Path, within: &[&str], src: bool) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else { return };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() && !p.ends_with("target") {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    let mut out = Vec::new();
    for folder in within {
        walk(&if src { root.join(folder).join("src") } else { root.join(folder) }, &mut out);
    }
    out.iter().filter_map(|p| p.strip_prefix(root).ok().map(Path::to_path_buf)).collect()
}

/// Whether `doc` names source file `file`: by its file name, or — a
/// module's `mod.rs`, a crate's `lib.rs` or `main.rs` — by its folder
/// (`probe/`; a crate's root by the crate's, `hosts/demo/`).
fn names(doc: &str, file: &Path) -> bool {
    let name = file.file_name().and_then(|n| n.to_str()).unwrap_or_default();
    let word = |w: &str| {
        doc.match_indices(w).any(|(i, _)| {
            let before = doc[..i].chars().next_back();
            !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
        })
    };
    if ["mod.rs", "lib.rs", "main.rs"].contains(&name) {
        let folder = file.parent().unwrap_or(Path::new(""));
        let last = folder.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        // A crate's root by the crate's folder (`hosts/demo/`), a module's by its own.
        let named = if last == "src" { folder.parent().unwrap_or(folder) } else { folder };
        let short = named.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        return word(&format!("{}/", named.to_string_lossy())) || (last != "src" && word(&format!("{short}/")));
    }
    word(name)
}

/// The `.rs` files `doc` names that no crate's source holds.
fn stale(doc: &str, files: &[PathBuf]) -> Vec<String> {
    let held: std::collections::BTreeSet<String> =
        files.iter().filter_map(|f| f.file_name().and_then(|n| n.to_str()).map(str::to_owned)).collect();
    let mut named: Vec<String> = doc
        .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '.'))
        .filter(|w| w.ends_with(".rs") && w.len() > 3)
        .map(str::to_owned)
        .filter(|w| !held.contains(w))
        .collect();
    named.sort();
    named.dedup();
    named
}

/// `ARCHITECTURE.md` names every source file of every crate (a module's
/// folder for its `mod.rs`), and no file that does not exist.
#[test]
fn the_architecture_page_names_every_source_file_and_no_other() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let crates = ["core", "sim", "hosts/cli", "hosts/demo", "hosts/llvmpipe", "hosts/cortex-m", "python"];
    let files = rust_files(root, &crates, true);
    assert!(files.len() > 120, "found {} source files: the walk is not reading the crates", files.len());
    let missing: Vec<String> =
        files.iter().filter(|f| !names(&doc, f)).map(|f| f.to_string_lossy().into_owned()).collect();
    assert_eq!(missing, Vec::<String>::new(), "source files ARCHITECTURE.md does not name");
    // Tests, benches and examples may be named too.
    let all = [files, rust_files(root, &["tests", "benches", "examples", "fuzz", "hosts/cli/tests"], false)].concat();
    assert_eq!(stale(&doc, &all), Vec::<String>::new(), "files ARCHITECTURE.md names that do not exist");
}

/// The check itself: a page without a file's name misses it, and a name
/// of no file is stale.
#[test]
fn the_architecture_check_sees_a_missing_and_a_stale_file() {
    let files = [PathBuf::from("sim/src/render/replay.rs"), PathBuf::from("core/src/probe/mod.rs")];
    assert!(!names("render/ holds pictures.rs", &files[0]));
    assert!(names("render/ holds replay.rs", &files[0]));
    assert!(!names("the unreplay.rs file", &files[0]));
    assert!(names("probe/ (events)", &files[1]));
    assert_eq!(stale("see report.rs and replay.rs", &files), ["report.rs"]);
}
