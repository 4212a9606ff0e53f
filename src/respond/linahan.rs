//! Linahan's `sphere_sweep` (the paper's Table II), as written.
//!
//! Iterative, three iterations, state `(pos, vel, dest)` carried: near point
//! `pos + unit(vel) * max(|vel| t - eps, 0)`; first hit: `dest` projected to
//! `1 + eps` from the sliding plane; second hit: motion along the crease
//! `unit(n1 x n2)`; third hit: stop at the near point. The sliding plane is
//! the plane through the contact point whose normal points to the touch
//! point (`pos + vel t`). Unguarded normalisations are kept: parallel planes
//! make the crease NaN.

use super::{Frame, StopReason, unguarded_normalize as normalized};
use crate::Real;
use crate::geom::{Plane, Vec3, cross, dot, norm};

/// Linahan's constant.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
pub struct LinahanOptions {
    /// `very_close_dist` (eSpace units): the near-point shortening and the
    /// long-radius excess. The paper gives no value; default `5e-5`, the
    /// same as Fauerby's `veryCloseDistance` in metres.
    pub very_close_distance: f64,
}

impl Default for LinahanOptions {
    fn default() -> Self {
        LinahanOptions { very_close_distance: 5e-5 }
    }
}

/// One pass of `sphere_sweep` from eSpace `pos` by eSpace `vel`.
pub(crate) fn sphere_sweep<T: Real>(
    frame: &mut Frame<'_, T>,
    mut pos: Vec3<T>,
    mut vel: Vec3<T>,
    opts: &LinahanOptions,
) -> Vec3<T> {
    let eps = T::c(opts.very_close_distance);
    let mut dest = &pos + &vel;
    let mut first_normal = Vec3::zeros();
    for i in 0..3 {
        let Some(hit) = frame.check_collision(&pos, &vel) else {
            frame.trace.stop = StopReason::Free;
            return dest;
        };
        let touch = &pos + &vel * hit.t.clone();
        let sliding = Plane::from_point_normal(&hit.point, normalized(&(touch - &hit.point)));
        let dist = norm(&vel) * &hit.t;
        let short_dist = (dist - &eps).max(T::zero());
        pos += normalized(&vel) * short_dist;
        frame.record(hit, sliding.normal.clone());
        match i {
            0 => {
                let long_radius = T::one() + &eps;
                dest -= &sliding.normal * (sliding.signed_distance(&dest) - long_radius);
                vel = &dest - &pos;
                first_normal = sliding.normal;
            }
            1 => {
                let crease = normalized(&cross(&first_normal, &sliding.normal));
                let dis = dot(&(&dest - &pos), &crease);
                vel = crease * dis;
                dest = &pos + &vel;
            }
            _ => {}
        }
    }
    frame.trace.stop = StopReason::ThirdPlane;
    pos
}
