//! The leaf utilities every stage of the data flow uses and none of which uses a stage: the
//! determinism modes and their transcendental functions, the SIMD dispatch, the crate's own
//! exponential, the per-wave-vector random numbers, the row FFTs and transposes, the grid
//! conventions, and periodic grid cells.

pub(crate) mod determinism;
pub(crate) mod exp;
pub(crate) mod fft2d;
pub(crate) mod grid;
pub(crate) mod periodic;
pub(crate) mod rng;
pub(crate) mod simd;
