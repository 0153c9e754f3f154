//! A set-associative cache with LRU replacement, for the camera pass's map
//! reads: how many bytes the shadow unit really pulls from memory for a
//! given cache size, line and associativity.
//!
//! ```
//! use umbra_sim::cost::cache::Cache;
//! // Two sets of two 16-byte ways: lines 0, 2 and 4 (addresses 0, 32 and
//! // 64) share set 0, so the third evicts the least recently used.
//! let mut c = Cache::new(64, 16, 2)?;
//! let hits: Vec<bool> = [0, 32, 0, 64, 32].iter().map(|&a| c.access(a)).collect();
//! assert_eq!(hits, [false, false, true, false, false]);
//! assert_eq!(c.stats().fetched_bytes, 4 * 16);
//! # Ok::<(), umbra_sim::cost::cache::CacheError>(())
//! ```

use serde::Serialize;
use umbra_core::probe::{Buffer, Probe, TexelRead};

/// A cache geometry that cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CacheError {
    /// Line size not a power of two, or ways zero, or the size not a whole
    /// number of sets of `ways` lines.
    #[error(
        "cache of {size} bytes with {line}-byte lines and {ways} ways: the line must be a power of two and the size a multiple of line × ways"
    )]
    Geometry {
        /// Total bytes.
        size: u64,
        /// Line bytes.
        line: u32,
        /// Associativity.
        ways: u32,
    },
}

/// The tag of a slot that holds no line: no byte address shifts to it.
const EMPTY: u64 = u64::MAX;

/// A set-associative, least-recently-used cache over byte addresses.
#[derive(Clone, Debug)]
pub struct Cache {
    line_shift: u32,
    ways: usize,
    sets: u64,
    /// `sets − 1` when the sets are a power of two: a line's set is then
    /// its low bits, no division.
    set_mask: Option<u64>,
    /// Per set, `ways` slots' line tags ([`EMPTY`] for none) and, beside
    /// them, each slot's last use (0 for none).
    tags: Vec<u64>,
    used: Vec<u64>,
    /// Per slot, whether the line was written since it was fetched.
    dirty: Vec<bool>,
    /// The line of the last access and its slot: a run of accesses to one
    /// line skips the set's search (the result is the same).
    last: Option<(u64, usize)>,
    clock: u64,
    /// Accesses that found their line.
    pub hits: u64,
    /// Accesses that fetched their line.
    pub misses: u64,
    /// Dirty lines written back (evicted, or flushed at a pass's end).
    pub writebacks: u64,
}

/// A cache's statistics over a pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct CacheStats {
    /// Accesses (reads, and read-modify-writes through a write-back cache).
    pub accesses: u64,
    /// Accesses that found their line.
    pub hits: u64,
    /// Accesses that fetched their line.
    pub misses: u64,
    /// Hits over accesses (0 without accesses).
    pub hit_rate: f64,
    /// Bytes fetched from DRAM: a line a miss.
    pub fetched_bytes: u64,
    /// Bytes written back to DRAM: a line a dirty eviction or flush.
    pub written_back_bytes: u64,
}

impl CacheStats {
    /// Every count times `k` (a pass run `k` times over the same stream).
    #[must_use]
    pub(crate) fn times(self, k: u64) -> Self {
        Self {
            accesses: self.accesses * k,
            hits: self.hits * k,
            misses: self.misses * k,
            fetched_bytes: self.fetched_bytes * k,
            written_back_bytes: self.written_back_bytes * k,
            ..self
        }
    }

    /// Two streams' counts added (two passes through caches of one
    /// geometry), the hit rate of the two.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    pub(crate) fn plus(self, o: Self) -> Self {
        let (accesses, hits) = (self.accesses + o.accesses, self.hits + o.hits);
        Self {
            accesses,
            hits,
            misses: self.misses + o.misses,
            hit_rate: if accesses == 0 { 0.0 } else { hits as f64 / accesses as f64 },
            fetched_bytes: self.fetched_bytes + o.fetched_bytes,
            written_back_bytes: self.written_back_bytes + o.written_back_bytes,
        }
    }
}

