//! Fixed-capacity slot storage with typed, generational handles.
//!
//! An [`Arena`] owns a slice of slots whose length is its capacity, chosen when it
//! is created and never changed: either borrowed from the caller (`&mut [Slot<T>]`,
//! works without an allocator) or, with the `alloc` feature, an owned `Vec`. This
//! is smoltcp's "managed" storage pattern. A full arena hands the value back
//! (`Err(value)`, as `heapless::Vec::push` does), never grows and never panics.
//!
//! A [`Handle`] is a slot index, a generation and the tag of the world that
//! issued it (as Box2D's ids carry a world index). Removing an object bumps its
//! slot's generation, so an old handle stops resolving (`None` /
//! [`Error::StaleHandle`]) instead of silently naming whatever reuses the slot;
//! a handle from another world never matches the arena's tag, so it is stale
//! too. The all-zero handle ([`Handle::NULL`]) never resolves.
//!
//! Generations run from 1 to `u32::MAX`: a slot serves 2³² − 1 objects in
//! turn, and when its last one is removed the slot is *retired* (generation 0,
//! never reused) rather than wrapping around to a generation an old handle
//! still holds. At one reuse per step at 60 Hz that is 2.3 years of one slot.
//!
//! World tags come from a process-wide counter (1 to 4,095, then round again),
//! so they depend on how many worlds the process created before: they are never
//! part of a snapshot or of the state hash, which store index and generation
//! only, and `restore` gives every handle it brings back the restoring world's
//! tag. A tag tells apart the worlds alive at once in one process (up to
//! 4,095); it is not an identity across processes or peers: for those, send
//! [`Handle::index`] and [`Handle::generation`] and rebuild the handle with
//! [`World::handle_from_parts`](crate::World::handle_from_parts).
//!
//! Slot reuse is deterministic and independent of capacity: new objects take the
//! most recently freed slot first (a LIFO free list), otherwise the lowest slot
//! never used. Iteration is in slot-index order. Both depend only on the history
//! of inserts and removals, never on addresses or capacity.
//!
//! [`Error::StaleHandle`]: crate::Error::StaleHandle

use core::fmt;
use core::marker::PhantomData;

use managed::ManagedSlice;

mod handle;

pub(crate) use handle::next_world_tag;
use handle::TAG_MASK;
pub use handle::{Handle, HANDLE_INDEX_BITS, HANDLE_TAG_BITS, MAX_SLOTS};

/// Marks the end of the free list.
pub(crate) const NO_SLOT: u32 = u32::MAX;

/// One slot of an [`Arena`]: an optional value and the slot's generation.
///
/// Callers only create empty slots ([`Slot::EMPTY`]) to hand storage to an arena.
pub struct Slot<T> {
    generation: u32,
    next_free: u32,
    value: Option<T>,
}

impl<T> Slot<T> {
    /// An empty slot, for building borrowed arena storage: `[Slot::EMPTY; N]`
    /// (or `[const { Slot::EMPTY }; N]` for non-`Copy` values).
    pub const EMPTY: Self = Self { generation: 0, next_free: NO_SLOT, value: None };
}

impl<T: Clone> Clone for Slot<T> {
    fn clone(&self) -> Self {
        Self { generation: self.generation, next_free: self.next_free, value: self.value.clone() }
    }
}

impl<T: Copy> Copy for Slot<T> {}

impl<T> Default for Slot<T> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<T: fmt::Debug> fmt::Debug for Slot<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Slot").field("generation", &self.generation).field("value", &self.value).finish()
    }
}

/// The slots an [`Arena`] runs on: a managed (borrowed or owned) slice, or an
/// inline array for small stores that live inside their owner.
pub trait SlotStorage<T> {
    /// The slots.
    fn slots(&self) -> &[Slot<T>];
    /// The slots, mutably.
    fn slots_mut(&mut self) -> &mut [Slot<T>];
}

impl<T> SlotStorage<T> for ManagedSlice<'_, Slot<T>> {
    fn slots(&self) -> &[Slot<T>] {
        self
    }
    fn slots_mut(&mut self) -> &mut [Slot<T>] {
        self
    }
}

