//! What an architecture file implies: its peak rates, the DRAM bandwidth
//! it can achieve (the lesser of its bandwidth and the latency ceiling of
//! Little's law, `requests_in_flight × burst / latency`), its caches'
//! geometry and miss ceilings, and the on-chip bytes a tile needs; the
//! warnings where one key makes another ineffective; and the difference
//! between two files, key by key and figure by figure.
//!
//! ```
//! use umbra_sim::Arch;
//! let arch = Arch::bundled("mobile-tbdr")?;
//! let figure = |name: &str| arch.derived().into_iter().find(|f| f.name == name).map(|f| f.value);
//! // 180 requests in flight × 64 B bursts / 225 ns of latency.
//! assert_eq!(figure("DRAM latency ceiling").map(f64::round), Some(51.2e9));
//! # Ok::<(), umbra_sim::cost::arch::ArchError>(())
//! ```

use super::keys::PARAMS;
use super::machine::Arch;
use super::measure::Unit;
use super::units::CacheParams;

/// One derived figure: a name, its value in the unit's base, the unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// What it is.
    pub name: &'static str,
    /// Its value (bytes, B/s, Hz, s, or a plain number).
    pub value: f64,
    /// Its unit: `Unit::Frequency` for a rate a second (written with an SI
    /// prefix and `/s`), `Unit::Number` for a plain number.
    pub unit: Unit,
    /// How it is worked out.
    pub how: &'static str,
}

impl Figure {
    /// The value written with its unit (`51.2GB/s`).
    #[must_use]
    pub fn text(&self) -> String {
        match self.unit {
            Unit::Number | Unit::Count => format!("{}", (self.value * 1000.0).round() / 1000.0),
            Unit::Frequency => {
                let (scale, prefix) = [(1e12, "T"), (1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, "")]
                    .into_iter()
                    .find(|&(k, _)| self.value >= k)
                    .unwrap_or((1.0, ""));
                format!("{} {prefix}/s", (self.value / scale * 1000.0).round() / 1000.0)
            }
            u => u.show(self.value),
        }
    }
}

/// The latency ceiling of a memory that keeps `in_flight` requests of
/// `bytes` each outstanding at `latency` seconds: Little's law, B/s
/// (infinite at zero latency).
#[must_use]
#[allow(clippy::cast_precision_loss, reason = "counts and sizes below 2^53")]
pub(crate) fn latency_ceiling(in_flight: u64, bytes: u64, latency: f64) -> f64 {
    if latency > 0.0 { in_flight as f64 * bytes as f64 / latency } else { f64::INFINITY }
}

impl Arch {
    /// The DRAM bandwidth the machine can sustain: its bandwidth, or the
    /// latency ceiling when that is lower.
    #[must_use]
    pub(crate) fn achievable_bandwidth(&self) -> f64 {
        self.dram.bandwidth.min(self.dram_latency_ceiling())
    }

    /// The DRAM bandwidth the requests kept in flight sustain at the
    /// latency (Little's law): `requests_in_flight × burst / latency`.
    #[must_use]
    pub(crate) fn dram_latency_ceiling(&self) -> f64 {
        latency_ceiling(self.dram.requests_in_flight, self.dram.burst, self.dram.latency)
    }

    /// Every derived figure, in a fixed order.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "sizes and counts below 2^53")]
    pub fn derived(&self) -> Vec<Figure> {
        let clock = self.clock;
        let tile = u64::from(self.raster.tile);
        let texels = (tile * tile) as f64;
        let mut out = vec![
            Figure {
                name: "raster fill",
                value: self.raster.fragments_per_clock * clock,
                unit: Unit::Frequency,
                how: "raster.fragments_per_clock × clock, fragments a second (0: an evaluator per tile)",
            },
            Figure {
                name: "depth rate",
                value: self.depth.fragments_per_clock * clock,
                unit: Unit::Frequency,
                how: "depth.fragments_per_clock × clock, fragments a second per buffer (0: bit-serial)",
            },
            Figure {
                name: "shadow sample rate",
                value: self.shadow.samples_per_clock * clock,
                unit: Unit::Frequency,
                how: "shadow.samples_per_clock × clock, map samples a second",
            },
            Figure { name: "DRAM bandwidth", value: self.dram.bandwidth, unit: Unit::Bandwidth, how: "dram.bandwidth" },
            Figure {
                name: "DRAM latency ceiling",
                value: self.dram_latency_ceiling(),
                unit: Unit::Bandwidth,
                how: "dram.requests_in_flight × dram.burst / dram.latency (Little's law)",
            },
            Figure {
                name: "DRAM achievable",
                value: self.achievable_bandwidth(),
                unit: Unit::Bandwidth,
                how: "the lesser of the bandwidth and the latency ceiling",
            },
            Figure {
                name: "DRAM bytes a clock",
                value: self.achievable_bandwidth() / clock,
                unit: Unit::Number,
                how: "achievable bandwidth / clock",
            },
            Figure {
                name: "DRAM latency in clocks",
                value: self.latency_cycles(),
                unit: Unit::Number,
                how: "dram.latency × clock",
            },
            Figure {
                name: "light depth a tile",
                value: 2.0 * 4.0 * texels,
                unit: Unit::Bytes,
                how: "raster.tile² × 4 bytes × 2 buffers (z1, z2), on chip when on_chip.light_depth",
            },
            Figure {
                name: "camera depth and ids a tile",
                value: 8.0 * texels,
                unit: Unit::Bytes,
                how: "raster.tile² × (4 bytes depth + 4 bytes id), on chip when on_chip.camera_depth",
            },
        ];
        for (prefix, c) in [("map cache", &self.map_cache), ("depth cache", &self.depth_cache)] {
            out.extend(cache_figures(prefix, c, self.dram.latency));
        }
        out
    }

