//! The documentation cannot go stale. Every figure in `README.md` and
//! `docs/*.md` sits in a block that names the `umbra` command printing it:
//!
//! ````text
//! <!-- figure: umbra render --out target/figures/render-default -->
//! ```text
//! …what that command prints…
//! ```
//! <!-- /figure -->
//! ````
//!
//! and every picture in a line `<!-- picture: target/figures/… -> docs/… -->`
//! that names the file such a command wrote. This test runs each command
//! and holds each block, and each picture, to what the current code
//! writes; `UPDATE_FIGURES=1 cargo test -p umbra-cli --test docs` writes
//! them instead. The one part of an output that names the commit it was
//! built from, the version's `(git …)`, is written as `(git <revision>)`:
//! a page cannot hold the revision of the commit that holds it. Every other `cargo umbra …` line in a shell block is held
//! to the command line's grammar (run with `--help` appended, so nothing
//! runs): a flag or a value the command no longer takes fails here.

#[path = "docs/commands.rs"]
mod commands;
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root, where the documented commands run.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().expect("the workspace")
}

/// README.md and every page of the guide.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![root().join("README.md")];
    let mut guide: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    guide.sort();
    pages.extend(guide);
    pages
}

/// One figure block: the command and the text between its fences (or, for
/// Markdown a command prints, between its markers).
struct Figure {
    command: String,
    /// Byte range of the text inside the fences.
    body: std::ops::Range<usize>,
}

const OPEN: &str = "<!-- figure: ";
const CLOSE: &str = "<!-- /figure -->";

fn figures(text: &str, page: &Path) -> Vec<Figure> {
    let mut out = Vec::new();
    let mut at = 0;
    while let Some(start) = text[at..].find(OPEN).map(|k| k + at) {
        let line_end = text[start..].find("-->").map(|k| k + start).expect("a figure marker ends with -->");
        let command = text[start + OPEN.len()..line_end].trim().to_owned();
        let close = text[line_end..].find(CLOSE).map(|k| k + line_end);
        let Some(close) = close else { panic!("{}: the figure `{command}` has no {CLOSE}", page.display()) };
        // In a ```text block, or (Markdown the command prints, a table)
        // as it is between the markers.
        let fence = text[line_end..close].find("```text\n").map(|k| k + line_end + "```text\n".len());
        let (body_start, body_end) = match fence {
            Some(start) => (start, text[..close].rfind("```").expect("a closing fence")),
            None => (line_end + "-->\n".len(), close),
        };
        assert!(body_start <= body_end, "{}: the figure `{command}` is malformed", page.display());
        out.push(Figure { command, body: body_start..body_end });
        at = close + CLOSE.len();
    }
    out
}

/// Run a documented `umbra …` command from the workspace root; its stdout.
fn run(command: &str) -> String {
    let args: Vec<&str> = command.split_whitespace().collect();
    assert_eq!(args.first(), Some(&"umbra"), "a figure's command starts with `umbra`: {command}");
    let out = Command::new(env!("CARGO_BIN_EXE_umbra"))
        .args(&args[1..])
        .current_dir(root())
        .env("RUST_BACKTRACE", "0")
        .output()
        .expect("the command runs");
    assert!(out.status.success(), "`{command}` failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// `text` with every `(git <hex>[-modified])` written `(git <revision>)`.
fn without_revision(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("(git ") {
        let after = &rest[at + "(git ".len()..];
        let end = after.find(')').unwrap_or(after.len());
        let rev = &after[..end];
        let hex = rev.trim_end_matches("-modified");
        out.push_str(&rest[..at]);
        if !hex.is_empty() && hex.chars().all(|c| c.is_ascii_hexdigit()) {
            out.push_str("(git <revision>)");
        } else {
            out.push_str(&rest[at..at + "(git ".len() + end + usize::from(end < after.len())]);
        }
        rest = &after[(end + 1).min(after.len())..];
    }
    out.push_str(rest);
    out
}

/// `target/figures/x.png -> docs/x.png` lines: a written picture and where
/// the guide keeps it.
fn pictures(text: &str) -> Vec<(PathBuf, PathBuf)> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix("<!-- picture: ")?.strip_suffix("-->"))
        .map(|l| {
            let (from, to) = l.split_once("->").expect("`from -> to`");
            (root().join(from.trim()), root().join(to.trim()))
        })
        .collect()
}

/// Whether a figure's command reads Debian's scene data (a path under
/// `/usr/share/`), which a fresh clone's machine may lack.
fn reads_system_data(command: &str) -> bool {
    command.split_whitespace().any(|w| w.starts_with("/usr/share/"))
}

