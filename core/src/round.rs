//! Rounding of the vertex unit's f64 values to integers.

const TWO_52: f64 = 4_503_599_627_370_496.0;

/// Round to the nearest integer, ties to even (the IEEE default), saturating
/// at the `i64` range; NaN gives 0. Adding and removing 2⁵² makes the FPU
/// round: two adds, the same on every target, where a library `round` is a
/// slow software routine on the vertex path.
#[inline]
#[must_use]
pub fn round_ties_even(v: f64) -> i64 {
    let r = if v.abs() < TWO_52 {
        if v >= 0.0 { (v + TWO_52) - TWO_52 } else { (v - TWO_52) + TWO_52 }
    } else {
        v // already an integer (or not finite)
    };
    #[allow(clippy::cast_possible_truncation, reason = "an `as` cast saturates, which is the documented behaviour")]
    let i = r as i64;
    i
}

#[cfg(test)]
mod tests {
    use super::round_ties_even;

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
}
