//! `merge` refuses every input that would make the merged run lie, naming
//! the file: a missing shard, a shard of another sweep, a shard given
//! twice, a shard without its manifest, a truncated or empty results file,
//! and a row that fails validation (a negative error, a NaN).

use std::path::{Path, PathBuf};

use crate::Algorithm;
use crate::experiment::study::{self, Manifest, Row, Shard, Spec, StudyError, Variant};
use crate::input::limits::Limits;
use crate::output::folder::RunManifest;

use super::scratch::Scratch;

/// A scratch folder of this test process for `name`, removed when dropped.
fn dir(name: &str) -> super::scratch::Scratch {
    super::scratch_dir("umbra-merge", name)
}

/// A tiny sweep: one scene, two algorithms, one format, map, filter and
/// architecture, 48×27.
fn tiny(hash: &str) -> Spec {
    let scenes = study::load_scenes(&["table-and-sphere"], &Limits::DEFAULT).expect("bundled");
    let mut spec = Spec::quick(scenes);
    spec.variants = vec![Variant::new(Algorithm::First, 0.002), Variant::new(Algorithm::Second, 0.0)];
    spec.formats.truncate(1);
    spec.map_sizes = vec![128];
    spec.filters.truncate(1);
    spec.archs.truncate(1);
    spec.images = vec![[48, 27]];
    spec.reference_rays = 1;
    spec.hash = hash.to_owned();
    spec
}

/// Shard `i/n` of `spec` written into a folder named `tag-i`.
fn shard(spec: &Spec, tag: &str, i: usize, n: usize) -> Scratch {
    let d = dir(&format!("{tag}-{i}"));
    let s = Shard { index: i, count: n };
    let rows = study::run(spec, s, &indicatif::ProgressBar::hidden()).expect("within the limits");
    study::write_run(&d, &rows, &Manifest::new(spec, s, rows.len())).expect("write");
    d
}

/// `merge` of `inputs` must fail with a message naming `file` and saying
/// `what`.
fn refused(inputs: &[PathBuf], file: &Path, what: &str) {
    let out = dir("out");
    let e = study::merge(inputs, &out, &Limits::DEFAULT).expect_err("refused");
    let text = e.to_string();
    assert!(text.contains(&file.display().to_string()) && text.contains(what), "{what}: {text}");
    assert!(!out.join("results.jsonl").exists(), "nothing is written on refusal");
}

fn rewrite(d: &Path, edit: impl Fn(&mut Row)) {
    let mut rows = study::read_rows(d, &Limits::DEFAULT).expect("rows");
    rows.iter_mut().for_each(edit);
    let run: RunManifest =
        serde_json::from_slice(&std::fs::read(d.join("manifest.json")).expect("manifest")).expect("JSON");
    let m: Manifest = serde_json::from_value(run.study.expect("a study's manifest")).expect("study record");
    study::write_run(d, &rows, &m).expect("write");
}

#[test]
fn merge_refuses_what_would_lie() {
    let spec = tiny("aaaa");
    let shards: Vec<Scratch> = (0..2).map(|i| shard(&spec, "good", i, 2)).collect();
    let s: Vec<PathBuf> = shards.iter().map(|d| d.to_path_buf()).collect();
    // The good case merges.
    let out = dir("ok");
    assert_eq!(study::merge(&s, &out, &Limits::DEFAULT).expect("merges"), 2);
    // A missing shard: 1 of 2.
    refused(&s[..1], &dir("out"), "shard 1/2");
    // A shard given twice.
    refused(&[s[0].clone(), s[0].clone()], &s[0], "given again");
    // Two folders holding the same shard.
    let again = shard(&spec, "again", 0, 2);
    refused(
        &[s[0].clone(), again.to_path_buf(), s[1].clone()],
        &again.join("manifest.json"),
        "shard 0/2 is given twice",
    );
    // A shard of another sweep.
    let other = shard(&tiny("bbbb"), "other", 1, 2);
    refused(&[s[0].clone(), other.to_path_buf()], &other.join("manifest.json"), "another sweep");
    // A shard of a run split another way.
    let three = shard(&spec, "three", 1, 3);
    refused(&[s[0].clone(), three.to_path_buf()], &three.join("manifest.json"), "3-ways");
    // No manifest.
    let bare = dir("bare");
    std::fs::copy(s[1].join("results.jsonl"), bare.join("results.jsonl")).expect("copy");
    refused(&[s[0].clone(), bare.to_path_buf()], &bare.join("manifest.json"), "");
    // An empty results file where the manifest counts a row.
    let empty = shard(&spec, "empty", 1, 2);
    std::fs::write(empty.join("results.jsonl"), "").expect("truncate");
    refused(&[s[0].clone(), empty.to_path_buf()], &empty.join("results.jsonl"), "differs from the manifest");
    // A row with a negative error, and one with NaN.
    let negative = shard(&spec, "negative", 1, 2);
    rewrite(&negative, |r| r.metrics.iter_mut().for_each(|m| m.misclassified_percent = -5.0));
    refused(&[s[0].clone(), negative.to_path_buf()], &negative.join("results.jsonl"), "misclassified_percent -5");
    let nan = shard(&spec, "nan", 1, 2);
    rewrite(&nan, |r| r.metrics.iter_mut().for_each(|m| m.rms_error = f64::NAN));
    let e = study::merge(&[s[0].clone(), nan.to_path_buf()], &dir("out"), &Limits::DEFAULT).expect_err("refused");
    assert!(e.to_string().contains("results.jsonl"), "{e}");
    // A row of another sweep slipped into a shard.
    let foreign = shard(&spec, "foreign", 1, 2);
    rewrite(&foreign, |r| r.config.sweep_hash = "cccc".into());
    refused(&[s[0].clone(), foreign.to_path_buf()], &foreign.join("results.jsonl"), "of sweep cccc");
    assert!(matches!(study::merge(&[], &dir("none"), &Limits::DEFAULT), Err(StudyError::Merge { .. })));
}

