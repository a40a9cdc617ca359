//! Snapshots: the whole state of a world that affects its future, saved to bytes and restored,
//! after which stepping reproduces the original bit for bit (rollback netcode, replays).
//! The format is specified in `docs/snapshot-format.md`.
//!
//! * [`Snap`] is implemented once per stored type: `put` appends the value little-endian,
//!   `get` reads it back. Structs use [`snap_struct!`], which destructures the struct
//!   *exhaustively* in `put` (`let Body { a, b, .. }` is never written), so a field added to a
//!   stored struct later fails to compile until it is listed here, either stored or named as
//!   `skip` (rebuilt on restore: scratch that every step rewrites before reading it).
//! * `write.rs` frames the payload (magic, version, length, FNV-1a 64 checksum) and writes
//!   the world section by section; `read.rs` checks the frame, decodes every section into a
//!   new world state and only then swaps it into the target world, so a failing restore
//!   changes nothing.
//! * Ids keep their slot index and reuse counter; the world tag in their top bits is the
//!   target world's. Restored into the same world, every id the host holds stays valid and
//!   ids created afterwards equal those the original created after the same calls.
//! * User callbacks (user force and contact generators) are not stored: a restore into the
//!   same world keeps the callback each such generator has now (when the generator is still
//!   there with the same id and kind); anywhere else the generator comes back without one and
//!   the host re-registers it (`World::user_generators_missing_callbacks`).

mod check;
mod read;
mod types;
mod write;

pub use read::restore;
pub use write::{save, saved_size};

/// First eight bytes of every snapshot.
pub const MAGIC: [u8; 8] = *b"HEARTHSS";
/// Format version; a snapshot of another version is refused.
pub const VERSION: u32 = 1;
/// Bytes before the payload: magic, version, payload length (u64), checksum (u64).
pub const HEADER_LEN: usize = 8 + 4 + 8 + 8;

/// Why a snapshot could not be restored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SnapshotError(pub String);

pub type ReadResult<T> = std::result::Result<T, SnapshotError>;

pub(crate) fn bad<T>(msg: impl Into<String>) -> ReadResult<T> {
    Err(SnapshotError(msg.into()))
}

/// The checksum: FNV-1a 64 taken over the payload's 8-byte little-endian words (then its
/// last bytes one at a time): eight times fewer multiplications than byte-wise FNV-1a. Each
/// step `h = (h ^ word) · prime` is a bijection of `h`, so any change of one word (one byte,
/// one bit) changes the result.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut words = bytes.chunks_exact(8);
    for w in &mut words {
        h ^= u64::from_le_bytes(w.try_into().expect("8 bytes"));
        h = h.wrapping_mul(PRIME);
    }
    for &b in words.remainder() {
        h ^= b as u64;
        h = h.wrapping_mul(PRIME);
    }
    h
}

/// Appends little-endian values to a byte buffer (or only counts them).
pub struct Writer<'a> {
    out: Option<&'a mut Vec<u8>>,
    len: usize,
}

impl<'a> Writer<'a> {
    pub fn new(out: &'a mut Vec<u8>) -> Writer<'a> {
        Writer { out: Some(out), len: 0 }
    }

    /// A writer that only counts bytes.
    pub fn counter() -> Writer<'static> {
        Writer { out: None, len: 0 }
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Overwrites bytes written earlier, `at` counted from this writer's start.
    pub(crate) fn patch(&mut self, at: usize, b: &[u8]) {
        if let Some(o) = self.out.as_mut() {
            let start = o.len() - self.len + at;
            o[start..start + b.len()].copy_from_slice(b);
        }
    }

    #[inline(always)]
    pub fn bytes(&mut self, b: &[u8]) {
        self.len += b.len();
        if let Some(o) = self.out.as_mut() {
            o.extend_from_slice(b);
        }
    }
}

/// Reads little-endian values from a byte slice; every read past the end is an error.
pub struct Reader<'a> {
    data: &'a [u8],
    at: usize,
    /// The target world's tag, put into the top bits of every id read.
    pub(crate) tag: u32,
}