impl Cache {
    /// A cache of `size` bytes, `line`-byte lines and `ways` ways.
    ///
    /// # Errors
    /// [`CacheError::Geometry`] for an impossible geometry.
    pub fn new(size: u64, line: u32, ways: u32) -> Result<Self, CacheError> {
        let bad = CacheError::Geometry { size, line, ways };
        let set_bytes = u64::from(line) * u64::from(ways);
        if !line.is_power_of_two() || ways == 0 || size == 0 || !size.is_multiple_of(set_bytes) {
            return Err(bad);
        }
        let sets = size / set_bytes;
        let slots = usize::try_from(sets * u64::from(ways)).map_err(|_| bad)?;
        Ok(Self {
            line_shift: line.trailing_zeros(),
            ways: ways as usize,
            sets,
            set_mask: sets.is_power_of_two().then(|| sets - 1),
            tags: vec![EMPTY; slots],
            used: vec![0; slots],
            dirty: vec![false; slots],
            last: None,
            clock: 0,
            hits: 0,
            misses: 0,
            writebacks: 0,
        })
    }

    /// Its geometry: size in bytes, line bytes, ways.
    #[must_use]
    pub(crate) const fn geometry(&self) -> (u64, u32, u32) {
        #[allow(clippy::cast_possible_truncation, reason = "built from a u32 line and ways")]
        (self.sets * self.ways as u64 * self.line(), self.line() as u32, self.ways as u32)
    }

    /// Bytes of one line.
    #[must_use]
    pub(crate) const fn line(&self) -> u64 {
        1 << self.line_shift
    }

    /// Touch a byte address; whether its line was present.
    pub fn access(&mut self, address: u64) -> bool {
        self.touch(address, false).0
    }

    /// Read and write a byte address (a read-modify-write through a
    /// write-back cache): whether its line was present, and whether a dirty
    /// line was evicted for it (a line written back).
    pub fn access_write(&mut self, address: u64) -> (bool, bool) {
        self.touch(address, true)
    }

    fn touch(&mut self, address: u64, write: bool) -> (bool, bool) {
        self.clock += 1;
        let line = address >> self.line_shift;
        if let Some((last, k)) = self.last
            && last == line
            && let (Some(used), Some(dirty)) = (self.used.get_mut(k), self.dirty.get_mut(k))
        {
            *used = self.clock;
            *dirty |= write;
            self.hits += 1;
            return (true, false);
        }
        let set = usize::try_from(self.set_mask.map_or_else(|| line % self.sets, |m| line & m)).unwrap_or(0);
        let range = set * self.ways..(set + 1) * self.ways;
        let (tags, used, dirty) =
            (&mut self.tags[range.clone()], &mut self.used[range.clone()], &mut self.dirty[range]);
        if let Some(k) = tags.iter().position(|&tag| tag == line) {
            used[k] = self.clock;
            dirty[k] |= write;
            self.hits += 1;
            self.last = Some((line, set * self.ways + k));
            return (true, false);
        }
        self.misses += 1;
        // An empty slot (last used at 0), else the least recently used.
        let victim = (0..used.len()).min_by_key(|&k| used[k]).unwrap_or(0);
        let writeback = tags[victim] != EMPTY && dirty[victim];
        self.writebacks += u64::from(writeback);
        tags[victim] = line;
        used[victim] = self.clock;
        dirty[victim] = write;
        self.last = Some((line, set * self.ways + victim));
        (false, writeback)
    }

    /// Write back every dirty line (the end of a pass); how many.
    pub fn flush(&mut self) -> u64 {
        let n = self.dirty.iter().filter(|&&d| d).count() as u64;
        self.writebacks += n;
        self.last = None;
        self.dirty.fill(false);
        n
    }

    /// Bytes fetched from memory: one line per miss.
    #[must_use]
    pub const fn fetched_bytes(&self) -> u64 {
        self.misses * self.line()
    }

    /// Its statistics so far.
    #[must_use]
    pub fn stats(&self) -> CacheStats {
        let accesses = self.hits + self.misses;
        #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
        let hit_rate = if accesses == 0 { 0.0 } else { self.hits as f64 / accesses as f64 };
        CacheStats {
            accesses,
            hits: self.hits,
            misses: self.misses,
            hit_rate,
            fetched_bytes: self.fetched_bytes(),
            written_back_bytes: self.writebacks * self.line(),
        }
    }
}

