//! The byte cursor that snapshot parsing reads through: little-endian, and
//! bounds-checked on every read, so a truncated or hostile buffer is an
//! [`Error::InvalidSnapshot`] ("truncated"), never a panic or an out-of-bounds
//! slice.

use super::invalid;
use crate::arena::Handle;
use crate::error::Error;
use crate::math::scalar::Scalar;
use crate::math::{Rect, Rot, Vector2};

/// A bounds-checked little-endian reader.
#[derive(Clone, Copy)]
pub(super) struct Cursor<'b> {
    buf: &'b [u8],
    pos: usize,
    /// The world tag the handles read get (see [`Cursor::handle`]).
    tag: u16,
}

impl<'b> Cursor<'b> {
    #[inline]
    pub(super) fn at(buf: &'b [u8], pos: usize) -> Self {
        Self { buf, pos, tag: 0 }
    }

    /// The same cursor, giving the handles it reads the world tag `tag`.
    #[inline]
    pub(super) fn tagged(self, tag: u16) -> Self {
        Self { tag, ..self }
    }

    /// A handle stored as index and generation (a snapshot holds no world tag),
    /// tagged with the cursor's tag: the restoring world's.
    #[inline]
    pub(super) fn handle<T>(&mut self) -> Result<Handle<T>, Error> {
        let (index, generation) = (self.u32()?, self.u32()?);
        Ok(Handle::tagged(index, generation, self.tag))
    }

    /// Offset of the next byte to read.
    #[inline]
    pub(super) fn pos(&self) -> usize {
        self.pos
    }

    #[inline]
    pub(super) fn take<const N: usize>(&mut self) -> Result<[u8; N], Error> {
        let end = self.pos.checked_add(N).ok_or_else(|| invalid("truncated"))?;
        let bytes = self.buf.get(self.pos..end).ok_or_else(|| invalid("truncated"))?;
        self.pos = end;
        let mut out = [0u8; N];
        out.copy_from_slice(bytes);
        Ok(out)
    }

    #[inline]
    pub(super) fn u8(&mut self) -> Result<u8, Error> {
        Ok(self.take::<1>()?[0])
    }
    #[inline]
    pub(super) fn u16(&mut self) -> Result<u16, Error> {
        Ok(u16::from_le_bytes(self.take()?))
    }
    #[inline]
    pub(super) fn u32(&mut self) -> Result<u32, Error> {
        Ok(u32::from_le_bytes(self.take()?))
    }
    #[inline]
    pub(super) fn u64(&mut self) -> Result<u64, Error> {
        Ok(u64::from_le_bytes(self.take()?))
    }
    #[inline]
    pub(super) fn bool(&mut self) -> Result<bool, Error> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(invalid("a flag is neither 0 nor 1")),
        }
    }
    #[inline]
    pub(super) fn scalar(&mut self) -> Result<Scalar, Error> {
        Ok(Scalar::from_bits(i64::from_le_bytes(self.take()?)))
    }
    #[inline]
    pub(super) fn vector(&mut self) -> Result<Vector2, Error> {
        Ok(Vector2::new(self.scalar()?, self.scalar()?))
    }
    #[inline]
    pub(super) fn rot(&mut self) -> Result<Rot, Error> {
        Ok(Rot { c: self.scalar()?, s: self.scalar()? })
    }
    #[inline]
    pub(super) fn rect(&mut self) -> Result<Rect, Error> {
        Ok(Rect { min: self.vector()?, max: self.vector()? })
    }
    #[inline]
    pub(super) fn skip(&mut self, n: usize) -> Result<(), Error> {
        let end = self.pos.checked_add(n).ok_or_else(|| invalid("truncated"))?;
        if end > self.buf.len() {
            return Err(invalid("truncated"));
        }
        self.pos = end;
        Ok(())
    }
}
