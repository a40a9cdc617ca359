//! The payload's column layout: every value is written into the column (stream) named by
//! the path of struct fields that leads to it (`bodies` › `xf` › `p`), so the values of one
//! field of every body sit together. Counts, option flags, enum tags, pool slot counters
//! and map keys and values each get a column of their own under their parent. A column
//! whose values all have one width (2, 4 or 8 bytes) is stored as byte planes (every
//! value's first byte, then every second byte, …): equal fields (masses, inertias, zero
//! velocities of sleeping bodies, sign and exponent bytes of nearby positions) become long
//! runs that the zstd stage after this one shrinks. When enough of such a column's values
//! are zero, it is stored sparse instead: a bitmap of the non-zero values, then only those
//! as byte planes (`SPARSE`). zstd's cost follows the bytes it reads, and the pile's columns
//! are two-thirds zero bytes (unused contact points, empty caches, resting bodies).
//!
//! A column is known by its path only while writing; the payload lists the columns in the
//! order the writer first entered them, and the reader, which walks the same structure in
//! the same order, gives each path it enters the next column of the list. Both sides
//! compare field names, never addresses, so the pairing does not depend on how the
//! compiler laid out the code.

use super::{bad, ReadResult};

/// Width marker of a column whose values differ in width (stored as is).
const MIXED: u8 = 0xFF;
/// Added to a plane column's width (2, 4 or 8) in the column table when it is stored in
/// the sparse form: a bitmap of its non-zero values, then only those, as byte planes.
pub(crate) const SPARSE: u8 = 0x40;

#[derive(Default)]
struct WColumn {
    bytes: Vec<u8>,
    /// 0: nothing written yet; the width of every value written; or `MIXED`.
    width: u8,
    children: Vec<(&'static str, u32)>,
    /// Where the next lookup among `children` starts (fields are entered in order).
    hint: usize,
}

/// Values `Writer::values` gathers before appending them to their column.
const BATCH: usize = 32;

/// Appends little-endian values to the columns of a payload.
pub struct Writer {
    /// The payload's columns are `columns[..used]`; the rest are columns of an earlier
    /// payload kept for their capacity (`clear`).
    columns: Vec<WColumn>,
    used: u32,
    cur: u32,
    /// `finish`'s scratch, kept between payloads.
    scratch: Packed,
}

/// A plane column's bitmap of non-zero values and those values, packed (`gather`).
#[derive(Default)]
struct Packed {
    bits: Vec<u8>,
    w16: Vec<u16>,
    w32: Vec<u32>,
    w64: Vec<u64>,
}

/// Appends column `c` (of byte planes, its values in `$m`'s width) to `out` in the shorter
/// of its forms; its code.
macro_rules! encode {
    ($m:ident, $words:ident, $c:expr, $s:expr, $out:expr, $at:ident) => {{
        let (c, s, out): (&WColumn, &mut Packed, &mut Vec<u8>) = ($c, $s, $out);
        let w = c.width as usize;
        let nb = (c.bytes.len() / w).div_ceil(8);
        let k = $m::gather(&c.bytes, &mut s.bits, &mut s.$words);
        let at = $at;
        if nb + k * w < c.bytes.len() {
            $at += nb + k * w;
            grow(out, $at);
            out[at..at + nb].copy_from_slice(&s.bits[..nb]);
            $m::split_words(&s.$words[..k], &mut out[at + nb..$at]);
            c.width | SPARSE
        } else {
            $at += c.bytes.len();
            grow(out, $at);
            $m::split(&c.bytes, &mut out[at..$at]);
            c.width
        }
    }};
}

/// Makes `out` at least `len` bytes long (zeros added), keeping what it holds.
fn grow(out: &mut Vec<u8>, len: usize) {
    if out.len() < len {
        out.resize(len, 0);
    }
}

impl Default for Writer {
    fn default() -> Self {
        Self::new()
    }
}

impl Writer {
    pub fn new() -> Writer {
        Writer {
            columns: vec![WColumn::default()],
            used: 1,
            cur: 0,
            scratch: Packed::default(),
        }
    }

    /// Empties the writer for another payload, keeping its buffers' capacity. What it
    /// writes next does not depend on what it wrote before: columns are numbered afresh.
    pub fn clear(&mut self) {
        self.used = 0;
        self.cur = 0;
        self.new_column();
    }

    /// A new empty column (a kept one when there is one); its id.
    fn new_column(&mut self) -> u32 {
        let id = self.used;
        self.used += 1;
        match self.columns.get_mut(id as usize) {
            Some(c) => {
                c.bytes.clear();
                c.width = 0;
                c.children.clear();
                c.hint = 0;
            }
            None => self.columns.push(WColumn::default()),
        }
        id
    }

    /// The payload's columns.
    fn live(&self) -> &[WColumn] {
        &self.columns[..self.used as usize]
    }

