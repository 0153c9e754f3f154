//! The shading's cycles charged from per-tile tallies against the same
//! charges made event by event: every bundled architecture, every
//! algorithm, three filters.

use serde_json::Value;

use super::shared::variants;
use crate::cost::arch::Arch;
use crate::cost::timing::charges_event_by_event;
use crate::input::limits::Limits;
use crate::render::{RenderConfig, TruthSource, render_costed, truth};
use crate::world::scene::Scene;
use umbra_core::DepthFormatKind;
use umbra_core::shadow::{Filter, Jitter};

/// The largest relative difference of two reports' numbers, with every
/// integer and every string equal (`where_` names the first that is not).
fn largest_difference(a: &Value, b: &Value, at: &str) -> Result<f64, String> {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) if x.len() == y.len() => x.iter().try_fold(0.0f64, |m, (k, v)| {
            let w = y.get(k).ok_or_else(|| format!("{at}.{k} is missing"))?;
            Ok(m.max(largest_difference(v, w, &format!("{at}.{k}"))?))
        }),
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .try_fold(0.0f64, |m, (i, (v, w))| Ok(m.max(largest_difference(v, w, &format!("{at}[{i}]"))?))),
        (Value::Number(x), Value::Number(y)) if x.is_f64() || y.is_f64() => {
            let (p, q) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            let scale = p.abs().max(q.abs());
            Ok(if scale == 0.0 { 0.0 } else { (p - q).abs() / scale })
        }
        _ if a == b => Ok(0.0),
        _ => Err(format!("{at}: {a} against {b}")),
    }
}

/// Tallied, a tile's shade and shadow cycles are one product a count
/// (`pixels × program`, `samples ÷ rate`, …); event by event they were a
/// sum of one term an event. Every integer (bytes, requests, misses,
/// events) is the same either way, and a float differs only by the sum's
/// rounding: at most `(n − 1)·2⁻⁵³` of it for `n` terms. The most terms a
/// unit sums here are an immediate machine's whole shading in one unit:
/// 80 × 45 pixels at up to ten events a pixel, 36 000 terms, so 4·10⁻¹²;
/// the tolerance is 10⁻¹¹ (2.5× that bound), and the largest difference
/// measured is printed. Breaking a charge (a culled lookup's compare
/// dropped from the tallies) moves the Shadow stage by whole cycles, far
/// beyond it.
#[test]
#[allow(clippy::needless_update, reason = "a parameter the study does not vary takes its default")]
fn tallied_costs_are_the_event_by_event_costs_to_their_rounding() {
    const TOLERANCE: f64 = 1e-11;
    let limits = Limits::DEFAULT;
    let scene = Scene::open("table-and-sphere", &limits).expect("bundled");
    let archs = Arch::presets().expect("bundled");
    let (w, h) = (80, 45);
    let t = truth(&scene, w, h, 1, &indicatif::ProgressBar::hidden()).expect("a reference");
    let (mut largest, mut compared, mut differing) = (0.0f64, 0, 0);
    for v in variants() {
        for filter in [Filter::Bilinear, Filter::Box { size: 3 }, Filter::Jittered(Jitter::REEVES)] {
            let cfg = RenderConfig {
                algorithm: v.algorithm,
                format: DepthFormatKind::D24,
                map_size: 128,
                filter,
                bias: v.bias,
                virtual_samples: v.virtual_samples,
                width: w,
                height: h,
                reference_rays: 1,
                culling: v.culling,
                ..RenderConfig::DEFAULT
            };
            let job = cfg.check(&scene, &limits).expect("checked");
            let (_, tallied) = render_costed(&job, TruthSource::Given(t.clone()), &archs).expect("renders");
            let (_, events) =
                charges_event_by_event(|| render_costed(&job, TruthSource::Given(t.clone()), &archs)).expect("renders");
            for ((a, x), y) in archs.iter().zip(&tallied).zip(&events) {
                let json = |r: &Result<_, _>| serde_json::to_value(r.as_ref().expect("costed")).expect("serialises");
                let (x, y) = (json(x), json(y));
                let d = largest_difference(&x, &y, "report")
                    .unwrap_or_else(|e| panic!("{} on {}: {e}", cfg.describe(), a.name));
                assert!(d <= TOLERANCE, "{} on {}: relative difference {d:e}", cfg.describe(), a.name);
                largest = largest.max(d);
                differing += usize::from(x != y);
                compared += 1;
            }
        }
    }
    println!(
        "largest relative difference, tallied against event by event: {largest:e} ({differing} of {compared} reports differ at all)"
    );
    assert_eq!(compared, 12 * 3 * archs.len());
}
