//! Eight Newton searches at once, one a lane ([`Searches`]): the first guesses of eight
//! points ([`Guesses`]), each lane's update with the single query's operations, and what
//! each search found ([`Found`]).

use super::evaluate::{coast_factors, evaluate, SummedLanes};
use super::shuffle::Shuffle;
use super::{each, F32s, F64s, LANES};
use crate::cascade::MAX_CASCADES;
use crate::coast::Factors;
use crate::query::frame::Fields;
use crate::query::inversion::{guessing, MIN_DETERMINANT};
use crate::query::results::Location;

/// `newton_step` lane by lane: the Newton step δ solving (I + ∇D) δ = `residual` for the
/// Jacobian `j`, or `residual` itself where the surface (nearly) folds.
#[inline(always)]
fn newton_steps(residual: &[F64s; 2], j: &[F32s; 4]) -> [F64s; 2] {
    let a: F64s = each(|l| 1.0 + f64::from(j[0][l]));
    let b: F64s = each(|l| f64::from(j[1][l]));
    let c: F64s = each(|l| f64::from(j[2][l]));
    let d: F64s = each(|l| 1.0 + f64::from(j[3][l]));
    let determinant: F64s = each(|l| a[l] * d[l] - b[l] * c[l]);
    let newton: [bool; LANES] = each(|l| determinant[l] > MIN_DETERMINANT);
    [
        each(|l| {
            let s = (d[l] * residual[0][l] - b[l] * residual[1][l]) / determinant[l];
            if newton[l] {
                s
            } else {
                residual[0][l]
            }
        }),
        each(|l| {
            let s = (a[l] * residual[1][l] - c[l] * residual[0][l]) / determinant[l];
            if newton[l] {
                s
            } else {
                residual[1][l]
            }
        }),
    ]
}

/// Up to eight points about to be searched for, with their first guesses.
pub(super) struct Guesses {
    /// The batch index of the first, how many there are, and how many were given a lane.
    pub(super) first: usize,
    pub(super) count: usize,
    pub(super) taken: usize,
    pub(super) target: [[f64; 2]; LANES],
    /// Each one's first guess `[x, z]` (`first_guess`, lane by lane).
    pub(super) start: [F64s; 2],
    /// The coast's factors at each target (`None`: no depth map).
    pub(super) factors: Option<[Factors; LANES]>,
}

impl Guesses {
    pub(super) const EMPTY: Guesses = Guesses {
        first: 0,
        count: 0,
        taken: 0,
        target: [[0.0; 2]; LANES],
        start: [[0.0; LANES]; 2],
        factors: None,
    };

    /// The first guesses of `points` (at most [`LANES`], the first being the batch's point
    /// `first`): one Newton step on the larger cascades, less the smaller cascades'
    /// displacement there, with the single query's operations.
    #[inline(always)]
    pub(super) fn of<S: Shuffle>(
        shuffle: S,
        fields: &Fields<'_>,
        points: &[[f64; 2]],
        first: usize,
    ) -> Guesses {
        let target: [[f64; 2]; LANES] =
            std::array::from_fn(|l| *points.get(l).unwrap_or(&points[0]));
        let at = [each(|l| target[l][0]), each(|l| target[l][1])];
        let count = fields.frame().grids.len();
        let cascades = guessing(count);
        let rest = cascades.end..count;
        let factors = coast_factors(fields, &at);
        let f = factors.as_ref();
        let summed = evaluate::<S, true, true, false, false>(shuffle, fields, &at, cascades, f);
        let d = &summed.displacement;
        let residual = [each(|l| -f64::from(d[0][l])), each(|l| -f64::from(d[1][l]))];
        let step = newton_steps(&residual, &summed.jacobian);
        let stepped = [
            each(|l| at[0][l] + step[0][l]),
            each(|l| at[1][l] + step[1][l]),
        ];
        let short = evaluate::<S, true, false, false, false>(shuffle, fields, &stepped, rest, f);
        let d = &short.displacement;
        Guesses {
            first,
            count: points.len(),
            taken: 0,
            target,
            start: [
                each(|l| stepped[0][l] - f64::from(d[0][l])),
                each(|l| stepped[1][l] - f64::from(d[1][l])),
            ],
            factors,
        }
    }
}

