//! Properties of the math layer, checked by proptest over wide input ranges.

use arphysics::math::scalar::{self, Scalar};
use arphysics::{Matrix22, Rot, Vector2};
use proptest::prelude::*;

/// A scalar in ±`limit` metres with full fractional resolution.
fn scalar_in(limit: i64) -> impl Strategy<Value = Scalar> {
    (-(limit << 32)..=(limit << 32)).prop_map(Scalar::from_bits)
}

fn vector_in(limit: i64) -> impl Strategy<Value = Vector2> {
    (scalar_in(limit), scalar_in(limit)).prop_map(|(x, y)| Vector2::new(x, y))
}

fn close(a: Scalar, b: Scalar, tol: f64) -> bool {
    (a - b).abs().to_num::<f64>() <= tol
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn rotation_stays_unit_length_however_long_it_spins(angle in scalar_in(1000), omega_h in scalar_in(1), steps in 1usize..2000) {
        // ω·h is limited to a quarter turn per step by the world; test up to 1 rad.
        let mut q = Rot::from_angle(angle);
        for _ in 0..steps {
            q = q.integrate(omega_h);
        }
        let len2 = q.c * q.c + q.s * q.s;
        prop_assert!(close(len2, Scalar::ONE, 5e-9), "|q|² = {len2}");
    }

    #[test]
    fn rotating_then_rotating_back_is_the_identity(v in vector_in(1000), angle in scalar_in(100)) {
        let q = Rot::from_angle(angle);
        let back = q.inv_rotate(q.rotate(v));
        prop_assert!((back - v).length().to_num::<f64>() <= 1e-6, "{v:?} -> {back:?}");
        // Rotation preserves length.
        prop_assert!(close(q.rotate(v).length(), v.length(), 1e-6));
    }

    #[test]
    fn vector_identities_hold(a in vector_in(30_000), b in vector_in(30_000)) {
        prop_assert_eq!(a.dot(b), b.dot(a));
        prop_assert_eq!(a.cross(b), -b.cross(a));
        prop_assert_eq!((a + b) - b, a);
        prop_assert_eq!(-(-a), a);
        // Products round down (floor), so (−y)·x and −(y·x) can differ by one ulp:
        // perp(a)·a is zero to within two ulps, not exactly.
        prop_assert!(a.perp().dot(a).abs() <= Scalar::DELTA * 2, "{}", a.perp().dot(a));
        prop_assert_eq!(a.perp().perp(), -a);
        // (a × s) and (s × a) are perpendicular to a.
        let s = Scalar::from_num(3);
        prop_assert_eq!(a.cross_vs(s), -Vector2::cross_sv(s, a));
    }

    #[test]
    fn normalize_gives_unit_vectors_or_zero(v in vector_in(1_000_000)) {
        let (n, len) = v.normalize_and_length();
        if v.is_zero() {
            prop_assert_eq!((n, len), (Vector2::ZERO, Scalar::ZERO));
        } else {
            prop_assert!(close(n.length(), Scalar::ONE, 2e-9), "|n| = {}", n.length());
            prop_assert!((n * len - v).length().to_num::<f64>() <= 1e-6 * (1.0 + len.to_num::<f64>()));
        }
    }

    #[test]
    fn lengths_match_f64_at_every_scale(v in vector_in(1_000_000)) {
        let (x, y) = v.to_f64();
        let exact = x.hypot(y);
        let got = v.length().to_num::<f64>();
        prop_assert!((got - exact).abs() <= 1e-9 * (1.0 + exact), "{got} vs {exact}");
    }

    #[test]
    fn a_solved_system_satisfies_its_equations(m in prop::array::uniform4(scalar_in(100)), b in vector_in(100)) {
        let m = Matrix22::new(m[0], m[1], m[2], m[3]);
        match m.solve(b) {
            None => prop_assert_eq!(m.determinant(), Scalar::ZERO),
            Some(x) => {
                // Only meaningful when the matrix is not nearly singular.
                let det = m.determinant().abs().to_num::<f64>();
                if det > 1e-3 && x.length() < scalar::from_int(1000) {
                    let r = m * x - b;
                    prop_assert!(r.length().to_num::<f64>() <= 1e-6 * (1.0 + 1.0 / det), "residual {r:?}");
                }
            }
        }
    }
}
