//! [`Hook`]: how a world stores a game's object behind a trait (a force
//! generator, a collision handler, a spatial index, a constraint).
//!
//! A hook is either borrowed for the world's lifetime (no allocator needed: the
//! game keeps the object, e.g. in a `static` or on the stack of its main loop)
//! or, with the `alloc` feature, boxed and owned by the world. One type serves
//! every kind of hook, so the choice reads the same everywhere:
//! `Hook::Borrowed(&mut obj)` or `Hook::Boxed(Box::new(obj))`.
//!
//! Hooks are not simulation state: a snapshot records where they are, not what
//! they hold (see [`crate::snapshot`]).

use core::ops::{Deref, DerefMut};

/// A game's object stored in a world behind the trait `T` (a trait object such
/// as `dyn ForceGenerator + Send`): borrowed, or with `alloc` boxed.
pub enum Hook<'a, T: ?Sized + 'a> {
    /// Borrowed for the world's lifetime; the game owns the object.
    Borrowed(&'a mut T),
    /// Owned by the world.
    #[cfg(feature = "alloc")]
    Boxed(alloc::boxed::Box<T>),
}

impl<'a, T: ?Sized + 'a> Hook<'a, T> {
    /// A hook on an object the game keeps.
    pub fn borrowed(object: &'a mut T) -> Self {
        Self::Borrowed(object)
    }

    /// A hook that owns its object.
    #[cfg(feature = "alloc")]
    pub fn boxed(object: alloc::boxed::Box<T>) -> Self {
        Self::Boxed(object)
    }
}

impl<'a, T: ?Sized + 'a> Deref for Hook<'a, T> {
    type Target = T;
    fn deref(&self) -> &T {
        match self {
            Self::Borrowed(r) => r,
            #[cfg(feature = "alloc")]
            Self::Boxed(b) => b,
        }
    }
}

impl<'a, T: ?Sized + 'a> DerefMut for Hook<'a, T> {
    fn deref_mut(&mut self) -> &mut T {
        match self {
            Self::Borrowed(r) => r,
            #[cfg(feature = "alloc")]
            Self::Boxed(b) => b,
        }
    }
}

impl<'a, T: ?Sized + 'a> From<&'a mut T> for Hook<'a, T> {
    fn from(object: &'a mut T) -> Self {
        Self::Borrowed(object)
    }
}

#[cfg(feature = "alloc")]
impl<'a, T: ?Sized + 'a> From<alloc::boxed::Box<T>> for Hook<'a, T> {
    fn from(object: alloc::boxed::Box<T>) -> Self {
        Self::Boxed(object)
    }
}

impl<T: ?Sized> core::fmt::Debug for Hook<'_, T> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::Borrowed(_) => "Hook::Borrowed(..)",
            #[cfg(feature = "alloc")]
            Self::Boxed(_) => "Hook::Boxed(..)",
        })
    }
}
