//! Wakes: a window of linear free-surface waves around a point the game chooses, in which
//! hulls make Kelvin wakes, evolved exactly with the ocean's dispersion and added to every
//! world query inside the window. Its config and hulls, its simulation (a tick at a time, in
//! its own clock), its transforms, and the buffers the queries and a renderer read. The ocean
//! ([`crate::ocean`]) owns it and advances it on its one path through time.

mod config;
mod fft;
pub(crate) mod sim;
#[cfg(test)]
mod tests;
mod window;

pub use config::{Hull, WakeConfig};
pub use window::Wakes;
