//! Mass properties of a body, validated so that the quantities the step multiplies
//! them with stay well inside the Q32.32 range.
//!
//! # Ranges, and why
//! The step multiplies masses by velocities (momentum, impulses) and inertias by
//! angular velocities. Q32.32 holds magnitudes up to 2^31 ≈ 2.1e9.
//!
//! * Mass in [[`MIN_MASS`], [`MAX_MASS`]] = [0.001, 100,000] kg. At the speed
//!   limit of 2,000 m/s a body's momentum is at most 2e8 kg·m/s, ten times below
//!   the Q32.32 limit, and an impulse stopping two bodies that close at 4,000 m/s
//!   is at most 4e8 N·s. (A limit of 1e6 kg would put the momentum itself at 2e9,
//!   with no headroom at all.) At 1 g the mass still has 4.3 million steps of
//!   2^-32 (relative rounding 1.2e-7), and `inv_mass` is at most 1,000.
//! * Moment of inertia in [[`MIN_INERTIA`], [`MAX_INERTIA`]] = [1e-6, 1e6] kg·m².
//!   For angular speeds up to 200 rad/s (about 32 turns per second, comparable to
//!   the per-sub-step rotation caps of other engines) the angular momentum is at
//!   most 2e8 kg·m²/s, the same headroom as the linear momentum. **The world must
//!   clamp |ω| to 200 rad/s for this to hold.** At 1e-6 kg·m² the inertia still
//!   has 4,295 steps of 2^-32 (relative rounding 1.2e-4), and `inv_inertia` is at
//!   most 1e6. For scale: a 1,000 kg, 4 m × 2 m box has 1,667 kg·m²; a 100 t,
//!   7.7 m square is at the upper limit; a 1 g, 11 cm square at the lower one.
//!
//! * Both ranges hold at once, so the limits table has a row for the inertia:
//!   a body is legal when its mass **and** its inertia are in range. For a circle
//!   I = m·r²/2, so m·r² ∈ [2e-6, 2e6] kg·m²: a 128 m circle weighs at most
//!   122 kg, a 1 cm circle at least 20 g, a 100 t circle is at most 4.47 m in
//!   radius (the audit's 128 m, 1,000 kg circle and 1 cm, 1 g circle are
//!   `OutOfRange { what: "inertia" }`). For a w × h box I = m·(w² + h²)/12.
//!   Widening the inertia range is not safe: above 1e6 kg·m² the angular
//!   momentum I·ω at the highest spin limit (256 rad/s) passes 2.6e8 towards
//!   Q32.32's 2.1e9, and below 1e-6 kg·m² the inverse inertia (> 1e6) turns the
//!   impulses of a contact at a 1 m arm into spins far past every limit.
//! * A circle's unit inertia π·r⁴/2 is rounded to 2^-32: from 1 cm (67 steps)
//!   it is within 1 %; below about 3.5 mm it rounds to 0 and the body is an
//!   `inertia` error whatever its mass.
//!
//! Static bodies (and kinematic ones) use [`MassData::STATIC`], all zeros: an
//! inverse mass of 0 is what makes them immovable in the solver. A mass or
//! density given to such a body is ignored, whatever its value.

use crate::error::Error;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Vector2;

/// Smallest mass of a dynamic body: 0.001 kg (see the [module docs](self)).
pub const MIN_MASS: Scalar = Scalar::lit("0.001");
/// Largest mass of a dynamic body: 100,000 kg (see the [module docs](self)).
pub const MAX_MASS: Scalar = Scalar::from_int(100_000);
/// Smallest moment of inertia of a dynamic body: 1e-6 kg·m² (see the
/// [module docs](self)).
pub const MIN_INERTIA: Scalar = Scalar::lit("0.000001");
/// Largest moment of inertia of a dynamic body: 1e6 kg·m² (see the
/// [module docs](self)).
pub const MAX_INERTIA: Scalar = Scalar::from_int(1_000_000);

/// Mass properties of a body.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MassData {
    /// Mass in kg (0 for static and kinematic bodies).
    pub mass: Scalar,
    /// 1 / mass, or 0.
    pub inv_mass: Scalar,
    /// Moment of inertia about the centre of mass, kg·m².
    pub inertia: Scalar,
    /// 1 / inertia, or 0.
    pub inv_inertia: Scalar,
}

