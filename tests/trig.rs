//! Accuracy and contract tests for `arphysics::math::trig`, with `libm` (f64)
//! as the oracle.
//!
//! The contract is a maximum absolute error of 2e-8 over the whole input
//! range ([`CONTRACT`]). The implementation is designed to be within about half
//! an ulp (2^-33 ≈ 1.16e-10) of the exact value, so every check also asserts a
//! much tighter bound ([`SIN_COS_TIGHT`], [`ATAN2_TIGHT`]) to catch accuracy
//! regressions long before they would break the contract.
//!
//! Oracle precision: a Q32.32 value has up to 63 significant bits, more than an
//! `f64` holds, so `sin`/`cos` are evaluated as `sin(hi + lo)` with `hi` the
//! integer part and `lo` the fraction (both exact in `f64`) via the addition
//! formulas; libm reduces large arguments correctly, so the oracle's error is a
//! few 1e-16. For `atan2` only the ratio matters, and rounding each input to
//! `f64` perturbs it by ≤ 2^-53 relative, which moves the angle by ≤ 2^-53.

use arphysics::math::trig::{atan, atan2, cos, sin, sin_cos};
use arphysics::Scalar;
use proptest::prelude::*;

/// The accuracy contract from the issue.
const CONTRACT: f64 = 2e-8;
/// One unit in the last place of a `Scalar`, 2^-32.
const ULP: f64 = 1.0 / 4_294_967_296.0;
/// ½ ulp (correct rounding) + room for the internal error (< 2^-50) and the
/// oracle's own error.
const SIN_COS_TIGHT: f64 = 0.5 * ULP + 1e-14;
/// As above, plus the range clamp of `atan2` to ±`Scalar::PI`, which costs at
/// most 0.022 ulp beyond ½ ulp (`Scalar::PI` is π rounded down, 0.522 ulp
/// below π).
const ATAN2_TIGHT: f64 = 0.53 * ULP + 1e-14;

/// ⌊(π/2)·2^80⌋, for building arguments next to multiples of π/2.
const FRAC_PI_2_Q80: i128 = 0x0001_921f_b544_42d1_8469_898c;

fn f(x: Scalar) -> f64 {
    x.to_num::<f64>()
}

/// (sin x, cos x) of the exact value of `x`, to a few 1e-16.
fn oracle_sin_cos(x: Scalar) -> (f64, f64) {
    let bits = x.to_bits();
    let hi = (bits >> 32) as f64; // integer part (floor), |hi| ≤ 2^31: exact
    let lo = (bits & 0xffff_ffff) as f64 * ULP; // fraction in [0, 1): exact
    let (sh, ch) = (libm::sin(hi), libm::cos(hi));
    let (sl, cl) = (libm::sin(lo), libm::cos(lo));
    (sh * cl + ch * sl, ch * cl - sh * sl)
}

/// Absolute errors of `(sin x, cos x)`; also checks `sin`/`cos` agree with
/// `sin_cos` bit for bit.
fn sin_cos_errors(x: Scalar) -> (f64, f64) {
    let (s, c) = sin_cos(x);
    assert_eq!(sin(x), s, "sin({x:?}) differs from sin_cos");
    assert_eq!(cos(x), c, "cos({x:?}) differs from sin_cos");
    assert!(s.abs() <= Scalar::ONE && c.abs() <= Scalar::ONE);
    let (es, ec) = oracle_sin_cos(x);
    ((f(s) - es).abs(), (f(c) - ec).abs())
}

fn check_sin_cos(x: Scalar) {
    let (e_s, e_c) = sin_cos_errors(x);
    assert!(e_s <= CONTRACT && e_c <= CONTRACT, "contract: x = {x:?}");
    assert!(e_s <= SIN_COS_TIGHT, "sin({x:?}) error {e_s:e} ({} ulp)", e_s / ULP);
    assert!(e_c <= SIN_COS_TIGHT, "cos({x:?}) error {e_c:e} ({} ulp)", e_c / ULP);
}

