//! Why two architectures differ on a render: the difference in time,
//! energy and DRAM bytes by purpose attributed to each key that differs by
//! its Shapley value — its marginal effect averaged over every order of
//! changing the keys from the first file toward the second — ranked by
//! the effect on time.
//!
//! With `a` and `b` differing in keys `k₁ … kₙ` and `v(S)` the cost of `a`
//! with the keys of `S` taken from `b`, less the cost of `a`, key `i`'s
//! share is `Σ_{S ∌ i} |S|! (n − |S| − 1)! / n! · (v(S ∪ {i}) − v(S))`
//! (Shapley 1953). The shares add up to `v(all) = cost(b) − cost(a)` with
//! no remainder (the interaction of keys is split among them), do not
//! depend on the order the keys are listed in, and `diff b a` is key by
//! key the negative of `diff a b`. Up to [`EXACT_KEYS`] keys every one of
//! the `2ⁿ` coalitions is costed (grouped, as a study's architectures
//! are, into as few runs of the passes as their tilings allow); beyond,
//! [`PERMUTATIONS`] random orders are, and each share carries the standard
//! error of its mean. Keys that cannot change without one another (a cache
//! size whose sets need the other file's ways too) are one player: they
//! share one row.

mod markdown;

use std::collections::BTreeMap;

use serde::Serialize;

use crate::cost::arch::{Arch, PARAMS, Unit};
use crate::cost::dram::Purpose;
use crate::cost::report::CostReport;
use crate::render::{Checked, RenderError, cost_others};
use crate::world::occluders::Lit;

/// Keys up to which every coalition is costed; beyond, orders are sampled.
pub const EXACT_KEYS: usize = 12;

/// Random orders sampled beyond [`EXACT_KEYS`] keys.
pub const PERMUTATIONS: usize = 64;

/// Architectures costed in one grouped costing: bounds the memory of a
/// run of the passes however many coalitions there are.
const GROUP: usize = 64;

/// A difference of costs: time, energy, and DRAM bytes in all and by
/// purpose (light and camera passes together). Bytes are real: a Shapley
/// share is an average of integer differences.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Delta {
    /// Frame time, seconds.
    pub seconds: f64,
    /// Frame energy, joules.
    pub joules: f64,
    /// Silicon area of the units the render uses, square metres.
    pub square_metres: f64,
    /// DRAM bytes of the frame.
    pub bytes: f64,
    /// DRAM bytes by purpose, in [`Purpose::ALL`] order: name, change.
    pub bytes_by_purpose: Vec<(&'static str, f64)>,
}

/// A coalition's cost, or a weighted sum of differences of them, as the
/// shares weigh it: reals for time and energy, integers for bytes by
/// purpose (numerators over a common denominator, so that the shares'
/// bytes are exact).
#[derive(Clone, Copy, Debug, Default)]
struct Value {
    seconds: f64,
    joules: f64,
    square_metres: f64,
    bytes: [i128; 12],
}

impl Value {
    fn of(r: &CostReport) -> Self {
        let d = r.dram();
        Self {
            seconds: r.seconds(),
            joules: r.energy().total(),
            square_metres: r.square_metres(),
            bytes: Purpose::ALL.map(|p| i128::from(d.get(p))),
        }
    }

    /// Add `w × (x − y)`, `w` the term's weight and `r` its real share.
    fn add(&mut self, (w, r): (i128, f64), x: &Value, y: &Value) {
        self.seconds += r * (x.seconds - y.seconds);
        self.joules += r * (x.joules - y.joules);
        self.square_metres += r * (x.square_metres - y.square_metres);
        for (s, (a, b)) in self.bytes.iter_mut().zip(x.bytes.iter().zip(y.bytes)) {
            *s += w * (a - b);
        }
    }

    /// As a delta, its bytes divided by `denominator`.
    #[allow(clippy::cast_precision_loss, reason = "bytes times a weight, far below 2^100")]
    fn delta(&self, denominator: i128) -> Delta {
        let bytes: Vec<(&'static str, f64)> =
            Purpose::ALL.iter().zip(self.bytes).map(|(p, b)| (p.name(), b as f64 / denominator as f64)).collect();
        let all: i128 = self.bytes.iter().sum();
        Delta {
            seconds: self.seconds,
            joules: self.joules,
            square_metres: self.square_metres,
            bytes: all as f64 / denominator as f64,
            bytes_by_purpose: bytes,
        }
    }
}

/// One differing key, as each file writes it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Key {
    /// The key.
    pub key: &'static str,
    /// Its value in `a`, then in `b`.
    pub values: (String, String),
}

/// A player's share of the difference.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Share {
    /// Its keys: one, or those that cannot change without one another.
    pub keys: Vec<Key>,
    /// Its Shapley value.
    pub share: Delta,
    /// What changing its keys alone from `a` does (its marginal effect
    /// first in the order).
    pub alone: Delta,
    /// What changing its keys last does (its marginal effect last in the
    /// order): the negative of changing them alone from `b`.
    pub last: Delta,
    /// The standard error of `share.seconds` when orders were sampled.
    pub standard_error_seconds: Option<f64>,
}

