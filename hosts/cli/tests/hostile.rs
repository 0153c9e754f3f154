//! The command against an adversarial user: inputs that would block, a
//! full disk, a closed stdout, a killed run, a stale folder, names that
//! would leave `--out`, and loose values. Each ends in a clear error or a
//! folder that tells the truth about itself.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use umbra_sim::output::folder::{MANIFEST, PENDING, RunManifest};

mod common;
use common::{dir, umbra};

fn text(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 temp path")
}

fn command(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_umbra"));
    c.args(args).env("RUST_BACKTRACE", "0").env("RUST_LIB_BACKTRACE", "0");
    c
}

/// `umbra` failed, and its message holds each of `needles`.
fn fails_saying(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "succeeded: {}", String::from_utf8_lossy(&o.stdout));
    for n in needles {
        assert!(err.contains(n), "`{n}` missing from: {err}");
    }
}

/// A tiny sweep file (two scenes, three variants, 64×36) in `d`, or with
/// `scenes` in place of its scenes.
fn tiny_sweep(d: &Path, scenes: &str) -> PathBuf {
    std::fs::create_dir_all(d).expect("dir");
    let path = d.join("tiny.toml");
    let text = format!(
        "name = \"tiny\"\nscenes = {scenes}\nimages = [[64, 36]]\nreference_rays = 1\nformats = [\"d24\"]\n\
         maps = [128]\nfilters = [\"point\"]\narchs = [\"talisman\"]\nbudgets = [1.0]\n\
         [[algorithms]]\nalgo = \"first\"\nbias = [0.0, 0.005]\n[[algorithms]]\nalgo = \"second\"\n"
    );
    std::fs::write(&path, text).expect("sweep");
    path
}