impl MassData {
    /// The mass data of a static (or kinematic) body: everything 0, so impulses
    /// do not move it.
    pub const STATIC: Self = Self { mass: ZERO, inv_mass: ZERO, inertia: ZERO, inv_inertia: ZERO };

    /// Mass data of a shape of `area` (m²) and `unit_inertia` (kg·m² at density
    /// 1 kg/m², e.g. [`PolygonPath::unit_inertia`](super::PolygonPath::unit_inertia)
    /// or [`circle_unit_inertia`](super::circle_unit_inertia)) made of a material
    /// of `density` kg/m².
    ///
    /// `mass = density · area` and `inertia = density · unit_inertia`, each computed
    /// exactly and rounded once to nearest.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `what`:
    /// * `"density"` when `density ≤ 0`;
    /// * `"area"` when `area ≤ 0`;
    /// * `"inertia"` when `unit_inertia ≤ 0`, or the inertia is outside
    ///   [[`MIN_INERTIA`], [`MAX_INERTIA`]];
    /// * `"mass"` when the mass is outside [[`MIN_MASS`], [`MAX_MASS`]].
    pub fn from_density(density: Scalar, area: Scalar, unit_inertia: Scalar) -> Result<Self, Error> {
        if density <= ZERO {
            return Err(out_of_range("density"));
        }
        check_shape(area, unit_inertia)?;
        let mass = mul_div_round(density, area, scalar::ONE)
            .filter(|m| (MIN_MASS..=MAX_MASS).contains(m))
            .ok_or(out_of_range("mass"))?;
        let inertia = mul_div_round(density, unit_inertia, scalar::ONE).ok_or(out_of_range("inertia"))?;
        Self::checked(mass, inertia)
    }

    /// Mass data of a shape of `area` (m²) and `unit_inertia` (kg·m² at density
    /// 1 kg/m²) with a total `mass` in kg (the density being `mass / area`).
    ///
    /// `inertia = mass · unit_inertia / area`, computed exactly and rounded once to
    /// nearest (no intermediate density is rounded).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `what`:
    /// * `"mass"` when `mass` is outside [[`MIN_MASS`], [`MAX_MASS`]];
    /// * `"area"` when `area ≤ 0`;
    /// * `"inertia"` when `unit_inertia ≤ 0`, or the inertia is outside
    ///   [[`MIN_INERTIA`], [`MAX_INERTIA`]].
    pub fn from_mass(mass: Scalar, area: Scalar, unit_inertia: Scalar) -> Result<Self, Error> {
        if !(MIN_MASS..=MAX_MASS).contains(&mass) {
            return Err(out_of_range("mass"));
        }
        check_shape(area, unit_inertia)?;
        let inertia = mul_div_round(mass, unit_inertia, area).ok_or(out_of_range("inertia"))?;
        Self::checked(mass, inertia)
    }

    /// True for the all-zero mass data of static and kinematic bodies.
    #[inline]
    #[must_use]
    pub fn is_static(&self) -> bool {
        self.inv_mass == ZERO && self.inv_inertia == ZERO
    }

    /// Mass data from a mass and an inertia, both checked against their ranges.
    fn checked(mass: Scalar, inertia: Scalar) -> Result<Self, Error> {
        if !(MIN_MASS..=MAX_MASS).contains(&mass) {
            return Err(out_of_range("mass"));
        }
        if !(MIN_INERTIA..=MAX_INERTIA).contains(&inertia) {
            return Err(out_of_range("inertia"));
        }
        Ok(Self { mass, inv_mass: mass.recip(), inertia, inv_inertia: inertia.recip() })
    }
}

/// One shape's share of a body of several shapes: its mass (kg), its centre
/// of mass in the body's frame (m) and its moment of inertia about that
/// centre (kg·m²), as [`MassData::from_density`] gives them for the shape
/// alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MassPart {
    /// Mass in kg (> 0).
    pub mass: Scalar,
    /// Centre of mass of the shape in the body's frame (m).
    pub centre: Vector2,
    /// Moment of inertia about the shape's own centre of mass (kg·m², ≥ 0).
    pub inertia: Scalar,
}

