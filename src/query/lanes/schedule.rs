//! Which points the lanes take and when ([`locate`]): a lane takes the batch's next point as
//! its search ends, or a query of heights alone reads them with its searches; the results are
//! written eight at a time.

use super::evaluate::{evaluate, foam};
use super::search::{Found, Guesses, Searches};
use super::shuffle::Shuffle;
use super::{each, LANES};
use crate::query::frame::Fields;
use crate::query::results::{surface, SurfaceSample};

/// A batch's result for one point, from what its search found.
pub(crate) trait FromFound: Sized {
    fn from_found(found: Found) -> Self;
}

impl FromFound for f32 {
    #[inline(always)]
    fn from_found(found: Found) -> f32 {
        found.height
    }
}

impl FromFound for SurfaceSample {
    #[inline(always)]
    fn from_found(found: Found) -> SurfaceSample {
        surface(found.height, found.displacement, found.slope, found.foam)
    }
}

/// Each of `points` located and its result written into `out`, eight points at a time.
/// A query of heights alone (`HEIGHT` without `SLOPE`) reads them with its search (see
/// [`heights_with_search`]); otherwise lanes take the next point as their searches end (see
/// [`refilling`]) and, with `SLOPE`, eight found points at a time, the height (with
/// `HEIGHT`), the slope and the foam are read where they were found. Each result has the
/// bits of its single query.
#[inline(always)]
pub(crate) fn locate<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    out: &mut [T],
) {
    let mut ended = Ended::EMPTY;
    if HEIGHT && !SLOPE {
        heights_with_search::<S, T, HEIGHT, SLOPE>(shuffle, fields, points, &mut ended, out);
    } else {
        refilling::<S, T, HEIGHT, SLOPE>(shuffle, fields, points, &mut ended, out);
    }
    let count = ended.count;
    finish::<S, T, HEIGHT, SLOPE>(
        shuffle,
        fields,
        &mut ended.found[..count],
        &ended.at[..count],
        out,
    );
}

/// The searches for `points`, eight at a time from their first guesses, each lane taking
/// the batch's next point when its search ends (so that a group does not wait for its
/// slowest point); no heights are read.
#[inline(always)]
fn refilling<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    ended: &mut Ended,
    out: &mut [T],
) {
    let mut searches = Searches::new();
    // The points not yet started, eight at a time with their first guesses.
    let mut chunks = points.chunks(LANES).enumerate();
    let mut next = Guesses::EMPTY;
    loop {
        for l in 0..LANES {
            if searches.point[l].is_none() {
                if next.taken == next.count {
                    if let Some((c, chunk)) = chunks.next() {
                        next = Guesses::of(shuffle, fields, chunk, c * LANES);
                    }
                }
                if next.taken < next.count {
                    searches.start(l, &next, next.taken);
                    next.taken += 1;
                }
            }
        }
        if searches.point.iter().all(Option::is_none) {
            break;
        }
        // (Calls, not a closure: a closure out of line would run without the SIMD level.)
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut searches, false, ended, out);
    }
}

/// The searches for `points` of a query of heights alone, eight points at a time: their
/// first guesses, an evaluation of the displacement and its Jacobian at each (after which
/// a search almost never ends, so the heights are not read there) and a second that reads
/// the heights too. The searches that go on (about one in twelve on the default sea) move
/// to a second set of lanes, evaluated with the heights whenever all its lanes are busy and
/// at the end. Each search keeps its best iterate's height; [`finish`] reads it for one
/// whose best iterate was evaluated without it.
#[inline(always)]
fn heights_with_search<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    ended: &mut Ended,
    out: &mut [T],
) {
    let mut stragglers = Searches::new();
    for (c, chunk) in points.chunks(LANES).enumerate() {
        let mut searches = Searches::begin(&Guesses::of(shuffle, fields, chunk, c * LANES));
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut searches, false, ended, out);
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut searches, true, ended, out);
        for l in 0..LANES {
            if searches.point[l].is_none() {
                continue;
            }
            let to = loop {
                if let Some(to) = stragglers.point.iter().position(Option::is_none) {
                    break to;
                }
                advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut stragglers, true, ended, out);
            };
            searches.hand_over(l, &mut stragglers, to);
        }
    }
    while stragglers.point.iter().any(Option::is_some) {
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut stragglers, true, ended, out);
    }
}

