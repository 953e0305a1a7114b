//! Wakes: a window of linear free-surface waves around a point the game chooses, in which
//! hulls make Kelvin wakes, evolved exactly with the ocean's dispersion and added to every
//! world query inside the window. Its config and hulls, its simulation (a tick at a time, in
//! its own clock), its transforms, and the buffers the queries and a renderer read. The ocean
//! ([`crate::ocean`]) owns it and advances it on its one path through time.

mod config;
mod fft;
mod foam;
pub(crate) mod sim;
#[cfg(test)]
mod tests;
mod window;

pub use config::{Hull, WakeConfig};
pub use window::Wakes;

/// The smooth bump (1 − u²)³ on |u| < 1, 0 outside: the waterplane's shape along each axis
/// (zero with its first two derivatives at the ends).
#[inline(always)]
pub(crate) fn bump(u: f32) -> f32 {
    let w = 1.0 - u * u;
    if w > 0.0 {
        w * w * w
    } else {
        0.0
    }
}
