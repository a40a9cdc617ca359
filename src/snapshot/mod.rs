//! Snapshots: the whole state of a world that affects its future, saved to bytes and restored,
//! after which stepping reproduces the original bit for bit (rollback netcode, replays).
//! The format is specified in `docs/snapshot-format.md`.
//!
//! * [`Snap`] is implemented once per stored type: `put` appends the value little-endian,
//!   `get` reads it back. Structs use [`snap_struct!`], which destructures the struct
//!   *exhaustively* in `put` (`let Body { a, b, .. }` is never written), so a field added to a
//!   stored struct later fails to compile until it is listed here, either stored or named as
//!   `skip` (scratch that every step rewrites before reading it, or a value `predicted.rs`
//!   stores after the pool only where it differs from what the reader rebuilds).
//! * `write.rs` writes the world section by section into columns (`columns.rs`: one column
//!   per field path, byte planes), compresses them with zstd and frames them (magic,
//!   version, length, checksum); `read.rs` checks the frame, decompresses, decodes every section
//!   into a new world state, checks its cross-references (`check.rs`) and only then swaps it
//!   into the target world, so a failing restore changes nothing.
//! * Ids keep their slot index and reuse counter; the world tag in their top bits is the
//!   target world's. Restored into the same world, every id the host holds stays valid and
//!   ids created afterwards equal those the original created after the same calls.
//! * User callbacks (user force and contact generators) are not stored: a restore into the
//!   same world keeps the callback each such generator has now (when the generator is still
//!   there with the same id and kind); anywhere else the generator comes back without one and
//!   the host re-registers it (`World::user_generators_missing_callbacks`).

mod check;
mod columns;
mod predicted;
mod read;
mod types;
mod write;

pub use read::restore;
pub use write::{column_sizes, save, saved_size};

/// First eight bytes of every snapshot.
pub const MAGIC: [u8; 8] = *b"HEARTHSS";
/// Format version; a snapshot of another version is refused.
pub const VERSION: u32 = 5;
/// Bytes before the payload: magic, version, payload length (u64), checksum (u64).
pub const HEADER_LEN: usize = 8 + 4 + 8 + 8;

/// Why a snapshot could not be restored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SnapshotError(pub String);

pub type ReadResult<T> = std::result::Result<T, SnapshotError>;

pub(crate) fn bad<T>(msg: impl Into<String>) -> ReadResult<T> {
    Err(SnapshotError(msg.into()))
}

/// The checksum: over the payload's 8-byte little-endian words (the last one padded with
/// zeros), then its length, each step `h = m((h ^ word) · P)` with `P` the FNV-1a 64 prime
/// and `m(y) = y ^ (y >> 29)`. Both `x ↦ x · P` (P odd) and `m` are bijections, so each step
/// is a bijection of `h` and any change of one word (one byte, one bit) changes the result;
/// the shift carries a word's high bits down into the low ones, which the product alone
/// never does (plain FNV-1a over words misses two flips of the same high bit in two words).
pub fn checksum64(bytes: &[u8]) -> u64 {
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let step = |h: u64, w: u64| {
        let y = (h ^ w).wrapping_mul(PRIME);
        y ^ (y >> 29)
    };
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut words = bytes.chunks_exact(8);
    for w in &mut words {
        h = step(h, u64::from_le_bytes(w.try_into().expect("8 bytes")));
    }
    let rest = words.remainder();
    if !rest.is_empty() {
        let mut last = [0u8; 8];
        last[..rest.len()].copy_from_slice(rest);
        h = step(h, u64::from_le_bytes(last));
    }
    step(h, bytes.len() as u64)
}

#[cfg(test)]
pub(crate) use columns::unpack;
pub use columns::{Reader, Writer};

impl Writer {
    /// Writes a count (of the elements that follow) into the current column's `#len`.
    #[inline]
    pub fn put_len(&mut self, n: usize) {
        self.within("#len", |w| (n as u64).put(w));
    }

    /// Writes an enum's variant tag into the current column's `#tag`.
    #[inline]
    pub fn put_tag(&mut self, t: u8) {
        self.within("#tag", |w| t.put(w));
    }

