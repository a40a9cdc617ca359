//! The payload's column layout: every value is written into the column (stream) named by
//! the path of struct fields that leads to it (`bodies` › `xf` › `p`), so the values of one
//! field of every body sit together. Counts, option flags, enum tags, pool slot counters
//! and map keys and values each get a column of their own under their parent. A column
//! whose values all have one width (2, 4 or 8 bytes) is stored as byte planes (every
//! value's first byte, then every second byte, …): equal fields (masses, inertias, zero
//! velocities of sleeping bodies, sign and exponent bytes of nearby positions) become long
//! runs that the zstd stage after this one shrinks.
//!
//! A column is known by its path only while writing; the payload lists the columns in the
//! order the writer first entered them, and the reader, which walks the same structure in
//! the same order, gives each path it enters the next column of the list. Both sides
//! compare field names, never addresses, so the pairing does not depend on how the
//! compiler laid out the code.

use super::{bad, ReadResult};

/// Width marker of a column whose values differ in width (stored as is).
const MIXED: u8 = 0xFF;

#[derive(Default)]
struct WColumn {
    bytes: Vec<u8>,
    /// 0: nothing written yet; the width of every value written; or `MIXED`.
    width: u8,
    children: Vec<(&'static str, u32)>,
    /// Where the next lookup among `children` starts (fields are entered in order).
    hint: usize,
}

/// Appends little-endian values to the columns of a payload.
pub struct Writer {
    /// The payload's columns are `columns[..used]`; the rest are columns of an earlier
    /// payload kept for their capacity (`clear`).
    columns: Vec<WColumn>,
    used: u32,
    cur: u32,
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
        let c = &mut self.columns[self.cur as usize];
        let start = c.bytes.len();
        // Internal iteration: the chains of maps, filters and flat maps that lead here fold
        // far faster than they step.
        values.for_each(|v| c.bytes.extend_from_slice(&v));
        if c.bytes.len() > start && c.width != W as u8 {
            c.width = if c.width == 0 { W as u8 } else { MIXED };
        }
    }

    /// Appends groups of values of one width (`W` bytes each, `B / W` per group) to the
    /// current column: a vector's components in order, as `values` would append them one
    /// by one.
    #[inline]
    pub fn value_groups<const W: usize, const B: usize>(&mut self, groups: impl Iterator<Item = [u8; B]>) {
        let c = &mut self.columns[self.cur as usize];
        let start = c.bytes.len();
        groups.for_each(|v| c.bytes.extend_from_slice(&v));
        if c.bytes.len() > start && c.width != W as u8 {
            c.width = if c.width == 0 { W as u8 } else { MIXED };
        }
    }

    /// Bytes the payload takes before compression.
    pub fn raw_len(&self) -> usize {
        4 + 9 * self.live().len() + self.live().iter().map(|c| c.bytes.len()).sum::<usize>()
    }

    /// Replaces `out`'s content with the payload: the column count (`u32`), each column's length (`u64`)
    /// and width (`u8`: 2, 4 or 8 for byte planes, otherwise stored as is), then the
    /// columns in order.
    pub fn finish(&self, out: &mut Vec<u8>) {
        // Sized once and written in place: a buffer reused from the last payload of about
        // this size is neither cleared nor zeroed again.
        out.resize(self.raw_len(), 0);
        let live = self.live();
        out[..4].copy_from_slice(&(live.len() as u32).to_le_bytes());
        for (k, c) in live.iter().enumerate() {
            let e = &mut out[4 + 9 * k..4 + 9 * k + 9];
            e[..8].copy_from_slice(&(c.bytes.len() as u64).to_le_bytes());
            e[8] = c.width;
        }
        let mut at = 4 + 9 * live.len();
        for c in live {
            let dst = &mut out[at..at + c.bytes.len()];
            match planes(c.width, c.bytes.len()) {
                1 => dst.copy_from_slice(&c.bytes),
                w => to_planes(&c.bytes, dst, w),
            }
            at += c.bytes.len();
        }
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
            let one = Writer {
                columns: vec![WColumn {
                    bytes: c.bytes.clone(),
                    width: c.width,
                    children: Vec::new(),
                    hint: 0,
                }],
                used: 1,
                cur: 0,
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

/// Splits `values` (of width `w`: 2, 4 or 8) into byte planes in `dst` (same length): every
/// value's first byte, then every second byte, and so on.
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

            /// Byte planes of the little-endian values in `values`, into `dst`.
            pub(super) fn split(values: &[u8], dst: &mut [u8]) {
                let n = values.len() / W;
                let mut words = [0 as $t; BLOCK];
                let mut plane = [0u8; BLOCK];
                for (b, chunk) in values.chunks(BLOCK * W).enumerate() {
                    let (i, k) = (b * BLOCK, chunk.len() / W);
                    for (x, v) in words.iter_mut().zip(chunk.chunks_exact(W)) {
                        *x = <$t>::from_le_bytes(v.try_into().expect("W bytes"));
                    }
                    for p in 0..W {
                        for (y, x) in plane.iter_mut().zip(&words) {
                            *y = (x >> (8 * p)) as u8;
                        }
                        dst[p * n + i..p * n + i + k].copy_from_slice(&plane[..k]);
                    }
                }
            }

            /// Little-endian values from the byte planes in `src`, into `dst`.
            pub(super) fn join(src: &[u8], dst: &mut [u8]) {
                let n = src.len() / W;
                let mut words = [0 as $t; BLOCK];
                for (b, chunk) in dst.chunks_mut(BLOCK * W).enumerate() {
                    let (i, k) = (b * BLOCK, chunk.len() / W);
                    words.fill(0);
                    for p in 0..W {
                        for (x, &y) in words.iter_mut().zip(&src[p * n + i..p * n + i + k]) {
                            *x |= (y as $t) << (8 * p);
                        }
                    }
                    for (v, x) in chunk.chunks_exact_mut(W).zip(&words) {
                        v.copy_from_slice(&x.to_le_bytes());
                    }
                }
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
    let mut at = 0usize;
    let body = &payload[table_len..];
    // Written in place: a buffer kept from the last restore is not zeroed again.
    plain.resize(body.len(), 0);
    for k in 0..count as usize {
        let e = &payload[4 + 9 * k..4 + 9 * k + 9];
        let len = u64::from_le_bytes(e[..8].try_into().expect("8"));
        let len = match usize::try_from(len) {
            Ok(l) if l <= body.len() - at => l,
            _ => return corrupt(),
        };
        let (src, dst) = (&body[at..at + len], &mut plain[at..at + len]);
        match planes(e[8], len) {
            1 => dst.copy_from_slice(src),
            w => from_planes(src, dst, w),
        }
        spans.push((at, at + len));
        at += len;
    }
    if at != body.len() {
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
}