/// `status` tells each shard folder's state from what its run left — a
/// manifest its files match (complete), a pending manifest with the lock
/// held (running) or free (abandoned), files that differ (corrupt) — and
/// the shards no complete folder holds; `merge` refuses an unfinished
/// shard by its folder; a complete shard is recognised for a rerun to skip.
#[test]
fn status_tells_every_shards_state_and_merge_refuses_the_unfinished() {
    use crate::output::folder::{Claim, OutputFolder, RunKind};
    let spec = tiny("status");
    let limits = Limits::DEFAULT;
    let shards: Vec<Scratch> = (0..2).map(|i| shard(&spec, "status", i, 4)).collect();
    let done: Vec<PathBuf> = shards.iter().map(|d| d.to_path_buf()).collect();
    // Shard 2 killed mid-run: its folder opened, never finished.
    let abandoned = dir("status-2");
    let mut killed = OutputFolder::create(&abandoned, Claim::new(RunKind::Study)).expect("opened");
    killed.write("results.jsonl", b"").expect("a partial file");
    drop(killed);
    // Shard 3 under way: a run holds its folder.
    let running = dir("status-3");
    let held = OutputFolder::create(&running, Claim::new(RunKind::Study)).expect("opened");
    // A complete folder whose results were edited since.
    let corrupt = shard(&spec, "status-edited", 1, 4);
    std::fs::write(corrupt.join("results.jsonl"), "{}\n").expect("edit");
    let inputs =
        vec![done[0].clone(), done[1].clone(), abandoned.to_path_buf(), running.to_path_buf(), corrupt.to_path_buf()];
    let s = study::status(&inputs, &limits);
    let states: Vec<study::ShardState> = s.folders.iter().map(|f| f.state.clone()).collect();
    use study::ShardState::{Abandoned, Complete, Corrupt, Running};
    assert_eq!(states, [Complete, Complete, Abandoned, Running, Corrupt]);
    assert_eq!((s.count, s.missing.clone(), s.ready()), (Some(4), vec![2, 3], false));
    let md = s.markdown();
    assert!(md.contains("2 of 4 shards complete; not complete: 2/4, 3/4"), "{md}");
    refused(
        &[done[0].clone(), abandoned.to_path_buf()],
        &abandoned,
        "not a finished shard: its run stopped before finishing",
    );
    refused(&[done[0].clone(), running.to_path_buf()], &running, "not a finished shard: its run is under way");
    drop(held);
    // The rerun's check: shard 0's folder holds shard 0 of this sweep and
    // version; not shard 1's, nor another sweep's, nor an edited one.
    let m = |i: usize, spec: &Spec| Manifest::new(spec, Shard { index: i, count: 4 }, 0);
    assert!(study::already_complete(&done[0], &m(0, &spec), &limits));
    assert!(!study::already_complete(&done[0], &m(1, &spec), &limits));
    assert!(!study::already_complete(&done[0], &m(0, &tiny("other")), &limits));
    assert!(!study::already_complete(&corrupt, &m(1, &spec), &limits));
}