impl<'a> Reader<'a> {
    pub fn new(data: &'a [u8], tag: u32) -> Reader<'a> {
        Reader { data, at: 0, tag }
    }

    #[inline]
    pub fn take(&mut self, n: usize) -> ReadResult<&'a [u8]> {
        if self.data.len() - self.at < n {
            return bad(format!(
                "snapshot truncated: {} bytes wanted at offset {}, {} left",
                n,
                self.at,
                self.data.len() - self.at
            ));
        }
        let s = &self.data[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }

    pub fn remaining(&self) -> usize {
        self.data.len() - self.at
    }

    /// A count of elements that follow, each at least one byte: larger than what is left
    /// is an error (so a corrupted count cannot ask for a huge allocation).
    pub fn count(&mut self) -> ReadResult<usize> {
        let n = u64::get(self)?;
        if n > self.remaining() as u64 {
            return bad(format!(
                "snapshot corrupted: count {n} exceeds the {} bytes left",
                self.remaining()
            ));
        }
        Ok(n as usize)
    }
}

/// A type stored in snapshots.
pub trait Snap: Sized {
    fn put(&self, w: &mut Writer);
    fn get(r: &mut Reader) -> ReadResult<Self>;
}

/// Implements [`Snap`] for a struct by listing its fields, all of them: the writer
/// destructures without `..`, so a new field is a compile error here. Fields after `;
/// skip` are not stored and come back as `Default::default()` (scratch rewritten before
/// it is read by every step).
#[macro_export]
#[doc(hidden)]
macro_rules! snap_struct {
    ($t:ident { $($f:ident),* $(,)? $(; skip $($s:ident),* $(,)?)? }) => {
        impl $crate::snapshot::Snap for $t {
            fn put(&self, w: &mut $crate::snapshot::Writer) {
                let $t { $($f,)* $($($s: _,)*)? } = self;
                $( $crate::snapshot::Snap::put($f, w); )*
            }
            fn get(r: &mut $crate::snapshot::Reader) -> $crate::snapshot::ReadResult<Self> {
                Ok($t {
                    $($f: $crate::snapshot::Snap::get(r)?,)*
                    $($($s: Default::default(),)*)?
                })
            }
        }
    };
}
pub use snap_struct;

macro_rules! snap_num {
    ($($t:ty),*) => {$(
        impl Snap for $t {
            #[inline]
            fn put(&self, w: &mut Writer) {
                w.bytes(&self.to_le_bytes());
            }
            #[inline]
            fn get(r: &mut Reader) -> ReadResult<Self> {
                let b = r.take(std::mem::size_of::<$t>())?;
                Ok(<$t>::from_le_bytes(b.try_into().expect("sized")))
            }
        }
    )*};
}
snap_num!(u8, u16, u32, u64, i8, i32, f32, f64);

impl Snap for usize {
    fn put(&self, w: &mut Writer) {
        (*self as u64).put(w)
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let v = u64::get(r)?;
        usize::try_from(v).or_else(|_| bad("snapshot corrupted: size out of range"))
    }
}

impl Snap for bool {
    fn put(&self, w: &mut Writer) {
        (*self as u8).put(w)
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        match u8::get(r)? {
            0 => Ok(false),
            1 => Ok(true),
            v => bad(format!("snapshot corrupted: flag {v} is not 0 or 1")),
        }
    }
}

impl<T: Snap> Snap for Vec<T> {
    fn put(&self, w: &mut Writer) {
        self.len().put(w);
        for x in self {
            x.put(w);
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let n = r.count()?;
        let mut v = Vec::with_capacity(n);
        for _ in 0..n {
            v.push(T::get(r)?);
        }
        Ok(v)
    }
}

impl<T: Snap> Snap for Option<T> {
    fn put(&self, w: &mut Writer) {
        match self {
            None => 0u8.put(w),
            Some(x) => {
                1u8.put(w);
                x.put(w)
            }
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(if bool::get(r)? { Some(T::get(r)?) } else { None })
    }
}

impl<T: Snap, const N: usize> Snap for [T; N] {
    fn put(&self, w: &mut Writer) {
        for x in self {
            x.put(w);
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let mut v = Vec::with_capacity(N);
        for _ in 0..N {
            v.push(T::get(r)?);
        }
        Ok(v.try_into().ok().expect("N elements"))
    }
}

macro_rules! snap_tuple {
    ($($n:tt $t:ident),*) => {
        impl<$($t: Snap),*> Snap for ($($t,)*) {
            fn put(&self, w: &mut Writer) {
                $( self.$n.put(w); )*
            }
            fn get(r: &mut Reader) -> ReadResult<Self> {
                Ok(($($t::get(r)?,)*))
            }
        }
    };
}
snap_tuple!(0 A, 1 B);
snap_tuple!(0 A, 1 B, 2 C);
snap_tuple!(0 A, 1 B, 2 C, 3 D);

/// Maps are stored as their entries sorted by key, so equal maps give equal bytes whatever
/// their insertion history (they are only looked up, never iterated, by the engine).
impl<K: Snap + Ord + Copy + std::hash::Hash + Eq, V: Snap + Clone, S: std::hash::BuildHasher + Default> Snap
    for std::collections::HashMap<K, V, S>
{
    fn put(&self, w: &mut Writer) {
        let mut keys: Vec<K> = self.keys().copied().collect();
        keys.sort_unstable();
        keys.len().put(w);
        for k in keys {
            k.put(w);
            self[&k].put(w);
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let n = r.count()?;
        let mut m = Self::with_capacity_and_hasher(n, S::default());
        for _ in 0..n {
            let k = K::get(r)?;
            let v = V::get(r)?;
            if m.insert(k, v).is_some() {
                return bad("snapshot corrupted: a map key appears twice");
            }
        }
        Ok(m)
    }
}

macro_rules! snap_floats {
    ($($t:ty: $($f:ident),*;)*) => {$(
        impl Snap for $t {
            fn put(&self, w: &mut Writer) {
                $( self.$f.put(w); )*
            }
            fn get(r: &mut Reader) -> ReadResult<Self> {
                let mut v = <$t>::ZERO;
                $( v.$f = Snap::get(r)?; )*
                Ok(v)
            }
        }
    )*};
}
snap_floats! {
    glam::Vec3: x, y, z;
    glam::Vec3A: x, y, z;
    glam::DVec3: x, y, z;
    glam::Mat3: x_axis, y_axis, z_axis;
    glam::Mat3A: x_axis, y_axis, z_axis;
}

impl Snap for glam::Quat {
    fn put(&self, w: &mut Writer) {
        self.to_array().put(w)
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(glam::Quat::from_array(Snap::get(r)?))
    }
}

impl Snap for glam::DQuat {
    fn put(&self, w: &mut Writer) {
        self.to_array().put(w)
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(glam::DQuat::from_array(Snap::get(r)?))
    }
}

impl crate::world::World {
    /// Bytes a snapshot of the world takes now.
    pub fn snapshot_size(&self) -> usize {
        saved_size(self)
    }

    /// Writes the world's snapshot into `out` (cleared first).
    pub fn save_snapshot(&self, out: &mut Vec<u8>) {
        save(self, out)
    }

    /// Restores the world from a snapshot; on error it is unchanged.
    pub fn restore_snapshot(&mut self, bytes: &[u8]) -> ReadResult<()> {
        restore(self, bytes)
    }

    /// User generators that have no callback (restored from a snapshot into a world that did
    /// not have them): the host sets their callbacks before stepping.
    pub fn user_generators_missing_callbacks(&self) -> impl Iterator<Item = crate::pool::Handle> + '_ {
        use crate::generators::GeneratorDef as G;
        self.generators.iter().filter_map(|(h, g)| match g.def {
            G::ExternalForce { callback: 0, .. } | G::ExternalContact { callback: 0, .. } => Some(h),
            _ => None,
        })
    }
}

impl crate::world::World {
    /// Sets the callback (and user data, and a contact generator's capacity) of a user
    /// generator: after a restore into a world that did not have it, or to replace it.
    /// `def` must be of the generator's kind (`ExternalForce` or `ExternalContact`).
    pub fn set_user_generator_callback(
        &mut self,
        h: crate::pool::Handle,
        def: &crate::generators::GeneratorDef,
    ) -> crate::error::Result<()> {
        use crate::generators::GeneratorDef as G;
        let g = self
            .generators
            .get_mut(h)
            .ok_or(crate::error::Error::InvalidId("generator"))?;
        match (&g.def, def) {
            (G::ExternalForce { .. }, G::ExternalForce { .. })
            | (G::ExternalContact { .. }, G::ExternalContact { .. }) => {}
            _ => {
                return Err(crate::error::invalid(
                    "generator: not a user generator of this kind (force callbacks go to user force \
                     generators, contact callbacks to user contact generators)",
                ))
            }
        }
        def.validate()?;
        g.def = *def;
        Ok(())
    }
}
