//! [`Handle`]: a slot index, a generation and the tag of the world that issued
//! it, packed into 64 bits (see the [module docs of `arena`](super) for why
//! generations retire and what a world tag is and is not).

use core::fmt;
use core::hash::{Hash, Hasher};
use core::marker::PhantomData;

/// Bits of the slot index in a packed handle ([`Handle::to_bits`]).
pub const HANDLE_INDEX_BITS: u32 = 20;
/// Bits of the world tag in a packed handle ([`Handle::to_bits`]).
pub const HANDLE_TAG_BITS: u32 = 12;
/// Most slots one store of a world may have: 2²⁰ − 1 = 1,048,575 (so that every
/// handle packs into 64 bits; a larger capacity is an error at world creation).
/// Slot index 2²⁰ − 1 itself is never a slot.
pub const MAX_SLOTS: usize = (1 << HANDLE_INDEX_BITS) - 1;
/// The largest index a handle holds: no arena of a world has this slot.
pub(super) const MAX_INDEX: u32 = (1 << HANDLE_INDEX_BITS) - 1;
pub(super) const TAG_MASK: u16 = (1 << HANDLE_TAG_BITS) - 1;

/// The next world tag, from 1 to 4,095 and round again (never 0: untagged
/// handles, such as [`Handle::from_parts`] makes, resolve in no world).
pub(crate) fn next_world_tag() -> u16 {
    use core::sync::atomic::{AtomicU32, Ordering};
    static NEXT: AtomicU32 = AtomicU32::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    // n % 4095 < 4095, so the tag is in 1..=4095 and fits 12 bits.
    (n % u32::from(TAG_MASK)) as u16 + 1
}

/// A typed handle to an object in an [`Arena`](super::Arena): slot index, generation, and the
/// tag of the world that issued it.
///
/// A handle resolves only in the world that issued it, and only while the object
/// it was issued for is alive: a removed object's handle, a handle from another
/// world, a made-up one, and [`Handle::NULL`] are all [`Error::StaleHandle`]
/// (`None` from the arena), never another object and never a panic.
///
/// [`Error::StaleHandle`]: crate::Error::StaleHandle
pub struct Handle<T> {
    /// The world tag in the high 12 bits, the slot index in the low 20 (so a
    /// handle stays 8 bytes, as it was before it carried its world).
    pub(super) place: u32,
    pub(super) generation: u32,
    pub(super) marker: PhantomData<fn() -> T>,
}

impl<T> Handle<T> {
    /// The null handle: resolves to nothing in every arena; packs to `0`.
    pub const NULL: Self = Self { place: 0, generation: 0, marker: PhantomData };

    /// The slot index (for canonical ordering and encoding).
    #[inline]
    #[must_use]
    pub const fn index(self) -> u32 {
        self.place & MAX_INDEX
    }

    /// The generation of the slot when this handle was issued.
    #[inline]
    #[must_use]
    pub const fn generation(self) -> u32 {
        self.generation
    }

    /// The tag of the world that issued this handle (1 to 4,095; 0 for
    /// [`Handle::NULL`] and for handles from [`Handle::from_parts`]). It differs
    /// from run to run and from peer to peer: never store it in game state.
    #[inline]
    #[must_use]
    pub const fn world_tag(self) -> u16 {
        (self.place >> HANDLE_INDEX_BITS) as u16
    }

    /// Rebuilds an untagged handle from its parts. It belongs to no world, so no
    /// world resolves it: to name an object of a world by index and generation
    /// (decoded from a network message, say), use
    /// [`World::handle_from_parts`](crate::World::handle_from_parts). An index
    /// above 2²⁰ − 2 (no world has such a slot) becomes 2²⁰ − 1.
    #[inline]
    #[must_use]
    pub const fn from_parts(index: u32, generation: u32) -> Self {
        Self::tagged(index, generation, 0)
    }

    /// A handle with the given world tag (an index past every slot is kept past
    /// every slot; the tag is cut to its 12 bits).
    #[inline]
    pub(crate) const fn tagged(index: u32, generation: u32, tag: u16) -> Self {
        let index = if index > MAX_INDEX { MAX_INDEX } else { index };
        let tag = (tag & TAG_MASK) as u32;
        Self { place: (tag << HANDLE_INDEX_BITS) | index, generation, marker: PhantomData }
    }

    /// Packs the handle into one `u64`, for a post-step callback key or a user-data
    /// word: the slot index in the high 20 bits, the world tag in the next 12, the
    /// generation in the low 32 (`index << 44 | tag << 32 | generation`). The
    /// packing is lossless, so `Handle::from_bits(h.to_bits()) == h` for every
    /// handle, and [`Handle::NULL`] packs to `0`. Packed handles of one world
    /// compare as `u64`s in the handles' canonical order (index, then generation).
    ///
    /// The bits hold the world tag, which depends on how many worlds the process
    /// created before this one: use them as keys inside this process, but keep
    /// them out of state that must be the same on every peer (a body's user data
    /// is in the state hash); there, store `index` and `generation`.
    #[inline]
    #[must_use]
    pub const fn to_bits(self) -> u64 {
        let (index, tag) = (self.index() as u64, self.world_tag() as u64);
        (index << (32 + HANDLE_TAG_BITS)) | (tag << 32) | self.generation as u64
    }

    /// Unpacks a handle packed by [`Handle::to_bits`] (index in the high 20 bits,
    /// world tag in the next 12, generation in the low 32); `0` gives
    /// [`Handle::NULL`].
    ///
    /// Every `u64` decodes, and what it decodes to is just a handle: if it names
    /// no live object of the world asked (made-up bits, an object removed since it
    /// was packed, or a handle of another world), the arena resolves it to `None`
    /// and the world answers [`Error::StaleHandle`], never a panic and never
    /// another object.
    ///
    /// [`Error::StaleHandle`]: crate::Error::StaleHandle
    #[inline]
    #[must_use]
    pub const fn from_bits(bits: u64) -> Self {
        let index = (bits >> (32 + HANDLE_TAG_BITS)) as u32;
        let tag = ((bits >> 32) as u16) & TAG_MASK;
        Self::tagged(index, bits as u32, tag)
    }

    /// True for [`Handle::NULL`] (and any handle of generation 0, which no
    /// object ever has).
    #[inline]
    #[must_use]
    pub const fn is_null(self) -> bool {
        self.generation == 0
    }
}

impl<T> Clone for Handle<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Handle<T> {}
impl<T> PartialEq for Handle<T> {
    fn eq(&self, o: &Self) -> bool {
        self.place == o.place && self.generation == o.generation
    }
}
impl<T> Eq for Handle<T> {}
impl<T> PartialOrd for Handle<T> {
    fn partial_cmp(&self, o: &Self) -> Option<core::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl<T> Ord for Handle<T> {
    /// Orders by slot index, then world tag, then generation: within one world,
    /// the canonical order of the engine (slot index, then generation).
    fn cmp(&self, o: &Self) -> core::cmp::Ordering {
        self.to_bits().cmp(&o.to_bits())
    }
}
impl<T> Hash for Handle<T> {
    fn hash<H: Hasher>(&self, h: &mut H) {
        self.to_bits().hash(h);
    }
}
impl<T> Default for Handle<T> {
    fn default() -> Self {
        Self::NULL
    }
}
impl<T> fmt::Debug for Handle<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Handle({}v{}w{})", self.index(), self.generation, self.world_tag())
    }
}