/// The Newton searches of up to [`LANES`] points, one a lane (see
/// [`inversion`](crate::query::inversion)'s `Search`, whose update each lane runs), and the fields
/// at each one's best iterate.
pub(super) struct Searches {
    /// The point each lane searches for (an index into the batch), or `None`.
    pub(super) point: [Option<usize>; LANES],
    /// Evaluations each lane's search has made.
    iteration: [usize; LANES],
    target: [F64s; 2],
    /// The iterate to evaluate next.
    pub(super) next: [F64s; 2],
    base: [F64s; 2],
    step: [F64s; 2],
    fraction: F64s,
    best: [F64s; 2],
    miss: F32s,
    iterations: [usize; LANES],
    converged: [bool; LANES],
    /// The summed displacement at the best iterate.
    displacement: [F32s; 2],
    /// The summed height at the best iterate, where `height_read`.
    height: F32s,
    /// Whether the evaluation of the best iterate read the height.
    height_read: [bool; LANES],
    /// The coast's factors at each lane's target (all 1 without a depth map: unread).
    pub(super) factors: [Factors; LANES],
}

/// What a search found: where the water at a point comes from, and the summed fields there
/// (the height and slope once read).
#[derive(Clone, Copy)]
pub(crate) struct Found {
    pub(super) location: Location,
    pub(super) displacement: [f32; 2],
    pub(super) height: f32,
    /// Whether `height` was read (with the search or after it).
    pub(super) height_read: bool,
    pub(super) slope: [f32; 2],
    /// Foam coverage in [0, 1] (with the slope).
    pub(super) foam: f32,
    /// The coast's factors at the target (all 1 without a depth map: unread).
    pub(super) factors: Factors,
}

impl Found {
    pub(super) const EMPTY: Found = Found {
        location: Location {
            undisplaced: [0.0; 2],
            miss: f32::INFINITY,
            iterations: 0,
            converged: false,
        },
        displacement: [0.0; 2],
        height: 0.0,
        height_read: false,
        slope: [0.0; 2],
        foam: 0.0,
        factors: [1.0; MAX_CASCADES],
    };
}

impl Searches {
    pub(super) fn new() -> Searches {
        let zero = [[0.0; LANES]; 2];
        Searches {
            point: [None; LANES],
            iteration: [0; LANES],
            target: zero,
            next: zero,
            base: zero,
            step: zero,
            fraction: [1.0; LANES],
            best: zero,
            miss: [f32::INFINITY; LANES],
            iterations: [0; LANES],
            converged: [false; LANES],
            displacement: [[0.0; LANES]; 2],
            height: [0.0; LANES],
            height_read: [false; LANES],
            factors: [[1.0; MAX_CASCADES]; LANES],
        }
    }

    /// The searches of the points `guesses` holds, one a lane from lane 0 (`Search::new`
    /// of each).
    #[inline(always)]
    pub(super) fn begin(guesses: &Guesses) -> Searches {
        let mut searches = Searches::new();
        searches.point = each(|l| (l < guesses.count).then_some(guesses.first + l));
        for k in 0..2 {
            searches.target[k] = each(|l| guesses.target[l][k]);
            searches.next[k] = guesses.start[k];
            searches.base[k] = guesses.start[k];
            searches.best[k] = guesses.start[k];
        }
        if let Some(factors) = guesses.factors {
            searches.factors = factors;
        }
        searches
    }

    /// Starts lane `l` on the point `guesses` holds at `p` (`Search::new`).
    #[inline(always)]
    pub(super) fn start(&mut self, l: usize, guesses: &Guesses, p: usize) {
        self.point[l] = Some(guesses.first + p);
        self.iteration[l] = 0;
        for k in 0..2 {
            self.target[k][l] = guesses.target[p][k];
            self.next[k][l] = guesses.start[k][p];
            self.base[k][l] = guesses.start[k][p];
            self.step[k][l] = 0.0;
            self.best[k][l] = guesses.start[k][p];
        }
        self.fraction[l] = 1.0;
        self.miss[l] = f32::INFINITY;
        self.iterations[l] = 0;
        self.converged[l] = false;
        self.height_read[l] = false;
        if let Some(factors) = &guesses.factors {
            self.factors[l] = factors[p];
        }
    }

