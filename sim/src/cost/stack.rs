//! Every size of a cache from one pass over its addresses: LRU stack
//! distances (Mattson, Gecsei, Slutz & Traiger 1970), per set.
//!
//! An LRU cache of `S` sets and `W` ways hits an access exactly when fewer
//! than `W` distinct lines of the same set were used since the line's last
//! use (LRU's inclusion property): the line's *stack distance* within its
//! set. Keeping each set's lines in order of use, up to the most ways
//! asked, gives that distance for every associativity at once; one such
//! order for each number of sets asked gives every capacity. So one pass
//! over the addresses answers every geometry of one line size an
//! architecture axis names, each access costing a search of its set's
//! order for each number of sets (what a direct simulation of one cache
//! costs), a line read again at once costing nothing.
//!
//! ```
//! use umbra_sim::cost::cache::Cache;
//! use umbra_sim::cost::stack::StackDistances;
//! let addresses = [0u64, 64, 128, 0, 192, 64, 0, 256, 128, 0];
//! // Every cache of 64-byte lines with 1, 2 or 4 sets and up to 4 ways, in one pass.
//! let mut stack = StackDistances::new(64, &[1, 2, 4], 4)?;
//! addresses.iter().for_each(|&a| { stack.access(a); });
//! for (sets, ways) in [(1, 1), (1, 4), (2, 2), (4, 1)] {
//!     let mut direct = Cache::new(64 * sets * u64::from(ways), 64, ways)?;
//!     addresses.iter().for_each(|&a| { direct.access(a); });
//!     assert_eq!(stack.hits(sets, ways), Some(direct.hits));
//! }
//! # Ok::<(), umbra_sim::cost::cache::CacheError>(())
//! ```

use crate::cost::cache::CacheError;

/// A slot that holds no line: no byte address shifts to it.
const EMPTY: u64 = u64::MAX;

/// Each access's stack distance within its set, for several numbers of
/// sets, in one pass over the addresses.
#[derive(Clone, Debug)]
pub struct StackDistances {
    line_shift: u32,
    /// The numbers of sets answered.
    sets: Vec<u64>,
    /// Distances are told apart up to `depth` (the most ways asked); a
    /// longer one, or a first use, is a miss for every cache asked.
    depth: u32,
    /// For each number of sets, each set's lines, most recent first
    /// (`depth` slots a set), one order after the other.
    orders: Vec<u64>,
    /// Where each number of sets' order starts in `orders`.
    starts: Vec<usize>,
    /// `counts[k * (depth + 1) + d]`: accesses with `d` lines of their set
    /// (of `sets[k]`) used since their line's last use; `d = depth` for
    /// farther or none.
    counts: Vec<u64>,
    /// This access's distance for each number of sets.
    distances: Vec<u32>,
    /// The line accessed last (at distance 0 in every set order).
    last: u64,
    /// Accesses at distance 0 in every set order: to the line accessed
    /// last, or to the most recent line of its set in the fewest sets.
    repeats: u64,
    /// The fewest sets, when every other number asked is a multiple of it.
    coarsest: Option<usize>,
}

impl StackDistances {
    /// Distances of `line`-byte lines for caches of each of `sets` sets
    /// and up to `ways` ways.
    ///
    /// # Errors
    /// [`CacheError::Geometry`] unless the line is a power of two and every
    /// number of sets and the ways at least one.
    pub fn new(line: u32, sets: &[u64], ways: u32) -> Result<Self, CacheError> {
        let most = sets.iter().copied().max().unwrap_or(0);
        if !line.is_power_of_two() || sets.is_empty() || sets.contains(&0) || ways == 0 {
            return Err(CacheError::Geometry { size: most * u64::from(line) * u64::from(ways), line, ways });
        }
        let too_many = || CacheError::Geometry { size: most * u64::from(line) * u64::from(ways), line, ways };
        let mut starts = Vec::with_capacity(sets.len());
        let mut slots = 0usize;
        for &s in sets {
            starts.push(slots);
            let n = s.checked_mul(u64::from(ways)).and_then(|n| usize::try_from(n).ok()).ok_or_else(too_many)?;
            slots = slots.checked_add(n).ok_or_else(too_many)?;
        }
        Ok(Self {
            line_shift: line.trailing_zeros(),
            sets: sets.to_vec(),
            depth: ways,
            orders: vec![EMPTY; slots],
            starts,
            counts: vec![0; (ways as usize + 1) * sets.len()],
            distances: vec![0; sets.len()],
            last: EMPTY,
            repeats: 0,
            coarsest: sets
                .iter()
                .enumerate()
                .min_by_key(|&(_, &s)| s)
                .filter(|&(_, &fewest)| sets.iter().all(|s| s % fewest == 0))
                .map(|(k, _)| k),
        })
    }

    /// One access at byte address `address`: its distance for each number
    /// of sets, in the order given (the number of lines of its set used
    /// since its line's last use, up to the depth asked; the depth for a
    /// first use).
    pub fn access(&mut self, address: u64) -> &[u32] {
        let x = address >> self.line_shift;
        let depth = self.depth as usize;
        // The line accessed last, again; or, with sets nested (each number
        // of sets a multiple of the fewest), where a set of more sets holds
        // some of the lines of one set of the fewest, a line the most
        // recent of its set there: the most recent of its set in every
        // order, which it leaves as they are.
        let again = x == self.last
            || self.coarsest.is_some_and(|k| self.orders[self.starts[k] + set_of(x, self.sets[k]) * depth] == x);
        self.last = x;
        if again {
            self.repeats += 1;
            self.distances.fill(0);
            return &self.distances;
        }
        for (k, (&sets, &start)) in self.sets.iter().zip(&self.starts).enumerate() {
            let at = start + set_of(x, sets) * depth;
            let lines = &mut self.orders[at..at + depth];
            let at = lines.iter().position(|&l| l == x || l == EMPTY);
            let d = match at {
                Some(p) if lines[p] == x => p,
                _ => depth,
            };
            // To the front: the lines above it move down one, the last falls
            // out (by hand: a rotation of a few slots is a call to memmove).
            let mut carry = x;
            for slot in &mut lines[..=d.min(depth - 1)] {
                core::mem::swap(slot, &mut carry);
            }
            self.distances[k] = u32::try_from(d).unwrap_or(self.depth);
            self.counts[k * (depth + 1) + d] += 1;
        }
        &self.distances
    }

    /// Hits of an LRU cache of `sets` sets of `ways` ways over the accesses
    /// so far; `None` for a geometry this pass was not asked for.
    #[must_use]
    pub fn hits(&self, sets: u64, ways: u32) -> Option<u64> {
        let k = self.index(sets)?;
        let at = k * (self.depth as usize + 1);
        (ways <= self.depth).then(|| self.repeats + self.counts[at..at + ways as usize].iter().sum::<u64>())
    }

    /// Where `sets` is among the numbers of sets asked, for reading
    /// [`Self::access`]'s distances; `None` when it was not asked for.
    #[must_use]
    pub fn index(&self, sets: u64) -> Option<usize> {
        self.sets.iter().position(|&s| s == sets)
    }
}

/// The set of line `x` among `sets` sets: its low bits for a power of two.
fn set_of(x: u64, sets: u64) -> usize {
    usize::try_from(if sets.is_power_of_two() { x & (sets - 1) } else { x % sets }).unwrap_or(0)
}
