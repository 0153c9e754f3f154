//! A pass's time on an architecture and its ledgers: every cycle charged
//! to what bound it and every DRAM byte to its purpose, the pass's totals
//! their sums, and a pass as `cost.json` writes it.

use serde::Serialize;

use crate::cost::cache::CacheStats;
use crate::cost::dram::Dram;
use crate::cost::work::{Bottleneck, EnergySplit, MemoryTime, Stage};

/// A pass's time on an architecture, and its ledger: every cycle charged
/// to what bound it (`bound_cycles`, beside the fixed `overhead`) and every
/// DRAM byte to its purpose (`dram`). The pass's cycles and bytes are
/// those ledgers' sums ([`PassTiming::cycles`], [`PassTiming::bytes`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassTiming {
    /// Cycles per stage summed over the tiles (the front end's in setup and
    /// memory), in [`Stage::ALL`] order.
    pub stages: [f64; 6],
    /// The front end's cycles (setup and bin writes).
    pub front: f64,
    /// The tiles' cycles: each tile its slowest stage, summed.
    pub tiles: f64,
    /// The fixed overhead: cycles waiting for the host.
    pub overhead: f64,
    /// The cycles' ledger: the pass's cycles besides its overhead, each
    /// charged to what bound it, in [`Bottleneck::ALL`] order — a tile's
    /// to its slowest stage, the front end's (when it outlasts the tiles)
    /// to its own, the DRAM's shared by both (when it outlasts them) to
    /// its limit, each unit after the tiles to its slowest stage.
    pub bound_cycles: [f64; 9],
    /// Tiles (draws) with work bound by each bottleneck, in
    /// `Bottleneck::ALL` order.
    pub bound: [u64; 9],
    /// Memory time summed over the pass, as each limit would make it.
    pub memory: MemoryTime,
    /// The bytes' ledger: DRAM traffic by purpose.
    pub dram: Dram,
    /// The map cache, when the pass reads through one.
    pub map_cache: Option<CacheStats>,
    /// The depth cache, when the pass keeps depth off chip through one.
    pub depth_cache: Option<CacheStats>,
    /// Energy by unit, joules.
    pub energy: EnergySplit,
    /// The clock the cycles run at, hertz.
    pub clock: f64,
}

impl PassTiming {
    /// The pass's cycles: its overhead and its ledger's.
    #[must_use]
    pub fn cycles(&self) -> f64 {
        self.overhead + self.bound_cycles.iter().sum::<f64>()
    }

    /// The pass's DRAM bytes: its ledger's, every purpose.
    #[must_use]
    pub fn bytes(&self) -> u64 {
        self.dram.total()
    }

    /// What bounds the most of its cycles (the first on a tie);
    /// [`Bottleneck::Nothing`] for a pass with none.
    #[must_use]
    pub fn bottleneck(&self) -> Bottleneck {
        most(&self.bound_cycles)
    }

    /// DRAM bytes over the pass's time, bytes a second.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "bytes far below 2^53")]
    pub fn achieved_bytes_per_second(&self) -> f64 {
        let seconds = self.cycles() / self.clock;
        if seconds > 0.0 { self.bytes() as f64 / seconds } else { 0.0 }
    }

    /// The pass-level bound: the slowest stage summed over the whole pass.
    #[must_use]
    pub fn pass_bound(&self) -> f64 {
        self.overhead + self.stages.iter().copied().fold(0.0, f64::max)
    }

    /// Every stage's cycles added, as if nothing overlapped.
    #[must_use]
    pub fn serial(&self) -> f64 {
        self.overhead + self.stages.iter().sum::<f64>()
    }

    /// This pass, then `next` (a further light's pass), as one: every
    /// figure and both ledgers added.
    #[must_use]
    pub(crate) fn then(&self, next: &Self) -> Self {
        let add = |a: [f64; 9], b: [f64; 9]| core::array::from_fn(|k| a[k] + b[k]);
        let mut stages = self.stages;
        stages.iter_mut().zip(next.stages).for_each(|(a, b)| *a += b);
        let mut bound = self.bound;
        bound.iter_mut().zip(next.bound).for_each(|(a, b)| *a += b);
        let cache = |a: Option<CacheStats>, b: Option<CacheStats>| match (a, b) {
            (Some(a), Some(b)) => Some(a.plus(b)),
            (a, b) => a.or(b),
        };
        Self {
            stages,
            front: self.front + next.front,
            tiles: self.tiles + next.tiles,
            overhead: self.overhead + next.overhead,
            bound_cycles: add(self.bound_cycles, next.bound_cycles),
            bound,
            memory: self.memory.plus(&next.memory),
            dram: self.dram.plus(&next.dram),
            map_cache: cache(self.map_cache, next.map_cache),
            depth_cache: cache(self.depth_cache, next.depth_cache),
            energy: self.energy.plus(&next.energy),
            clock: if self.clock > 0.0 { self.clock } else { next.clock },
        }
    }
}

/// The bottleneck of the most cycles in a ledger (the first on a tie);
/// [`Bottleneck::Nothing`] when it holds none.
#[must_use]
pub(crate) fn most(bound_cycles: &[f64; 9]) -> Bottleneck {
    Bottleneck::ALL
        .into_iter()
        .zip(bound_cycles)
        .fold((Bottleneck::Nothing, 0.0), |b, (s, &c)| if c > b.1 { (s, c) } else { b })
        .0
}

impl Serialize for PassTiming {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        /// The pass as `cost.json` holds it: the totals beside the ledgers they sum.
        #[derive(Serialize)]
        struct Out<'a> {
            cycles: f64,
            bottleneck: Bottleneck,
            overhead_cycles: f64,
            #[serde(serialize_with = "by_bottleneck")]
            bound_cycles: &'a [f64; 9],
            #[serde(serialize_with = "by_stage")]
            stage_cycles: &'a [f64; 6],
            front_cycles: f64,
            tile_cycles: f64,
            #[serde(serialize_with = "by_bottleneck")]
            tiles_bound: &'a [u64; 9],
            memory: &'a MemoryTime,
            dram_bytes: u64,
            dram: &'a Dram,
            achieved_bytes_per_second: f64,
            map_cache: Option<CacheStats>,
            depth_cache: Option<CacheStats>,
            energy_joules: &'a EnergySplit,
        }
        Out {
            cycles: self.cycles(),
            bottleneck: self.bottleneck(),
            overhead_cycles: self.overhead,
            bound_cycles: &self.bound_cycles,
            stage_cycles: &self.stages,
            front_cycles: self.front,
            tile_cycles: self.tiles,
            tiles_bound: &self.bound,
            memory: &self.memory,
            dram_bytes: self.bytes(),
            dram: &self.dram,
            achieved_bytes_per_second: self.achieved_bytes_per_second(),
            map_cache: self.map_cache,
            depth_cache: self.depth_cache,
            energy_joules: &self.energy,
        }
        .serialize(s)
    }
}

/// Per-stage figures as a map from the stage's name.
fn by_stage<S: serde::Serializer>(v: &&[f64; 6], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(Stage::ALL.iter().map(|st| st.name()).zip(v.iter()))
}

/// Per-bottleneck figures as a map from the bottleneck's name.
fn by_bottleneck<S: serde::Serializer, T: Serialize>(v: &&[T; 9], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(Bottleneck::ALL.iter().map(|b| b.name()).zip(v.iter()))
}
