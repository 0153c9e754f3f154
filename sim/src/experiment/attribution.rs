//! Why two architectures differ on a render: the difference in time,
//! DRAM bytes by purpose and energy attributed to each key that differs,
//! by changing one key at a time from the first toward the second, plus
//! the remainder that only their interaction explains, ranked by the
//! effect on time.
//!
//! With `a` and `b` differing in keys `k₁ … kₙ`, key `kᵢ`'s effect is
//! `cost(a with kᵢ from b) − cost(a)`; the remainder is
//! `cost(b) − cost(a) − Σ effects`. The effects are exact where the keys
//! act alone (a tile size and a cache size on a frame bound by neither
//! interact little) and the remainder says how far they do not. A key
//! that cannot change alone (a cache size whose sets need `b`'s ways too)
//! has no effect of its own: it is named, and its share is in the
//! remainder.

use crate::output::table::{Align, Table};
use std::fmt::Write as _;

use serde::Serialize;

use crate::cost::arch::{Arch, PARAMS, Unit};
use crate::cost::report::CostReport;
use crate::render::{Checked, RenderError, cost_others};

/// A difference of costs: time, energy, and DRAM bytes by purpose (the
/// map's reads as DRAM fetched them; light and camera passes together).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Delta {
    /// Frame time, seconds.
    pub seconds: f64,
    /// Frame energy, joules.
    pub joules: f64,
    /// DRAM bytes of the frame.
    pub bytes: i64,
    /// DRAM bytes by purpose: name, change.
    pub bytes_by_purpose: Vec<(&'static str, i64)>,
}

impl Delta {
    /// `b` − `a`.
    fn between(a: &CostReport, b: &CostReport) -> Self {
        let purposes = |r: &CostReport| -> Vec<(&'static str, i64)> {
            r.dram().fields().map(|(p, b)| (p.name(), i64::try_from(b).unwrap_or(i64::MAX))).collect()
        };
        let bytes = |r: &CostReport| i64::try_from(r.bytes()).unwrap_or(i64::MAX);
        Self {
            seconds: b.seconds() - a.seconds(),
            joules: b.energy().total() - a.energy().total(),
            bytes: bytes(b) - bytes(a),
            bytes_by_purpose: purposes(a).into_iter().zip(purposes(b)).map(|((n, x), (_, y))| (n, y - x)).collect(),
        }
    }

    /// `self` + `k` × `o`.
    #[allow(clippy::cast_precision_loss, reason = "k is 1 or -1")]
    fn plus(&self, k: i64, o: &Self) -> Self {
        Self {
            seconds: self.seconds + k as f64 * o.seconds,
            joules: self.joules + k as f64 * o.joules,
            bytes: self.bytes + k * o.bytes,
            bytes_by_purpose: self
                .bytes_by_purpose
                .iter()
                .zip(&o.bytes_by_purpose)
                .map(|(&(n, x), &(_, y))| (n, x + k * y))
                .collect(),
        }
    }
}

/// One key's share of the difference.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Share {
    /// The key.
    pub key: &'static str,
    /// Its value in `a`, then in `b`, as files write them.
    pub values: (String, String),
    /// What changing it alone does; `None` when it cannot change alone.
    pub effect: Option<Delta>,
    /// Why it cannot change alone.
    pub alone: Option<String>,
}

/// The difference between two architectures on one render, attributed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Attribution {
    /// The first architecture's name.
    pub a: String,
    /// The second's.
    pub b: String,
    /// The render, in words.
    pub config: String,
    /// `a`'s frame time, seconds.
    pub a_seconds: f64,
    /// `b`'s.
    pub b_seconds: f64,
    /// `b` − `a`.
    pub total: Delta,
    /// Each differing key's share, ranked by the size of its effect on
    /// time (those that cannot change alone last).
    pub shares: Vec<Share>,
    /// What the shares do not explain: the keys' interaction.
    pub remainder: Delta,
}

