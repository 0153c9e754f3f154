//! Architecture files: every bundled file parses and round-trips through
//! the record outputs carry; a corrupted copy names its file, key and
//! problem; overrides read their units.

use umbra::sim::cost::arch::{Arch, ArchError};
use umbra::sim::cost::arch::{BUNDLED, PARAMS, Problem, Value};

#[test]
fn every_bundled_file_parses_and_round_trips() {
    for (name, text) in BUNDLED {
        let a = Arch::parse(text, name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.name, name, "the name key matches the file");
        let again = Arch::parse(&a.to_toml(), "record").unwrap_or_else(|e| panic!("{name}: {e}\n{}", a.to_toml()));
        assert_eq!(again, a, "{name}");
        // Every key of the table is in the record, with its meaning.
        for p in PARAMS {
            assert!(a.to_toml().contains(&format!("{} = ", p.key)), "{name}: {}", p.key);
        }
    }
}

/// `text` with the first line starting `key =` replaced by `line`.
fn corrupt(text: &str, key: &str, line: &str) -> Result<Arch, ArchError> {
    let mut found = false;
    let edited: Vec<&str> = text
        .lines()
        .map(|l| {
            if !found && l.starts_with(&format!("{key} =")) {
                found = true;
                line
            } else {
                l
            }
        })
        .collect();
    assert!(found, "{key}");
    Arch::parse(&edited.join("\n"), "copy.toml")
}

/// A corruption: the key whose line is replaced, the new line, the key the
/// error must name, and the problem it must report.
type Case = (&'static str, &'static str, &'static str, fn(&Problem) -> bool);

#[test]
fn a_corrupted_copy_names_the_file_the_key_and_the_problem() {
    let text = BUNDLED[1].1;
    let cases: [Case; 7] = [
        ("clock", "clock = 75", "clock", |p| matches!(p, Problem::Type(_))),
        ("clock", "clock = \"75 parsecs\"", "clock", |p| matches!(p, Problem::Unit { .. })),
        ("tile", "tile = 48", "raster.tile", |p| matches!(p, Problem::Range { .. })),
        // A misspelt key is unknown, and the key it meant is missing: both in one error.
        (
            "bandwidth",
            "bandwidht = \"1.2GB/s\"",
            "(file)",
            |p| matches!(p, Problem::Several(v) if v.iter().map(|(k, _)| k.as_str()).eq(["dram.bandwidht", "dram.bandwidth"])),
        ),
        ("bandwidth", "# gone", "dram.bandwidth", |p| matches!(p, Problem::Missing)),
        ("size", "size = \"10000B\"", "map_cache.size", |p| matches!(p, Problem::Range { .. })),
        ("samples_per_clock", "samples_per_clock = 0", "shadow.samples_per_clock", |p| {
            matches!(p, Problem::Outside { .. })
        }),
    ];
    for (key, line, named, problem) in cases {
        let e = corrupt(text, key, line).expect_err(line);
        assert_eq!((e.file.as_str(), e.key.as_str()), ("copy.toml", named), "{line}: {e}");
        assert!(problem(&e.problem), "{line}: {e}");
        assert!(e.to_string().starts_with(&format!("copy.toml: {named}: ")), "{e}");
    }
    for bad in ["../../escaped", "a/b", "", "arch.v2"] {
        let e = corrupt(text, "name", &format!("name = \"{bad}\"")).expect_err(bad);
        assert!(matches!(e.problem, Problem::Name(_)) && e.key == "name", "{e}");
    }
    let e = Arch::parse("clock = [", "broken.toml").expect_err("syntax");
    assert!(matches!(e.problem, Problem::Syntax(_)) && e.key == "line 1, `clock = [`", "{e}");
    let e = Arch::bundled("cray-1").expect_err("no such preset");
    assert!(matches!(e.problem, Problem::NoSuchPreset), "{e}");
}

#[test]
fn overrides_read_their_units() {
    let mut a = Arch::bundled("talisman").expect("bundled");
    for (set, key, value) in [
        ("map_cache.size=16KiB", "map_cache.size", 16_384.0),
        ("dram.bandwidth=25.6GB/s", "dram.bandwidth", 25.6e9),
        ("clock=800MHz", "clock", 800e6),
        ("dram.latency=2ns", "dram.latency", 2e-9),
        ("energy.dram_byte=1.3nJ", "energy.dram_byte", 1.3e-9),
        ("raster.fragments_per_clock = 0.5", "raster.fragments_per_clock", 0.5),
    ] {
        a.set(set).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.get(key), Some(Value::Number(value)), "{set}");
    }
    a.set("front.overlap=false").expect("a flag");
    assert!(!a.front.overlap);
    for (bad, key) in [
        ("clock=fast", "clock"),
        ("dram.bandwidth=25.6GHz", "dram.bandwidth"),
        ("nonsense=1", "nonsense"),
        ("raster.tile=96", "raster.tile"),
        ("dram.burst=-4B", "dram.burst"),
    ] {
        let e = a.clone().set(bad).expect_err(bad);
        assert_eq!((e.file.as_str(), e.key.as_str()), ("--set", key), "{bad}: {e}");
    }
    assert!(matches!(a.set("clock").expect_err("no =").problem, Problem::Override));
}