    /// Makes the current column's child `name` current; returns the column to go back to
    /// (`leave`). Inlined for the usual case, the field after the last one entered.
    #[inline(always)]
    pub fn enter(&mut self, name: &'static str) -> u32 {
        let prev = self.cur;
        let c = &mut self.columns[prev as usize];
        if c.hint == c.children.len() {
            c.hint = 0;
        }
        if let Some(&(k, id)) = c.children.get(c.hint) {
            if k.as_ptr() == name.as_ptr() && k.len() == name.len() {
                c.hint += 1;
                self.cur = id;
                return prev;
            }
        }
        self.enter_other(name);
        prev
    }

    /// `enter` when `name` is not the hinted child: looked up among the children, or a new
    /// column the first time.
    #[inline(never)]
    fn enter_other(&mut self, name: &'static str) {
        let next_id = self.used;
        let c = &mut self.columns[self.cur as usize];
        let n = c.children.len();
        self.cur = match find_child(&c.children, c.hint, name) {
            Some(k) => {
                c.hint = k + 1;
                c.children[k].1
            }
            None => {
                c.children.push((name, next_id));
                c.hint = n + 1;
                self.new_column()
            }
        };
    }

    #[inline]
    pub fn leave(&mut self, prev: u32) {
        self.cur = prev;
    }

    /// Writes `f`'s values into the child column `name`.
    #[inline]
    pub fn within(&mut self, name: &'static str, f: impl FnOnce(&mut Writer)) {
        let p = self.enter(name);
        f(self);
        self.leave(p);
    }

    /// Appends one value's bytes to the current column.
    #[inline(always)]
    pub fn bytes(&mut self, b: &[u8]) {
        let c = &mut self.columns[self.cur as usize];
        let w = b.len() as u8;
        if c.width != w {
            c.width = if c.width == 0 { w } else { MIXED };
        }
        c.bytes.extend_from_slice(b);
    }

    /// Appends values of one width (`W` bytes each) to the current column.
    #[inline]
    pub fn values<const W: usize>(&mut self, values: impl Iterator<Item = [u8; W]>) {
        self.value_groups::<W, W>(values);
    }

    /// Appends groups of values of one width (`W` bytes each, `B / W` per group) to the
    /// current column: a vector's components in order, as `values` would append them one
    /// by one.
    #[inline]
    pub fn value_groups<const W: usize, const B: usize>(&mut self, groups: impl Iterator<Item = [u8; B]>) {
        let c = &mut self.columns[self.cur as usize];
        let start = c.bytes.len();
        // Internal iteration: the chains of maps, filters and flat maps that lead here fold
        // far faster than they step. The values are gathered in a small array and appended
        // `BATCH` at a time, so each costs a store rather than a check of the column's room.
        let mut batch = [[0u8; B]; BATCH];
        let mut k = 0;
        groups.for_each(|v| {
            batch[k % BATCH] = v;
            k += 1;
            if k == BATCH {
                c.bytes.extend_from_slice(batch.as_flattened());
                k = 0;
            }
        });
        c.bytes.extend_from_slice(batch[..k].as_flattened());
        if c.bytes.len() > start && c.width != W as u8 {
            c.width = if c.width == 0 { W as u8 } else { MIXED };
        }
    }

    /// Bytes the payload takes before compression.
    pub fn raw_len(&self) -> usize {
        4 + 9 * self.live().len() + self.live().iter().map(|c| stored(c.width, &c.bytes).1).sum::<usize>()
    }

    /// Replaces `out`'s content with the payload: the column count (`u32`), each column's
    /// length (`u64`, before the sparse form) and code (`u8`: its width; 2, 4 or 8 for byte
    /// planes, plus `SPARSE` for the sparse form; otherwise stored as is), then the columns
    /// in order. A plane column is read once to find its non-zero values (`gather`), which
    /// decides its form; the sparse form is then written from what that pass packed.
    pub fn finish(&mut self, out: &mut Vec<u8>) {
        let Writer {
            columns, used, scratch, ..
        } = self;
        let live = &columns[..*used as usize];
        // `out` only grows: a buffer kept from the last payload of about this size is
        // written over, not zeroed again; it is cut to the payload's length at the end.
        let table = 4 + 9 * live.len();
        grow(out, table);
        out[..4].copy_from_slice(&(live.len() as u32).to_le_bytes());
        let mut at = table;
        for (k, c) in live.iter().enumerate() {
            let code = match planes(c.width, c.bytes.len()) {
                1 => {
                    grow(out, at + c.bytes.len());
                    out[at..at + c.bytes.len()].copy_from_slice(&c.bytes);
                    at += c.bytes.len();
                    c.width
                }
                2 => encode!(planes_u16, w16, c, scratch, out, at),
                4 => encode!(planes_u32, w32, c, scratch, out, at),
                _ => encode!(planes_u64, w64, c, scratch, out, at),
            };
            let e = &mut out[4 + 9 * k..4 + 9 * k + 9];
            e[..8].copy_from_slice(&(c.bytes.len() as u64).to_le_bytes());
            e[8] = code;
        }
        out.truncate(at);
    }

