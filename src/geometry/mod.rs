//! Shapes and their mass properties: [`PolygonPath`] (convex hull, optionally
//! with rounded corners; area, centroid, moment of inertia), circles
//! ([`circle_area`], [`circle_unit_inertia`]), [`Capsule`]s and [`Segment`]s,
//! ray casts against each ([`ray`]), and [`MassData`].
//!
//! Every quantity here is computed from the raw Q32.32 bits with exact integer
//! arithmetic and rounded once, to nearest, at the end. The results are therefore
//! a function of the input values alone, on every target, and correctly rounded
//! (to within a fraction of the last bit) rather than carrying the round-off of a
//! chain of fixed-point operations.

pub mod capsule;
pub mod chain;
pub mod chain_segment;
pub mod circle;
pub mod mass;
pub mod polygon_path;
pub mod ray;

pub use capsule::{Capsule, Segment, MIN_SEGMENT_LENGTH};
pub use chain::{ChainHandle, ChainNode, ChainPath, CHAIN_BYTES_PER_VERTEX, MAX_CHAIN_VERTICES};
pub use chain_segment::ChainSegment;
pub use circle::{circle_area, circle_unit_inertia, MAX_CIRCLE_RADIUS};
pub use mass::{compound_mass, MassData, MassPart, MAX_INERTIA, MAX_MASS, MIN_INERTIA, MIN_MASS};
pub use polygon_path::{
    PolygonPath, MAX_POLYGON_RADIUS, MAX_POLYGON_VERTICES, MIN_POLYGON_AREA, MIN_POLYGON_THICKNESS,
};

/// Exact unsigned 256-bit arithmetic, just enough for second moments of area.
///
/// A polygon's moment of inertia is a sum of products of two 80-bit integers (a
/// cross product and a sum of squares of raw coordinate bits), which does not fit
/// an `i128`. Rather than dropping low bits (and making the rounding depend on the
/// scale), the products are formed exactly here and rounded once.
mod wide {
    /// The low 64 bits of a `u128`.
    const LOW64: u128 = u64::MAX as u128;

    /// An unsigned 256-bit integer `hi · 2^128 + lo`.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
    pub(super) struct U256 {
        hi: u128,
        lo: u128,
    }

    impl U256 {
        /// The exact product `a · b`.
        pub(super) fn mul(a: u128, b: u128) -> Self {
            let (a1, a0) = (a >> 64, a & LOW64);
            let (b1, b0) = (b >> 64, b & LOW64);
            // Each partial product multiplies two values below 2^64, so it is below
            // 2^128: the `wrapping_*` never wraps here, it only states the policy.
            let p00 = a0.wrapping_mul(b0);
            let p01 = a0.wrapping_mul(b1);
            let p10 = a1.wrapping_mul(b0);
            let p11 = a1.wrapping_mul(b1);
            // The middle column sums three values below 2^64: below 2^66.
            let mid = (p00 >> 64).wrapping_add(p01 & LOW64).wrapping_add(p10 & LOW64);
            let lo = (p00 & LOW64) | ((mid & LOW64) << 64);
            // The full product is below 2^256, so the high half cannot wrap.
            let hi = p11.wrapping_add(p01 >> 64).wrapping_add(p10 >> 64).wrapping_add(mid >> 64);
            Self { hi, lo }
        }

        /// `self + o` (modulo 2^256; callers keep sums far below that).
        pub(super) fn add(self, o: Self) -> Self {
            let (lo, carry) = self.lo.overflowing_add(o.lo);
            let hi = self.hi.wrapping_add(o.hi).wrapping_add(u128::from(carry));
            Self { hi, lo }
        }

        /// `self − o`, or 0 when `o > self`.
        pub(super) fn saturating_sub(self, o: Self) -> Self {
            if o >= self {
                return Self::default();
            }
            let (lo, borrow) = self.lo.overflowing_sub(o.lo);
            let hi = self.hi.wrapping_sub(o.hi).wrapping_sub(u128::from(borrow));
            Self { hi, lo }
        }

        /// `self · 2^k` for `k < 128` (modulo 2^256; callers keep it far below).
        pub(super) fn shl(self, k: u32) -> Self {
            if k == 0 || k >= 128 {
                return if k == 0 { self } else { Self::default() };
            }
            Self { hi: (self.hi << k) | (self.lo >> (128 - k)), lo: self.lo << k }
        }

        /// `⌊self / 2^k⌋` for `k < 128`.
        pub(super) fn shr(self, k: u32) -> Self {
            if k == 0 || k >= 128 {
                return if k == 0 { self } else { Self::default() };
            }
            Self { hi: self.hi >> k, lo: (self.lo >> k) | (self.hi << (128 - k)) }
        }

        /// `self / (d · 2^shift)` rounded to nearest (ties up), for `1 ≤ shift ≤ 125`
        /// and `1 ≤ d ≤ 3`. `None` when the arguments are outside those limits or
        /// the quotient does not fit a `u128`.
        pub(super) fn div_round(self, shift: u32, d: u128) -> Option<u128> {
            if !(1..=125).contains(&shift) || !(1..=3).contains(&d) {
                return None;
            }
            if self.hi >> shift != 0 {
                return None;
            }
            // self = s · 2^shift + r, with r < 2^shift.
            let s = (self.hi << 128u32.saturating_sub(shift)) | (self.lo >> shift);
            let r = self.lo & ((1u128 << shift).wrapping_sub(1));
            let (q, rd) = (s.checked_div(d)?, s.checked_rem(d)?);
            // self / (d·2^shift) = q + rem / den, with rem < den ≤ 3 · 2^125.
            let rem = (rd << shift) | r;
            let den = d << shift;
            let up = rem >= den.wrapping_sub(rem);
            q.checked_add(u128::from(up))
        }
    }

    /// `√d · 2^62` for `d < 2^82`, `None` above: the square root with 62 more
    /// fraction bits than `d`'s unit gives (for raw Q32.32 squares `d` in units of
    /// 2^-64 m², the length in units of 2^-94 m).
    ///
    /// `isqrt(d · 2^44)` gives 22 extra bits (`s ≥ 2^22` for `d ≥ 1`); one Newton
    /// step from it, `s + (d·2^44 − s²) / (2s)`, adds 40 more. Newton from below
    /// overshoots by at most `1 / (2s) ≤ 2^-23` of a unit of `s`, so the result is
    /// within 2^-45 of `d`'s square-root unit above or below the exact value (for a
    /// length in raw bits, within 2^-77 m).
    pub(super) fn sqrt_q62(d: u128) -> Option<u128> {
        if d >= 1 << 82 {
            return None;
        }
        if d == 0 {
            return Some(0);
        }
        let n = d << 44; // < 2^126
        let s = n.isqrt(); // 2^22 ≤ s < 2^63
        let rem = n.checked_sub(s.checked_mul(s)?)?; // ≤ 2s < 2^64
        let frac = (rem << 40).checked_div(s.checked_mul(2)?)?; // < 2^41
        (s << 40).checked_add(frac)
    }
}