/// The keys added after the first release: each key's last part, the
/// format it came in, and the value that keeps the earlier behaviour.
const ADDED: [(&str, u32, &str); 12] = [
    ("frame_overhead_cycles", 2, "0"),
    ("program_cycles", 2, "0"),
    ("peel_cycles", 2, "0"),
    ("combine_cycles", 2, "0"),
    ("cycles_per_sample", 2, "0"),
    ("cycles_per_weights", 2, "0"),
    ("per_fragment", 2, "false"),
    ("node", 3, "\"\""),
    ("sram_bit", 3, "\"0mm2\""),
    ("array_efficiency", 3, "0.7"),
    ("gate", 3, "\"0mm2\""),
    ("leakage", 3, "\"0W/mm2\""),
];

/// The added key a line of a file gives, if it gives one.
fn added(line: &str) -> Option<&'static (&'static str, u32, &'static str)> {
    ADDED.iter().find(|(k, _, _)| line.starts_with(&format!("{k} =")))
}

/// A bundled file as format `format` wrote it: no `format` line, none of
/// the keys added after `format` (nor a table left with none of its keys).
fn as_of(text: &str, format: u32) -> String {
    text.lines()
        .filter(|l| !l.starts_with("format =") && added(l).is_none_or(|a| a.1 <= format))
        .filter(|l| format >= 3 || *l != "[technology]")
        .map(|l| format!("{l}\n"))
        .collect()
}