impl<T, const N: usize> SlotStorage<T> for [Slot<T>; N] {
    fn slots(&self) -> &[Slot<T>] {
        self
    }
    fn slots_mut(&mut self) -> &mut [Slot<T>] {
        self
    }
}

/// Fixed-capacity storage of `T`s addressed by [`Handle<K>`] (`K` defaults to `T`;
/// a marker type gives values that borrow, like trait objects, plain handles).
/// `S` is the slot storage, by default a [`ManagedSlice`].
pub struct Arena<'a, T, K = T, S: SlotStorage<T> = ManagedSlice<'a, Slot<T>>> {
    slots: S,
    /// Slots `0..used` have been occupied at least once.
    used: u32,
    /// Head of the LIFO list of freed slots.
    free_head: u32,
    /// Live objects.
    len: u32,
    /// The tag of the world that owns the arena, carried by its handles.
    tag: u16,
    marker: Markers<'a, T, K>,
}

/// Variance markers: handles typed by `K`, values of type `T`, storage borrowed for `'a`.
type Markers<'a, T, K> = PhantomData<(fn() -> K, fn() -> T, &'a ())>;

impl<'a, T, K> Arena<'a, T, K> {
    /// An empty arena on the given storage; its capacity is the storage's length
    /// (at most `u32::MAX − 1` slots are used). Any content is discarded.
    pub fn new(storage: impl Into<ManagedSlice<'a, Slot<T>>>) -> Self {
        Self::on(storage.into())
    }

    /// An empty arena with `capacity` slots on the heap.
    #[cfg(feature = "alloc")]
    #[must_use]
    pub fn with_capacity(capacity: usize) -> Self {
        let mut v = alloc::vec::Vec::with_capacity(capacity);
        v.resize_with(capacity, || Slot::EMPTY);
        Self::new(v)
    }
}

impl<T, K, const N: usize> Arena<'_, T, K, [Slot<T>; N]> {
    /// An empty arena stored inline (`const`, so it can be part of a `static`).
    #[must_use]
    pub const fn inline() -> Self {
        Self {
            slots: [const { Slot::EMPTY }; N],
            used: 0,
            free_head: NO_SLOT,
            len: 0,
            tag: 0,
            marker: PhantomData,
        }
    }
}

