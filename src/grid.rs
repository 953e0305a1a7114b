//! Facts about the N×N grids shared by the cascades, the FFTs and the world queries: which
//! sizes are valid, the signed wave index of a grid index, and the buffer index convention
//! (sample (i, j) at index `j * N + i`, z the row).

use crate::error::Error;
use crate::MAX_SIZE;

/// Checks a grid size: even, at least 4, at most [`MAX_SIZE`].
pub(crate) fn check_size(size: usize) -> Result<usize, Error> {
    if size < 4 || size % 2 != 0 || size > MAX_SIZE {
        return Err(Error::InvalidSize { size });
    }
    Ok(size)
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