    /// Writes the enum values `items` as one pass of their tags (the `#tag` column, made at
    /// the first value, as `put_tag` one by one makes it), then each value's fields.
    pub fn put_tagged_all<'s, T: 's, I>(&mut self, items: I, tag: impl Fn(&T) -> u8, fields: impl Fn(&T, &mut Writer))
    where
        I: Iterator<Item = &'s T> + Clone,
    {
        if items.clone().next().is_none() {
            return;
        }
        self.within("#tag", |w| w.values(items.clone().map(|v| [tag(v)])));
        for v in items {
            fields(v, self);
        }
    }
}

impl Reader<'_> {
    /// A count of elements that follow, each at least one byte: larger than what is left
    /// is an error (so a corrupted count cannot ask for a huge allocation).
    pub fn count(&mut self) -> ReadResult<usize> {
        let n = self.within("#len", u64::get)?;
        if n > self.remaining() as u64 {
            return bad(format!(
                "snapshot corrupted: count {n} exceeds the {} bytes left",
                self.remaining()
            ));
        }
        Ok(n as usize)
    }

    /// `n` counts from the current column's `#len`, as `n` calls of `count` would read them
    /// and check them: together they are at most what is left, so the elements they
    /// announce cannot ask for a huge allocation.
    pub fn counts(&mut self, n: usize) -> ReadResult<Vec<usize>> {
        let lens = self.within("#len", |r| u64::get_all(n, r))?;
        let mut total = 0u64;
        for &k in &lens {
            total = total.saturating_add(k);
            if total > self.remaining() as u64 {
                return bad(format!(
                    "snapshot corrupted: count {k} exceeds the {} bytes left",
                    self.remaining()
                ));
            }
        }
        Ok(lens.into_iter().map(|k| k as usize).collect())
    }

    /// An enum's variant tag, below `n`.
    pub fn tag(&mut self, what: &str, n: u8) -> ReadResult<u8> {
        let t = self.within("#tag", u8::get)?;
        if t >= n {
            return bad(format!("snapshot corrupted: {what} variant {t} unknown"));
        }
        Ok(t)
    }

    /// Reads `count` enum values written by `Writer::put_tagged_all`: their tags in one
    /// pass (each below `n`, else an error naming `what`), then each value's fields.
    pub fn get_tagged_all<T>(
        &mut self,
        count: usize,
        what: &str,
        n: u8,
        fields: impl Fn(u8, &mut Self) -> ReadResult<T>,
    ) -> ReadResult<Vec<T>> {
        if count == 0 {
            return Ok(Vec::new());
        }
        let tags = self.within("#tag", |r| r.take_values(count, 1))?;
        if let Some(t) = tags.iter().find(|&&t| t >= n) {
            return bad(format!("snapshot corrupted: {what} variant {t} unknown"));
        }
        tags.iter().map(|&t| fields(t, self)).collect()
    }
}

/// A type stored in snapshots.
///
/// `put_all` and `get_all` store and load many values at once, column by column: a struct
/// enters each field's column once and writes that field of every value, so the per-value
/// cost is a plain loop rather than a column lookup per field. They write and read the
/// same bytes in every column as `put` and `get` on each value in order would; the
/// defaults do exactly that, one value at a time, and structs, numbers, vectors, options,
/// arrays and pools override them.
pub trait Snap: Sized {
    fn put(&self, w: &mut Writer);
    fn get(r: &mut Reader) -> ReadResult<Self>;

    /// `put` of every value of `items`, in order.
    #[inline]
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        for x in items {
            x.put(w);
        }
    }

    /// `n` values, as `n` calls of `get` would read them.
    #[inline]
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let mut v = Vec::with_capacity(n.min(r.remaining()));
        for _ in 0..n {
            v.push(Self::get(r)?);
        }
        Ok(v)
    }

    /// The `n` values `get_all` reads, each stored straight into its place in `dst`
    /// (`at(dst, i)` for value `i`) rather than collected first: a struct's fields, its
    /// fields' fields and so on down to the numbers are filled where they will stay, with
    /// no vector per field between (`snap_struct!`'s `get_all` does so for every
    /// `SnapBlank`). The default collects with `get_all`, then moves.
    #[inline]
    fn get_into<O>(
        dst: &mut [O],
        n: usize,
        at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
        r: &mut Reader,
    ) -> ReadResult<()> {
        for (i, x) in Self::get_all(n, r)?.into_iter().enumerate() {
            *at(dst, i) = x;
        }
        Ok(())
    }

    /// Vectors of `lens[i]` values each, as `Vec::<Self>::get` on each would read them
    /// (the counts already read). The default reads them all, then moves them into their
    /// vectors; `u32` fills vectors kept from the last restore (`Reader::spare`).
    fn get_vecs(lens: &[usize], r: &mut Reader) -> ReadResult<Vec<Vec<Self>>> {
        let mut all = Self::get_all(lens.iter().sum(), r)?.into_iter();
        Ok(lens.iter().map(|&k| all.by_ref().take(k).collect()).collect())
    }
}