impl<T, K, S: SlotStorage<T>> Arena<'_, T, K, S> {
    /// An empty arena on `slots`; any content is discarded.
    pub fn on(mut slots: S) -> Self {
        for s in slots.slots_mut().iter_mut() {
            *s = Slot::EMPTY;
        }
        Self { slots, used: 0, free_head: NO_SLOT, len: 0, tag: 0, marker: PhantomData }
    }

    /// The same empty arena, issuing handles tagged `tag` (a world gives all its
    /// arenas its own tag when it is created). An arena made by [`Arena::new`] has
    /// tag 0, like the handles of [`Handle::from_parts`].
    #[must_use]
    pub(crate) fn with_tag(mut self, tag: u16) -> Self {
        self.tag = tag & TAG_MASK;
        self
    }

    /// The tag this arena's handles carry.
    #[inline]
    pub(crate) fn tag(&self) -> u16 {
        self.tag
    }

    /// The slot `h` names, if `h` is of this arena's world and the slot exists
    /// (the generation is not checked).
    #[inline]
    fn slot_of(&self, h: Handle<K>) -> Option<&Slot<T>> {
        if h.world_tag() != self.tag {
            return None;
        }
        self.slots.slots().get(h.index() as usize)
    }

    /// Maximum number of objects.
    #[inline]
    #[must_use]
    pub fn capacity(&self) -> usize {
        self.slots.slots().len().min(NO_SLOT as usize)
    }

    /// Number of live objects.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.len as usize
    }

    /// True when there are no live objects.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// True when an insert would fail.
    #[inline]
    #[must_use]
    pub fn is_full(&self) -> bool {
        self.free_head == NO_SLOT && self.used as usize >= self.capacity()
    }

    /// Stores `value` and returns its handle, or gives the value back when full.
    ///
    /// # Errors
    /// `Err(value)` when every slot is occupied.
    pub fn insert(&mut self, value: T) -> Result<Handle<K>, T> {
        let index = if self.free_head != NO_SLOT {
            self.free_head
        } else if (self.used as usize) < self.capacity() {
            self.used
        } else {
            return Err(value);
        };
        let Some(slot) = self.slots.slots_mut().get_mut(index as usize) else {
            return Err(value);
        };
        if index == self.free_head {
            self.free_head = slot.next_free;
        } else {
            self.used = self.used.saturating_add(1);
        }
        // Generation 0 is reserved for the null handle (and marks a retired
        // slot, which is never on the free list): a fresh slot starts at 1.
        if slot.generation == 0 {
            slot.generation = 1;
        }
        slot.next_free = NO_SLOT;
        slot.value = Some(value);
        self.len = self.len.saturating_add(1);
        Ok(Handle::tagged(index, slot.generation, self.tag))
    }

    /// Removes and returns the object, or `None` for a stale, foreign or null
    /// handle.
    ///
    /// The slot's generation is bumped so every outstanding handle goes stale,
    /// and the slot goes on the free list; a slot whose generation is already
    /// `u32::MAX` is retired instead (generation 0, never reused), so no
    /// generation is ever issued twice for one slot.
    pub fn remove(&mut self, h: Handle<K>) -> Option<T> {
        if h.world_tag() != self.tag {
            return None;
        }
        let slot = self.slots.slots_mut().get_mut(h.index() as usize)?;
        if slot.generation != h.generation || slot.value.is_none() {
            return None;
        }
        let value = slot.value.take();
        self.len = self.len.saturating_sub(1);
        match slot.generation.checked_add(1) {
            Some(next) => {
                slot.generation = next;
                slot.next_free = self.free_head;
                self.free_head = h.index();
            }
            None => {
                slot.generation = 0;
                slot.next_free = NO_SLOT;
            }
        }
        value
    }

    /// Slots retired after their last generation (see [`Arena::remove`]).
    #[must_use]
    pub fn retired(&self) -> usize {
        self.used_slots().iter().filter(|s| s.generation == 0 && s.value.is_none()).count()
    }

    /// How many inserts in a row would succeed: the free slots, neither live
    /// nor retired (a scan of the used slots).
    #[must_use]
    pub(crate) fn room(&self) -> usize {
        self.capacity().saturating_sub(self.len()).saturating_sub(self.retired())
    }

    /// The object behind `h`, or `None` for a stale or null handle.
    #[inline]
    #[must_use]
    pub fn get(&self, h: Handle<K>) -> Option<&T> {
        let slot = self.slot_of(h)?;
        if slot.generation == h.generation {
            slot.value.as_ref()
        } else {
            None
        }
    }

    /// The object behind `h`, mutably, or `None` for a stale or null handle.
    #[inline]
    pub fn get_mut(&mut self, h: Handle<K>) -> Option<&mut T> {
        if h.world_tag() != self.tag {
            return None;
        }
        let slot = self.slots.slots_mut().get_mut(h.index() as usize)?;
        if slot.generation == h.generation {
            slot.value.as_mut()
        } else {
            None
        }
    }

    /// True when `h` names a live object.
    #[inline]
    #[must_use]
    pub fn contains(&self, h: Handle<K>) -> bool {
        self.get(h).is_some()
    }

    /// The handle of the live object in slot `index`, if any.
    #[must_use]
    pub fn handle_at(&self, index: u32) -> Option<Handle<K>> {
        let slot = self.slots.slots().get(index as usize)?;
        slot.value.as_ref().map(|_| Handle::tagged(index, slot.generation, self.tag))
    }

    /// The handle of the live object in slot `index` and the object, if
    /// any: [`handle_at`](Self::handle_at) and [`get_at`](Self::get_at) from
    /// one look at the slot.
    #[inline]
    pub(crate) fn entry_at(&self, index: u32) -> Option<(Handle<K>, &T)> {
        let slot = self.slots.slots().get(index as usize)?;
        Some((Handle::tagged(index, slot.generation, self.tag), slot.value.as_ref()?))
    }

    /// The live object in slot `index`, if any (no generation check).
    #[inline]
    #[must_use]
    pub fn get_at(&self, index: u32) -> Option<&T> {
        self.slots.slots().get(index as usize)?.value.as_ref()
    }

    /// The live object in slot `index`, mutably, if any (no generation check).
    #[inline]
    pub fn get_at_mut(&mut self, index: u32) -> Option<&mut T> {
        self.slots.slots_mut().get_mut(index as usize)?.value.as_mut()
    }

    /// The live objects in two different slots, both mutably (for a pair of
    /// bodies in the solver). `None` if `i == j` or either slot is empty.
    pub(crate) fn get2_at_mut(&mut self, i: u32, j: u32) -> Option<(&mut T, &mut T)> {
        let (i, j) = (i as usize, j as usize);
        let slots = self.slots.slots_mut();
        // `split_at_mut` panics past the end: indices from outside (a restored
        // joint naming a slot this arena never had) must not get that far.
        if i >= slots.len() || j >= slots.len() {
            return None;
        }
        if i < j {
            let (lo, hi) = slots.split_at_mut(j);
            Some((lo.get_mut(i)?.value.as_mut()?, hi.first_mut()?.value.as_mut()?))
        } else if j < i {
            let (lo, hi) = slots.split_at_mut(i);
            Some((hi.first_mut()?.value.as_mut()?, lo.get_mut(j)?.value.as_mut()?))
        } else {
            None
        }
    }

    /// The live objects behind two different handles, both mutably (for the two
    /// bodies of a game constraint). `None` if either is stale, foreign or null,
    /// or both name the same object.
    pub(crate) fn get2_mut(&mut self, a: Handle<K>, b: Handle<K>) -> Option<(&mut T, &mut T)> {
        let live = |h: Handle<K>| self.get(h).is_some();
        if !live(a) || !live(b) {
            return None;
        }
        self.get2_at_mut(a.index(), b.index())
    }

    /// Number of slots ever used: every live object has a slot index below this.
    #[inline]
    #[must_use]
    pub fn slots_used(&self) -> u32 {
        self.used
    }

    /// The live objects with their handles, in slot-index order.
    pub fn iter(&self) -> impl Iterator<Item = (Handle<K>, &T)> + '_ {
        let tag = self.tag;
        self.used_slots().iter().enumerate().filter_map(move |(i, s)| {
            let value = s.value.as_ref()?;
            Some((Handle::tagged(i as u32, s.generation, tag), value))
        })
    }

    /// The live objects with their handles, mutably, in slot-index order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (Handle<K>, &mut T)> + '_ {
        let (used, tag) = (self.used as usize, self.tag);
        self.slots.slots_mut().iter_mut().take(used).enumerate().filter_map(move |(i, s)| {
            let generation = s.generation;
            let value = s.value.as_mut()?;
            Some((Handle::tagged(i as u32, generation, tag), value))
        })
    }

    /// The slots that have ever been used, for the step's index-ordered sweeps.
    #[inline]
    pub(crate) fn used_slots(&self) -> &[Slot<T>] {
        self.slots.slots().get(..self.used as usize).unwrap_or(&[])
    }

    /// Allocator state for encoding: (slots used, free-list head, live count).
    pub(crate) fn allocator_state(&self) -> (u32, u32, u32) {
        (self.used, self.free_head, self.len)
    }

    /// Generation and free-list link of slot `index`, for encoding.
    pub(crate) fn slot_meta(&self, index: u32) -> Option<(u32, u32)> {
        self.slots.slots().get(index as usize).map(|s| (s.generation, s.next_free))
    }

    /// Overwrites slot `index` (restoring a snapshot); `keep_value` leaves the
    /// current value in place (a game hook the snapshot does not hold).
    pub(crate) fn write_slot(
        &mut self,
        index: u32,
        generation: u32,
        next_free: u32,
        value: Option<T>,
        keep_value: bool,
    ) {
        if let Some(slot) = self.slots.slots_mut().get_mut(index as usize) {
            slot.generation = generation;
            slot.next_free = next_free;
            if !keep_value {
                slot.value = value;
            }
        }
    }

    /// Empties every slot from `index` on and sets the allocator state
    /// (restoring a snapshot), so the arena is exactly one that saw that history.
    pub(crate) fn finish_restore(&mut self, used: u32, free_head: u32, len: u32) {
        for slot in self.slots.slots_mut().iter_mut().skip(used as usize) {
            *slot = Slot::EMPTY;
        }
        self.used = used;
        self.free_head = free_head;
        self.len = len;
    }
}

