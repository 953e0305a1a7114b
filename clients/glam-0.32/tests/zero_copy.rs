//! ocean-fft's buffers as glam 0.32 types (the glam of Bevy 0.19 and godot-core), without
//! copying.

#[path = "../../zero_copy.rs"]
mod zero_copy;
