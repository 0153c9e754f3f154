//! Quantisation is monotonic and saturating in every format, and matches
//! the D3D rule `round(z · (2ⁿ − 1))` computed independently in f64.

use proptest::prelude::*;
use umbra::core::depth::{PlaneZ, Texel};
use umbra::core::{D16, D24, DepthFormat, F32};

fn any_depth() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => 0.0f32..=1.0,
        1 => -10.0f32..10.0,
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => prop::num::f32::ANY.prop_filter("ordered", |v| !v.is_nan()),
    ]
}

fn monotonic<F: DepthFormat>(a: f32, b: f32) -> Result<(), TestCaseError> {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    prop_assert!(F::quantize(lo) <= F::quantize(hi), "{:?}: q({}) > q({})", F::KIND, lo, hi);
    Ok(())
}

/// The texels `F` makes of `a` and `b` (rounded and from the interpolator)
/// are at most `FAR` (the clear value) and keyed in their own order.
fn order<F: DepthFormat>(a: i64, b: i64) -> Result<(), TestCaseError> {
    let texels =
        [F::texel(PlaneZ::from_bits(a)), F::texel(PlaneZ::from_bits(b)), F::texel_inside(a), F::texel_inside(b)];
    for &t in &texels {
        prop_assert!(t.to_raw() <= F::FAR.to_raw(), "{:?}: {t:?}", F::KIND);
        for &u in &texels {
            prop_assert_eq!(t.key().cmp(&u.key()), t.cmp(&u), "{:?}: {:?} against {:?}", F::KIND, t, u);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn quantisation_is_monotonic(a in any_depth(), b in any_depth()) {
        monotonic::<D16>(a, b)?;
        monotonic::<D24>(a, b)?;
        monotonic::<F32>(a, b)?;
    }

    #[test]
    fn fixed_point_rounding_is_monotonic(a in any::<i64>(), b in any::<i64>()) {
        let (lo, hi) = (PlaneZ::from_bits(a.min(b)), PlaneZ::from_bits(a.max(b)));
        prop_assert!(D16::texel(lo) <= D16::texel(hi));
        prop_assert!(D24::texel(lo) <= D24::texel(hi));
        prop_assert!(F32::texel(lo) <= F32::texel(hi));
    }

    #[test]
    fn unorm_formats_round_like_d3d(z in 0.0f32..=1.0) {
        // z · (2ⁿ − 1) has at most 24 + 24 significant bits: exact in f64.
        let d16 = (f64::from(z) * 65535.0).round() as u16;
        let d24 = (f64::from(z) * 16_777_215.0).round() as u32;
        prop_assert_eq!(D16::quantize(z), d16);
        prop_assert_eq!(D24::quantize(z), d24);
    }

    #[test]
    fn f32_format_stores_the_depth_itself(z in 2.0f32.powi(-32)..=1.0) {
        prop_assert_eq!(F32::quantize(z), z.to_bits());
    }

    /// Whatever the interpolator hands the depth unit (any bits, inside a
    /// triangle or not), a texel stays on the format's wires and the
    /// comparators' keys order texels as the texels are ordered.
    #[test]
    fn comparators_order_every_texel_a_format_stores(a in any::<i64>(), b in any::<i64>()) {
        order::<D16>(a, b)?;
        order::<D24>(a, b)?;
        order::<F32>(a, b)?;
    }

    #[test]
    fn out_of_range_saturates(z in 1.0f32..f32::MAX, n in f32::MIN..=0.0f32) {
        prop_assert_eq!(D16::quantize(z), D16::FAR);
        prop_assert_eq!(D24::quantize(z), D24::FAR);
        prop_assert_eq!(F32::quantize(z), F32::FAR);
        prop_assert_eq!(D16::quantize(n), 0);
        prop_assert_eq!(D24::quantize(n), 0);
        prop_assert_eq!(F32::quantize(n), 0);
    }
}

#[test]
fn nan_is_far() {
    assert_eq!(D16::quantize(f32::NAN), D16::FAR);
    assert_eq!(D24::quantize(f32::NAN), D24::FAR);
    assert_eq!(F32::quantize(f32::NAN), F32::FAR);
}