#[cfg(test)]
mod tests {
    use super::handle::MAX_INDEX;
    use super::*;

    #[test]
    fn full_arena_hands_the_value_back() {
        let mut storage = [Slot::EMPTY; 2];
        let mut a: Arena<'_, u8> = Arena::new(&mut storage[..]);
        let h1 = a.insert(1).expect("room");
        let _h2 = a.insert(2).expect("room");
        assert_eq!(a.insert(3), Err(3));
        assert_eq!(a.remove(h1), Some(1));
        assert!(a.insert(4).is_ok());
        assert_eq!(a.len(), 2);
    }

    #[test]
    fn stale_handle_does_not_reach_the_new_occupant() {
        let mut storage = [Slot::EMPTY; 4];
        let mut a: Arena<'_, u8> = Arena::new(&mut storage[..]);
        let old = a.insert(10).expect("room");
        assert_eq!(a.remove(old), Some(10));
        let new = a.insert(20).expect("room");
        assert_eq!(new.index(), old.index(), "the freed slot is reused");
        assert_eq!(a.get(old), None);
        assert_eq!(a.remove(old), None);
        assert_eq!(a.get(new), Some(&20));
        assert_eq!(a.get(Handle::NULL), None);
    }

    #[test]
    fn a_handle_is_as_small_as_an_untagged_one() {
        assert_eq!(core::mem::size_of::<Handle<u8>>(), 8);
        assert_eq!(core::mem::size_of::<Option<Handle<u8>>>(), 12);
    }

