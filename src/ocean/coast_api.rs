//! The ocean's coast: its depth map and the waves' factors over it.

use std::sync::Arc;

use super::OceanState;
use crate::coast::{self, Coast, CoastField, DepthMap};
use crate::error::Error;

impl OceanState {
    /// Sets the depth of the water over a rectangle of the world (`None`: the open sea
    /// everywhere, as without a map). The waves of each cascade shoal and break over it
    /// (see [`CoastField`] and docs/theory.md, "Coasts"); every world query and the foam
    /// carry it. Solved here, once (3–4 s for a 512² map on one core of a 2026 server
    /// CPU: docs/performance.md, "Coasts"), for the ocean's spectrum and cascades as they
    /// are now, not at each step.
    ///
    /// A map set while a previous one (or none) is in use blends into it over
    /// [`coast::BLEND_SECONDS`] of simulated time from now, so that a harbour built or a
    /// tide (a uniform change of depth) shows no pop. Moving the time back before that
    /// (`set_time`, `restore`) ends the blend: the map set last holds.
    ///
    /// **Weather.** A change of weather
    /// ([`set_spectrum`](Self::set_spectrum)) does not solve the map again: the solve takes
    /// about 35 default steps for a 512² map (docs/performance.md, "Coasts"), which a game
    /// ramping the weather each frame cannot spend,
    /// and the change draws its new waves over several steps. The factors of the sea the map
    /// was set under stay in use (their breaking limits the heights to the depth whatever
    /// the sea, but the surf zone's width and Q_b are the old sea's); call `set_depth_map`
    /// again with the same map once the change has ended
    /// ([`Diagnostics::transition_progress`](super::Diagnostics::transition_progress) is
    /// `None`), and the new sea's factors blend in over 2 s.
    ///
    /// **Snapshots** ([`OceanSnapshot`](crate::OceanSnapshot)) do not carry the map (it is
    /// world data the game owns, and costly to solve): `restore` keeps the ocean's current
    /// map; set it again after restoring into an ocean that has none.
    ///
    /// Over land (depth ≤ 0) the queries answer the still water level: height 0, no
    /// displacement, flat; [`Water::depth_at`](crate::Water::depth_at) says where that is.
    ///
    /// # Errors
    /// Those of [`DepthMap::validate`]; [`Error::OutOfMemory`] if the system refuses the
    /// factors' room. Nothing changes then.
    pub fn set_depth_map(&mut self, map: Option<DepthMap>) -> Result<(), Error> {
        let field = match map {
            Some(map) => {
                map.validate()?;
                Some(Arc::new(coast::solve(
                    map,
                    &self.spectrum,
                    &self.cascades,
                    self.config.determinism,
                )?))
            }
            None => None,
        };
        let previous = self
            .frames
            .current
            .coast
            .as_ref()
            .and_then(|c| c.current.clone());
        let coast = if field.is_none() && previous.is_none() {
            None
        } else {
            Some(Coast::new(field, previous, self.time))
        };
        self.frames.set_coast(coast);
        Ok(())
    }

    /// The waves over the current depth map (`None` without one); public as
    /// [`Textures::coast`](crate::gpu::Textures::coast).
    pub(crate) fn coast_field(&self) -> Option<&CoastField> {
        self.coast_state().and_then(|c| c.current.as_deref())
    }

    /// The coast the queries read (the current field and the one it replaces), if any.
    pub(crate) fn coast_state(&self) -> Option<&Coast> {
        self.frames.current.coast.as_ref()
    }
}