/// The mass data of a body made of `parts`, and its centre of mass in the
/// same frame as the parts' centres: the masses summed, the centre their
/// mass-weighted mean, and the inertia the sum of each part's own plus
/// `mᵢ·|cᵢ − c|²` (the parallel-axis theorem about the common centre).
///
/// The centre is computed exactly in 128 bits and rounded once to nearest;
/// each parallel-axis term `mᵢ·|cᵢ − c|²` is rounded twice (the square, then
/// the product), so the inertia is within a few units of 2^-32 kg·m² per part
/// of the exact sum. The order of `parts` does not change the result (every
/// sum is exact, each term rounded alone).
///
/// # Errors
/// [`Error::OutOfRange`] with `what`:
/// * `"mass"` when `parts` is empty, a part's mass is not positive, or the
///   total is outside [[`MIN_MASS`], [`MAX_MASS`]];
/// * `"inertia"` when a part's inertia is negative, or the total does not
///   fit or is outside [[`MIN_INERTIA`], [`MAX_INERTIA`]].
pub fn compound_mass(parts: &[MassPart]) -> Result<(MassData, Vector2), Error> {
    let mut total: i128 = 0;
    let (mut mx, mut my): (i128, i128) = (0, 0);
    for p in parts {
        if p.mass <= ZERO {
            return Err(out_of_range("mass"));
        }
        if p.inertia < ZERO {
            return Err(out_of_range("inertia"));
        }
        let m = i128::from(p.mass.to_bits());
        total = total.checked_add(m).ok_or(out_of_range("mass"))?;
        // |m| < 2^63 and |x| < 2^63: each product is below 2^126, and a
        // world's bodies have at most a few shapes.
        mx = mx
            .checked_add(m.checked_mul(i128::from(p.centre.x.to_bits())).ok_or(out_of_range("mass"))?)
            .ok_or(out_of_range("mass"))?;
        my = my
            .checked_add(m.checked_mul(i128::from(p.centre.y.to_bits())).ok_or(out_of_range("mass"))?)
            .ok_or(out_of_range("mass"))?;
    }
    let mass = i64::try_from(total).ok().map(Scalar::from_bits).filter(|m| (MIN_MASS..=MAX_MASS).contains(m));
    let mass = mass.ok_or(out_of_range("mass"))?;
    let mean = |sum: i128| div_round(sum, total).and_then(|q| i64::try_from(q).ok()).map(Scalar::from_bits);
    let centre = match (mean(mx), mean(my)) {
        (Some(x), Some(y)) => Vector2::new(x, y),
        _ => return Err(out_of_range("mass")),
    };
    let mut inertia = ZERO;
    for p in parts {
        let term = parallel_axis(p, centre).ok_or(out_of_range("inertia"))?;
        inertia = inertia.checked_add(term).ok_or(out_of_range("inertia"))?;
    }
    Ok((MassData::checked(mass, inertia)?, centre))
}

/// A part's inertia about `centre`: its own plus `m·|c − centre|²`.
fn parallel_axis(p: &MassPart, centre: Vector2) -> Option<Scalar> {
    let dx = p.centre.x.checked_sub(centre.x)?;
    let dy = p.centre.y.checked_sub(centre.y)?;
    let d2 = mul_div_round(dx, dx, scalar::ONE)?.checked_add(mul_div_round(dy, dy, scalar::ONE)?)?;
    p.inertia.checked_add(mul_div_round(p.mass, d2, scalar::ONE)?)
}

/// `num / den` rounded to nearest (ties away from zero), `den > 0`.
fn div_round(num: i128, den: i128) -> Option<i128> {
    if den <= 0 {
        return None;
    }
    let half = den / 2;
    if num >= 0 {
        num.checked_add(half)?.checked_div(den)
    } else {
        Some(-((-num).checked_add(half)?.checked_div(den)?))
    }
}

/// [`Error::OutOfRange`] for `what`.
const fn out_of_range(what: &'static str) -> Error {
    Error::OutOfRange { what }
}

/// The shape's own numbers must be positive.
fn check_shape(area: Scalar, unit_inertia: Scalar) -> Result<(), Error> {
    if area <= ZERO {
        return Err(out_of_range("area"));
    }
    if unit_inertia <= ZERO {
        return Err(out_of_range("inertia"));
    }
    Ok(())
}