/// A FIFO given as any input is refused before it is opened (opening one
/// blocks until a writer comes): each command ends within the time limit.
#[test]
fn a_fifo_never_blocks_an_input() {
    let d = dir("fifo");
    std::fs::create_dir_all(&d).expect("dir");
    let fifo = d.join("pipe.toml");
    assert!(Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs").success());
    let out = d.join("out");
    let f = text(&fifo);
    for args in [
        vec!["render", f, "--out", text(&out)],
        vec!["depth", "--mesh", f, "--out", text(&out)],
        vec!["depth", "--matrix", f, "--out", text(&out)],
        vec!["merge", f, "--out", text(&out)],
        vec!["study", "--sweep", f, "--out", text(&out)],
        vec!["cost", "--arch", f, "--out", text(&out)],
    ] {
        let mut child = command(&args).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().expect("spawns");
        let start = Instant::now();
        while child.try_wait().expect("waits").is_none() {
            if start.elapsed() > Duration::from_secs(60) {
                let _ = child.kill();
                panic!("`umbra {}` blocked on a FIFO", args.join(" "));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        fails_saying(&child.wait_with_output().expect("output"), &["pipe.toml", "not a regular file"]);
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Every write error ends the command non-zero naming what failed: a
/// stdout that is `/dev/full` (ENOSPC), and a file past the size the OS
/// allows this process (EFBIG, `ulimit -f`), after which the folder has no
/// manifest: it does not look complete.
#[test]
fn a_write_error_fails_the_command() {
    let d = dir("full");
    let out = d.join("out");
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full");
    let o = command(&["depth", "--map", "64", "--out", text(&d.join("printed"))]).stdout(full).output().expect("runs");
    fails_saying(&o, &["stdout", "No space left on device"]);
    // 8 KiB of file: the 512² z1.npy (1 MiB) cannot be written. SIGXFSZ is
    // ignored so that the write returns the error.
    let o = Command::new("sh")
        .args(["-c", "trap '' XFSZ; ulimit -f 8; exec \"$0\" \"$@\"", env!("CARGO_BIN_EXE_umbra")])
        .args(["depth", "--map", "512", "--out", text(&out)])
        .env("RUST_BACKTRACE", "0")
        .output()
        .expect("runs");
    fails_saying(&o, &["z1.npy", "File too large"]);
    assert!(!out.join(MANIFEST).exists() && !out.join("z1.npy").exists(), "no half-written output");
    assert!(RunManifest::verify(&out, u64::MAX).is_err());
    let _ = std::fs::remove_dir_all(&d);
}

/// A reader that goes away (`| head`) stops the printing quietly; the run
/// still finishes its folder.
#[test]
fn a_closed_stdout_ends_quietly() {
    let d = dir("pipe");
    let out = d.join("out");
    let mut child = command(&["depth", "--map", "64", "--out", text(&out)])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    drop(child.stdout.take());
    let o = child.wait_with_output().expect("output");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && err.is_empty(), "{:?}: {err}", o.status);
    RunManifest::verify(&out, u64::MAX).expect("the folder is complete");
    let _ = std::fs::remove_dir_all(&d);
}

/// A second run into a folder removes what the first wrote and it does
/// not (a first-depth render leaves no old `z2`; a shard run leaves no
/// summary of a whole run), and keeps the user's own files.
#[test]
fn no_stale_output_survives() {
    let d = dir("stale");
    let out = d.join("out");
    assert!(umbra(&["depth", "--map", "64", "--unit", "dual", "--out", text(&out)]).status.success());
    assert!(out.join("z2.png").exists() && out.join("z2.npy").exists());
    std::fs::write(out.join("notes.txt"), "mine").expect("a user's file");
    let single = ["depth", "--map", "64", "--unit", "single", "--out", text(&out)];
    fails_saying(&umbra(&single), &["notes.txt", "--replace"]);
    assert!(out.join("z2.png").exists(), "a refused run removed a file");
    assert!(umbra(&[&single[..], &["--replace"]].concat()).status.success());
    assert!(!out.join("z2.png").exists() && !out.join("z2.npy").exists(), "stale z2");
    assert!(out.join("notes.txt").exists(), "a file Umbra did not write was removed");
    RunManifest::verify(&out, u64::MAX).expect("complete");
    let sweep = tiny_sweep(&d, r#"["table-and-sphere", "weiskopf-l"]"#);
    let study = d.join("study");
    assert!(umbra(&["study", "--sweep", text(&sweep), "--out", text(&study)]).status.success());
    assert!(study.join("summary.md").exists());
    let o = umbra(&["study", "--sweep", text(&sweep), "--shard", "0/2", "--out", text(&study)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!study.join("summary.md").exists() && !study.join("pareto-table-and-sphere-time.png").exists());
    let m = RunManifest::verify(&study, u64::MAX).expect("complete");
    assert_eq!(m.study.and_then(|s| s.get("shard").cloned()), Some(serde_json::json!("0/2")));
    let _ = std::fs::remove_dir_all(&d);
}

/// No run deletes its input or another command's results: a render of
/// the city `scene city` wrote, into the same folder, is refused (naming
/// the file and `--replace`) and with `--replace` keeps the model; a study
/// into a render's folder and a render into a study's are refused, and
/// nothing is deleted.
#[test]
fn no_run_loses_its_input_or_another_commands_results() {
    let d = dir("inputs");
    let city = d.join("scene-city");
    let o = umbra(&["scene", "city", "--side", "2", "--columns", "2", "--storeys", "2", "--out", text(&city)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let model = city.join("city.glb");
    let glb = std::fs::read(&model).expect("the model");
    let small = ["--width", "96", "--height", "54", "--map", "128", "--reference-rays", "1"];
    let render = |scene: &Path, out: &Path, more: &[&str]| {
        umbra(&[&["render", text(scene)][..], &small[..], &["--out", text(out)], more].concat())
    };
    fails_saying(&render(&model, &city, &[]), &["city.glb", "a generated scene", "umbra scene city", "--replace"]);
    let o = render(&model, &city, &["--replace"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&model).expect("kept"), glb, "the render's own input");
    let o = render(&model, &city, &[]);
    assert!(o.status.success(), "a render again, its input beside it: {}", String::from_utf8_lossy(&o.stderr));
    assert!(model.exists() && city.join("shaded.png").exists());
    let sweep = tiny_sweep(&d, r#"["table-and-sphere"]"#);
    let study = d.join("study");
    assert!(umbra(&["study", "--sweep", text(&sweep), "--out", text(&study)]).status.success());
    let before = RunManifest::verify(&study, u64::MAX).expect("complete");
    let table = Path::new("table-and-sphere");
    fails_saying(&render(table, &study, &[]), &["a study", "results.csv", "--replace"]);
    assert_eq!(RunManifest::verify(&study, u64::MAX).expect("untouched"), before);
    fails_saying(&umbra(&["study", "--sweep", text(&sweep), "--out", text(&city)]), &["a render", "--replace"]);
    RunManifest::verify(&city, u64::MAX).expect("the render's folder untouched");
    let _ = std::fs::remove_dir_all(&d);
}

/// A run killed while it works leaves a folder without a manifest (an
/// earlier run's manifest is gone with the start of the new one).
#[test]
fn a_killed_run_does_not_look_complete() {
    let d = dir("killed");
    let out = d.join("out");
    let sweep = tiny_sweep(&d, r#"["table-and-sphere"]"#);
    assert!(umbra(&["study", "--sweep", text(&sweep), "--out", text(&out)]).status.success());
    RunManifest::verify(&out, u64::MAX).expect("the first run is complete");
    // The quick sweep runs for minutes here: it is killed at its start.
    let mut child = command(&["study", "--quick", "--out", text(&out)])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawns");
    // The run has begun once its pending record stands and the earlier
    // manifest is gone (it writes the one, then removes the other; between
    // the two the earlier run's record still holds). Waited for on the
    // child's own signs, however slow the machine: only its exit ends it.
    while !out.join(PENDING).exists() || out.join(MANIFEST).exists() {
        assert!(child.try_wait().expect("waits").is_none(), "the run ended before it began writing");
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("killed");
    let _ = child.wait();
    assert!(out.join(PENDING).exists() && !out.join(MANIFEST).exists(), "the folder looks complete");
    assert!(RunManifest::verify(&out, u64::MAX).is_err());
    let _ = std::fs::remove_dir_all(&d);
}

/// Scene names reach file names only as slugs: a name that climbs out of
/// the folder writes inside it, and two names of one slug are refused.
#[test]
fn no_name_leaves_the_output_folder() {
    let d = dir("names");
    let base = d.join("a").join("b");
    std::fs::create_dir_all(&base).expect("dir");
    let table = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/table-and-sphere.toml"))
        .expect("the bundled table");
    let named = |file: &str, name: &str| {
        let body = table.lines().filter(|l| !l.starts_with("name =")).collect::<Vec<_>>().join("\n");
        std::fs::write(base.join(file), format!("name = {name:?}\n{body}")).expect("scene");
        text(&base.join(file)).to_owned()
    };
    let (up, dot) = (named("up.toml", "/../../../ESCAPED"), named("dot.toml", "a.b"));
    let sweep = tiny_sweep(&base, &format!("[{up:?}, {dot:?}]"));
    let out = base.join("out");
    let o = umbra(&["study", "--sweep", text(&sweep), "--out", text(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let files: Vec<String> =
        RunManifest::verify(&out, u64::MAX).expect("complete").files.into_iter().map(|f| f.path).collect();
    assert!(files.iter().any(|f| f == "pareto-__________ESCAPED-time.png"), "{files:?}");
    assert!(files.iter().any(|f| f == "pareto-a_b-bytes.svg"), "{files:?}");
    let mut above: Vec<_> = std::fs::read_dir(&d).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    above.extend(std::fs::read_dir(d.join("a")).expect("dir").map(|e| e.expect("entry").file_name()));
    assert_eq!(above.len(), 2, "only a/ and a/b/: {above:?}");
    let clash = named("slash.toml", "a/b");
    let sweep = tiny_sweep(&base, &format!("[{dot:?}, {clash:?}]"));
    fails_saying(&umbra(&["study", "--sweep", text(&sweep), "--out", text(&out)]), &["`a.b` and `a/b`"]);
    let _ = std::fs::remove_dir_all(&d);
}

/// What can be known to fail is found before the work: an output folder
/// that cannot be made fails naming the folder, not a file written after
/// the sweep ran.
#[test]
fn an_unwritable_output_folder_fails_first() {
    let d = dir("preflight");
    std::fs::create_dir_all(&d).expect("dir");
    std::fs::write(d.join("file"), "not a folder").expect("file");
    let out = d.join("file").join("out");
    let o = umbra(&["study", "--quick", "--out", text(&out)]);
    fails_saying(&o, &[text(&out)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("results.jsonl") && o.stdout.is_empty(), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Every flag and field is read strictly: zero sizes, doubled units,
/// repeated list entries, conflicting flags and inline JSON that is not a
/// matrix are refused naming the flag.
#[test]
fn loose_values_are_refused_naming_the_flag() {
    let d = dir("strict");
    let out = d.join("out");
    let o = text(&out);
    for (args, says) in [
        (vec!["render", "--width", "0", "--out", o], "--width"),
        (vec!["render", "--reference-rays", "17", "--out", o], "--reference-rays"),
        (vec!["depth", "--map", "0", "--out", o], "--map"),
        (vec!["plan", "--error-budget", "50%%", "--out", o], "`50%%` is not a percentage"),
        (vec!["plan", "--budget", "glare=1%", "--out", o], "`glare` is not a measure"),
        (vec!["depth", "--matrix", r#"{"a": 1}"#, "--out", o], "not a 4×4 JSON array"),
        (vec!["study", "--maps", "256,256", "--out", o], "--maps `256` is given twice"),
        (vec!["study", "--budgets", "1,1", "--out", o], "repeats budget 0"),
        (vec!["study", "--budgets", "1e308", "--out", o], "not a percentage"),
        (vec!["cost", "--arch", "talisman", "--arch", "talisman", "--out", o], "chosen twice"),
        (vec!["cost", "--set", "clock=1GHz", "--set", "clock=2GHz", "--out", o], "--set `clock` is given twice"),
        (vec!["study", "--quick", "--sweep", "full", "--out", o], "--sweep"),
    ] {
        fails_saying(&umbra(&args), &[says]);
    }
    assert!(!out.exists(), "nothing is written for a refused command");
}

/// An OBJ's polylines and points are reported as ignored, not filled.
#[test]
fn polylines_are_reported_not_drawn() {
    let d = dir("polyline");
    std::fs::create_dir_all(&d).expect("dir");
    let obj = d.join("lines.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nl 1 2 3 4 1\np 4\n").expect("obj");
    let out = d.join("out");
    let args = ["depth", "--mesh", text(&obj), "--map", "32", "--out", text(&out)];
    let o = umbra(&args);
    let printed = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(printed.contains("4 polyline segments and 1 points"), "{printed}");
    assert!(printed.contains("triangles 1 submitted"), "{printed}");
    fails_saying(
        &umbra(&[&["--max-triangles", "5"][..], &args].concat()),
        &["6 primitives, 1 of them triangles", "max_triangles"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// The README's order, each command into its default folder: a cost and a
/// trace after a render leave the render's pictures, and all three
/// folders are whole.
#[test]
fn render_cost_and_trace_keep_each_others_outputs() {
    let d = dir("defaults");
    std::fs::create_dir_all(&d).expect("dir");
    let small = ["table-and-sphere", "--width", "96", "--height", "54", "--map", "128", "--reference-rays", "1"];
    for sub in ["render", "cost", "trace"] {
        let o = command(&[&[sub][..], &small[..]].concat()).current_dir(&d).output().expect("runs");
        assert!(o.status.success(), "{sub}: {}", String::from_utf8_lossy(&o.stderr));
    }
    for (folder, file) in [("render", "shaded.png"), ("cost", "cost.json"), ("trace", MANIFEST)] {
        let f = d.join("out").join(folder);
        assert!(f.join(file).is_file(), "{}", f.join(file).display());
        RunManifest::verify(&f, u64::MAX).unwrap_or_else(|e| panic!("{folder}: {e}"));
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// `merge` never writes into one of its inputs.
#[test]
fn merge_refuses_an_input_as_its_output() {
    let d = dir("merge-into-input");
    let sweep = tiny_sweep(&d, r#"["table-and-sphere"]"#);
    let shard = d.join("s0");
    let o = umbra(&["study", "--sweep", text(&sweep), "--shard", "0/1", "--out", text(&shard)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let before = std::fs::read(shard.join(MANIFEST)).expect("the shard's manifest");
    fails_saying(&umbra(&["merge", text(&shard), "--out", text(&shard)]), &["s0", "is also --out"]);
    assert_eq!(std::fs::read(shard.join(MANIFEST)).expect("kept"), before, "the shard is untouched");
    let _ = std::fs::remove_dir_all(&d);
}

/// Arguments that are not UTF-8: a folder or a mesh path is taken as the
/// OS gives it and recorded in the manifest's command line in bash's
/// `$'…'` quoting; a scene name, which must be text, is refused by clap
/// naming it. Never a panic.
#[cfg(unix)]
#[test]
fn arguments_that_are_not_utf8_are_taken_or_refused_never_a_panic() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    let d = dir("not-utf8");
    std::fs::create_dir_all(&d).expect("dir");
    let out = d.join(OsStr::from_bytes(b"out\xff"));
    let o = command(&["depth", "--map", "32"]).arg("--out").arg(&out).output().expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m = RunManifest::verify(&out, u64::MAX).expect("a whole folder");
    assert!(m.command.contains(r"out\377'"), "{}", m.command);
    // The recorded word is the same bytes to the shell.
    let word = m.command.split(' ').find(|w| w.starts_with("$'")).expect("a quoted word");
    let echoed = Command::new("bash").arg("-c").arg(format!("printf %s {word}")).output().expect("bash");
    assert_eq!(echoed.stdout, out.as_os_str().as_bytes());
    let mesh = d.join(OsStr::from_bytes(b"t\xff.obj"));
    let o = command(&["depth", "--out", text(&d.join("m"))]).arg("--mesh").arg(&mesh).output().expect("runs");
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let o = command(&["render"]).arg(OsStr::from_bytes(b"t\xff")).output().expect("runs");
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("UTF-8"));
    let _ = std::fs::remove_dir_all(&d);
}

/// Every cache key has a stated range, checked before anything is
/// allocated, and the error names the key at fault (not always the size).
#[test]
fn cache_geometry_is_checked_key_by_key_before_allocating() {
    let d = dir("cache-keys");
    let o = text(&d);
    for (set, says) in [
        ("map_cache.size=64GiB", "map_cache.size"),
        ("map_cache.size=9e15B", "map_cache.size"),
        ("map_cache.line=4GiB", "map_cache.line"),
        ("map_cache.line=1B", "map_cache.line"),
        ("map_cache.ways=0", "map_cache.ways"),
        ("map_cache.ways=1048576", "map_cache.ways"),
        ("map_cache.misses_in_flight=0", "map_cache.misses_in_flight"),
    ] {
        fails_saying(&umbra(&["cost", "--arch", "mobile-tbdr", "--set", set, "--out", o]), &[says]);
    }
    assert!(!d.exists(), "nothing is written for a refused architecture");
}

/// An `--out` that is a dangling or looping link is named as such; an
/// earlier manifest above its size limit is refused naming the limit.
#[cfg(unix)]
#[test]
fn a_dangling_out_and_a_huge_manifest_are_named() {
    let d = dir("dangling");
    std::fs::create_dir_all(&d).expect("dir");
    std::os::unix::fs::symlink(d.join("nowhere"), d.join("dangling")).expect("a link");
    std::os::unix::fs::symlink(d.join("loop"), d.join("loop")).expect("a loop");
    for out in ["dangling", "loop"] {
        fails_saying(
            &umbra(&["depth", "--map", "32", "--out", text(&d.join(out))]),
            &[out, "symbolic link to nothing"],
        );
    }
    let out = d.join("big");
    assert!(umbra(&["depth", "--map", "32", "--out", text(&out)]).status.success());
    let f = std::fs::File::options().append(true).open(out.join(MANIFEST)).expect("manifest");
    f.set_len(17 << 20).expect("grown past the limit");
    let err = RunManifest::verify(&out, u64::MAX).expect_err("too big");
    assert!(err.to_string().contains("larger than the 16777216 bytes"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A thread count far beyond the machine is lowered, with a notice, and the
/// run gives the same result.
#[test]
fn a_huge_thread_count_is_lowered_with_a_notice() {
    let d = dir("threads");
    let small = ["render", "weiskopf-l", "--width", "64", "--height", "48", "--map", "64", "--reference-rays", "1"];
    let run = |threads: &str, out: &str| {
        let o = command(&small).args(["--out", text(&d.join(out))]).env("RAYON_NUM_THREADS", threads).output();
        o.expect("runs")
    };
    let (many, one) = (run("100000", "many"), run("1", "one"));
    assert!(many.status.success() && one.status.success(), "{}", String::from_utf8_lossy(&many.stderr));
    assert!(String::from_utf8_lossy(&many.stderr).contains("RAYON_NUM_THREADS=100000 is more than 256"));
    let metrics = |out: &str| std::fs::read_to_string(d.join(out).join("metrics.json")).expect("metrics");
    let strip = |m: String| m.lines().filter(|l| !l.contains("\"command\"")).collect::<Vec<_>>().join("\n");
    assert_eq!(strip(metrics("many")), strip(metrics("one")));
    let _ = std::fs::remove_dir_all(&d);
}

/// An architecture's description with `|`, a newline and a backslash (the
/// issue's case broke `arch show`'s table) reads as itself in its heading
/// and leaves both tables whole; `arch diff` of it keeps its table whole too.
#[test]
fn a_description_of_any_text_keeps_arch_show_whole() {
    let d = dir("described");
    let toml = umbra_sim::Arch::bundled("talisman").expect("bundled").to_toml();
    let line = toml.lines().find(|l| l.starts_with("description = ")).expect("a description").to_owned();
    std::fs::create_dir_all(&d).expect("dir");
    let file = d.join("odd.toml");
    std::fs::write(&file, toml.replace(&line, r#"description = "a | b\nc \\ d""#)).expect("write");
    let o = umbra(&["arch", "show", "--arch", text(&file)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    let first = out.lines().next().expect("a heading");
    assert!(first.contains(r"a \| b\u{a}c \\ d"), "{first}");
    let unescaped = |l: &str| l.replace("\\\\", "").replace("\\|", "").matches('|').count();
    let rows: Vec<&str> = out.lines().filter(|l| l.starts_with('|')).collect();
    // Three columns in the keys' and derived figures' tables, five in the
    // units' silicon.
    assert!(rows.len() > 40 && rows.iter().all(|l| [4, 6].contains(&unescaped(l))), "{out}");
    let o = umbra(&["arch", "diff", "talisman", text(&file)]);
    let out = String::from_utf8_lossy(&o.stdout);
    let rows: Vec<&str> = out.lines().filter(|l| l.starts_with('|')).collect();
    assert!(rows.iter().any(|l| l.contains("description")) && rows.iter().all(|l| unescaped(l) == 4), "{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A user's mistake is one line on stderr and exit status 1, never a stack
/// trace, whatever `RUST_BACKTRACE` asks for.
#[test]
fn an_error_is_one_line_even_with_backtraces_asked_for() {
    for value in ["1", "full"] {
        let o = Command::new(env!("CARGO_BIN_EXE_umbra"))
            .args(["render", "no-such-scene"])
            .env("RUST_BACKTRACE", value)
            .env("RUST_LIB_BACKTRACE", value)
            .output()
            .expect("runs");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("Error: ") && err.contains("no bundled scene `no-such-scene`"), "{err}");
    }
}

/// The bare command's help says what the bare command does: the maps,
/// the render and the quick study, each into its folder.
#[test]
fn the_help_says_what_the_bare_command_does() {
    let o = command(&["--help"]).output().expect("runs");
    let help = String::from_utf8_lossy(&o.stdout);
    for folder in ["out/depth/", "out/render/", "out/study/"] {
        assert!(help.contains(folder), "`umbra --help` does not name {folder}: {help}");
    }
}

/// `--in-place` writes nowhere but its file and keeps what it replaces: a
/// link planted at the old fixed temporary name is left alone (and its
/// target unchanged), the file's permissions and CRLF line endings are
/// kept, a link is upgraded at its target and stays a link, and a
/// read-only file is refused and left as it was.
#[cfg(unix)]
#[test]
fn an_in_place_upgrade_keeps_what_it_replaces() {
    use std::os::unix::fs::PermissionsExt;
    let d = dir("in-place");
    let sub = d.join("sub");
    std::fs::create_dir_all(&sub).expect("dir");
    let old = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/first-release-gpu.toml"))
        .expect("an earlier release's file");
    assert!(!old.contains("\nformat = "), "the example states no format");
    // Upgraded: the format stated first of the keys, the header comment first.
    const STATED: &str = "\nformat = 3  # upgraded from format 1\n";
    let header = old.lines().next().expect("a header");
    let upgrade = |file: &Path| umbra(&["arch", "upgrade", "--in-place", text(file)]);
    let upgraded = |file: &Path| std::fs::read_to_string(file).expect("read").replace("\r\n", "\n");
    let mode = |file: &Path| std::fs::metadata(file).expect("meta").permissions().mode() & 0o777;
    // A link planted where the old code wrote its temporary.
    let (file, victim) = (sub.join("x.toml"), d.join("v.txt"));
    std::fs::write(&file, &old).expect("file");
    std::fs::write(&victim, "the user's").expect("victim");
    std::os::unix::fs::symlink("../v.txt", sub.join(".x.toml.upgrading")).expect("a planted link");
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o600)).expect("private");
    let o = upgrade(&file);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(&victim).expect("victim"), "the user's", "written through the link");
    assert!(std::fs::symlink_metadata(sub.join(".x.toml.upgrading")).expect("link").file_type().is_symlink());
    assert!(std::fs::symlink_metadata(&file).expect("file").file_type().is_file(), "the file became a link");
    assert!(upgraded(&file).contains(STATED) && upgraded(&file).starts_with(header), "upgraded");
    assert_eq!(mode(&file), 0o600, "a private file stays private");
    let names: Vec<_> = std::fs::read_dir(&sub).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    assert_eq!(names.len(), 2, "no temporary left: {names:?}");
    // An executable file and CRLF line endings.
    let crlf = sub.join("crlf.toml");
    std::fs::write(&crlf, old.replace('\n', "\r\n")).expect("file");
    std::fs::set_permissions(&crlf, std::fs::Permissions::from_mode(0o755)).expect("mode");
    assert!(upgrade(&crlf).status.success());
    let bytes = std::fs::read(&crlf).expect("read");
    assert!(String::from_utf8_lossy(&bytes).contains(&STATED.replace('\n', "\r\n")), "CRLF kept");
    assert!(bytes.windows(2).filter(|w| w[1] == b'\n').all(|w| w[0] == b'\r'), "every line ends in CRLF");
    assert_eq!(mode(&crlf), 0o755);
    let again = upgrade(&crlf);
    assert!(String::from_utf8_lossy(&again.stderr).contains("already in the current format"), "an upgraded CRLF file");
    // A link: upgraded at its target, and still a link.
    let (real, link) = (d.join("real.toml"), sub.join("link.toml"));
    std::fs::write(&real, &old).expect("file");
    std::os::unix::fs::symlink(&real, &link).expect("a link");
    let o = upgrade(&link);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stderr).contains("real.toml"), "names the target");
    assert!(std::fs::symlink_metadata(&link).expect("link").file_type().is_symlink(), "the link stays a link");
    assert!(upgraded(&real).contains(STATED), "its target upgraded");
    // A read-only file is refused, and left as it was.
    let locked = sub.join("locked.toml");
    std::fs::write(&locked, &old).expect("file");
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o444)).expect("read-only");
    fails_saying(&upgrade(&locked), &["locked.toml", "read-only"]);
    assert_eq!(std::fs::read_to_string(&locked).expect("read"), old);
    let _ = std::fs::remove_dir_all(&d);
}

/// A glTF file whose primitive names an accessor it does not have (the
/// `gltf` crate's validation indexes it unchecked) is an error naming the
/// attribute, never a panic: as a model, as a scene file's mesh and as
/// `arch diff --scene`.
#[test]
fn a_gltf_file_never_panics_the_command() {
    let d = dir("gltf-panic");
    std::fs::create_dir_all(&d).expect("dir");
    let model = d.join("p.gltf");
    std::fs::write(&model, r#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#)
        .expect("model");
    let table = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/table-and-sphere.toml"))
        .expect("the bundled table");
    let scene = d.join("s.toml");
    let mesh = table.lines().find(|l| l.trim_start().starts_with("mesh = ")).expect("a mesh line");
    std::fs::write(&scene, table.replacen(mesh, "mesh = { gltf = \"p.gltf\" }", 1)).expect("scene");
    let out = d.join("out");
    for args in [
        vec!["render", text(&model), "--out", text(&out)],
        vec!["render", text(&scene), "--out", text(&out)],
        vec!["arch", "diff", "talisman", "pixelflow", "--scene", text(&model)],
    ] {
        let o = umbra(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        fails_saying(&o, &["attributes.POSITION", "names accessors[0]"]);
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Every list and size is bounded before work, naming the option: a plan
/// over 4097 map sides or a side past `--max-map-side`, a study over 4097,
/// a city past the triangles a render reads or past a building's 16-bit
/// indices (each with the largest allowed).
#[test]
fn lists_and_generated_sizes_are_bounded_before_work() {
    let d = dir("lists");
    let many: String = (1000..=5096).map(|s| s.to_string()).collect::<Vec<_>>().join(",");
    let plan = |maps: &str| umbra(&["plan", "table-and-sphere", "--image", "64x36", "--maps", maps, "--out", text(&d)]);
    fails_saying(&plan(&many), &["--maps", "4097 values", "at most 4096"]);
    fails_saying(&plan("16384"), &["--maps 16384", "8192", "--max-map-side"]);
    fails_saying(&umbra(&["study", "--quick", "--maps", &many, "--out", text(&d)]), &["--maps", "at most 4096"]);
    let city = |a: &[&str]| umbra(&[&["scene", "city"][..], a, &["--out", text(&d)]].concat());
    fails_saying(&city(&["--side", "1024"]), &["--side 1024", "335544322 triangles", "--max-triangles", "at most 114"]);
    fails_saying(&city(&["--columns", "1024"]), &["--columns 1024", "16-bit", "--columns is at most 128"]);
    fails_saying(&city(&["--columns", "8192", "--storeys", "8192"]), &["no --columns fits"]);
    assert!(!d.exists(), "nothing written");
}