    /// Each column's path, length, and length compressed alone (byte planes, zstd), for
    /// size reports.
    pub fn column_sizes(&self) -> Vec<(String, usize, usize)> {
        let mut names = vec![String::new(); self.live().len()];
        for (i, c) in self.live().iter().enumerate() {
            for &(name, k) in &c.children {
                names[k as usize] = if i == 0 {
                    name.to_string()
                } else {
                    format!("{}.{name}", names[i])
                };
            }
        }
        let packed = |c: &WColumn| {
            let mut one = Writer {
                columns: vec![WColumn {
                    bytes: c.bytes.clone(),
                    width: c.width,
                    children: Vec::new(),
                    hint: 0,
                }],
                used: 1,
                cur: 0,
                scratch: Packed::default(),
            };
            let mut raw = Vec::new();
            one.finish(&mut raw);
            let mut z = Vec::new();
            super::write::compress_into(&raw[13..], &mut z);
            z.len()
        };
        names
            .into_iter()
            .zip(self.live().iter().map(|c| (c.bytes.len(), packed(c))))
            .map(|(n, (l, z))| (n, l, z))
            .collect()
    }
}

/// The index of the child column named `name` among `children`, looked for at `hint` (the
/// one after the last entered: fields are entered in order) first. Names are compared as
/// strings; a name is nearly always the same `&'static str` (one `stringify!` or literal per
/// call site), so they are first compared by address and length, which is enough to know
/// they are equal, and only a miss falls back to comparing the characters.
#[inline(always)]
fn find_child(children: &[(&'static str, u32)], hint: usize, name: &'static str) -> Option<usize> {
    let same = |a: &str| a.as_ptr() == name.as_ptr() && a.len() == name.len();
    if let Some(k) = children.get(hint) {
        if same(k.0) {
            return Some(hint);
        }
    }
    children
        .iter()
        .position(|k| same(k.0))
        .or_else(|| children.iter().position(|k| k.0 == name))
}

/// Byte planes a column of `len` bytes with value width `width` is stored as (1: as is).
fn planes(width: u8, len: usize) -> usize {
    match width {
        2 | 4 | 8 if len % width as usize == 0 => width as usize,
        _ => 1,
    }
}

/// How a column of width code `width` holding `bytes` is stored: its code in the table
/// (the width, or the width plus `SPARSE`) and its stored length. A plane column whose
/// zero values are many enough that a bitmap of the others (one bit per value) plus the
/// others alone is shorter is stored sparse: unused contact points, resting velocities,
/// off-diagonal inertia, empty caches cost a bit each instead of their width.
fn stored(width: u8, bytes: &[u8]) -> (u8, usize) {
    let w = planes(width, bytes.len());
    if w == 1 {
        return (width, bytes.len());
    }
    let n = bytes.len() / w;
    let k = match w {
        2 => planes_u16::nonzero(bytes),
        4 => planes_u32::nonzero(bytes),
        _ => planes_u64::nonzero(bytes),
    };
    let sparse = n.div_ceil(8) + k * w;
    if sparse < bytes.len() {
        (width | SPARSE, sparse)
    } else {
        (width, bytes.len())
    }
}

/// The sparse form of `values` (width `w`: 2, 4 or 8) into `dst`: the bitmap of non-zero
/// values (bit `i % 8` of byte `i / 8` for value `i`), then the non-zero values as byte
/// planes. `dst` has the length `stored` gave.
#[cfg(test)]
fn to_sparse(values: &[u8], dst: &mut [u8], w: usize) {
    match w {
        2 => planes_u16::split_sparse(values, dst),
        4 => planes_u32::split_sparse(values, dst),
        _ => planes_u64::split_sparse(values, dst),
    }
}

/// Undoes `to_sparse`: the values of width `w` into `dst` (their whole length) from the
/// start of `src`; returns the bytes of `src` used. Refuses a bitmap with bits past the
/// last value or announcing more values than `src` holds.
fn from_sparse(src: &[u8], dst: &mut [u8], w: usize) -> ReadResult<usize> {
    match w {
        2 => planes_u16::join_sparse(src, dst),
        4 => planes_u32::join_sparse(src, dst),
        _ => planes_u64::join_sparse(src, dst),
    }
}

/// Splits `values` (of width `w`: 2, 4 or 8) into byte planes in `dst` (same length): every
/// value's first byte, then every second byte, and so on.
#[cfg(test)]
fn to_planes(values: &[u8], dst: &mut [u8], w: usize) {
    match w {
        2 => planes_u16::split(values, dst),
        4 => planes_u32::split(values, dst),
        _ => planes_u64::split(values, dst),
    }
}

/// Undoes `to_planes`: joins the byte planes of `src` into values of width `w` in `dst`.
fn from_planes(src: &[u8], dst: &mut [u8], w: usize) {
    match w {
        2 => planes_u16::join(src, dst),
        4 => planes_u32::join(src, dst),
        _ => planes_u64::join(src, dst),
    }
}

/// Values are moved in blocks of this many: a block's words and planes stay in the first
/// level cache, and the loops over a block are shifts over fixed-length arrays, which the
/// compiler vectorises.
const BLOCK: usize = 64;

macro_rules! planes_of {
    ($m:ident, $t:ty) => {
        mod $m {
            use super::BLOCK;
            const W: usize = std::mem::size_of::<$t>();

            /// The values of `chunk` (at most `BLOCK` little-endian values) into `block`,
            /// zeros after them.
            #[inline(always)]
            fn load(chunk: &[u8], block: &mut [$t; BLOCK]) {
                if chunk.len() == BLOCK * W {
                    let c: &[u8; BLOCK * W] = chunk.try_into().expect("a whole block");
                    for (x, v) in block.iter_mut().zip(c.chunks_exact(W)) {
                        *x = <$t>::from_le_bytes(v.try_into().expect("W bytes"));
                    }
                } else {
                    block.fill(0);
                    for (x, v) in block.iter_mut().zip(chunk.chunks_exact(W)) {
                        *x = <$t>::from_le_bytes(v.try_into().expect("W bytes"));
                    }
                }
            }

            /// The first `chunk.len() / W` values of `block` into `chunk`, little-endian.
            #[inline(always)]
            fn store(block: &[$t; BLOCK], chunk: &mut [u8]) {
                if chunk.len() == BLOCK * W {
                    let c: &mut [u8; BLOCK * W] = chunk.try_into().expect("a whole block");
                    for (v, x) in c.chunks_exact_mut(W).zip(block) {
                        v.copy_from_slice(&x.to_le_bytes());
                    }
                } else {
                    for (v, x) in chunk.chunks_exact_mut(W).zip(block) {
                        v.copy_from_slice(&x.to_le_bytes());
                    }
                }
            }

            /// Byte `p` of each of the `k` first values of `block` into `dst` (`k` bytes).
            #[inline(always)]
            fn plane_out(block: &[$t; BLOCK], p: usize, dst: &mut [u8]) {
                if dst.len() == BLOCK {
                    let d: &mut [u8; BLOCK] = dst.try_into().expect("a whole block");
                    for (y, x) in d.iter_mut().zip(block) {
                        *y = (x >> (8 * p)) as u8;
                    }
                } else {
                    for (y, x) in dst.iter_mut().zip(block) {
                        *y = (x >> (8 * p)) as u8;
                    }
                }
            }

            /// Adds byte plane `p` (`src`, at most `BLOCK` bytes) into the values of `block`.
            #[inline(always)]
            fn plane_in(src: &[u8], p: usize, block: &mut [$t; BLOCK]) {
                if src.len() == BLOCK {
                    let s: &[u8; BLOCK] = src.try_into().expect("a whole block");
                    for (x, &y) in block.iter_mut().zip(s) {
                        *x |= (y as $t) << (8 * p);
                    }
                } else {
                    for (x, &y) in block.iter_mut().zip(src) {
                        *x |= (y as $t) << (8 * p);
                    }
                }
            }

            /// A block's mask from its bitmap bytes (at most 8).
            #[inline(always)]
            fn mask_at(bits: &[u8]) -> u64 {
                match <[u8; 8]>::try_from(bits) {
                    Ok(b) => u64::from_le_bytes(b),
                    Err(_) => bits.iter().rev().fold(0, |m, &b| m << 8 | b as u64),
                }
            }

            /// A block's mask into its bitmap bytes (at most 8).
            #[inline(always)]
            fn put_mask(mask: u64, bits: &mut [u8]) {
                match <&mut [u8; 8]>::try_from(&mut *bits) {
                    Ok(b) => *b = mask.to_le_bytes(),
                    Err(_) => {
                        for (i, b) in bits.iter_mut().enumerate() {
                            *b = (mask >> (8 * i)) as u8;
                        }
                    }
                }
            }

            /// Byte planes of the little-endian values in `values`, into `dst`.
            pub(super) fn split(values: &[u8], dst: &mut [u8]) {
                let n = values.len() / W;
                let mut block = [0 as $t; BLOCK];
                for (b, chunk) in values.chunks(BLOCK * W).enumerate() {
                    let (i, k) = (b * BLOCK, chunk.len() / W);
                    load(chunk, &mut block);
                    for p in 0..W {
                        plane_out(&block, p, &mut dst[p * n + i..p * n + i + k]);
                    }
                }
            }

            /// Byte planes of `words`, into `dst` (`W` bytes per word).
            pub(super) fn split_words(words: &[$t], dst: &mut [u8]) {
                let n = words.len();
                let mut block = [0 as $t; BLOCK];
                for (b, chunk) in words.chunks(BLOCK).enumerate() {
                    let (i, k) = (b * BLOCK, chunk.len());
                    block[..k].copy_from_slice(chunk);
                    for p in 0..W {
                        plane_out(&block, p, &mut dst[p * n + i..p * n + i + k]);
                    }
                }
            }

            /// Little-endian values from the byte planes in `src`, into `dst`.
            pub(super) fn join(src: &[u8], dst: &mut [u8]) {
                let n = src.len() / W;
                let mut block = [0 as $t; BLOCK];
                for (b, chunk) in dst.chunks_mut(BLOCK * W).enumerate() {
                    let (i, k) = (b * BLOCK, chunk.len() / W);
                    block.fill(0);
                    for p in 0..W {
                        plane_in(&src[p * n + i..p * n + i + k], p, &mut block);
                    }
                    store(&block, chunk);
                }
            }

            /// How many of the little-endian values in `values` are not zero.
            pub(super) fn nonzero(values: &[u8]) -> usize {
                let mut block = [0 as $t; BLOCK];
                let mut k = 0;
                for chunk in values.chunks(BLOCK * W) {
                    if chunk.iter().fold(0, |a, &x| a | x) == 0 {
                        continue;
                    }
                    load(chunk, &mut block);
                    k += block.iter().map(|x| (*x != 0) as u32).sum::<u32>() as usize;
                }
                k
            }

            /// Bit `t` set for each value `block[t]` that is not zero: the flags as bytes
            /// (a vector compare), then each eight of them gathered into a byte by one
            /// multiplication (flag `i` of a word moves to bit `56 + i`; the products of
            /// the other flags land on other bits, without carries).
            #[inline(always)]
            fn nonzero_mask(block: &[$t; BLOCK]) -> u64 {
                let mut flags = [0u8; BLOCK];
                for (f, x) in flags.iter_mut().zip(block) {
                    *f = (*x != 0) as u8;
                }
                let mut mask = 0u64;
                for (g, group) in flags.chunks_exact(8).enumerate() {
                    let b = u64::from_le_bytes(group.try_into().expect("8 flags"));
                    mask |= (b.wrapping_mul(0x0102_0408_1020_4080) >> 56) << (8 * g);
                }
                mask
            }

            /// One pass over `values`: their bitmap of non-zero values into `bits[..⌈n/8⌉]`
            /// and the non-zero values, in order, into `words[..k]`; returns `k`. The
            /// buffers grow to fit and are otherwise reused as they are (only what is
            /// returned is written). A block of non-zero values is copied whole; in others
            /// only the set bits of the block's mask are visited.
            pub(super) fn gather(values: &[u8], bits: &mut Vec<u8>, words: &mut Vec<$t>) -> usize {
                let n = values.len() / W;
                if bits.len() < n.div_ceil(8) {
                    bits.resize(n.div_ceil(8), 0);
                }
                if words.len() < n + BLOCK {
                    words.resize(n + BLOCK, 0);
                }
                let mut block = [0 as $t; BLOCK];
                let mut k = 0;
                for (b, chunk) in values.chunks(BLOCK * W).enumerate() {
                    let nb = (chunk.len() / W).div_ceil(8);
                    let out_bits = &mut bits[b * BLOCK / 8..b * BLOCK / 8 + nb];
                    if chunk.iter().fold(0, |a, &x| a | x) == 0 {
                        put_mask(0, out_bits);
                        continue;
                    }
                    load(chunk, &mut block);
                    let mask = nonzero_mask(&block);
                    put_mask(mask, out_bits);
                    let out: &mut [$t; BLOCK] = (&mut words[k..k + BLOCK]).try_into().expect("BLOCK words");
                    if mask == u64::MAX {
                        *out = block;
                        k += BLOCK;
                        continue;
                    }
                    let mut left = mask;
                    let mut j = 0;
                    while left != 0 {
                        out[j % BLOCK] = block[left.trailing_zeros() as usize % BLOCK];
                        left &= left - 1;
                        j += 1;
                    }
                    k += j;
                }
                k
            }

            /// The sparse form of `values` into `dst` (of the length it takes): bitmap,
            /// then the non-zero values' byte planes.
            #[cfg(test)]
            pub(super) fn split_sparse(values: &[u8], dst: &mut [u8]) {
                let (mut bits, mut words) = (Vec::new(), Vec::new());
                let k = gather(values, &mut bits, &mut words);
                let nb = (values.len() / W).div_ceil(8);
                dst[..nb].copy_from_slice(&bits[..nb]);
                split_words(&words[..k], &mut dst[nb..nb + k * W]);
            }

            /// Undoes `split_sparse`: fills `dst` (all `n` values) from the start of `src`;
            /// returns the bytes used.
            pub(super) fn join_sparse(src: &[u8], dst: &mut [u8]) -> super::ReadResult<usize> {
                let n = dst.len() / W;
                let nb = n.div_ceil(8);
                let Some(bits) = src.get(..nb) else {
                    return super::bad("snapshot corrupted: a sparse column's bitmap ends early");
                };
                if n % 8 != 0 && bits[nb - 1] >> (n % 8) != 0 {
                    return super::bad("snapshot corrupted: a sparse column's bitmap has bits past its values");
                }
                let whole = bits.chunks_exact(8);
                let tail = whole
                    .remainder()
                    .iter()
                    .map(|b| b.count_ones() as usize)
                    .sum::<usize>();
                let k = tail
                    + whole
                        .map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes")).count_ones() as usize)
                        .sum::<usize>();
                let Some(rest) = src.get(nb..nb + k * W) else {
                    return super::bad("snapshot corrupted: a sparse column ends early");
                };
                let mut packed = [0 as $t; BLOCK];
                let mut block = [0 as $t; BLOCK];
                let mut j = 0;
                for (b, chunk) in dst.chunks_mut(BLOCK * W).enumerate() {
                    let cb = (chunk.len() / W).div_ceil(8);
                    let mask = mask_at(&bits[b * BLOCK / 8..b * BLOCK / 8 + cb]);
                    if mask == 0 {
                        if let Ok(c) = <&mut [u8; BLOCK * W]>::try_from(&mut *chunk) {
                            *c = [0; BLOCK * W];
                        } else {
                            chunk.fill(0);
                        }
                        continue;
                    }
                    let m = mask.count_ones() as usize;
                    packed.fill(0);
                    for p in 0..W {
                        plane_in(&rest[p * k + j..p * k + j + m], p, &mut packed);
                    }
                    if mask == u64::MAX {
                        store(&packed, chunk);
                    } else {
                        block.fill(0);
                        let mut left = mask;
                        for &x in &packed[..m] {
                            block[left.trailing_zeros() as usize % BLOCK] = x;
                            left &= left - 1;
                        }
                        store(&block, chunk);
                    }
                    j += m;
                }
                Ok(nb + k * W)
            }
        }
    };
}
planes_of!(planes_u16, u16);
planes_of!(planes_u32, u32);
planes_of!(planes_u64, u64);

/// The error of a read past a column's end (out of line: `take` is on every value's path).
#[cold]
#[inline(never)]
fn ends_early<T>(wanted: usize, left: usize) -> ReadResult<T> {
    bad(format!(
        "snapshot corrupted: a column ends early ({wanted} bytes wanted, {left} left)"
    ))
}

struct RColumn {
    at: usize,
    end: usize,
    children: Vec<(&'static str, u32)>,
    hint: usize,
}

/// Reads little-endian values from the columns of a payload; every read past a column's
/// end is an error.
pub struct Reader<'a> {
    data: &'a [u8],
    columns: Vec<RColumn>,
    /// Columns paired with a path so far.
    assigned: u32,
    cur: u32,
    /// Bytes not read yet, over all columns.
    left: usize,
    /// The target world's tag, put into the top bits of every id read.
    pub(crate) tag: u32,
    /// Emptied vectors of ids and of `u32` to fill (`get_vecs`) before allocating new
    /// ones.
    pub(crate) spare: super::read::Spare,
}

/// Splits a payload into its column table and its columns, undoing the byte planes into
/// `plain`. Returns each column's span in `plain`.
pub(crate) fn unpack(payload: &[u8], plain: &mut Vec<u8>) -> ReadResult<Vec<(usize, usize)>> {
    let corrupt = || bad("snapshot corrupted: its column table does not match its length");
    let Some(head) = payload.get(..4) else {
        return corrupt();
    };
    let count = u32::from_le_bytes(head.try_into().expect("4"));
    let table_len = (count as usize)
        .checked_mul(9)
        .and_then(|t| t.checked_add(4))
        .filter(|&t| t <= payload.len() && count > 0);
    let Some(table_len) = table_len else {
        return corrupt();
    };
    let mut spans = Vec::with_capacity(count as usize);
    let body = &payload[table_len..];
    // The columns' lengths before the sparse form (which may exceed the body's length);
    // each is checked against what is left of the stream as it is read.
    let mut total = 0usize;
    for k in 0..count as usize {
        let e = &payload[4 + 9 * k..4 + 9 * k + 9];
        let len = u64::from_le_bytes(e[..8].try_into().expect("8"));
        let sparse_max = body.len().saturating_mul(64);
        match usize::try_from(len) {
            Ok(l) if l <= sparse_max => total += l,
            _ => return corrupt(),
        }
        if total > sparse_max {
            return corrupt();
        }
    }
    // Written in place: a buffer kept from the last restore is not zeroed again.
    plain.resize(total, 0);
    let (mut at, mut from) = (0usize, 0usize);
    for k in 0..count as usize {
        let e = &payload[4 + 9 * k..4 + 9 * k + 9];
        let len = u64::from_le_bytes(e[..8].try_into().expect("8")) as usize;
        let code = e[8];
        let dst = &mut plain[at..at + len];
        let src = &body[from..];
        let used = if code & SPARSE != 0 && code != MIXED {
            let w = (code & !SPARSE) as usize;
            if planes(w as u8, len) == 1 {
                return bad("snapshot corrupted: a sparse column's width is not 2, 4 or 8");
            }
            from_sparse(src, dst, w)?
        } else {
            if len > src.len() {
                return corrupt();
            }
            match planes(code, len) {
                1 => dst.copy_from_slice(&src[..len]),
                w => from_planes(&src[..len], dst, w),
            }
            len
        };
        spans.push((at, at + len));
        at += len;
        from += used;
    }
    if from != body.len() {
        return corrupt();
    }
    Ok(spans)
}

impl<'a> Reader<'a> {
    /// A reader of `data` (from `unpack`) with its column spans.
    pub(crate) fn new(data: &'a [u8], spans: &[(usize, usize)], tag: u32) -> Reader<'a> {
        Reader {
            data,
            columns: spans
                .iter()
                .map(|&(at, end)| RColumn {
                    at,
                    end,
                    children: Vec::new(),
                    hint: 0,
                })
                .collect(),
            assigned: 1,
            cur: 0,
            left: data.len(),
            tag,
            spare: Default::default(),
        }
    }

    /// Makes the current column's child `name` current (the next column of the payload
    /// the first time the path is entered); returns the column to go back to (`leave`).
    /// Inlined for the usual case, the field after the last one entered.
    #[inline(always)]
    pub fn enter(&mut self, name: &'static str) -> ReadResult<u32> {
        let prev = self.cur;
        let c = &mut self.columns[prev as usize];
        if c.hint == c.children.len() {
            c.hint = 0;
        }
        if let Some(&(k, id)) = c.children.get(c.hint) {
            if k.as_ptr() == name.as_ptr() && k.len() == name.len() {
                c.hint += 1;
                self.cur = id;
                return Ok(prev);
            }
        }
        self.enter_other(name)?;
        Ok(prev)
    }

    /// `enter` when `name` is not the hinted child: looked up among the children, or the
    /// payload's next column the first time.
    #[inline(never)]
    fn enter_other(&mut self, name: &'static str) -> ReadResult<()> {
        let c = &mut self.columns[self.cur as usize];
        let n = c.children.len();
        self.cur = match find_child(&c.children, c.hint, name) {
            Some(k) => {
                c.hint = k + 1;
                c.children[k].1
            }
            None => {
                let id = self.assigned;
                c.children.push((name, id));
                c.hint = n + 1;
                if id as usize >= self.columns.len() {
                    return bad("snapshot corrupted: fewer columns than its content needs");
                }
                self.assigned += 1;
                id
            }
        };
        Ok(())
    }

    #[inline]
    pub fn leave(&mut self, prev: u32) {
        self.cur = prev;
    }

    /// Reads `f` from the child column `name`.
    #[inline]
    pub fn within<T>(&mut self, name: &'static str, f: impl FnOnce(&mut Reader<'a>) -> ReadResult<T>) -> ReadResult<T> {
        let p = self.enter(name)?;
        let v = f(self)?;
        self.leave(p);
        Ok(v)
    }

    #[inline(always)]
    pub fn take(&mut self, n: usize) -> ReadResult<&'a [u8]> {
        let c = &mut self.columns[self.cur as usize];
        if c.end - c.at < n {
            return ends_early(n, c.end - c.at);
        }
        let s = &self.data[c.at..c.at + n];
        c.at += n;
        self.left -= n;
        Ok(s)
    }

    /// `n` values of `width` bytes from the current column, as `n` calls of `take(width)`.
    #[inline]
    pub fn take_values(&mut self, n: usize, width: usize) -> ReadResult<&'a [u8]> {
        match n.checked_mul(width) {
            Some(len) => self.take(len),
            None => ends_early(
                usize::MAX,
                self.columns[self.cur as usize].end - self.columns[self.cur as usize].at,
            ),
        }
    }

    /// Bytes not read yet, over all columns.
    pub fn remaining(&self) -> usize {
        self.left
    }

    /// Every column paired and read to its end (nothing left over).
    pub(crate) fn finish(&self) -> ReadResult<()> {
        if self.assigned as usize != self.columns.len() || self.left != 0 {
            return bad(format!(
                "snapshot corrupted: {} of {} columns read, {} bytes left over",
                self.assigned,
                self.columns.len(),
                self.left
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Byte planes: value `i`'s byte `p` lands at `p * n + i`, and `from_planes` undoes it,
    /// for every width; a corrupted table's empty plane-stored column is no panic.
    #[test]
    fn planes_round_trip() {
        for w in [2usize, 4, 8] {
            let n = 37;
            let values: Vec<u8> = (0..n * w).map(|k| (k * 7 + 3) as u8).collect();
            let mut planed = vec![0; values.len()];
            to_planes(&values, &mut planed, w);
            for i in 0..n {
                for p in 0..w {
                    assert_eq!(planed[p * n + i], values[i * w + p]);
                }
            }
            let mut back = vec![0; values.len()];
            from_planes(&planed, &mut back, w);
            assert_eq!(back, values);
            from_planes(&[], &mut [], w);
            to_planes(&[], &mut [], w);
        }
    }

    /// Values of width `w`, `n` of them, about one in `every` non-zero (seeded, so the
    /// zero pattern crosses block and byte boundaries irregularly).
    fn sparse_values(n: usize, w: usize, every: u64, seed: u64) -> Vec<u8> {
        let mut x = seed;
        let mut out = Vec::with_capacity(n * w);
        for _ in 0..n {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let nonzero = (x >> 33) % every == 0;
            for p in 0..w {
                // A non-zero value has a non-zero byte, somewhere (here: its last).
                let b = if nonzero {
                    ((x >> (8 * (p % 4))) as u8) | (p == w - 1) as u8
                } else {
                    0
                };
                out.push(b);
            }
        }
        out
    }

    /// The sparse form: bitmap then non-zero values as byte planes, for every width, for
    /// lengths around the block and byte sizes and for all-zero and all-non-zero columns;
    /// `from_sparse` undoes it and reports the bytes it used.
    #[test]
    fn sparse_round_trip() {
        for w in [2usize, 4, 8] {
            for n in [0usize, 1, 7, 8, 9, 63, 64, 65, 200, 1000] {
                for every in [1u64, 3, 17, 1_000_000] {
                    let values = sparse_values(n, w, every, (n * w) as u64 + every);
                    let k = values.chunks(w).filter(|v| v.iter().any(|&b| b != 0)).count();
                    let len = n.div_ceil(8) + k * w;
                    let mut dst = vec![0xAA; len];
                    to_sparse(&values, &mut dst, w);
                    for i in 0..n {
                        let bit = dst[i / 8] >> (i % 8) & 1;
                        assert_eq!(bit == 1, values[i * w..i * w + w].iter().any(|&b| b != 0));
                    }
                    let mut back = vec![0x55; values.len()];
                    let mut src = dst.clone();
                    src.extend_from_slice(&[9, 9, 9]);
                    assert_eq!(from_sparse(&src, &mut back, w), Ok(len), "w {w} n {n} every {every}");
                    assert_eq!(back, values, "w {w} n {n} every {every}");
                }
            }
        }
    }

    /// The writer stores a mostly-zero plane column sparse and others as planes or as is,
    /// whichever is shorter, and `unpack` gives back every column's bytes.
    #[test]
    fn payload_round_trip_chooses_the_shorter_form() {
        let mut w = Writer::new();
        let zeros = sparse_values(1000, 4, 50, 1);
        let dense = sparse_values(1000, 4, 1, 2);
        w.within("zeros", |w| {
            w.values(zeros.chunks(4).map(|c| <[u8; 4]>::try_from(c).unwrap()))
        });
        w.within("dense", |w| {
            w.values(dense.chunks(4).map(|c| <[u8; 4]>::try_from(c).unwrap()))
        });
        w.within("bytes", |w| {
            w.bytes(&[1, 2]);
            w.bytes(&[3]);
        });
        let mut payload = Vec::new();
        w.finish(&mut payload);
        assert_eq!(payload.len(), w.raw_len());
        let code = |k: usize| payload[4 + 9 * k + 8];
        assert_eq!(code(1), 4 | SPARSE, "the mostly-zero column is sparse");
        assert_eq!(code(2), 4, "the dense column is byte planes");
        assert_eq!(code(3), MIXED);
        // The sparse column: a 125-byte bitmap and about 20 values of 4 bytes, not 4,000.
        let sparse = payload.len() - (4 + 9 * 4 + 4000 + 3);
        assert!(sparse < 125 + 4 * 60, "{sparse} bytes");
        let mut plain = Vec::new();
        let spans = unpack(&payload, &mut plain).unwrap();
        assert_eq!(&plain[spans[1].0..spans[1].1], &zeros[..]);
        assert_eq!(&plain[spans[2].0..spans[2].1], &dense[..]);
        assert_eq!(
            &plain[spans[3].0..spans[3].1],
            &[1, 2, 3],
            "values of mixed widths as is"
        );
    }

    /// A sparse column whose bitmap has bits past its last value, announces more values
    /// than the stream holds, or whose width is not 2, 4 or 8 is refused, never a panic.
    #[test]
    fn corrupted_sparse_columns_are_refused() {
        let values = sparse_values(13, 4, 3, 7);
        let k = values.chunks(4).filter(|v| v.iter().any(|&b| b != 0)).count();
        let mut sparse = vec![0; 2 + 4 * k];
        to_sparse(&values, &mut sparse, 4);
        let mut out = vec![0; values.len()];
        assert!(from_sparse(&sparse, &mut out, 4).is_ok());
        let mut stray = sparse.clone();
        stray[1] |= 0x80;
        assert!(from_sparse(&stray, &mut out, 4).is_err(), "a bit past the last value");
        let mut more = sparse.clone();
        more[0] = 0xFF;
        more[1] |= 0x1F;
        assert!(from_sparse(&more, &mut out, 4).is_err(), "more values than stored");
        assert!(from_sparse(&sparse[..1], &mut out, 4).is_err(), "a bitmap cut short");
        // The same column in a payload, with its code's width made 3 or 1.
        let mut payload = vec![1, 0, 0, 0];
        payload.extend_from_slice(&(values.len() as u64).to_le_bytes());
        payload.push(4 | SPARSE);
        payload.extend_from_slice(&sparse);
        let mut plain = Vec::new();
        assert!(unpack(&payload, &mut plain).is_ok());
        for bad in [3 | SPARSE, 1 | SPARSE, 16 | SPARSE] {
            payload[12] = bad;
            assert!(unpack(&payload, &mut plain).is_err(), "code {bad}");
        }
        payload[12] = 4 | SPARSE;
        payload.push(0);
        assert!(unpack(&payload, &mut plain).is_err(), "a byte left over");
        payload.pop();
        // Lengths beyond 64 times the column data are refused before anything is
        // allocated; up to it, the bitmap decides.
        let body = (payload.len() - 13) as u64;
        for (len, ok) in [(64 * body + 4, false), (u64::MAX, false), (values.len() as u64, true)] {
            payload[4..12].copy_from_slice(&len.to_le_bytes());
            let got = unpack(&payload, &mut plain);
            assert_eq!(got.is_ok(), ok, "length {len}");
            if !ok {
                assert!(got.unwrap_err().0.contains("column table"), "length {len}");
            }
        }
    }
}