/// A value for `get_all` to read a struct into in place: `get_into` overwrites every
/// stored field with what the snapshot holds and every skipped one with its default, so
/// nothing of the blank is left. Every type with a default is one; the bodies, shapes and
/// contacts have theirs in `types.rs`.
pub trait SnapBlank {
    fn blank() -> Self;
}

impl<T: Default> SnapBlank for T {
    #[inline]
    fn blank() -> Self {
        T::default()
    }
}

/// Chooses how `snap_struct!`'s `get_all` makes its values, by whether the struct is a
/// `SnapBlank` (autoref specialisation: the macro names the concrete type, so the method
/// found is `Blank`'s when the bound holds and `NoBlank`'s otherwise).
#[doc(hidden)]
pub struct Probe<T>(std::marker::PhantomData<T>);

impl<T> Probe<T> {
    #[doc(hidden)]
    pub fn new() -> Self {
        Probe(std::marker::PhantomData)
    }
}

#[doc(hidden)]
pub trait Blank<T> {
    /// `n` blank values to read into in place (`n` is at most the bytes left: every
    /// stored value takes at least one).
    fn blank(&self, n: usize) -> Option<Vec<T>>;
}

/// Bytes of memory per byte left in the payload up to which `get_all` makes blanks to read
/// into (a count past it is corrupted: the struct's fields are then read first).
#[doc(hidden)]
pub const BLANK_RATIO: usize = 16;

impl<T: SnapBlank> Blank<T> for Probe<T> {
    #[inline]
    fn blank(&self, n: usize) -> Option<Vec<T>> {
        Some(std::iter::repeat_with(T::blank).take(n).collect())
    }
}

#[doc(hidden)]
pub trait NoBlank<T> {
    /// None: the values are built field by field.
    fn blank(&self, n: usize) -> Option<Vec<T>>;
}

impl<T> NoBlank<T> for &Probe<T> {
    #[inline]
    fn blank(&self, _: usize) -> Option<Vec<T>> {
        None
    }
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
                $( w.within(stringify!($f), |w| $crate::snapshot::Snap::put($f, w)); )*
            }
            fn get(r: &mut $crate::snapshot::Reader) -> $crate::snapshot::ReadResult<Self> {
                Ok($t {
                    $($f: r.within(stringify!($f), $crate::snapshot::Snap::get)?,)*
                    $($($s: Default::default(),)*)?
                })
            }
            fn put_all<'s, I>(items: I, w: &mut $crate::snapshot::Writer)
            where
                I: Iterator<Item = &'s Self> + Clone,
                Self: 's,
            {
                $( w.within(stringify!($f), |w| {
                    $crate::snapshot::Snap::put_all(items.clone().map(|x: &'s $t| &x.$f), w)
                }); )*
            }
            fn get_into<O>(
                dst: &mut [O],
                n: usize,
                at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
                r: &mut $crate::snapshot::Reader,
            ) -> $crate::snapshot::ReadResult<()> {
                $( r.within(stringify!($f), |r| {
                    $crate::snapshot::Snap::get_into(dst, n, move |d: &mut [O], i| &mut at(d, i).$f, r)
                })?; )*
                $($( for i in 0..n { at(dst, i).$s = Default::default(); } )*)?
                Ok(())
            }
            fn get_all(
                n: usize,
                r: &mut $crate::snapshot::Reader,
            ) -> $crate::snapshot::ReadResult<Vec<Self>> {
                #[allow(unused_imports)]
                use $crate::snapshot::{Blank as _, NoBlank as _};
                if n > r.remaining() {
                    return $crate::snapshot::bad("snapshot corrupted: a count exceeds the bytes left");
                }
                // The blanks are made before any column is read, so a corrupted count must
                // not make many: past `BLANK_RATIO` bytes of blanks per byte left (the pile's
                // bodies and contacts take a tenth of it or less), the field-by-field path below reads the values
                // instead, allocating only as each field's column proves long enough (and
                // refusing a short one). Both paths read the same values.
                let fits = n.saturating_mul(std::mem::size_of::<$t>())
                    <= r.remaining().saturating_mul($crate::snapshot::BLANK_RATIO);
                #[allow(clippy::needless_borrow)]
                let blanks = if fits { (&$crate::snapshot::Probe::<$t>::new()).blank(n) } else { None };
                if let Some(mut v) = blanks {
                    <$t as $crate::snapshot::Snap>::get_into(&mut v, n, |d: &mut [$t], i| &mut d[i], r)?;
                    return Ok(v);
                }
                $( let mut $f = r
                    .within(stringify!($f), |r| $crate::snapshot::Snap::get_all(n, r))?
                    .into_iter(); )*
                Ok((0..n)
                    .map(|_| $t {
                        $($f: $f.next().expect("n values"),)*
                        $($($s: Default::default(),)*)?
                    })
                    .collect())
            }
        }
    };
}
pub use snap_struct;

