//! Every size of a cache from one pass over its addresses: LRU stack
//! distances (Mattson, Gecsei, Slutz & Traiger 1970), for every number of
//! sets that is a power of two at once (Hill & Smith 1989's
//! all-associativity simulation for sets chosen by a line's low bits).
//!
//! An LRU cache of `S` sets and `W` ways hits an access exactly when fewer
//! than `W` distinct lines of the same set were used since the line's last
//! use (LRU's inclusion property). One most-recently-used-first list of
//! every line seen gives that count for every `S = 2ᵏ` at once: a line
//! above the one accessed shares its set under `2ᵏ` sets exactly when their
//! low `k` bits agree. So one pass answers every capacity and
//! associativity of one line size, which is what an architecture axis of
//! cache sizes asks.
//!
//! ```
//! use umbra_sim::cost::cache::Cache;
//! use umbra_sim::cost::stack::StackDistances;
//! let addresses = [0u64, 64, 128, 0, 192, 64, 0, 256, 128, 0];
//! // Every cache of 64-byte lines with up to 4 sets and 4 ways, in one pass.
//! let mut stack = StackDistances::new(64, 4, 4)?;
//! addresses.iter().for_each(|&a| { stack.access(a); });
//! for (sets, ways) in [(1, 1), (1, 4), (2, 2), (4, 1)] {
//!     let mut direct = Cache::new(64 * sets * u64::from(ways), 64, ways)?;
//!     addresses.iter().for_each(|&a| { direct.access(a); });
//!     assert_eq!(stack.hits(sets, ways), Some(direct.hits));
//! }
//! # Ok::<(), umbra_sim::cost::cache::CacheError>(())
//! ```

use std::collections::HashMap;

use crate::cost::cache::CacheError;

/// The end of the list.
const NONE: u32 = u32::MAX;

/// Each access's distance for every power-of-two number of sets, in one
/// pass over the addresses.
#[derive(Clone, Debug)]
pub struct StackDistances {
    line_shift: u32,
    /// Set counts `2⁰ … 2^(levels − 1)` are answered.
    levels: usize,
    /// Distances are told apart up to `depth` (the most ways asked); a
    /// longer one, or a first use, is a miss for every cache asked.
    depth: u32,
    /// The lines, most recently used first, as a linked list over slots.
    line: Vec<u64>,
    next: Vec<u32>,
    prev: Vec<u32>,
    head: u32,
    slot: HashMap<u64, u32>,
    /// `counts[k][d]`: accesses with `d` lines of their set (of `2ᵏ` sets)
    /// used since their line's last use; `d = depth` for farther or none.
    counts: Vec<Vec<u64>>,
    /// This access's distance for each level.
    distances: Vec<u32>,
}

impl StackDistances {
    /// Distances of `line`-byte lines for up to `sets` sets (rounded up to a
    /// power of two) and `ways` ways.
    ///
    /// # Errors
    /// [`CacheError::Geometry`] unless the line is a power of two and the
    /// sets and ways at least one.
    pub fn new(line: u32, sets: u64, ways: u32) -> Result<Self, CacheError> {
        if !line.is_power_of_two() || sets == 0 || ways == 0 {
            return Err(CacheError::Geometry { size: sets * u64::from(line) * u64::from(ways), line, ways });
        }
        let levels = sets.next_power_of_two().trailing_zeros() as usize + 1;
        Ok(Self {
            line_shift: line.trailing_zeros(),
            levels,
            depth: ways,
            line: Vec::new(),
            next: Vec::new(),
            prev: Vec::new(),
            head: NONE,
            slot: HashMap::new(),
            counts: vec![vec![0; ways as usize + 1]; levels],
            distances: vec![0; levels],
        })
    }

    /// One access at byte address `address`: its distance under `2ᵏ` sets
    /// for each `k` (the number of lines of its set used since its line's
    /// last use, up to the depth asked; the depth for a first use).
    pub fn access(&mut self, address: u64) -> &[u32] {
        let x = address >> self.line_shift;
        let top = self.levels - 1;
        let mut same = [0u32; 64];
        let mut node = self.head;
        let mut found = None;
        // Walk from the most recent until the line, or until even the
        // most sets have `depth` lines of its set above it (a miss for all).
        while node != NONE {
            let i = node as usize;
            let l = self.line[i];
            if l == x {
                found = Some(node);
                break;
            }
            let shared = ((l ^ x).trailing_zeros() as usize).min(top);
            same[shared] += 1;
            if shared == top && same[top] >= self.depth {
                break;
            }
            node = self.next[i];
        }
        // Lines sharing the set under 2ᵏ sets share it under fewer.
        let mut above = 0;
        for k in (0..self.levels).rev() {
            above += same[k];
            let d = if found.is_some() { above.min(self.depth) } else { self.depth };
            self.distances[k] = d;
            self.counts[k][d as usize] += 1;
        }
        self.bring_forward(x, found);
        &self.distances
    }

    /// Move line `x` (at `found`, or new, or deeper than the walk went) to the front.
    fn bring_forward(&mut self, x: u64, found: Option<u32>) {
        let node = match found.or_else(|| self.slot.get(&x).copied()) {
            Some(n) => {
                if n == self.head {
                    return;
                }
                let (p, q) = (self.prev[n as usize], self.next[n as usize]);
                if p != NONE {
                    self.next[p as usize] = q;
                }
                if q != NONE {
                    self.prev[q as usize] = p;
                }
                n
            }
            None => {
                let n = u32::try_from(self.line.len()).unwrap_or(NONE - 1);
                self.line.push(x);
                self.next.push(NONE);
                self.prev.push(NONE);
                self.slot.insert(x, n);
                n
            }
        };
        let i = node as usize;
        self.prev[i] = NONE;
        self.next[i] = self.head;
        if self.head != NONE {
            self.prev[self.head as usize] = node;
        }
        self.head = node;
    }

    /// Hits of an LRU cache of `sets` sets (a power of two) of `ways` ways
    /// over the accesses so far; `None` for a geometry this pass does not
    /// answer (sets not a power of two, or more sets or ways than asked).
    #[must_use]
    pub fn hits(&self, sets: u64, ways: u32) -> Option<u64> {
        let k = sets.is_power_of_two().then(|| sets.trailing_zeros() as usize)?;
        (ways <= self.depth).then(|| self.counts.get(k).map(|c| c[..ways as usize].iter().sum()))?
    }

    /// The level that answers `sets` sets, for reading [`Self::access`]'s
    /// distances; `None` as for [`Self::hits`].
    #[must_use]
    pub fn level(&self, sets: u64) -> Option<usize> {
        sets.is_power_of_two().then(|| sets.trailing_zeros() as usize).filter(|&k| k < self.levels)
    }
}