/// `a · b / c` for positive `a`, `b`, `c`, exact in `i128` (the raw product is
/// below 2^126) and rounded once to nearest; `None` when the result does not fit.
pub(crate) fn mul_div_round(a: Scalar, b: Scalar, c: Scalar) -> Option<Scalar> {
    let num = i128::from(a.to_bits()).checked_mul(i128::from(b.to_bits()))?;
    let den = i128::from(c.to_bits());
    if num < 0 || den <= 0 {
        return None;
    }
    // (2·num + den) / (2·den), the raw units of num / den being 2^-32.
    let q = num.checked_mul(2)?.checked_add(den)?.checked_div(den.checked_mul(2)?)?;
    i64::try_from(q).ok().map(Scalar::from_bits)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(mass: &str, x: &str, y: &str, inertia: f64) -> MassPart {
        MassPart {
            mass: Scalar::lit(mass),
            centre: Vector2::new(Scalar::lit(x), Scalar::lit(y)),
            inertia: Scalar::from_num(inertia),
        }
    }

    /// An L of two 2 m × 1 m boxes at 1 kg/m² (a foot along x, a leg up y):
    /// each I = m(w² + h²)/12 = 10/12; the common centre (0.25, 0.75) is
    /// √0.625 m from both, so I = 2·10/12 + 2·2·0.625 = 25/6 kg·m².
    #[test]
    fn an_l_of_two_boxes_sums_by_the_parallel_axis_theorem() {
        let foot = part("2", "0", "0", 10.0 / 12.0);
        let leg = part("2", "0.5", "1.5", 10.0 / 12.0);
        let (m, c) = compound_mass(&[foot, leg]).unwrap();
        assert_eq!(m.mass, Scalar::from_int(4));
        assert_eq!(c, Vector2::new(Scalar::lit("0.25"), Scalar::lit("0.75")));
        let exact = 25.0 / 6.0;
        assert!((m.inertia.to_f64() - exact).abs() < 1e-8, "{} vs {exact}", m.inertia.to_f64());
        assert_eq!(m.inv_mass, Scalar::lit("0.25"));
        // The order of the parts changes nothing, bit for bit.
        assert_eq!(compound_mass(&[leg, foot]).unwrap(), (m, c));
    }

    /// Unequal masses: the centre is the weighted mean, rounded once.
    #[test]
    fn the_centre_is_the_mass_weighted_mean() {
        let a = part("1", "-1", "0", 0.5);
        let b = part("3", "1", "2", 0.25);
        let (m, c) = compound_mass(&[a, b]).unwrap();
        assert_eq!(c, Vector2::new(Scalar::lit("0.5"), Scalar::lit("1.5")));
        // 0.5 + 0.25 + 1·(2.25 + 2.25) + 3·(0.25 + 0.25) = 6.75.
        assert_eq!(m.inertia, Scalar::lit("6.75"));
        // A third that cannot be represented exactly rounds to nearest.
        let (_, c3) = compound_mass(&[part("1", "0", "0", 1.0), part("2", "1", "0", 1.0)]).unwrap();
        assert!((c3.x.to_f64() - 2.0 / 3.0).abs() <= 2f64.powi(-33));
    }

    #[test]
    fn bad_parts_are_errors() {
        let ok = part("1", "0", "0", 1.0);
        assert_eq!(compound_mass(&[]), Err(Error::OutOfRange { what: "mass" }));
        assert_eq!(compound_mass(&[ok, part("0", "1", "0", 1.0)]), Err(Error::OutOfRange { what: "mass" }));
        assert_eq!(
            compound_mass(&[ok, part("1", "1", "0", -1.0)]),
            Err(Error::OutOfRange { what: "inertia" })
        );
        let heavy = part("60000", "0", "0", 1.0);
        assert_eq!(compound_mass(&[heavy, heavy]), Err(Error::OutOfRange { what: "mass" }));
        // Parts far apart: the parallel-axis term is past the inertia limit.
        let far = part("1000", "100", "0", 1.0);
        assert_eq!(
            compound_mass(&[part("1000", "-100", "0", 1.0), far]),
            Err(Error::OutOfRange { what: "inertia" })
        );
    }
}
