//! The solver's copy of a body: what the sub-step loop reads and writes of it.
//!
//! The loop touches each body's velocity and pose a dozen times a step, so it
//! works on a compact record per body slot ([`SolverBody`], 88 bytes against
//! 216 for a [`Body`] slot), loaded once at the start of the step and stored
//! back at the end. Contacts and joints alike act on these records.

use crate::body::Body;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Vector2};

/// A body's state as the solver sees it during a step (solver scratch, one per
/// body slot; see [`Storage`](crate::Storage)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolverBody {
    pub(crate) v: Vector2,
    pub(crate) w: Scalar,
    pub(crate) p: Vector2,
    pub(crate) q: Rot,
    /// The angle turned since the start of the step (rad).
    pub(crate) angle: Scalar,
    /// This sub-step's share of the force generators' velocity change.
    pub(crate) force_dv: Vector2,
    pub(crate) force_dw: Scalar,
    /// Receives the generators' velocity change (dynamic, in bounds).
    pub(crate) forced: bool,
    /// Integrates its position (not static, in bounds).
    pub(crate) moves: bool,
    /// Takes impulses (dynamic, in bounds): contacts change its velocity.
    pub(crate) dynamic: bool,
}

impl SolverBody {
    /// An unused record.
    pub const EMPTY: Self = Self {
        v: Vector2::ZERO,
        w: ZERO,
        p: Vector2::ZERO,
        q: Rot::IDENTITY,
        angle: ZERO,
        force_dv: Vector2::ZERO,
        force_dw: ZERO,
        forced: false,
        moves: false,
        dynamic: false,
    };

    /// Loads a body's state; `inv_n` is 1 / sub-steps. A frozen (out of
    /// bounds) body is loaded as a static one: no forces, no impulses, not
    /// integrated.
    #[inline]
    pub(crate) fn load(b: &Body, inv_n: Scalar) -> Self {
        Self {
            v: b.linear_velocity,
            w: b.angular_velocity,
            p: b.position,
            q: b.rotation,
            angle: ZERO,
            force_dv: b.force_dv * inv_n,
            force_dw: b.force_dw * inv_n,
            forced: b.is_dynamic() && !b.out_of_bounds,
            moves: b.moved_by_step(),
            dynamic: b.is_dynamic() && !b.out_of_bounds,
        }
    }

    /// Writes the velocity and pose back to the body.
    #[inline]
    pub(crate) fn store(&self, b: &mut Body) {
        b.linear_velocity = self.v;
        b.angular_velocity = self.w;
        b.position = self.p;
        b.rotation = self.q;
    }

    /// Velocity of the point at offset `r` from the centre of mass.
    #[inline]
    pub(crate) fn velocity_at_offset(&self, r: Vector2) -> Vector2 {
        self.v + Vector2::cross_sv(self.w, r)
    }

    /// Takes the velocity and pose from the body (after joints moved it).
    #[inline]
    pub(crate) fn reload(&mut self, b: &Body) {
        self.v = b.linear_velocity;
        self.w = b.angular_velocity;
        self.p = b.position;
        self.q = b.rotation;
    }
}

impl Default for SolverBody {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Inverse mass and inertia a body contributes to a contact or a joint (0
/// unless dynamic and in bounds: a frozen body is as immovable as a static one,
/// see [`Body::is_out_of_bounds`]).
pub(crate) fn inverse_mass(b: &Body) -> (Scalar, Scalar) {
    if b.is_dynamic() && !b.out_of_bounds {
        (b.mass.inv_mass, b.mass.inv_inertia)
    } else {
        (ZERO, ZERO)
    }
}

/// Bodies `i` and `j`, mutably; `None` if they are the same or out of range.
#[inline(always)]
pub(crate) fn pair_at(
    bodies: &mut [SolverBody],
    i: u32,
    j: u32,
) -> Option<(&mut SolverBody, &mut SolverBody)> {
    let (i, j) = (i as usize, j as usize);
    if i < j {
        let (lo, hi) = bodies.split_at_mut(j);
        Some((lo.get_mut(i)?, hi.first_mut()?))
    } else if j < i {
        let (lo, hi) = bodies.split_at_mut(i);
        Some((hi.first_mut()?, lo.get_mut(j)?))
    } else {
        None
    }
}