/// Absolute error of `atan2(y, x)` (0 for the documented `atan2(0, 0) = 0`),
/// after checking the result is within ±`Scalar::PI` (hence in (−π, π]).
fn atan2_error(y: Scalar, x: Scalar) -> f64 {
    let a = atan2(y, x);
    assert!(a >= -Scalar::PI && a <= Scalar::PI, "atan2({y:?}, {x:?}) = {a:?}");
    if x == Scalar::ZERO && y == Scalar::ZERO {
        assert_eq!(a, Scalar::ZERO);
        return 0.0;
    }
    (f(a) - libm::atan2(f(y), f(x))).abs()
}

fn check_atan2(y: Scalar, x: Scalar) {
    let e = atan2_error(y, x);
    assert!(e <= CONTRACT, "contract: atan2({y:?}, {x:?})");
    assert!(e <= ATAN2_TIGHT, "atan2({y:?}, {x:?}) error {e:e} ({} ulp)", e / ULP);
}

/// The Q32.32 value nearest `k·π/2 + offset·2^-32`.
fn near_multiple_of_frac_pi_2(k: i32, offset: i32) -> Scalar {
    // |k|·⌊(π/2)·2^80⌋ < 2^31·2^81: no i128 overflow.
    let exact = i128::from(k) * FRAC_PI_2_Q80;
    let bits = (exact + (1 << 47)) >> 48;
    let bits = i64::try_from(bits).unwrap().saturating_add(i64::from(offset));
    Scalar::from_bits(bits)
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        // Do not write regression files into the source tree.
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Any bit pattern biased toward small magnitudes: a random i64 shifted right
/// by a random amount, so every scale from 2^-32 to 2^31 is well covered.
fn any_scale() -> impl Strategy<Value = Scalar> {
    (any::<i64>(), 0_u32..64).prop_map(|(b, s)| Scalar::from_bits(b >> s))
}

proptest! {
    #![proptest_config(config(100_000))]

    #[test]
    fn sin_cos_full_range(bits in any::<i64>()) {
        check_sin_cos(Scalar::from_bits(bits));
    }

    #[test]
    fn sin_cos_all_scales(x in any_scale()) {
        check_sin_cos(x);
    }

    #[test]
    fn sin_cos_small_arguments(bits in -(10_i64 << 32)..=(10_i64 << 32)) {
        check_sin_cos(Scalar::from_bits(bits));
    }

    #[test]
    fn sin_cos_tiny_arguments(bits in -(1_i64 << 20)..=(1_i64 << 20)) {
        check_sin_cos(Scalar::from_bits(bits));
    }

    #[test]
    fn sin_cos_near_multiples_of_frac_pi_2(
        k in prop_oneof![-64_i32..=64, -1_367_130_551_i32..=1_367_130_551],
        offset in -1000_i32..=1000,
    ) {
        check_sin_cos(near_multiple_of_frac_pi_2(k, offset));
    }

    #[test]
    fn sin_odd_cos_even(bits in (i64::MIN + 1)..=i64::MAX) {
        let x = Scalar::from_bits(bits);
        let (s, c) = sin_cos(x);
        let (sn, cn) = sin_cos(Scalar::from_bits(-bits));
        prop_assert_eq!(sn, -s);
        prop_assert_eq!(cn, c);
    }

    #[test]
    fn pythagorean_identity(bits in any::<i64>()) {
        let (s, c) = sin_cos(Scalar::from_bits(bits));
        // Exact in i128: |s|, |c| ≤ 2^32 in bits.
        let (sb, cb) = (i128::from(s.to_bits()), i128::from(c.to_bits()));
        let sum = sb * sb + cb * cb; // (s² + c²)·2^64
        let dev = (sum - (1_i128 << 64)).abs();
        // Each value is within ½ ulp, so s² + c² is within ~1 ulp of 1.
        prop_assert!(dev <= 3 << 32, "deviation {} ulp", dev as f64 / 2f64.powi(32));
    }

    #[test]
    fn atan2_full_range(yb in any::<i64>(), xb in any::<i64>()) {
        check_atan2(Scalar::from_bits(yb), Scalar::from_bits(xb));
    }

    #[test]
    fn atan2_all_scales(y in any_scale(), x in any_scale()) {
        check_atan2(y, x);
    }

    #[test]
    fn atan2_small_arguments(
        yb in -(10_i64 << 32)..=(10_i64 << 32),
        xb in -(10_i64 << 32)..=(10_i64 << 32),
    ) {
        check_atan2(Scalar::from_bits(yb), Scalar::from_bits(xb));
    }

    #[test]
    fn atan2_on_the_axes(v in any::<i64>(), which in 0_u8..2) {
        let v = Scalar::from_bits(v);
        if which == 0 {
            check_atan2(v, Scalar::ZERO);
        } else {
            check_atan2(Scalar::ZERO, v);
        }
    }

    #[test]
    fn atan2_huge_and_tiny_ratios(
        big in prop_oneof![Just(i64::MAX), Just(i64::MIN), any::<i64>()],
        small in -1000_i64..=1000,
        swap in any::<bool>(),
    ) {
        let (big, small) = (Scalar::from_bits(big), Scalar::from_bits(small));
        if swap {
            check_atan2(small, big);
        } else {
            check_atan2(big, small);
        }
    }

    #[test]
    fn atan2_near_the_diagonals(m in any::<i64>(), d in -1000_i64..=1000, sy in any::<bool>(), sx in any::<bool>()) {
        let a = (m >> 1).saturating_abs();
        let b = a.saturating_add(d).max(0);
        let y = Scalar::from_bits(if sy { -a } else { a });
        let x = Scalar::from_bits(if sx { -b } else { b });
        check_atan2(y, x);
    }

    #[test]
    fn atan2_next_to_the_branch_cut(xb in i64::MIN..0, yb in -1000_i64..=1000) {
        check_atan2(Scalar::from_bits(yb), Scalar::from_bits(xb));
    }

    #[test]
    fn atan2_is_odd_in_y(yb in (i64::MIN + 1)..=i64::MAX, xb in any::<i64>()) {
        let (y, x) = (Scalar::from_bits(yb), Scalar::from_bits(xb));
        // y = 0 is excluded: atan2(0, x < 0) is +PI by convention.
        if yb != 0 {
            prop_assert_eq!(atan2(Scalar::from_bits(-yb), x), -atan2(y, x));
        }
    }

    #[test]
    fn atan_matches_atan2(xb in any::<i64>()) {
        let x = Scalar::from_bits(xb);
        prop_assert_eq!(atan(x), atan2(x, Scalar::ONE));
        let e = (f(atan(x)) - libm::atan(f(x))).abs();
        prop_assert!(e <= SIN_COS_TIGHT, "atan({:?}) error {:e}", x, e);
    }
}

/// The Q32.32 value nearest `v` (test helper for exact expectations).
fn q(v: f64) -> Scalar {
    Scalar::from_num(v)
}

#[test]
fn exact_special_values() {
    let z = Scalar::ZERO;
    let one = Scalar::ONE;
    assert_eq!(sin_cos(z), (z, one));
    assert_eq!(sin(z), z);
    assert_eq!(cos(z), one);
    assert_eq!(sin(Scalar::DELTA), Scalar::DELTA);
    assert_eq!(sin(Scalar::FRAC_PI_2), one);
    assert_eq!(cos(Scalar::PI), -one);
    // FRAC_PI_3 and FRAC_PI_6 are below π/3 and π/6 by up to 1 ulp, so their
    // cosine/sine round to 0.5 ± 1 ulp: check accuracy rather than equality.
    check_sin_cos(Scalar::FRAC_PI_3);
    check_sin_cos(Scalar::FRAC_PI_6);
    assert_eq!(sin(Scalar::FRAC_PI_4), cos(Scalar::FRAC_PI_4));
    assert_eq!(sin(Scalar::FRAC_PI_4), q(core::f64::consts::FRAC_1_SQRT_2));

    assert_eq!(atan2(z, z), z);
    assert_eq!(atan2(z, one), z);
    assert_eq!(atan2(z, -one), Scalar::PI);
    assert_eq!(atan2(z, Scalar::MIN), Scalar::PI);
    assert_eq!(atan2(one, z), Scalar::FRAC_PI_2);
    assert_eq!(atan2(-one, z), -Scalar::FRAC_PI_2);
    assert_eq!(atan2(one, one), Scalar::FRAC_PI_4);
    assert_eq!(atan2(-one, -one), -q(3.0 * core::f64::consts::FRAC_PI_4));
    assert_eq!(atan2(Scalar::MAX, Scalar::MAX), Scalar::FRAC_PI_4);
    assert_eq!(atan2(Scalar::MIN, Scalar::MIN), -q(3.0 * core::f64::consts::FRAC_PI_4));
    assert_eq!(atan(one), Scalar::FRAC_PI_4);
    // atan(±2^31) = ±(π/2 − 2^-31): two ulps inside ±FRAC_PI_2.
    assert_eq!(atan(Scalar::MIN), -Scalar::FRAC_PI_2 + 2 * Scalar::DELTA);
    check_atan2(Scalar::MIN, one);
    check_atan2(Scalar::MAX, one);
    // The `fixed` crate rounds its constants down: Scalar::PI is 0.522 ulp
    // below π (so atan2's range [−PI, PI] lies inside (−π, π]); FRAC_PI_2
    // happens to also be the nearest value.
    assert!(f(Scalar::PI) < core::f64::consts::PI);
    assert_eq!(Scalar::PI + Scalar::DELTA, q(core::f64::consts::PI));
    assert_eq!(Scalar::FRAC_PI_2, q(core::f64::consts::FRAC_PI_2));
}

#[test]
fn atan2_range_is_clamped_to_pi() {
    // Next to the negative x axis the rounded angle would be ±(PI + 2^-32),
    // outside (−π, π] on one side; both are clamped to ±Scalar::PI.
    assert_eq!(atan2(Scalar::DELTA, Scalar::MIN), Scalar::PI);
    assert_eq!(atan2(-Scalar::DELTA, Scalar::MIN), -Scalar::PI);
    assert_eq!(atan2(Scalar::ZERO, -Scalar::DELTA), Scalar::PI);
    check_atan2(Scalar::DELTA, Scalar::MIN);
    check_atan2(-Scalar::DELTA, Scalar::MIN);
    check_atan2(Scalar::MIN, -Scalar::DELTA);
}

#[test]
fn extreme_inputs() {
    let extremes = [
        Scalar::MIN,
        Scalar::MAX,
        Scalar::from_bits(i64::MIN + 1),
        Scalar::from_bits(i64::MAX - 1),
        Scalar::DELTA,
        -Scalar::DELTA,
        Scalar::ZERO,
        Scalar::ONE,
        -Scalar::ONE,
    ];
    for &x in &extremes {
        check_sin_cos(x);
        for &y in &extremes {
            check_atan2(y, x);
        }
    }
}

/// SplitMix64: a fixed, seedable sample for the error report.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn scalar(&mut self) -> Scalar {
        // Uniform bits, then a random right shift so every scale is covered.
        let bits = self.next() as i64;
        let shift = (self.next() % 64) as u32;
        Scalar::from_bits(if shift < 16 { bits } else { bits >> (shift - 16) })
    }
}

