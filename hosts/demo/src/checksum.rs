//! The checksum both targets compute: 64-bit FNV-1a over little-endian
//! bytes.
//!
//! FNV-1a 64 (Fowler, Noll, Vo): start from the offset basis
//! `0xcbf2_9ce4_8422_2325`; for each byte, XOR it into the hash, then
//! multiply by the prime `0x100_0000_01b3` modulo 2⁶⁴. Multi-byte values
//! are fed as their little-endian bytes, whatever the target's own order.

use umbra_core::TileRect;
use umbra_core::depth::DepthFormat;
use umbra_core::shade::Shaded;
use umbra_core::shadow::Shadow;

/// A running FNV-1a 64 hash.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fnv1a(u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Self::new()
    }
}

impl Fnv1a {
    /// The FNV-1a 64 offset basis.
    pub const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    /// The FNV 64 prime.
    pub const PRIME: u64 = 0x0000_0100_0000_01b3;

    /// The hash of no bytes.
    #[must_use]
    pub const fn new() -> Self {
        Self(Self::OFFSET_BASIS)
    }

    /// Feed bytes in order.
    pub fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(Self::PRIME);
        }
    }

    /// Feed a `u16` as 2 little-endian bytes.
    pub fn u16(&mut self, v: u16) {
        self.bytes(&v.to_le_bytes());
    }

    /// Feed a `u32` as 4 little-endian bytes.
    pub fn u32(&mut self, v: u32) {
        self.bytes(&v.to_le_bytes());
    }

    /// Feed an `i32` as 4 little-endian bytes (two's complement).
    pub fn i32(&mut self, v: i32) {
        self.bytes(&v.to_le_bytes());
    }

    /// Feed an `i64` as 8 little-endian bytes (two's complement).
    pub fn i64(&mut self, v: i64) {
        self.bytes(&v.to_le_bytes());
    }

    /// The hash so far.
    #[must_use]
    pub const fn finish(self) -> u64 {
        self.0
    }
}

/// [`Summary::map_checksum`](crate::Summary::map_checksum) of maps of any format with 16-bit texels.
#[must_use]
pub fn map_checksum<F: DepthFormat<Texel = u16>>(z1: &[u16], z2: &[u16]) -> u64 {
    let mut h = Fnv1a::new();
    z1.iter().chain(z2).for_each(|&t| h.u16(t));
    h.finish()
}

/// The camera pass's checksum and counts, folded tile by tile in the order
/// the streamed pass makes them (tiles row-major, pixels row-major in a
/// tile): [`Summary::camera_checksum`](crate::Summary::camera_checksum), covered and shadowed pixels.
#[derive(Clone, Copy, Debug)]
pub struct CameraChecksum {
    hash: Fnv1a,
    /// Pixels the camera sees the scene in.
    pub covered: u32,
    /// Covered pixels wholly in shadow.
    pub shadowed: u32,
}

impl Default for CameraChecksum {
    fn default() -> Self {
        Self::new()
    }
}

impl CameraChecksum {
    /// Nothing folded in.
    #[must_use]
    pub const fn new() -> Self {
        Self { hash: Fnv1a::new(), covered: 0, shadowed: 0 }
    }

    /// Fold in one tile's results (its rectangle names it; the order of
    /// tiles is the caller's).
    pub fn tile(&mut self, _rect: TileRect, pixels: &[Shaded]) {
        for p in pixels {
            self.hash.u32(p.triangle);
            match p.light {
                None => self.hash.bytes(&[0]),
                Some(l) => {
                    self.hash.bytes(&[1]);
                    self.hash.i32(l.x.to_bits());
                    self.hash.i32(l.y.to_bits());
                    self.hash.i64(l.z.to_bits());
                }
            }
            self.hash.u32(p.shadow.to_bits());
            if p.triangle != umbra_core::NO_TRIANGLE {
                self.covered += 1;
                self.shadowed += u32::from(p.shadow == Shadow::ONE);
            }
        }
    }

    /// The checksum so far.
    #[must_use]
    pub fn finish(&self) -> u64 {
        self.hash.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::Fnv1a;

    fn hash(b: &[u8]) -> u64 {
        let mut h = Fnv1a::new();
        h.bytes(b);
        h.finish()
    }

    /// Published FNV-1a 64 test vectors (Noll's reference test suite).
    #[test]
    fn known_vectors() {
        assert_eq!(hash(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(hash(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(hash(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn integers_are_little_endian() {
        let mut h = Fnv1a::new();
        h.u32(0x6f6f_6661); // "afoo"
        h.u16(0x6162); // "ba"
        h.bytes(b"r");
        assert_eq!(h.finish(), hash(b"afoobar"));
    }
}