/// A probe that sends the shadow unit's texel reads through a [`Cache`].
///
/// The map lies in memory as texture hardware swizzles it: texels in
/// Morton (Z) order, so a 2-D neighbourhood falls in few lines and
/// neighbouring rows do not alias onto the same sets (a row-major map
/// with a power-of-two pitch maps every 16th row to the same set and
/// thrashes), and a dual map's `z1` and `z2` side by side per texel,
/// `bytes` each. A silhouette map, when there is one, lies in its own
/// region, swizzled the same way.
#[derive(Clone, Debug)]
pub struct MapCache {
    /// The cache.
    pub cache: Cache,
    buffers: u64,
    bytes: u64,
    silhouette_bytes: u64,
    /// Where the bound light's maps start: light `k`'s at `k · LIGHT_STRIDE`.
    base: u64,
}

/// The address space each light's maps (and silhouette map) take: 2⁴²
/// bytes, above any map's depths and its silhouette map
/// (`SILHOUETTE_BASE`), so that two lights' maps never share a line.
const LIGHT_STRIDE: u64 = 1 << 42;

/// Where the silhouette map starts (above any map's depths).
pub(crate) const SILHOUETTE_BASE: u64 = 1 << 40;

/// Each byte's bits spread to the even positions of 16.
const SPREAD: [u16; 256] = {
    let mut table = [0u16; 256];
    let mut b = 0;
    while b < 256 {
        let mut bit = 0;
        while bit < 8 {
            #[allow(clippy::cast_possible_truncation, reason = "one bit")]
            let one = ((b >> bit) & 1) as u16;
            table[b] |= one << (2 * bit);
            bit += 1;
        }
        b += 1;
    }
    table
};

/// Interleave the bits of `x` (even positions) and `y` (odd positions).
#[must_use]
pub fn morton(x: u32, y: u32) -> u64 {
    // A byte at a time, by table.
    let spread =
        |v: u32| v.to_le_bytes().iter().rev().fold(0u64, |acc, &b| (acc << 16) | u64::from(SPREAD[usize::from(b)]));
    spread(x) | (spread(y) << 1)
}

/// The Morton index one step along x from `m` (y unchanged): the x bits,
/// the odd ones filled so that the carry runs through them.
pub(crate) const fn morton_next_x(m: u64) -> u64 {
    const X: u64 = 0x5555_5555_5555_5555;
    (((m | !X).wrapping_add(1)) & X) | (m & !X)
}

impl MapCache {
    /// Model the reads of a map of `buffers` buffers (1 or 2) of
    /// `bytes`-byte texels.
    #[must_use]
    pub fn new(cache: Cache, buffers: u32, bytes: u32) -> Self {
        Self { cache, buffers: u64::from(buffers.max(1)), bytes: u64::from(bytes), silhouette_bytes: 4, base: 0 }
    }

    /// With a silhouette map of `bytes`-byte points.
    #[must_use]
    pub(crate) const fn with_silhouette(mut self, bytes: u32) -> Self {
        self.silhouette_bytes = bytes as u64;
        self
    }

    /// The byte address of a texel.
    #[must_use]
    pub fn address(&self, r: TexelRead) -> u64 {
        self.address_at(r, morton(r.x, r.y))
    }

    /// The byte address of a texel whose Morton index is `m`.
    #[must_use]
    pub(crate) const fn address_at(&self, r: TexelRead, m: u64) -> u64 {
        let plane = match r.buffer {
            Buffer::Silhouette => return self.base + SILHOUETTE_BASE + m * self.silhouette_bytes,
            Buffer::Z2 if self.buffers > 1 => 1,
            _ => 0,
        };
        self.base + (m * self.buffers + plane) * self.bytes
    }
}

impl Probe for MapCache {
    const TEXELS: bool = true;

    fn map_bound(&mut self, light: u16) {
        self.base = u64::from(light) * LIGHT_STRIDE;
    }

    fn texel_read(&mut self, read: TexelRead) {
        let a = self.address(read);
        self.cache.access(a);
    }
}