/// Measures the maximum errors over a large fixed sample and prints them (run
/// with `cargo test --test trig -- --nocapture max_error_report`).
#[test]
fn max_error_report() {
    const N: u32 = 1_000_000;
    let mut rng = SplitMix64(0x5eed_a7a7_2026);
    let (mut max_s, mut max_c, mut max_a) = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in 0..N {
        let x = match i % 3 {
            0 => rng.scalar(),
            1 => Scalar::from_bits((rng.next() as i64) >> 28), // |x| ≤ 8
            _ => near_multiple_of_frac_pi_2((rng.next() as i32) >> 1, ((rng.next() % 2001) as i32) - 1000),
        };
        let (es, ec) = sin_cos_errors(x);
        max_s = max_s.max(es);
        max_c = max_c.max(ec);
        let (y, x) = (rng.scalar(), rng.scalar());
        max_a = max_a.max(atan2_error(y, x));
    }
    println!(
        "trig max abs error over {N} samples each: sin {max_s:.3e} ({:.3} ulp), \
         cos {max_c:.3e} ({:.3} ulp), atan2 {max_a:.3e} ({:.3} ulp); contract {CONTRACT:e}",
        max_s / ULP,
        max_c / ULP,
        max_a / ULP,
    );
    assert!(max_s <= SIN_COS_TIGHT && max_c <= SIN_COS_TIGHT && max_a <= ATAN2_TIGHT);
}
