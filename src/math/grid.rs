//! Facts about the N×N grids shared by the cascades, the FFTs and the world queries: which
//! sizes are valid, the signed wave index of a grid index, and the buffer index convention
//! (sample (i, j) at index `j * N + i`, z the row).

use crate::error::Error;

/// Smallest grid size N.
pub(crate) const MIN_SIZE: usize = 4;

/// Largest grid size N: a 4096² cascade holds about 1.5 GiB.
pub(crate) const MAX_SIZE: usize = 4096;

/// Checks a grid size `name`: even, [`MIN_SIZE`] ≤ N ≤ [`MAX_SIZE`].
pub(crate) fn check_size(name: &'static str, size: usize) -> Result<usize, Error> {
    if !(MIN_SIZE..=MAX_SIZE).contains(&size) || !size.is_multiple_of(2) {
        return Err(Error::InvalidSize {
            name,
            size,
            min: MIN_SIZE,
            max: MAX_SIZE,
        });
    }
    Ok(size)
}

/// The default memory limit of a cascade, an ocean or an [`Fft2d`](crate::inspect::Fft2d): 4 GiB
/// (or the whole address space on targets with narrower pointers).
pub(crate) const DEFAULT_MEMORY_LIMIT: usize = (u32::MAX as usize).saturating_add(1);

/// Checks that `bytes` is within `limit`.
pub(crate) fn check_memory(bytes: usize, limit: usize) -> Result<(), Error> {
    if bytes > limit {
        return Err(Error::MemoryLimit { bytes, limit });
    }
    Ok(())
}

/// Signed wave-number index of grid index `i` on an N grid (plain FFT order).
#[inline]
pub(crate) fn wave_index(i: usize, n: usize) -> i32 {
    if i < n / 2 {
        i as i32
    } else {
        i as i32 - n as i32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wave_index_is_plain_fft_order() {
        let n = 8;
        let m: Vec<i32> = (0..n).map(|i| wave_index(i, n)).collect();
        assert_eq!(m, vec![0, 1, 2, 3, -4, -3, -2, -1]);
    }
}