macro_rules! snap_num {
    ($($t:ty $(: $vecs:ident)?),*) => {$(
        impl Snap for $t {
            #[inline]
            fn put(&self, w: &mut Writer) {
                w.bytes(&self.to_le_bytes());
            }
            #[inline(always)]
            fn get(r: &mut Reader) -> ReadResult<Self> {
                let b = r.take(std::mem::size_of::<$t>())?;
                Ok(<$t>::from_le_bytes(b.try_into().expect("sized")))
            }
            fn put_all<'s, I>(items: I, w: &mut Writer)
            where
                I: Iterator<Item = &'s Self> + Clone,
                Self: 's,
            {
                w.values(items.map(|x| x.to_le_bytes()));
            }
            fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
                const W: usize = std::mem::size_of::<$t>();
                let b = r.take_values(n, W)?;
                Ok(b.chunks_exact(W)
                    .map(|c| <$t>::from_le_bytes(c.try_into().expect("sized")))
                    .collect())
            }
            fn get_into<O>(
                dst: &mut [O],
                n: usize,
                at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
                r: &mut Reader,
            ) -> ReadResult<()> {
                const W: usize = std::mem::size_of::<$t>();
                let b = r.take_values(n, W)?;
                for (i, c) in b.chunks_exact(W).enumerate() {
                    *at(dst, i) = <$t>::from_le_bytes(c.try_into().expect("sized"));
                }
                Ok(())
            }
            $(
            fn get_vecs(lens: &[usize], r: &mut Reader) -> ReadResult<Vec<Vec<Self>>> {
                $vecs(lens, r)
            }
            )?
        }
    )*};
}
snap_num!(u8, u16, u32: get_u32_vecs, u64, i8, i32, f32, f64);

/// `u32` vectors (the bodies' shape and contact lists) are filled into vectors the last
/// restore on this thread freed (`Reader::spare`), so a restore does not allocate them
/// one by one again.
pub(crate) fn get_u32_vecs(lens: &[usize], r: &mut Reader) -> ReadResult<Vec<Vec<u32>>> {
    let b = r.take_values(lens.iter().sum(), 4)?;
    let mut values = b
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes(c.try_into().expect("4 bytes")));
    let mut out = Vec::with_capacity(lens.len());
    for &k in lens {
        let mut v = match k {
            0 => Vec::new(),
            _ => r.spare.1.pop().unwrap_or_default(),
        };
        v.clear();
        v.extend(values.by_ref().take(k));
        out.push(v);
    }
    Ok(out)
}

