//! The file's buffer data, and the budget of what accessors may read out of it: a few kilobytes of
//! JSON can point a thousand primitives (or a billion instances) at one accessor, or declare an
//! accessor without a buffer view (all zeros) of any count, so reads are counted against the data.
//!
//! Each accessor read is charged the bytes it allocates; the whole file may read
//! `READ_PER_BYTE` times its buffer bytes plus `READ_ALLOWANCE`, far above what real files need
//! (each accessor is read about once), far below what exhausts memory.

use std::cell::Cell;
use std::ops::Deref;

use super::error::AccessorError;

/// Bytes the accessors may read per byte of buffer data.
const READ_PER_BYTE: usize = 64;
/// Bytes the accessors may read whatever the buffers hold (bufferless accessors, small files).
const READ_ALLOWANCE: usize = 16 << 20;

/// Buffer data (index: the glTF buffer) with what may still be read from it.
pub(super) struct Buffers {
    data: Vec<Vec<u8>>,
    left: Cell<usize>,
}

impl Buffers {
    pub(super) fn new(data: Vec<Vec<u8>>) -> Self {
        let bytes: usize = data.iter().map(Vec::len).sum();
        let left = bytes
            .saturating_mul(READ_PER_BYTE)
            .saturating_add(READ_ALLOWANCE);
        Self {
            data,
            left: Cell::new(left),
        }
    }

    /// Charges a read of `count` elements of `size` bytes (what it allocates) to the budget, or
    /// refuses it before anything is allocated.
    pub(super) fn charge(
        &self,
        name: &str,
        count: usize,
        size: usize,
    ) -> Result<(), AccessorError> {
        let bytes = count.saturating_mul(size.max(1));
        match self.left.get().checked_sub(bytes) {
            Some(rest) => {
                self.left.set(rest);
                Ok(())
            }
            None => Err(AccessorError::Budget {
                name: name.to_owned(),
                count,
            }),
        }
    }
}

impl Deref for Buffers {
    type Target = [Vec<u8>];

    fn deref(&self) -> &[Vec<u8>] {
        &self.data
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_are_charged_until_the_budget_is_spent() {
        let b = Buffers::new(vec![vec![0; 1000]]);
        let budget = 1000 * READ_PER_BYTE + READ_ALLOWANCE;
        assert!(b.charge("a", budget / 16, 16).is_ok());
        let e = b.charge("accessor 7", 1, 16).unwrap_err().to_string();
        assert!(e.contains("accessor 7"), "{e}");
        assert!(b.charge("a", usize::MAX, 64).is_err());
        assert_eq!(b.len(), 1);
    }
}