/// Copy a finished folder's files into a new folder `tag`.
fn copy(from: &Path, tag: &str) -> Scratch {
    let d = dir(tag);
    for e in std::fs::read_dir(from).expect("folder") {
        let e = e.expect("entry");
        std::fs::copy(e.path(), d.join(e.file_name())).expect("copy");
    }
    d
}

/// What the hostile round found, each example and two of ours per
/// class: `status` said "ready" where `merge` refused. Now both refuse,
/// naming the same problem.
#[test]
fn status_and_merge_refuse_the_same_sets() {
    let spec = tiny("cccc");
    let limits = Limits::DEFAULT;
    let shards: Vec<Scratch> = (0..3).map(|i| shard(&spec, "same", i, 3)).collect();
    let s: Vec<PathBuf> = shards.iter().map(|d| d.to_path_buf()).collect();
    let whole = shard(&spec, "same-whole", 0, 1);
    let foreign = shard(&tiny("dddd"), "same-foreign", 1, 3);
    let links = dir("same-link");
    let link = links.join("s1");
    std::os::unix::fs::symlink(&s[1], &link).expect("link");
    let versioned = copy(&s[2], "same-version");
    let record = versioned.join("manifest.json");
    let text = std::fs::read_to_string(&record).expect("record");
    let edited = text.replacen(
        &format!("\"umbra_version\": \"{}\"", crate::output::provenance::version()),
        "\"umbra_version\": \"0.0.0\"",
        1,
    );
    assert_ne!(text, edited, "the record names its version");
    std::fs::write(&record, edited).expect("edit");
    let both = |inputs: &[PathBuf], what: &str| {
        let st = study::status(inputs, &limits);
        assert!(!st.ready(), "{what}: {}", st.markdown());
        let md = st.markdown();
        assert!(md.contains(what) && !md.contains(": ready to merge."), "{what}: {md}");
        let e = study::merge(inputs, &dir("same-out"), &limits).expect_err(what).to_string();
        assert!(e.contains(&st.problems[0].problem) && e.contains(what), "{what}: {e}");
    };
    let all = |extra: &PathBuf| vec![s[0].clone(), s[1].clone(), s[2].clone(), extra.clone()];
    // The examples: a shard twice, once through a link, another sweep's,
    // a whole run beside shards, a record whose two versions differ.
    both(&[s[0].clone(), s[0].clone(), s[1].clone(), s[2].clone()], "given again");
    both(&all(&link), "given again");
    both(&all(&foreign.to_path_buf()), "another sweep");
    both(&all(&whole.to_path_buf()), "never merged together");
    both(&[s[0].clone(), s[1].clone(), versioned.to_path_buf()], "version 0.0.0");
    // Ours: the same folder by its results file and through `..`; a
    // whole run first, then shards; a shard of a run split another way
    // after a missing one; a file that is not a results file; nothing.
    both(&[s[0].clone(), s[1].join("results.jsonl"), s[1].clone(), s[2].clone()], "given again");
    let dotted = s[2].join("..").join(s[2].file_name().expect("named"));
    both(&[s[0].clone(), s[1].clone(), s[2].clone(), dotted], "given again");
    both(&[whole.to_path_buf(), s[0].clone()], "never merged together");
    both(&[s[0].clone(), shard(&spec, "same-four", 1, 4).to_path_buf()], "4-ways");
    both(&[s[0].clone(), s[1].join("manifest.json"), s[2].clone()], "is a file, not a study's folder");
    both(&[s[0].clone(), s[1].join("nothing"), s[2].clone()], "does not exist");
    both(&[], "no shard to merge");
    // And the good sets are ready, and merge.
    for good in [vec![s[2].clone(), link.clone(), s[0].join("results.jsonl")], vec![whole.to_path_buf()]] {
        let st = study::status(&good, &limits);
        assert!(st.ready() && st.markdown().contains(": ready to merge."), "{}", st.markdown());
        let out = dir("same-merged");
        assert_eq!(study::merge(&good, &out, &limits).expect("merges"), 2);
    }
}

