//! A study as a host asks for it: checked and hashed in the library, so the
//! command line and Python cannot disagree.

use umbra::sim::Limits;
use umbra::sim::experiment::study::budget::Budget;
use umbra::sim::experiment::study::{Overrides, Request, StudyError};

fn request(overrides: Overrides) -> Request {
    Request {
        sweep: "quick".into(),
        overrides,
        shard: None,
        extremes: false,
        out: "target/unused".into(),
        replace: false,
    }
}

/// The replaced axes are hashed from one canonical text, written here by
/// hand: field names and `Debug` output play no part.
#[test]
fn the_replaced_axes_are_written_canonically() {
    let o = Overrides {
        scenes: vec!["crowd".into()],
        images: vec!["160x90".into()],
        reference_rays: Some(1),
        budgets: vec![Budget::artifacts(1.0), Budget::artifacts(0.5), "acne=0.01%".parse().expect("a budget")],
        maps: vec![256],
        ..Overrides::default()
    };
    assert_eq!(
        o.canonical(),
        "scenes=crowd\narch=\nset=\nimage=160x90\nreference_rays=1\nbudgets=1,0.5,acne=0.01%\nmaps=256"
    );
    assert!(Overrides::default().is_empty() && !o.is_empty());
}

/// No replaced axis: the sweep file's own hash; replaced axes: another,
/// the same for the same axes and different for different ones.
#[test]
fn the_hash_is_the_files_own_or_covers_the_replaced_axes() {
    let limits = Limits::DEFAULT;
    let hash = |o: Overrides| request(o).prepare(&limits, 1).expect("a study").spec.hash;
    let file = umbra::sim::SweepFile::open("quick", &limits).expect("bundled").spec(&limits).expect("a sweep").hash;
    assert_eq!(hash(Overrides::default()), file);
    let small = || Overrides { images: vec!["160x90".into()], ..Overrides::default() };
    assert_ne!(hash(small()), file);
    assert_eq!(hash(small()), hash(small()));
    assert_ne!(hash(small()), hash(Overrides { reference_rays: Some(1), ..small() }));
    // Cost limits change the summary, so the hash.
    let limited = umbra::sim::experiment::plan::CostLimits::parse(Some("2mm2"), None).expect("a limit");
    assert_ne!(hash(small()), hash(Overrides { cost_limits: limited, ..small() }));
}

/// Each mistake is refused before any folder is made, naming the flag.
#[test]
fn a_bad_request_names_its_flag() {
    let limits = Limits::DEFAULT;
    let err = |o: Overrides| request(o).prepare(&limits, 1).expect_err("refused").to_string();
    assert!(err(Overrides { images: vec!["160by90".into()], ..Overrides::default() }).contains("--image `160by90`"));
    assert!(err(Overrides { maps: vec![256, 256], ..Overrides::default() }).contains("--maps `256` is given twice"));
    assert!(err(Overrides { maps: vec![1 << 20], ..Overrides::default() }).contains("--maps 1048576"));
    // One size written two ways is one size.
    let images = |a: &str, b: &str| Overrides { images: vec![a.into(), b.into()], ..Overrides::default() };
    assert!(err(images("160x90", "160×90")).contains("`160x90` and `160×90` are one size"));
    assert!(err(images("160x90", "160 x 90")).contains("are one size, 160x90"));
    assert!(err(Overrides { reference_rays: Some(17), ..Overrides::default() }).contains("--reference-rays 17"));
    assert!(err(Overrides { budgets: vec![Budget::artifacts(0.0)], ..Overrides::default() }).contains("--budgets"));
    let shard = Request { shard: Some("2/2".into()), ..request(Overrides::default()) };
    assert!(matches!(shard.prepare(&limits, 1), Err(StudyError::Shard(_))));
    assert!(!std::path::Path::new("target/unused").exists(), "nothing is written by a refused request");
}
