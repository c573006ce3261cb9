//! What a panicking hook leaves: with `std`, nothing.
//!
//! The engine never panics, but a game's hooks may (a force generator, a
//! collision handler, a game constraint, a custom spatial index, a post-step or
//! joint-break callback). A panic that unwinds out of the middle of a step would
//! leave the world half-stepped: a state no uninterrupted run reaches. So with
//! `std`, a world that has hooks snapshots itself before each step into a buffer
//! allocated when the first hook is registered (never inside a step), runs the
//! step under `catch_unwind`, and on a panic restores that snapshot and lets the
//! panic continue: the caller sees the panic, and the world is exactly as it was
//! before the step (the hooks' own objects are the game's, and keep whatever they
//! changed). A world without hooks runs nothing that can panic and skips both.
//!
//! Measured cost: one snapshot per step (about 54 µs for 500 bodies with their
//! contacts on this project's build machine, against a step of about 1 ms);
//! [`World::set_panic_guard`](crate::World::set_panic_guard) turns it off. Without
//! `std` (or with `panic = "abort"`) there is no unwinding to catch: a panicking
//! hook leaves the world half-stepped, and restoring a snapshot taken before the
//! step is the way back.

use alloc::vec::Vec;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};

use crate::error::Error;
use crate::math::Scalar;
use crate::step::StepReport;

use super::World;

/// The guard's state: whether it is wanted, and the snapshot buffer.
#[derive(Debug, Default)]
pub(crate) struct PanicGuard {
    /// Turned off by the game.
    pub(crate) disabled: bool,
    /// Room for the world's largest snapshot once a hook is registered; empty
    /// before (or when that memory could not be had).
    buffer: Vec<u8>,
}

impl World<'_> {
    /// Turns the panic guard on (the default with `std`) or off. On, a world
    /// with hooks snapshots itself before every step so that a panicking hook
    /// leaves it exactly as before the step (see `world/panic_guard.rs`); off,
    /// it saves that snapshot's cost and a panicking hook leaves the world
    /// half-stepped.
    pub fn set_panic_guard(&mut self, on: bool) {
        self.panic_guard.disabled = !on;
    }

    /// Sizes the guard's buffer for this world's largest snapshot, once, when a
    /// hook is registered (so that no step allocates). If the memory cannot be
    /// had the guard stays off.
    pub(crate) fn arm_panic_guard(&mut self) {
        let need = self.max_snapshot_len();
        let guard = &mut self.panic_guard;
        if guard.buffer.len() < need && guard.buffer.try_reserve_exact(need - guard.buffer.len()).is_ok() {
            guard.buffer.resize(need, 0);
        }
    }

    /// Whether anything of the game's runs inside a step.
    fn has_hooks(&self) -> bool {
        use crate::collision::Index;
        use crate::force::Generator;
        !self.handlers.is_empty()
            || !self.constraints.is_empty()
            || self.break_callback.is_some()
            || matches!(self.broad_phase.index, Index::Custom(_))
            || self.generators.iter().any(|(_, g)| matches!(g, Generator::Custom(_)))
    }

    /// The step, under the guard when the world has hooks and the guard is on.
    pub(crate) fn step_guarded(&mut self, dt: Scalar) -> Result<StepReport, Error> {
        if self.panic_guard.disabled || self.panic_guard.buffer.is_empty() || !self.has_hooks() {
            return self.step_stages_and_hooks(dt);
        }
        let mut buffer = core::mem::take(&mut self.panic_guard.buffer);
        let saved = self.snapshot(&mut buffer).is_ok();
        let outcome = catch_unwind(AssertUnwindSafe(|| self.step_stages_and_hooks(dt)));
        match outcome {
            Ok(report) => {
                self.panic_guard.buffer = buffer;
                report
            }
            Err(panic) => {
                if saved {
                    // The world's own snapshot of a moment ago: it restores.
                    let _ = self.restore(&buffer);
                }
                self.in_step_hooks = false;
                self.panic_guard.buffer = buffer;
                resume_unwind(panic)
            }
        }
    }
}