/// How the shares were computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Every coalition of the players costed.
    Exact {
        /// The players.
        players: usize,
        /// The coalitions costed (`2^players`).
        coalitions: usize,
    },
    /// Random orders sampled.
    Sampled {
        /// The players.
        players: usize,
        /// The orders.
        permutations: usize,
        /// The distinct coalitions costed.
        coalitions: usize,
    },
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
    /// Each player's share, ranked by the size of its effect on time.
    pub shares: Vec<Share>,
    /// How the shares were computed.
    pub method: Method,
}

/// `a` with `keys` taken from `b`, checked once they all are; `None`
/// when they make no machine.
fn coalition(a: &Arch, b: &Arch, keys: &[&'static str]) -> Option<Arch> {
    let mut arch = a.clone();
    arch.take(keys, b).ok().map(|()| arch)
}

/// The keys of the players in `mask`.
fn keys_of(players: &[Vec<&'static str>], mask: u64) -> Vec<&'static str> {
    players.iter().enumerate().filter(|(i, _)| mask >> i & 1 == 1).flat_map(|(_, p)| p.iter().copied()).collect()
}

/// A small deterministic generator (splitmix64) for the sampled orders.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The orders of `n` players the shares average over: `None` for every
/// order (exact), else [`PERMUTATIONS`] shuffles.
fn orders(n: usize) -> Option<Vec<Vec<usize>>> {
    (n > EXACT_KEYS).then(|| {
        let mut state = 0x0005_a91e_u64;
        (0..PERMUTATIONS)
            .map(|_| {
                let mut order: Vec<usize> = (0..n).collect();
                for i in (1..n).rev() {
                    #[allow(clippy::cast_possible_truncation, reason = "an index below n")]
                    let j = (splitmix(&mut state) % (i as u64 + 1)) as usize;
                    order.swap(i, j);
                }
                order
            })
            .collect()
    })
}

/// The coalitions the shares of `n` players need: every one, or those
/// along each sampled order.
fn masks(n: usize, orders: Option<&[Vec<usize>]>) -> Vec<u64> {
    match orders {
        None => (0..1u64 << n).collect(),
        Some(orders) => {
            // The empty and the whole coalitions, and each player alone
            // and each last, beside those along the orders.
            let n = orders.first().map_or(0, Vec::len);
            let full = (1u64 << n) - 1;
            let mut all = vec![0u64, full];
            all.extend((0..n).flat_map(|i| [1 << i, full ^ 1 << i]));
            for order in orders {
                let mut m = 0u64;
                for &i in order {
                    m |= 1 << i;
                    all.push(m);
                }
            }
            all.sort_unstable();
            all.dedup();
            all
        }
    }
}

/// Attribute `b − a` on the render `job` to each key that differs, by
/// Shapley value.
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
/// // One key explains all of it.
/// assert_eq!(t.shares.len(), 1);
/// assert_eq!(t.shares[0].share, t.total);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// The render's or a costing's [`RenderError`].
pub fn attribute(job: &Checked<'_>, a: &Arch, b: &Arch) -> Result<Attribution, RenderError> {
    // Computed one way round whichever way it is asked, so that `diff b a`
    // is, bit for bit, the negative of `diff a b`.
    if b.to_toml() < a.to_toml() {
        return attribute(job, b, a).map(Attribution::reversed);
    }
    let differing: Vec<&'static str> =
        PARAMS.iter().filter(|p| p.unit != Unit::Text && p.written(a) != p.written(b)).map(|p| p.key).collect();
    let mut players: Vec<Vec<&'static str>> = differing.iter().map(|&k| vec![k]).collect();
    // Keys that cannot change without one another play as one: merge the
    // players of the first coalition that is no machine, until none is.
    let (archs, order) = loop {
        let n = players.len();
        let order = orders(n);
        let wanted = masks(n, order.as_deref());
        let mut archs = BTreeMap::new();
        let mut invalid = None;
        for &m in &wanted {
            match coalition(a, b, &keys_of(&players, m)) {
                Some(arch) => {
                    archs.insert(m, arch);
                }
                None => {
                    invalid = Some(m);
                    break;
                }
            }
        }
        let Some(m) = invalid else { break (archs, order) };
        let (mut joined, mut rest) = (Vec::new(), Vec::new());
        for (i, p) in players.into_iter().enumerate() {
            if m >> i & 1 == 1 { joined.extend(p) } else { rest.push(p) }
        }
        rest.insert(0, joined);
        players = rest;
    };
    let values = cost_all(job, &archs)?;
    let n = players.len();
    let v = |m: u64| values.get(&m).copied().unwrap_or_default();
    let full = (1u64 << n) - 1;
    let mut sums = vec![Value::default(); n];
    let mut squares = vec![0.0f64; n];
    let denominator: i128 = match &order {
        None => {
            // Weight of a coalition of s others: s! (n − s − 1)! over n!.
            let factorial = |k: usize| (1..=k as i128).product::<i128>();
            for (i, sum) in sums.iter_mut().enumerate() {
                for m in (0..=full).filter(|m| m >> i & 1 == 0) {
                    let s = m.count_ones() as usize;
                    let w = factorial(s) * factorial(n - s - 1);
                    #[allow(clippy::cast_precision_loss, reason = "at most 12!")]
                    let r = w as f64 / factorial(n) as f64;
                    sum.add((w, r), &v(m | 1 << i), &v(m));
                }
            }
            factorial(n)
        }
        Some(orders) => {
            #[allow(clippy::cast_precision_loss, reason = "a few orders")]
            let r = 1.0 / orders.len() as f64;
            for order in orders {
                let mut m = 0u64;
                for &i in order {
                    let (x, y) = (v(m | 1 << i), v(m));
                    sums[i].add((1, r), &x, &y);
                    squares[i] += (x.seconds - y.seconds).powi(2);
                    m |= 1 << i;
                }
            }
            orders.len() as i128
        }
    };
    let total = {
        let mut t = Value::default();
        t.add((1, 1.0), &v(full), &v(0));
        t.delta(1)
    };
    let mut shares: Vec<Share> = players
        .iter()
        .enumerate()
        .map(|(i, keys)| {
            let (mut alone, mut last) = (Value::default(), Value::default());
            alone.add((1, 1.0), &v(1 << i), &v(0));
            last.add((1, 1.0), &v(full), &v(full ^ 1 << i));
            let share = sums[i].delta(denominator);
            #[allow(clippy::cast_precision_loss, reason = "a few orders")]
            let standard_error_seconds = order.as_ref().map(|o| {
                let m = o.len() as f64;
                let var = (squares[i] / m - share.seconds.powi(2)).max(0.0) * m / (m - 1.0).max(1.0);
                (var / m).sqrt()
            });
            let keys = keys
                .iter()
                .map(|&key| {
                    let p = PARAMS.iter().find(|p| p.key == key);
                    Key { key, values: p.map(|p| (p.written(a), p.written(b))).unwrap_or_default() }
                })
                .collect();
            Share { keys, share, alone: alone.delta(1), last: last.delta(1), standard_error_seconds }
        })
        .collect();
    shares.sort_by(|x, y| y.share.seconds.abs().total_cmp(&x.share.seconds.abs()));
    let method = match &order {
        None => Method::Exact { players: n, coalitions: values.len() },
        Some(o) => Method::Sampled { players: n, permutations: o.len(), coalitions: values.len() },
    };
    let ra_seconds = v(0).seconds;
    Ok(Attribution {
        a: a.name.clone(),
        b: b.name.clone(),
        config: job.config().describe(),
        a_seconds: ra_seconds,
        b_seconds: v(full).seconds,
        total,
        shares,
        method,
    })
}

/// Every coalition's cost, [`GROUP`] architectures to a grouped costing.
fn cost_all(job: &Checked<'_>, archs: &BTreeMap<u64, Arch>) -> Result<BTreeMap<u64, Value>, RenderError> {
    let entries: Vec<(&u64, &Arch)> = archs.iter().collect();
    let lit = Lit::each(job.scene());
    let mut values = BTreeMap::new();
    for chunk in entries.chunks(GROUP) {
        let group: Vec<Arch> = chunk.iter().map(|(_, a)| (*a).clone()).collect();
        let mut out: Vec<Option<Result<CostReport, RenderError>>> = group.iter().map(|_| None).collect();
        cost_others((job, &lit), &group, &mut out);
        for ((m, _), r) in chunk.iter().zip(out) {
            let r = r.unwrap_or_else(|| Err(RenderError::Cost("not costed".into())))?;
            values.insert(**m, Value::of(&r));
        }
    }
    Ok(values)
}

impl Delta {
    /// The same difference, the other way.
    fn negated(&self) -> Self {
        Self {
            seconds: -self.seconds,
            joules: -self.joules,
            square_metres: -self.square_metres,
            bytes: -self.bytes,
            bytes_by_purpose: self.bytes_by_purpose.iter().map(|&(n, b)| (n, -b)).collect(),
        }
    }
}

impl Attribution {
    /// The attribution of `a − b`, from that of `b − a`: every difference
    /// negated, the files' roles swapped.
    fn reversed(self) -> Self {
        let shares = self
            .shares
            .into_iter()
            .map(|s| Share {
                keys: s.keys.into_iter().map(|k| Key { key: k.key, values: (k.values.1, k.values.0) }).collect(),
                share: s.share.negated(),
                alone: s.last.negated(),
                last: s.alone.negated(),
                standard_error_seconds: s.standard_error_seconds,
            })
            .collect();
        Self {
            a: self.b,
            b: self.a,
            config: self.config,
            a_seconds: self.b_seconds,
            b_seconds: self.a_seconds,
            total: self.total.negated(),
            shares,
            method: self.method,
        }
    }
}