/// The `--out` folder a figure's command writes, relative to the root.
fn out_folder(command: &str) -> Option<&str> {
    let words: Vec<&str> = command.split_whitespace().collect();
    words.windows(2).find(|w| w[0] == "--out").map(|w| w[1])
}

#[test]
fn every_documented_figure_is_what_the_code_prints() {
    check_figures(false);
}

/// The figures of Debian's scene data, which the test above leaves out.
#[test]
#[ignore = "needs Debian's assimp-testmodels: run with `cargo test --workspace --test docs -- --ignored`"]
fn the_figures_of_debian_scene_data_are_what_the_code_prints() {
    check_figures(true);
}

/// Hold every figure and picture to what the code writes: those whose
/// command reads system data when `system_data`, else all the others.
fn check_figures(system_data: bool) {
    let update = std::env::var_os("UPDATE_FIGURES").is_some();
    let mut stale = Vec::new();
    let mut count = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        let mut fresh = text.clone();
        let all = figures(&text, &page);
        // The folders of the figures this run leaves to the other.
        let elsewhere: Vec<&str> = all
            .iter()
            .filter(|f| reads_system_data(&f.command) != system_data)
            .filter_map(|f| out_folder(&f.command))
            .collect();
        // Back to front, so earlier ranges stay valid while rewriting.
        for f in all.iter().rev().filter(|f| reads_system_data(&f.command) == system_data) {
            count += 1;
            let printed = without_revision(&run(&f.command));
            if text[f.body.clone()] != printed {
                stale.push(format!("{}: `{}`", page.display(), f.command));
                fresh.replace_range(f.body.clone(), &printed);
            }
        }
        for (written, kept) in pictures(&text) {
            if elsewhere.iter().any(|folder| written.starts_with(root().join(folder))) {
                continue;
            }
            let now = std::fs::read(&written).unwrap_or_else(|e| panic!("{}: {e}", written.display()));
            if std::fs::read(&kept).ok().as_deref() != Some(now.as_slice()) {
                stale.push(format!("{}: {}", page.display(), kept.display()));
                if update {
                    std::fs::write(&kept, &now).expect("the picture is written");
                }
            }
        }
        if update && fresh != text {
            std::fs::write(&page, fresh).expect("the page is written");
        }
    }
    assert!(
        count >= if system_data { 1 } else { 5 },
        "only {count} figures: the README and the guide show what the tool prints"
    );
    assert!(update || stale.is_empty(), "stale (UPDATE_FIGURES=1 rewrites them):\n{}", stale.join("\n"));
}

/// The lines of a page's shell blocks, in order, each without its
/// trailing comment.
fn shell_lines(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut shell = false;
    for line in text.lines() {
        let t = line.trim();
        if t.starts_with("```") {
            shell = matches!(t, "```sh" | "```bash" | "```shell" | "```console");
            continue;
        }
        if shell {
            out.push(t.split(" #").next().unwrap_or_default().trim());
        }
    }
    out
}

/// The `cargo umbra …` lines of a page's shell blocks, without `cargo`.
fn commands(text: &str) -> Vec<String> {
    shell_lines(text)
        .into_iter()
        .filter_map(|t| t.strip_prefix("cargo umbra").map(|rest| format!("umbra{rest}")))
        .collect()
}