impl Snap for usize {
    fn put(&self, w: &mut Writer) {
        (*self as u64).put(w)
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let v = u64::get(r)?;
        usize::try_from(v).or_else(|_| bad("snapshot corrupted: size out of range"))
    }
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        w.values(items.map(|&x| (x as u64).to_le_bytes()));
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let b = r.take_values(n, 8)?;
        b.chunks_exact(8)
            .map(|c| {
                usize::try_from(u64::from_le_bytes(c.try_into().expect("8 bytes")))
                    .or_else(|_| bad("snapshot corrupted: size out of range"))
            })
            .collect()
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
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        w.values(items.map(|&x| [x as u8]));
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let b = r.take_values(n, 1)?;
        if let Some(v) = b.iter().find(|&&v| v > 1) {
            return bad(format!("snapshot corrupted: flag {v} is not 0 or 1"));
        }
        Ok(b.iter().map(|&v| v == 1).collect())
    }
    fn get_into<O>(
        dst: &mut [O],
        n: usize,
        at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
        r: &mut Reader,
    ) -> ReadResult<()> {
        let b = r.take_values(n, 1)?;
        if let Some(v) = b.iter().find(|&&v| v > 1) {
            return bad(format!("snapshot corrupted: flag {v} is not 0 or 1"));
        }
        for (i, &v) in b.iter().enumerate() {
            *at(dst, i) = v == 1;
        }
        Ok(())
    }
}

impl<T: Snap> Snap for Vec<T> {
    fn put(&self, w: &mut Writer) {
        w.put_len(self.len());
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
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        let mut total = 0;
        w.within("#len", |w| {
            w.values(items.clone().map(|v| {
                total += v.len();
                (v.len() as u64).to_le_bytes()
            }))
        });
        if total == 0 {
            // The elements' columns are made all the same, with no pass over the vectors.
            T::put_all(std::iter::empty(), w);
        } else {
            T::put_all(items.flat_map(|v| v.iter()), w);
        }
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let lens = r.counts(n)?;
        T::get_vecs(&lens, r)
    }
}