    /// Where one key makes another ineffective: `(keys, warning)`. The
    /// queues that cap the DRAM bandwidth, then every key set to do
    /// something that no unit reads ([`Arch::unread`]).
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "sizes and counts below 2^53")]
    pub fn warnings(&self) -> Vec<(&'static str, String)> {
        let mut w = Vec::new();
        // A ceiling equal to the bandwidth but for rounding (9500 × 32 B /
        // 400 ns is 760 GB/s to within 1 ulp) caps nothing.
        let below = |ceiling: f64, bandwidth: f64| ceiling < bandwidth * (1.0 - 1e-9);
        let ceiling = self.dram_latency_ceiling();
        if below(ceiling, self.dram.bandwidth) {
            let needed = (self.dram.bandwidth * self.dram.latency / self.dram.burst.max(1) as f64).ceil();
            w.push((
                "dram.bandwidth",
                format!(
                    "{} is above the latency ceiling of {} (dram.requests_in_flight {} × dram.burst {} / dram.latency {}): streams are latency-bound, and bandwidth above the ceiling buys nothing; {needed} requests in flight would use it",
                    Unit::Bandwidth.show(self.dram.bandwidth),
                    Unit::Bandwidth.show(ceiling),
                    self.dram.requests_in_flight,
                    Unit::Bytes.show(self.dram.burst as f64),
                    Unit::Time.show(self.dram.latency),
                ),
            ));
        }
        // Each cache's misses are a queue of their own: judged against the
        // peak, not what DRAM's own queue achieves, so that every key that
        // caps the bandwidth is named at once, in order along the chain.
        for (key, c) in
            [("map_cache.misses_in_flight", &self.map_cache), ("depth_cache.misses_in_flight", &self.depth_cache)]
        {
            let misses = latency_ceiling(c.misses_in_flight, c.line, self.dram.latency);
            if c.size > 0 && below(misses, self.dram.bandwidth) {
                let needed = (self.dram.bandwidth * self.dram.latency / c.line.max(1) as f64).ceil();
                w.push((
                    key,
                    format!(
                        "{} misses of {} in flight fetch at most {} at the DRAM latency, below the DRAM's {}: misses are latency-bound whatever dram.requests_in_flight is; {needed} would use the bandwidth",
                        c.misses_in_flight,
                        Unit::Bytes.show(c.line as f64),
                        Unit::Bandwidth.show(misses),
                        Unit::Bandwidth.show(self.dram.bandwidth),
                    ),
                ));
            }
        }
        // A key set to do something that no unit of this machine reads.
        for u in self.unread().into_iter().filter(|u| u.meant) {
            w.push((u.key, format!("has no effect: {}", u.why)));
        }
        w
    }
}

/// A cache's geometry and its miss ceiling at `latency`.
#[allow(clippy::cast_precision_loss, reason = "sizes and counts below 2^53")]
fn cache_figures(prefix: &'static str, c: &CacheParams, latency: f64) -> Vec<Figure> {
    let sets = if c.size == 0 { 0 } else { c.size / (c.line * c.ways).max(1) };
    let (size, sets_name, miss) = match prefix {
        "map cache" => ("map cache size", "map cache sets", "map cache miss ceiling"),
        _ => ("depth cache size", "depth cache sets", "depth cache miss ceiling"),
    };
    vec![
        Figure { name: size, value: c.size as f64, unit: Unit::Bytes, how: "size (0: none)" },
        Figure { name: sets_name, value: sets as f64, unit: Unit::Number, how: "size / (line × ways)" },
        Figure {
            name: miss,
            value: if c.size == 0 { 0.0 } else { latency_ceiling(c.misses_in_flight, c.line, latency) },
            unit: Unit::Bandwidth,
            how: "misses_in_flight × line / dram.latency",
        },
    ]
}

/// One difference: a key's or a figure's name, then `a`'s and `b`'s value
/// as text.
pub(crate) type Difference = (&'static str, String, String);

/// The differences between `a` and `b`: every key whose value differs,
/// then every derived figure that differs.
#[must_use]
pub fn diff(a: &Arch, b: &Arch) -> (Vec<Difference>, Vec<Difference>) {
    let keys =
        PARAMS.iter().filter(|p| p.written(a) != p.written(b)).map(|p| (p.key, p.written(a), p.written(b))).collect();
    let figures = a
        .derived()
        .into_iter()
        .zip(b.derived())
        .filter(|(x, y)| x.value.to_bits() != y.value.to_bits())
        .map(|(x, y)| (x.name, x.text(), y.text()))
        .collect();
    (keys, figures)
}