/// One evaluation of the busy lanes of `searches` (the height too if `read`), their
/// searches' updates, and the ended ones' results handed to `ended`.
#[inline(always)]
fn advance<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    searches: &mut Searches,
    read: bool,
    ended: &mut Ended,
    out: &mut [T],
) {
    let Some(busy) = searches.point.iter().position(Option::is_some) else {
        return;
    };
    // An idle lane evaluates a busy lane's iterate (any point the tiles cover would do).
    for l in 0..LANES {
        if searches.point[l].is_none() {
            for k in 0..2 {
                searches.next[k][l] = searches.next[k][busy];
            }
            searches.factors[l] = searches.factors[busy];
        }
    }
    let frame = fields.frame();
    let cascades = 0..frame.grids.len();
    let (at, factors) = (
        &searches.next,
        frame.coast.is_some().then_some(&searches.factors),
    );
    let summed = if read {
        evaluate::<S, true, true, true, false>(shuffle, fields, at, cascades, factors)
    } else {
        evaluate::<S, true, true, false, false>(shuffle, fields, at, cascades, factors)
    };
    let query = &frame.query;
    let done = searches.update(
        &summed,
        HEIGHT && !SLOPE,
        read,
        query.tolerance,
        query.max_iterations,
    );
    for l in 0..LANES {
        if done[l] {
            if let Some(index) = searches.point[l].take() {
                ended.push::<S, T, HEIGHT, SLOPE>(shuffle, fields, searches.found(l), index, out);
            }
        }
    }
}

/// Searches ended whose results are not yet written: what each found, and its point's
/// index in the batch.
struct Ended {
    found: [Found; LANES],
    at: [usize; LANES],
    count: usize,
}

impl Ended {
    const EMPTY: Ended = Ended {
        found: [Found::EMPTY; LANES],
        at: [0; LANES],
        count: 0,
    };

    /// Adds what the search for point `index` found, writing the results held so far first
    /// (see [`finish`]) if there are [`LANES`] of them.
    #[inline(always)]
    fn push<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
        &mut self,
        shuffle: S,
        fields: &Fields<'_>,
        found: Found,
        index: usize,
        out: &mut [T],
    ) {
        if self.count == LANES {
            finish::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut self.found, &self.at, out);
            self.count = 0;
        }
        self.found[self.count] = found;
        self.at[self.count] = index;
        self.count += 1;
    }
}

/// Reads the height (with `HEIGHT`), slope and foam at the points `found` (at most
/// [`LANES`]) when the query asks for the slope (`SLOPE`), or the height alone if a search
/// did not read it at its best iterate, and writes each result to `out[found_at[i]]`.
#[inline(always)]
fn finish<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    found: &mut [Found],
    found_at: &[usize],
    out: &mut [T],
) {
    if found.is_empty() {
        return;
    }
    if SLOPE || (HEIGHT && found.iter().any(|f| !f.height_read)) {
        let at = [
            each(|l| found.get(l).unwrap_or(&found[0]).location.undisplaced[0]),
            each(|l| found.get(l).unwrap_or(&found[0]).location.undisplaced[1]),
        ];
        let cascades = 0..fields.frame().grids.len();
        let factors = fields
            .frame()
            .coast
            .is_some()
            .then(|| each(|l| found.get(l).unwrap_or(&found[0]).factors));
        let f = factors.as_ref();
        let sums = evaluate::<S, false, false, HEIGHT, SLOPE>(shuffle, fields, &at, cascades, f);
        // The foam comes with the slope (a surface sample).
        let foam = if SLOPE {
            foam(fields, &at)
        } else {
            [0.0; LANES]
        };
        for (l, found) in found.iter_mut().enumerate() {
            if HEIGHT {
                found.height = sums.height[l];
            }
            if SLOPE {
                found.slope = [sums.slope[0][l], sums.slope[1][l]];
                found.foam = foam[l];
            }
        }
    }
    for (found, &index) in found.iter().zip(found_at) {
        out[index] = T::from_found(*found);
    }
}