    #[test]
    fn a_handle_survives_packing_into_bits() {
        let indices = [0, 1, 2, 0x8_0000, MAX_INDEX - 1, MAX_INDEX];
        let generations = [0, 1, 2, 0x8000_0000, u32::MAX - 1, u32::MAX];
        for index in indices {
            for generation in generations {
                for tag in [0, 1, 2, 0x800, TAG_MASK] {
                    let h: Handle<u8> = Handle::tagged(index, generation, tag);
                    let bits = h.to_bits();
                    assert_eq!(bits >> 44, u64::from(index), "index in the high 20 bits");
                    assert_eq!((bits >> 32) & 0xfff, u64::from(tag), "tag in the next 12");
                    assert_eq!(
                        bits & u64::from(u32::MAX),
                        u64::from(generation),
                        "generation in the low word"
                    );
                    assert_eq!(Handle::<u8>::from_bits(bits), h);
                }
            }
        }
        assert_eq!(Handle::<u8>::from_bits(u64::MAX), Handle::tagged(MAX_INDEX, u32::MAX, TAG_MASK));
    }

    #[test]
    fn an_index_no_world_has_stays_out_of_every_world() {
        // from_parts keeps an index past every slot past every slot, so packing
        // cannot fold it onto a real slot.
        let far: Handle<u8> = Handle::from_parts(u32::MAX, 1);
        assert_eq!(far.index(), MAX_INDEX);
        assert_eq!(Handle::<u8>::from_bits(far.to_bits()), far);
        assert!(MAX_SLOTS <= MAX_INDEX as usize, "slot MAX_INDEX is never a slot");
    }

    #[test]
    fn a_handle_of_another_world_does_not_resolve() {
        let (mut s1, mut s2) = ([Slot::EMPTY; 2], [Slot::EMPTY; 2]);
        let mut a: Arena<'_, u8> = Arena::new(&mut s1[..]).with_tag(1);
        let mut b: Arena<'_, u8> = Arena::new(&mut s2[..]).with_tag(2);
        let ha = a.insert(10).expect("room");
        let hb = b.insert(20).expect("room");
        assert_eq!(
            (ha.index(), ha.generation()),
            (hb.index(), hb.generation()),
            "same slot, same generation"
        );
        assert_ne!(ha, hb);
        assert_eq!(a.get(hb), None);
        assert_eq!(a.get_mut(hb), None);
        assert_eq!(a.remove(hb), None);
        assert_eq!(a.get(Handle::from_parts(0, 1)), None, "untagged");
        assert_eq!(a.get(ha), Some(&10), "world A's object is untouched");
        assert_eq!(a.iter().map(|(h, _)| h.world_tag()).next(), Some(1));
    }