/// The property: for random lists of folders — good shards, repeats, links,
/// results files, foreign shards, a whole run, unfinished, edited, absent —
/// `status` is ready exactly when `merge` succeeds, and exactly when the
/// list names each of one run's shards once (an independent rule, below).
#[test]
fn status_is_ready_exactly_when_merge_succeeds() {
    use crate::output::folder::{Claim, OutputFolder, RunKind};
    let spec = tiny("eeee");
    let limits = Limits::DEFAULT;
    let shards: Vec<Scratch> = (0..3).map(|i| shard(&spec, "prop", i, 3)).collect();
    let s: Vec<PathBuf> = shards.iter().map(|d| d.to_path_buf()).collect();
    let whole = shard(&spec, "prop-whole", 0, 1);
    let (foreign, two) = (shard(&tiny("ffff"), "prop-foreign", 2, 3), shard(&spec, "prop-two", 1, 2));
    let links = dir("prop-link");
    let link = links.join("s1");
    std::os::unix::fs::symlink(&s[1], &link).expect("link");
    let abandoned = dir("prop-abandoned");
    let mut killed = OutputFolder::create(&abandoned, Claim::new(RunKind::Study)).expect("opened");
    killed.write("results.jsonl", b"").expect("a partial file");
    drop(killed);
    let edited = copy(&s[0], "prop-edited");
    std::fs::write(edited.join("results.jsonl"), "{}\n").expect("edit");
    // Each entry: a path, and which good run's shard it names (`None` for
    // one no merge may take).
    let pool: Vec<(PathBuf, Option<&str>)> = vec![
        (s[0].clone(), Some("s0")),
        (s[1].clone(), Some("s1")),
        (s[2].clone(), Some("s2")),
        (link, Some("s1")),
        (s[2].join("results.jsonl"), Some("s2")),
        (whole.to_path_buf(), Some("whole")),
        (foreign.to_path_buf(), None),
        (two.to_path_buf(), None),
        (abandoned.to_path_buf(), None),
        (edited.to_path_buf(), None),
        (s[0].join("absent"), None),
    ];
    let ready_by_rule = |names: &[Option<&str>]| {
        let mut named: Vec<&str> = names.iter().map(|n| n.unwrap_or("bad")).collect();
        named.sort_unstable();
        named == ["s0", "s1", "s2"] || named == ["whole"]
    };
    // A fixed xorshift: the same lists every run.
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = |n: usize| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        usize::try_from(x % n as u64).unwrap_or(0)
    };
    let (mut ready, mut refused) = (0, 0);
    for case in 0..160 {
        // Half the lists are permutations of the good shards, with maybe
        // one more entry: the interesting edge.
        let mut picks: Vec<usize> = if case % 2 == 0 {
            let mut p = vec![0, 1, 2];
            p.swap(next(3), next(3));
            if next(2) == 0 {
                p.insert(next(4), next(pool.len()));
            }
            p
        } else {
            (0..next(5)).map(|_| next(pool.len())).collect()
        };
        if case % 7 == 0 {
            picks = vec![5];
        }
        let inputs: Vec<PathBuf> = picks.iter().map(|&i| pool[i].0.clone()).collect();
        let names: Vec<Option<&str>> = picks.iter().map(|&i| pool[i].1).collect();
        let st = study::status(&inputs, &limits);
        let merged = study::merge(&inputs, &dir("prop-out"), &limits);
        assert_eq!(st.ready(), merged.is_ok(), "{inputs:?}: {}\n{merged:?}", st.markdown());
        assert_eq!(st.ready(), ready_by_rule(&names), "{inputs:?}: {}", st.markdown());
        match merged {
            Ok(_) => ready += 1,
            Err(e) => {
                assert!(e.to_string().contains(&st.problems[0].problem), "{e} / {:?}", st.problems);
                refused += 1;
            }
        }
    }
    assert!(ready >= 20 && refused >= 60, "both sides are tried: {ready} ready, {refused} refused");
}

/// The case: folder names with `|` and a newline broke `status`'s
/// table (a row gained a column, or split). Ours: the same characters in
/// a folder given twice, whose problem names the folder too.
#[test]
fn a_folder_of_any_name_keeps_the_status_table_whole() {
    let spec = tiny("gggg");
    let odd = shard(&spec, "odd|name\nwith | bars", 0, 1);
    let s = study::status(&[odd.to_path_buf(), odd.to_path_buf()], &Limits::DEFAULT);
    let md = s.markdown();
    let table: Vec<&str> = md.lines().take_while(|l| l.starts_with('|')).collect();
    assert_eq!(table.len(), 4, "a heading, a rule and two rows: {md}");
    let unescaped = |l: &str| l.replace("\\\\", "").replace("\\|", "").matches('|').count();
    assert!(table.iter().all(|l| unescaped(l) == 6), "{md}");
    assert!(md.contains("odd\\|name\\u{a}with \\| bars"), "{md}");
    let problems: Vec<&str> = md.lines().filter(|l| l.starts_with("- ")).collect();
    assert_eq!(problems.len(), 1, "one line a problem: {md}");
    let _ = std::fs::remove_dir_all(odd);
}