/// Attribute `b − a` on the render `job` to each key that differs.
///
/// ```
/// use umbra_sim::{Arch, Limits, RenderConfig, Scene};
/// use umbra_sim::experiment::attribution::attribute;
/// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
/// let cfg = RenderConfig { width: 96, height: 54, map_size: 128, ..RenderConfig::DEFAULT };
/// let a = Arch::bundled("talisman")?;
/// let mut b = a.clone();
/// b.set("dram.bandwidth=2.4GB/s")?;
/// let t = attribute(&cfg.check(&scene, &Limits::DEFAULT)?, &a, &b)?;
/// assert_eq!(t.shares.len(), 1);
/// // One key explains all of it.
/// assert!(t.remainder.seconds.abs() <= 1e-12 && t.remainder.bytes == 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// The render's or a costing's [`RenderError`].
pub fn attribute(job: &Checked<'_>, a: &Arch, b: &Arch) -> Result<Attribution, RenderError> {
    let differing: Vec<&'static str> =
        PARAMS.iter().filter(|p| p.unit != Unit::Text && p.written(a) != p.written(b)).map(|p| p.key).collect();
    let mut archs = vec![a.clone(), b.clone()];
    let mut alone = Vec::new();
    for key in &differing {
        let mut one = a.clone();
        match one.take(key, b) {
            Ok(()) => {
                archs.push(one);
                alone.push(None);
            }
            Err((k, problem)) => alone.push(Some(format!("changed alone, {k}: {problem}"))),
        }
    }
    let mut out: Vec<Option<Result<CostReport, RenderError>>> = archs.iter().map(|_| None).collect();
    cost_others(job, &archs, &mut out);
    let mut reports = Vec::with_capacity(out.len());
    for r in out {
        reports.push(r.unwrap_or_else(|| Err(RenderError::Cost("not costed".into())))?);
    }
    let (ra, rb) = (&reports[0], &reports[1]);
    let total = Delta::between(ra, rb);
    let mut costed = reports[2..].iter();
    let mut shares: Vec<Share> = differing
        .iter()
        .zip(alone)
        .map(|(&key, alone)| {
            let p = PARAMS.iter().find(|p| p.key == key);
            let values = p.map(|p| (p.written(a), p.written(b))).unwrap_or_default();
            let effect = if alone.is_none() { costed.next().map(|r| Delta::between(ra, r)) } else { None };
            Share { key, values, effect, alone }
        })
        .collect();
    let explained =
        shares.iter().filter_map(|s| s.effect.as_ref()).fold(Delta::between(ra, ra), |acc, e| acc.plus(1, e));
    let remainder = total.plus(-1, &explained);
    shares.sort_by(|x, y| {
        let size = |s: &Share| s.effect.as_ref().map_or(-1.0, |e| e.seconds.abs());
        size(y).total_cmp(&size(x))
    });
    Ok(Attribution {
        a: a.name.clone(),
        b: b.name.clone(),
        config: ra.config.clone(),
        a_seconds: ra.seconds(),
        b_seconds: rb.seconds(),
        total,
        shares,
        remainder,
    })
}

impl Attribution {
    /// The attribution as a Markdown table: a row per key (ranked), the
    /// remainder and the total; time in µs and percent of `a`'s, energy
    /// in µJ, DRAM bytes in all and by every purpose that changes.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let purposes: Vec<(usize, &'static str)> = self
            .total
            .bytes_by_purpose
            .iter()
            .enumerate()
            .filter(|(k, _)| {
                self.shares
                    .iter()
                    .filter_map(|x| x.effect.as_ref())
                    .chain([&self.total, &self.remainder])
                    .any(|d| d.bytes_by_purpose[*k].1 != 0)
            })
            .map(|(k, &(n, _))| (k, n))
            .collect();
        let _ = writeln!(
            s,
            "From `{}` ({:.3} ms) to `{}` ({:.3} ms) on {}, one key at a time:\n",
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
            ("energy (µJ)".to_owned(), Align::Right),
            ("DRAM bytes".to_owned(), Align::Right),
        ];
        columns.extend(purposes.iter().map(|(_, n)| (format!("{n} bytes"), Align::Right)));
        let mut t = Table::new(&columns);
        let cells = |what: String, d: &Delta| {
            let mut cells = vec![
                what,
                format!("{:+.3}", d.seconds * 1e6),
                format!("{:+.1} %", 100.0 * d.seconds / self.a_seconds.max(f64::MIN_POSITIVE)),
                format!("{:+.3}", d.joules * 1e6),
                format!("{:+}", d.bytes),
            ];
            cells.extend(purposes.iter().map(|&(k, _)| format!("{:+}", d.bytes_by_purpose[k].1)));
            cells
        };
        for share in &self.shares {
            let what = format!("`{}` {} → {}", share.key, share.values.0, share.values.1);
            match &share.effect {
                Some(d) => t.row(cells(what, d)),
                None => t.row([format!("{what} ({})", share.alone.as_deref().unwrap_or(""))]),
            }
        }
        t.row(cells("the keys' interaction (the remainder)".to_owned(), &self.remainder));
        t.row(cells("**all of them**".to_owned(), &self.total));
        s.push_str(&t.markdown());
        s
    }
}