/// A file written before the added keys existed loads, each key at the
/// value that keeps the earlier behaviour (0 cycles; shading per pixel; no
/// technology: no area, no leakage), the same machine as the file stating
/// those values; so does a format-2 file without the technology table.
#[test]
fn a_file_from_before_the_added_keys_loads_as_it_did() {
    for (name, text) in BUNDLED {
        assert_eq!(text.lines().filter(|l| added(l).is_some()).count(), ADDED.len(), "{name}: each added key once");
        let stated: String = text
            .lines()
            .map(|l| match added(l) {
                Some((k, _, v)) => format!("{k} = {v}\n"),
                None => format!("{l}\n"),
            })
            .collect();
        let earlier = Arch::parse(&stated, "stated.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        let first = Arch::parse(&as_of(text, 1), "old.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(first, earlier, "{name}");
        let second = format!("format = 2\n{}", as_of(text, 2));
        let second = Arch::parse(&second, "two.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        let bundled = Arch::parse(text, name).expect("loads");
        assert_eq!(second, Arch { technology: earlier.technology.clone(), ..bundled }, "{name}");
        // A format-2 file must give the keys format 2 added.
        let e = Arch::parse(&format!("format = 2\n{}", as_of(text, 1)), "two.toml").expect_err("seven missing");
        let Problem::Several(problems) = &e.problem else { panic!("{e}") };
        assert_eq!(problems.len(), 7, "{e}");
    }
    // Keys every file must give have no default; each added one has.
    let defaulted: Vec<(&str, u32)> = PARAMS.iter().filter(|p| p.default.is_some()).map(|p| (p.key, p.since)).collect();
    assert_eq!(defaulted.len(), ADDED.len(), "{defaulted:?}");
    assert!(ADDED.iter().all(|(k, f, _)| defaulted.iter().any(|(d, g)| d.ends_with(k) && g == f)), "{defaulted:?}");
}

/// A file of the first release's keys, upgraded: the format stated, the
/// added keys written with the values that keep the earlier behaviour
/// (each with its meaning and the format that added it), every line of the
/// original still there in order, the same machine loaded; upgrading
/// again changes nothing. A file that states the current format must give
/// every key, and one stating a later format is refused naming it.
#[test]
fn an_upgraded_file_loads_as_the_original_did() {
    for (name, text) in BUNDLED {
        let old = as_of(text, 1);
        let new = Arch::upgrade(&old, "old.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        // The format first of the keys, after the header comment, which
        // stays first.
        let first_key = new.lines().find(|l| !l.trim().is_empty() && !l.starts_with('#'));
        assert_eq!(first_key, Some("format = 3  # upgraded from format 1"), "{name}");
        assert_eq!(new.lines().next(), old.lines().next(), "{name}: the header first");
        let mut lines = new.lines();
        for l in old.lines() {
            assert!(lines.any(|n| n == l), "{name}: `{l}` kept, in order");
        }
        for (k, format, _) in ADDED {
            let line = new.lines().find(|l| l.starts_with(&format!("{k} = "))).expect("added");
            let said = format!("added in format {format}, this value keeps the earlier behaviour");
            assert!(line.contains("  # ") && line.ends_with(&said), "{line}");
        }
        let (a, b) = (Arch::parse(&old, "old.toml"), Arch::parse(&new, "new.toml"));
        assert_eq!(a.expect("loads"), b.expect("loads"), "{name}");
        assert_eq!(Arch::upgrade(&new, "new.toml").expect("loads"), new, "{name}: idempotent");
        // Stating the current format, the file must be whole.
        let stated = format!("format = 3\n{old}");
        let e = Arch::parse(&stated, "stated.toml").expect_err("the added keys missing");
        let Problem::Several(problems) = &e.problem else { panic!("{e}") };
        assert_eq!(problems.len(), ADDED.len(), "{e}");
        assert!(problems.iter().all(|(_, p)| matches!(p, Problem::Missing)), "{e}");
    }
    // The shipped example of a first-release file: mobile-tbdr under its
    // own name, loading as it did, upgraded to the same machine.
    let shipped = include_str!("../../../examples/first-release-gpu.toml");
    let mut first = Arch::parse(shipped, "first-release-gpu.toml").expect("loads");
    let upgraded = Arch::parse(&Arch::upgrade(shipped, "x").expect("upgrades"), "x").expect("loads");
    assert_eq!(first, upgraded);
    let tbdr = Arch::bundled("mobile-tbdr").expect("bundled");
    // The technology table is the bundled file's alone: a first-release
    // file models no silicon.
    assert!(first.technology.node.is_empty() && first.technology.sram_bit == 0.0 && first.technology.leakage == 0.0);
    (first.name, first.description, first.technology) =
        (tbdr.name.clone(), tbdr.description.clone(), tbdr.technology.clone());
    assert_eq!(first, tbdr);
    let later = BUNDLED[0].1.replace("format = 3", "format = 4");
    let e = Arch::parse(&later, "later.toml").expect_err("a later format");
    assert_eq!(e.key, "format", "{e}");
    assert!(e.to_string().contains("reads formats 1 to 3"), "{e}");
}

/// One error names every missing and unknown key, in file order.
#[test]
fn one_error_names_every_missing_and_unknown_key() {
    let text: String = BUNDLED[0]
        .1
        .lines()
        .filter(|l| !l.starts_with("clock =") && !l.starts_with("bandwidth ="))
        .chain(["[extra]", "knob = 1"])
        .collect::<Vec<_>>()
        .join("\n");
    let e = Arch::parse(&text, "old.toml").expect_err("three problems");
    let Problem::Several(problems) = &e.problem else { panic!("{e}") };
    let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(keys, ["extra.knob", "clock", "dram.bandwidth"], "{e}");
    assert!(e.to_string().starts_with("old.toml: (file): 3 keys: extra.knob: unknown key; clock: missing"), "{e}");
}

/// A table the model does not know is refused as an unknown key is, even
/// empty: the file of a million empty tables loaded before. Ours:
/// one empty table alone, and an empty table of a known unit (which only
/// leaves that unit's keys missing). The message lists 20 problems and
/// counts the rest.
#[test]
fn an_unknown_table_is_refused_even_empty() {
    let file = BUNDLED[0].1;
    let e = Arch::parse(&format!("{file}\n[cache_tweaks]\n"), "t.toml").expect_err("an unknown table");
    assert_eq!((e.key.as_str(), e.problem.to_string().starts_with("unknown key")), ("cache_tweaks", true), "{e}");
    let nested = file.replace("[dram]", "[dram.timing]\n[dram]");
    let e = Arch::parse(&nested, "t.toml").expect_err("an unknown inner table");
    assert_eq!(e.key, "dram.timing", "{e}");
    let million: String = (0..1_000_000).map(|i| format!("[t{i}]\n")).collect();
    let e = Arch::parse(&format!("{file}\n{million}"), "m.toml").expect_err("a million unknown tables");
    let text = e.to_string();
    assert!(text.contains("1000000 keys: t0: unknown key") && text.ends_with("; and 999980 more"), "{}", &text[..200]);
    assert!(text.len() < 2000, "the message stays short: {} bytes", text.len());
    // An empty table of a known unit: its keys are missing, not unknown.
    let emptied: String = file
        .lines()
        .skip_while(|l| *l != "[map_cache]")
        .take_while(|l| !l.is_empty())
        .fold(file.to_owned(), |t, l| if l.starts_with('[') { t } else { t.replace(&format!("{l}\n"), "") });
    let e = Arch::parse(&emptied, "e.toml").expect_err("keys missing");
    assert!(e.to_string().contains("map_cache.size: missing") && !e.to_string().contains("map_cache: unknown"), "{e}");
}
