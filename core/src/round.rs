//! Rounding between the vertex unit's f64 values and integers, and wide
//! integers saturated to 64 bits.

use crate::budget::F64_ROUNDING;

/// Round to the nearest integer, ties to even (the IEEE default), saturating
/// at the `i64` range; NaN gives 0. Adding and removing 2⁵² makes the FPU
/// round: two adds, the same on every target, where a library `round` is a
/// slow software routine on the vertex path.
#[inline]
#[must_use]
pub fn round_ties_even(v: f64) -> i64 {
    let r = if v.abs() < F64_ROUNDING {
        if v >= 0.0 { (v + F64_ROUNDING) - F64_ROUNDING } else { (v - F64_ROUNDING) + F64_ROUNDING }
    } else {
        v // already an integer (or not finite)
    };
    #[allow(clippy::cast_possible_truncation, reason = "an `as` cast saturates, which is the documented behaviour")]
    let i = r as i64;
    i
}

/// `v` saturated to the `i64` range.
#[inline]
#[must_use]
pub const fn saturate(v: i128) -> i64 {
    #[allow(clippy::cast_possible_truncation, reason = "clamped to the i64 range first")]
    let s = if v < i64::MIN as i128 {
        i64::MIN
    } else if v > i64::MAX as i128 {
        i64::MAX
    } else {
        v as i64
    };
    s
}

/// `n` as the nearest f64 (ties to even), the same value as `n as f64`.
/// Setup's depth numerators often exceed `i64`, where the `as` cast is a
/// software routine of a hundred instructions; here a value beyond `i64`
/// is shifted into 63 bits with a sticky bit for what falls off (so the
/// hardware conversion still rounds correctly: 63 bits leave ten below the
/// rounding position) and scaled back by an exact power of two.
#[inline]
#[must_use]
pub fn i128_to_f64(n: i128) -> f64 {
    if let Ok(v) = i64::try_from(n) {
        #[allow(clippy::cast_precision_loss, reason = "the hardware conversion rounds to nearest")]
        return v as f64;
    }
    let m = n.unsigned_abs();
    // |n| ≥ 2^63, so 1 ≤ shift ≤ 65.
    let shift = 65 - m.leading_zeros();
    let sticky = u128::from(m & ((1u128 << shift) - 1) != 0);
    #[allow(clippy::cast_possible_truncation, reason = "below 2^63 after the shift")]
    let t = ((m >> shift) | sticky) as i64;
    #[allow(clippy::cast_precision_loss, reason = "the hardware conversion rounds to nearest")]
    let scaled = t as f64 * f64::from_bits(u64::from(1023 + shift) << 52);
    if n < 0 { -scaled } else { scaled }
}

#[cfg(test)]
mod tests {
    use super::{i128_to_f64, round_ties_even, saturate};

    #[test]
    #[allow(
        clippy::cast_precision_loss,
        clippy::cast_possible_truncation,
        reason = "the reference conversion; small ranges"
    )]
    fn wide_integers_convert_as_the_language_converts_them() {
        let mut rng = oorandom::Rand64::new(0x5e7u128);
        let check = |n: i128| assert_eq!(i128_to_f64(n).to_bits(), (n as f64).to_bits(), "{n}");
        for edge in [i128::MIN, i128::MAX, i128::from(i64::MIN), i128::from(i64::MAX), 0, 1, -1] {
            for d in -3..=3 {
                check(edge.saturating_add(d));
            }
        }
        for _ in 0..200_000 {
            let raw = (u128::from(rng.rand_u64()) << 64 | u128::from(rng.rand_u64())).cast_signed();
            // Every magnitude; and the same with its low twelve bits set to
            // exactly half of 2^12 (a tie for magnitudes in [2^64, 2^65)).
            let bits = rng.rand_range(0..128) as u32;
            check(raw >> bits);
            check((raw >> bits) & !((1i128 << 12) - 1) | (1i128 << 11));
            // Exact ties: an odd 54-bit integer, shifted past 2^63.
            let odd = i128::from((rng.rand_u64() >> 10) | (1 << 53) | 1);
            let shift = rng.rand_range(10..73) as u32;
            check(odd << shift);
            check(-(odd << shift));
        }
    }

    #[test]
    fn ties_go_to_even_and_large_values_pass_through() {
        assert_eq!(round_ties_even(0.5), 0);
        assert_eq!(round_ties_even(1.5), 2);
        assert_eq!(round_ties_even(2.5), 2);
        assert_eq!(round_ties_even(-0.5), 0);
        assert_eq!(round_ties_even(-1.5), -2);
        assert_eq!(round_ties_even(-2.4999), -2);
        assert_eq!(round_ties_even(3.0e17), 300_000_000_000_000_000);
        assert_eq!(round_ties_even(f64::INFINITY), i64::MAX);
        assert_eq!(round_ties_even(f64::NAN), 0);
    }

    #[test]
    fn wide_integers_saturate_to_the_i64_range() {
        #[allow(clippy::cast_possible_truncation, reason = "clamped first")]
        let clamp = |v: i128| v.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64;
        let mut rng = oorandom::Rand64::new(0x5a7);
        let (lo, hi) = (i128::from(i64::MIN), i128::from(i64::MAX));
        for edge in [i128::MIN, i128::MAX, lo, hi, 0, 1 << 64, -(1 << 64), (1 << 64) - 1, 1 << 63, -(1 << 63)] {
            for d in -3..=3 {
                let v = edge.saturating_add(d);
                assert_eq!(saturate(v), clamp(v), "{v}");
            }
        }
        for _ in 0..100_000 {
            let raw = (u128::from(rng.rand_u64()) << 64 | u128::from(rng.rand_u64())).cast_signed();
            let v = raw >> rng.rand_range(0..128);
            assert_eq!(saturate(v), clamp(v), "{v}");
        }
    }
}