    #[test]
    fn world_tags_are_never_zero_and_fit_twelve_bits() {
        for _ in 0..5000 {
            let t = next_world_tag();
            assert!((1..=TAG_MASK).contains(&t), "tag {t}");
        }
    }

    #[test]
    fn a_slot_is_retired_after_its_last_generation() {
        let mut storage = [Slot::EMPTY; 2];
        let mut a: Arena<'_, u8> = Arena::new(&mut storage[..]);
        let first = a.insert(1).expect("room");
        assert_eq!(a.remove(first), Some(1));
        // Slot 0 is free; pretend it has served 2^32 - 2 objects since.
        a.write_slot(0, u32::MAX, NO_SLOT, None, false);
        let last = a.insert(2).expect("room");
        assert_eq!((last.index(), last.generation()), (0, u32::MAX), "the last generation is issued");
        assert_eq!(a.remove(last), Some(2));
        assert_eq!(a.retired(), 1);
        // Neither the last handle nor the first (generation 1) comes back.
        let next = a.insert(3).expect("room");
        assert_eq!(next.index(), 1, "the retired slot is not reused");
        assert_eq!(a.get(last), None);
        assert_eq!(a.get(first), None);
        assert_eq!(a.insert(4), Err(4), "a retired slot is lost capacity");
        assert!(a.is_full());
        assert_eq!(a.len(), 1);
    }

    #[test]
    fn the_null_handle_packs_to_zero_and_back() {
        assert_eq!(Handle::<u8>::NULL.to_bits(), 0);
        let back = Handle::<u8>::from_bits(0);
        assert_eq!(back, Handle::NULL);
        assert!(back.is_null());
    }

    #[test]
    fn a_live_handle_still_resolves_after_a_round_trip_through_bits() {
        let mut storage = [Slot::EMPTY; 4];
        let mut a: Arena<'_, u8> = Arena::new(&mut storage[..]);
        let _first = a.insert(1).expect("room");
        let h = a.insert(2).expect("room");
        assert_eq!(a.get(Handle::from_bits(h.to_bits())), Some(&2));
    }

    #[test]
    fn a_stale_decoded_handle_is_rejected_by_the_arena() {
        let mut storage = [Slot::EMPTY; 4];
        let mut a: Arena<'_, u8> = Arena::new(&mut storage[..]);
        let old = a.insert(10).expect("room");
        let key = old.to_bits();
        assert_eq!(a.remove(old), Some(10));
        let new = a.insert(20).expect("room");
        assert_eq!(new.index(), old.index(), "the freed slot is reused");
        // The key outlived its object: it decodes, but names nothing.
        let decoded = Handle::from_bits(key);
        assert_eq!(a.get(decoded), None);
        assert_eq!(a.get_mut(decoded), None);
        assert!(!a.contains(decoded));
        assert_eq!(a.remove(decoded), None);
        assert_eq!(a.get(new), Some(&20), "the new occupant is untouched");
        // Made-up bits: a slot never used, a slot past the end, all ones.
        for bits in [2 << 32 | 1, 100 << 32 | 1, u64::MAX, u64::from(u32::MAX)] {
            assert_eq!(a.get(Handle::from_bits(bits)), None, "bits {bits:#x}");
            assert_eq!(a.remove(Handle::from_bits(bits)), None, "bits {bits:#x}");
        }
        assert_eq!(a.len(), 1);
    }

    #[test]
    fn reuse_order_is_lifo_and_iteration_is_by_index() {
        let mut storage = [Slot::EMPTY; 8];
        let mut a: Arena<'_, u8> = Arena::new(&mut storage[..]);
        let hs: [Handle<u8>; 5] = core::array::from_fn(|i| a.insert(i as u8).expect("room"));
        a.remove(hs[1]);
        a.remove(hs[3]);
        assert_eq!(a.insert(30).map(Handle::index), Ok(3));
        assert_eq!(a.insert(10).map(Handle::index), Ok(1));
        assert_eq!(a.insert(50).map(Handle::index), Ok(5));
        let order: [u8; 6] = {
            let mut it = a.iter().map(|(_, v)| *v);
            core::array::from_fn(|_| it.next().unwrap_or(255))
        };
        assert_eq!(order, [0, 10, 2, 30, 4, 50]);
    }
}