impl<T: Snap> Snap for Option<T> {
    fn put(&self, w: &mut Writer) {
        w.within("#some", |w| self.is_some().put(w));
        if let Some(x) = self {
            x.put(w)
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(if r.within("#some", bool::get)? {
            Some(T::get(r)?)
        } else {
            None
        })
    }
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        w.within("#some", |w| w.values(items.clone().map(|x| [x.is_some() as u8])));
        T::put_all(items.filter_map(|x| x.as_ref()), w);
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let some = r.within("#some", |r| bool::get_all(n, r))?;
        let mut values = T::get_all(some.iter().filter(|&&s| s).count(), r)?.into_iter();
        Ok(some.iter().map(|&s| if s { values.next() } else { None }).collect())
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
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        T::put_all(items.flat_map(|a| a.iter()), w);
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let Some(total) = n.checked_mul(N) else {
            return bad("snapshot corrupted: an array count out of range");
        };
        let mut all = T::get_all(total, r)?.into_iter();
        Ok((0..n)
            .map(|_| std::array::from_fn(|_| all.next().expect("n * N values")))
            .collect())
    }
    fn get_into<O>(
        dst: &mut [O],
        n: usize,
        at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
        r: &mut Reader,
    ) -> ReadResult<()> {
        let Some(total) = n.checked_mul(N) else {
            return bad("snapshot corrupted: an array count out of range");
        };
        T::get_into(dst, total, move |d: &mut [O], i| &mut at(d, i / N)[i % N], r)
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
    /// The keys and values go to their own columns, so writing all keys, then all values
    /// (`put_all`, `get_all`) gives the bytes entry-by-entry writing would; the two columns
    /// are entered (made) only when there is an entry, as that would.
    fn put(&self, w: &mut Writer) {
        let mut entries: Vec<(K, &V)> = self.iter().map(|(k, v)| (*k, v)).collect();
        entries.sort_unstable_by_key(|e| e.0);
        w.put_len(entries.len());
        if !entries.is_empty() {
            w.within("#key", |w| K::put_all(entries.iter().map(|e| &e.0), w));
            w.within("#value", |w| V::put_all(entries.iter().map(|e| e.1), w));
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let n = r.count()?;
        let mut m = Self::with_capacity_and_hasher(n, S::default());
        if n == 0 {
            return Ok(m);
        }
        let keys = r.within("#key", |r| K::get_all(n, r))?;
        let values = r.within("#value", |r| V::get_all(n, r))?;
        for (k, v) in keys.into_iter().zip(values) {
            if m.insert(k, v).is_some() {
                return bad("snapshot corrupted: a map key appears twice");
            }
        }
        Ok(m)
    }
}

/// `put` and `get` of a struct of `Snap` fields, field by field in order (used by the
/// two macros below).
macro_rules! snap_fields {
    ($t:ty: $($f:ident),*) => {
        fn put(&self, w: &mut Writer) {
            $( self.$f.put(w); )*
        }
        fn get(r: &mut Reader) -> ReadResult<Self> {
            let mut v = <$t>::default();
            $( v.$f = Snap::get(r)?; )*
            Ok(v)
        }
    };
}

macro_rules! snap_floats {
    ($($t:ty: $($n:literal $f:ident),*;)*) => {$(
        impl Snap for $t {
            snap_fields!($t: $($f),*);
            fn put_all<'s, I>(items: I, w: &mut Writer)
            where
                I: Iterator<Item = &'s Self> + Clone,
                Self: 's,
            {
                Snap::put_all(items.flat_map(|v: &'s $t| [$(&v.$f),*]), w);
            }
            fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
                const K: usize = [$(stringify!($f)),*].len();
                let Some(total) = n.checked_mul(K) else {
                    return bad("snapshot corrupted: a count out of range");
                };
                let mut all = Snap::get_all(total, r)?.into_iter();
                Ok((0..n)
                    .map(|_| {
                        let mut v = <$t>::default();
                        $( v.$f = all.next().expect("n * K values"); )*
                        v
                    })
                    .collect())
            }
            fn get_into<O>(
                dst: &mut [O],
                n: usize,
                at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
                r: &mut Reader,
            ) -> ReadResult<()> {
                const K: usize = [$(stringify!($f)),*].len();
                let Some(total) = n.checked_mul(K) else {
                    return bad("snapshot corrupted: a count out of range");
                };
                Snap::get_into(dst, total, move |d: &mut [O], i| {
                    let v = at(d, i / K);
                    match i % K {
                        $($n => &mut v.$f,)*
                        _ => unreachable!("K components"),
                    }
                }, r)
            }
        }
    )*};
}
snap_floats! {
    glam::DVec3: 0 x, 1 y, 2 z;
    glam::Mat3: 0 x_axis, 1 y_axis, 2 z_axis;
    glam::Mat3A: 0 x_axis, 1 y_axis, 2 z_axis;
    glam::DQuat: 0 x, 1 y, 2 z, 3 w;
}

/// Vectors of `f32`: the same bytes as `snap_floats` (each component's `f32`, in order, in
/// the one column), moved between the column and the values without a `Vec<f32>` between.
macro_rules! snap_f32s {
    ($($t:ty: $k:literal, $($f:ident),*;)*) => {$(
        impl Snap for $t {
            snap_fields!($t: $($f),*);
            fn put_all<'s, I>(items: I, w: &mut Writer)
            where
                I: Iterator<Item = &'s Self> + Clone,
                Self: 's,
            {
                w.value_groups::<4, { 4 * $k }>(items.map(|v: &'s $t| {
                    let mut b = [0u8; 4 * $k];
                    for (d, x) in b.chunks_exact_mut(4).zip([$(v.$f),*]) {
                        d.copy_from_slice(&x.to_le_bytes());
                    }
                    b
                }));
            }
            fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
                let b = r.take_values(n, 4 * $k)?;
                Ok(b.chunks_exact(4 * $k)
                    .map(|c| {
                        let mut v = <$t>::default();
                        let mut x = c.chunks_exact(4).map(|e| f32::from_le_bytes(e.try_into().expect("4 bytes")));
                        $( v.$f = x.next().expect("k components"); )*
                        v
                    })
                    .collect())
            }
            fn get_into<O>(
                dst: &mut [O],
                n: usize,
                at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
                r: &mut Reader,
            ) -> ReadResult<()> {
                let b = r.take_values(n, 4 * $k)?;
                for (i, c) in b.chunks_exact(4 * $k).enumerate() {
                    let v = at(dst, i);
                    let mut x = c.chunks_exact(4).map(|e| f32::from_le_bytes(e.try_into().expect("4 bytes")));
                    $( v.$f = x.next().expect("k components"); )*
                }
                Ok(())
            }
        }
    )*};
}
snap_f32s! {
    glam::Vec3: 3, x, y, z;
    glam::Vec3A: 3, x, y, z;
    glam::Quat: 4, x, y, z, w;
}

impl crate::world::World {
    /// Bytes a snapshot of the world takes now. The snapshot is compressed, so this runs a
    /// whole save into a scratch buffer (as costly as `save_snapshot`).
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
