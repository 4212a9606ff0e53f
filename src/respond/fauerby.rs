//! Fauerby's `collideWithWorld` (the paper's Table I), as written.
//!
//! Recursive (here: a loop over the same state, which is what his tail
//! recursion computes), depth cap 5, `veryCloseDistance = 0.005 *
//! unitsPerMeter / 100`, position and velocity passed on (the destination is
//! re-derived each level, one of the roundings Linahan points out). Every
//! NaN his arithmetic can produce is kept: normalising a zero vector divides
//! by zero.

use super::{Frame, StopReason, unguarded_normalize as normalized};
use crate::Real;
use crate::detect::hit_distance;
use crate::geom::{Plane, Vec3, norm};

/// Fauerby's constants.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
pub struct FauerbyOptions {
    /// World units per metre (his `unitsPerMeter`); `veryCloseDistance` is
    /// `0.005 * units_per_meter / 100` in eSpace units. Default 1 (metres),
    /// i.e. `veryCloseDistance = 5e-5`. His demos used 100 (centimetres).
    pub units_per_meter: f64,
    /// The recursion depth cap (his 5: levels 0 to 5 run, level 6 returns).
    pub max_depth: u32,
}

impl Default for FauerbyOptions {
    fn default() -> Self {
        FauerbyOptions { units_per_meter: 1.0, max_depth: 5 }
    }
}

impl FauerbyOptions {
    /// `veryCloseDistance` in eSpace units.
    #[must_use]
    pub fn very_close_distance(&self) -> f64 {
        0.005 * (self.units_per_meter / 100.0)
    }
}

/// `v` scaled to length `len`, as his `SetLength` does it (`v * len/|v|`).
fn set_length<T: Real>(v: &Vec3<T>, len: &T) -> Vec3<T> {
    v * (len.clone() / norm(v))
}

/// One pass of `collideWithWorld` from eSpace position `pos` with eSpace
/// velocity `vel`; returns the final eSpace position.
pub(crate) fn collide_and_slide<T: Real>(
    frame: &mut Frame<'_, T>,
    mut pos: Vec3<T>,
    mut vel: Vec3<T>,
    opts: &FauerbyOptions,
) -> Vec3<T> {
    let very_close = T::c(opts.very_close_distance());
    for _depth in 0..=opts.max_depth {
        let Some(hit) = frame.check_collision(&pos, &vel) else {
            frame.trace.stop = StopReason::Free;
            return pos + vel;
        };
        let destination = &pos + &vel;
        let mut new_base = pos.clone();
        let nearest = hit_distance(&hit, &vel);
        let mut intersection = hit.point.clone();
        if nearest >= very_close {
            let v = set_length(&vel, &(nearest - &very_close));
            new_base = &pos + &v;
            let v = normalized(&v);
            intersection -= v * very_close.clone();
        }
        let slide_normal = normalized(&(&new_base - &intersection));
        let plane = Plane::from_point_normal(&intersection, slide_normal.clone());
        let new_destination = &destination - &slide_normal * plane.signed_distance(&destination);
        let new_velocity = new_destination - &intersection;
        frame.record(hit, slide_normal);
        if norm(&new_velocity) < very_close {
            frame.trace.stop = StopReason::Exhausted;
            return new_base;
        }
        pos = new_base;
        vel = new_velocity;
    }
    frame.trace.stop = StopReason::DepthCap;
    pos
}
