//! Many bodies through one world at once.

use super::{Move, MoveOptions, move_body};
use crate::geom::{Ellipsoid, Vec3};
use crate::world::World;
use crate::{Error, Real};
use rayon::prelude::*;

/// One body's request for this frame.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyMove<T: Real> {
    /// The body's shape.
    pub body: Ellipsoid<T>,
    /// Where its centre is.
    pub position: Vec3<T>,
    /// Its displacement this frame.
    pub velocity: Vec3<T>,
    /// Its gravity displacement this frame, if any.
    pub gravity: Option<Vec3<T>>,
}

/// Moves every body through `world` in parallel (on the current rayon
/// pool; install a pool to choose the thread count). Bodies do not collide
/// with each other. The results come back in the order of `moves` and are
/// identical to calling [`move_body`] on each in turn: each move is
/// independent and deterministic, and each worker computes at the calling
/// thread's precision ([`Real::with_bits`]: [`crate::MpfrDyn`]'s is a
/// per-thread setting, which rayon's workers would otherwise leave at its
/// default of 53 bits).
pub fn move_bodies<T: Real>(
    world: &World<T>,
    moves: &[BodyMove<T>],
    options: &MoveOptions,
) -> Vec<Result<Move<T>, Error>> {
    let bits = T::bits();
    moves
        .par_iter()
        .map(|m| {
            T::with_bits(bits, || move_body(world, &m.body, &m.position, &m.velocity, m.gravity.as_ref(), options))
                .and_then(|moved| moved)
        })
        .collect()
}
