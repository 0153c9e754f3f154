//! A set-associative cache with LRU replacement, for the camera pass's map
//! reads: how many bytes the shadow unit really pulls from memory for a
//! given cache size, line and associativity.

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

/// A set-associative, least-recently-used cache over byte addresses.
#[derive(Clone, Debug)]
pub struct Cache {
    line_shift: u32,
    ways: usize,
    sets: u64,
    /// Per set, `ways` slots of (tag, last use).
    slots: Vec<Option<(u64, u64)>>,
    clock: u64,
    /// Accesses that found their line.
    pub hits: u64,
    /// Accesses that fetched their line.
    pub misses: u64,
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
            slots: vec![None; slots],
            clock: 0,
            hits: 0,
            misses: 0,
        })
    }

    /// Bytes of one line.
    #[must_use]
    pub const fn line(&self) -> u64 {
        1 << self.line_shift
    }

    /// Touch a byte address; whether its line was present.
    pub fn access(&mut self, address: u64) -> bool {
        self.clock += 1;
        let line = address >> self.line_shift;
        let set = usize::try_from(line % self.sets).unwrap_or(0);
        let slots = &mut self.slots[set * self.ways..(set + 1) * self.ways];
        if let Some(slot) = slots.iter_mut().flatten().find(|(tag, _)| *tag == line) {
            slot.1 = self.clock;
            self.hits += 1;
            return true;
        }
        self.misses += 1;
        // An empty slot, else the least recently used.
        if let Some(victim) = slots.iter_mut().min_by_key(|s| s.map_or(0, |(_, used)| used)) {
            *victim = Some((line, self.clock));
        }
        false
    }

    /// Bytes fetched from memory: one line per miss.
    #[must_use]
    pub const fn fetched_bytes(&self) -> u64 {
        self.misses * self.line()
    }
}

/// A probe that sends the shadow unit's texel reads through a [`Cache`].
/// The map lies row-major in memory, `z1` then `z2`, `bytes` per texel.
#[derive(Clone, Debug)]
pub struct MapCache {
    /// The cache.
    pub cache: Cache,
    width: u64,
    height: u64,
    bytes: u64,
}

impl MapCache {
    /// Model the reads of a `width × height` map of `bytes`-byte texels.
    #[must_use]
    pub fn new(cache: Cache, width: u32, height: u32, bytes: u32) -> Self {
        Self { cache, width: u64::from(width), height: u64::from(height), bytes: u64::from(bytes) }
    }

    /// The byte address of a texel.
    #[must_use]
    pub fn address(&self, r: TexelRead) -> u64 {
        let plane = match r.buffer {
            Buffer::Z1 | Buffer::Id => 0,
            Buffer::Z2 => 1,
        };
        ((plane * self.height + u64::from(r.y)) * self.width + u64::from(r.x)) * self.bytes
    }
}

impl Probe for MapCache {
    const TEXELS: bool = true;

    fn texel_read(&mut self, read: TexelRead) {
        let a = self.address(read);
        self.cache.access(a);
    }
}