#[test]
fn every_documented_command_is_one_umbra_takes() {
    let mut seen = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        for command in commands(&text) {
            seen += 1;
            // Words the shell would expand are left as they are: a
            // documented command is written out in full.
            let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
            args.push("--help");
            let out = common::umbra(&args);
            assert!(
                out.status.success(),
                "{}: `{command}` is not a command umbra takes: {}",
                page.display(),
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
    assert!(seen >= 5, "only {seen} documented commands");
}

/// The checker itself: a stale flag fails, and a block is found.
#[test]
fn the_checks_catch_a_stale_flag_and_find_a_block() {
    let out = common::umbra(&["render", "--filter", "box99", "--help"]);
    assert!(!out.status.success(), "a bad value before --help is refused");
    let out = common::umbra(&["render", "--no-such-flag", "--help"]);
    assert!(!out.status.success(), "an unknown flag before --help is refused");
    let page = "a\n<!-- figure: umbra depth --out x -->\n```text\nold\n```\n<!-- /figure -->\nb";
    let f = figures(page, Path::new("page.md"));
    assert_eq!(f.len(), 1);
    assert_eq!((f[0].command.as_str(), &page[f[0].body.clone()]), ("umbra depth --out x", "old\n"));
    assert_eq!(
        commands("```sh\ncargo umbra cost --arch a.toml   # note\n```\ncargo umbra no"),
        ["umbra cost --arch a.toml"]
    );
}

/// A file a page shows after `<!-- file: PATH -->` is the file the
/// repository ships at PATH, byte for byte.
#[test]
fn every_file_a_page_shows_is_the_shipped_file() {
    const MARK: &str = "<!-- file: ";
    let mut seen = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        for (at, _) in text.match_indices(MARK) {
            let rest = &text[at + MARK.len()..];
            let path = rest.split(" -->").next().expect("a marker ends with -->");
            let open = rest.find("```").expect("a block follows the marker");
            let body = &rest[open..];
            let start = body.find('\n').expect("a fence line") + 1;
            let end = body[start..].find("\n```").expect("a closing fence") + start + 1;
            let shipped = std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"));
            assert_eq!(&body[start..end], shipped, "{}: the block shown as {path}", page.display());
            seen += 1;
        }
    }
    assert!(seen >= 3, "only {seen} shipped files shown");
}

/// `docs/study.md`'s table of what a study writes names every file a
/// study writes: a study of the shipped sweep at small sizes, each file's
/// name with its scene written `<scene>` and its architecture `<name>`,
/// against the table's names (`a.svg/.png` standing for both).
#[test]
fn the_study_page_lists_every_file_a_study_writes() {
    let out = common::dir("docs-study-files");
    let sweep = root().join("examples/sweep.toml");
    let args = ["study", "--sweep", sweep.to_str().expect("UTF-8"), "--image", "64x36", "--maps", "64"];
    let o = common::umbra(&[&args[..], &["--reference-rays", "1", "--out", out.to_str().expect("UTF-8")]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = std::fs::read_to_string(root().join("docs/study.md")).expect("the page");
    let table = page.split("Under `out/study/`").nth(1).expect("the table");
    let mut listed: Vec<String> = Vec::new();
    for line in table.lines().skip_while(|l| !l.starts_with('|')).take_while(|l| l.starts_with('|')) {
        let cell = line.split('|').nth(1).unwrap_or_default();
        for name in cell.split('`').skip(1).step_by(2) {
            match name.split_once("/.") {
                Some((base, second)) => {
                    let stem = base.rsplit_once('.').map_or(base, |(s, _)| s);
                    listed.extend([base.to_owned(), format!("{stem}.{second}")]);
                }
                None => listed.push(name.to_owned()),
            }
        }
    }
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .expect("the folder")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('.'))
        .collect();
    names.sort();
    for name in names {
        let shape = name.replace("table-and-sphere", "<scene>").replace("sphere-over-a-wall", "<scene>");
        let shape = if shape.starts_with("arch-") && !shape.starts_with("arch-axes-") {
            "arch-<name>.toml".to_owned()
        } else {
            shape
        };
        assert!(listed.contains(&shape), "{name} (as {shape}) is not in docs/study.md's table: {listed:?}");
    }
    let _ = std::fs::remove_dir_all(&out);
}

/// The README's and the guide's commands, run one after another in any
/// order, lose no file: no folder is written by two kinds of command
/// (which the second would refuse, or with `--replace` replace). Each
/// command's folder is its `--out`, else its own default.
#[test]
fn no_two_documented_commands_of_different_kinds_share_a_folder() {
    use std::collections::BTreeMap;
    use umbra_sim::output::folder::RunKind;
    // Where each subcommand writes by default.
    let defaults = [
        ("depth", "out/depth"),
        ("render", "out/render"),
        ("cost", "out/cost"),
        ("trace", "out/trace"),
        ("correlate", "out/correlate"),
        ("study", "out/study"),
        ("merge", "out/study"),
        ("plan", "out/plan"),
        ("scene", "out/scene-city"),
    ];
    let mut folders: BTreeMap<String, (RunKind, String)> = BTreeMap::new();
    let mut seen = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        for command in commands(&text) {
            let words: Vec<&str> = command.split_whitespace().collect();
            // The kind the library reads from the command line.
            let (Some(kind), Some(&(_, default))) =
                (RunKind::of_command(&command), defaults.iter().find(|(sub, _)| words.get(1) == Some(sub)))
            else {
                continue;
            };
            if words.get(2) == Some(&"upgrade") {
                continue;
            }
            let folder = out_folder(&command).unwrap_or(default).trim_end_matches('/').to_owned();
            seen += 1;
            if let Some((other, first)) = folders.get(&folder) {
                assert!(
                    *other == kind,
                    "{folder} is written by `{first}` ({other:?}) and by `{command}` ({kind:?}) in {}",
                    page.display()
                );
            } else {
                folders.insert(folder, (kind, command.clone()));
            }
        }
    }
    assert!(seen >= 40, "only {seen} documented commands write a folder");
}