    /// Moves lane `l`'s search to lane `to` of `other` (whose lane `to` is idle).
    #[inline(always)]
    pub(super) fn hand_over(&mut self, l: usize, other: &mut Searches, to: usize) {
        other.point[to] = self.point[l].take();
        other.iteration[to] = self.iteration[l];
        for k in 0..2 {
            other.target[k][to] = self.target[k][l];
            other.next[k][to] = self.next[k][l];
            other.base[k][to] = self.base[k][l];
            other.step[k][to] = self.step[k][l];
            other.best[k][to] = self.best[k][l];
            other.displacement[k][to] = self.displacement[k][l];
        }
        other.fraction[to] = self.fraction[l];
        other.miss[to] = self.miss[l];
        other.iterations[to] = self.iterations[l];
        other.converged[to] = self.converged[l];
        other.height[to] = self.height[l];
        other.height_read[to] = self.height_read[l];
        other.factors[to] = self.factors[l];
    }

    /// Takes the sums at each lane's iterate, and sets the iterate after it; returns which
    /// lanes' searches ended. With `track` (a query of heights alone) each search keeps the
    /// height at its best iterate, which the sums hold if `read`.
    #[inline(always)]
    pub(super) fn update(
        &mut self,
        summed: &SummedLanes,
        track: bool,
        read: bool,
        tolerance: f32,
        max: usize,
    ) -> [bool; LANES] {
        let (d, j) = (&summed.displacement, &summed.jacobian);
        let mut residual = [[0.0f64; LANES]; 2];
        for k in 0..2 {
            residual[k] = each(|l| self.target[k][l] - (self.next[k][l] + f64::from(d[k][l])));
        }
        // A correctly rounded square root, as the single query's.
        let miss: F32s = each(|l| {
            let [rx, rz] = [residual[0][l], residual[1][l]];
            (rx * rx + rz * rz).sqrt() as f32
        });
        let step = newton_steps(&residual, j);
        let better: [bool; LANES] = each(|l| miss[l] < self.miss[l]);
        let converged: [bool; LANES] = each(|l| miss[l] < tolerance);
        for k in 0..2 {
            self.best[k] = each(|l| {
                if better[l] {
                    self.next[k][l]
                } else {
                    self.best[k][l]
                }
            });
            self.displacement[k] = each(|l| {
                if better[l] {
                    d[k][l]
                } else {
                    self.displacement[k][l]
                }
            });
            self.step[k] = each(|l| {
                if better[l] {
                    step[k][l]
                } else {
                    self.step[k][l]
                }
            });
            self.base[k] = each(|l| {
                if better[l] {
                    self.next[k][l]
                } else {
                    self.base[k][l]
                }
            });
        }
        if track {
            if read {
                self.height = each(|l| {
                    if better[l] {
                        summed.height[l]
                    } else {
                        self.height[l]
                    }
                });
            }
            self.height_read = each(|l| if better[l] { read } else { self.height_read[l] });
        }
        self.miss = each(|l| if better[l] { miss[l] } else { self.miss[l] });
        self.fraction = each(|l| {
            if better[l] {
                1.0
            } else {
                self.fraction[l] * 0.5
            }
        });
        for k in 0..2 {
            self.next[k] = each(|l| self.base[k][l] + self.fraction[l] * self.step[k][l]);
        }
        let mut ended = [false; LANES];
        for l in 0..LANES {
            if better[l] {
                self.iterations[l] = self.iteration[l];
                self.converged[l] = converged[l];
            }
            ended[l] = self.point[l].is_some()
                && ((better[l] && converged[l]) || self.iteration[l] == max);
            self.iteration[l] += 1;
        }
        ended
    }

    /// What lane `l`'s search found.
    #[inline(always)]
    pub(super) fn found(&self, l: usize) -> Found {
        Found {
            location: Location {
                undisplaced: [self.best[0][l], self.best[1][l]],
                miss: self.miss[l],
                iterations: self.iterations[l],
                converged: self.converged[l],
            },
            displacement: [self.displacement[0][l], self.displacement[1][l]],
            height: self.height[l],
            height_read: self.height_read[l],
            slope: [0.0; 2],
            foam: 0.0,
            factors: self.factors[l],
        }
    }
}
