//! Quadratic root finders: Fauerby's textbook one and a stable one.
//!
//! Both solve for the time `t` at which a moving point reaches distance 1
//! from a fixed point or line, `a t^2 + b t + c = 0` with `a >= 0`.

use crate::Real;

/// Fauerby's `getLowestRoot`, as he wrote it: the textbook formula
/// `(-b -+ sqrt(b^2 - 4ac)) / 2a`, roots sorted, the lower one returned if it
/// lies in `(0, max_r)`, *else the upper one* if it does.
///
/// Its defects are kept on purpose (this is the baseline the lab measures):
/// cancellation in `-b + sqrt(...)`, no guard for `a == 0` (division by
/// zero gives infinities or NaN, which then fail the comparisons), a root at
/// exactly `t = 0` is rejected, and when the body already overlaps the
/// feature (`c < 0`) the *exit* time is returned.
#[must_use]
pub fn textbook_lowest_root<T: Real>(a: &T, b: &T, c: &T, max_r: &T) -> Option<T> {
    let det = b.clone() * b - T::c(4.0) * a * c;
    if det < T::zero() {
        return None;
    }
    let sqrt_d = det.sqrt();
    let two_a = T::c(2.0) * a;
    let mut r1 = (-b.clone() - &sqrt_d) / &two_a;
    let mut r2 = (-b.clone() + &sqrt_d) / &two_a;
    if r1 > r2 {
        std::mem::swap(&mut r1, &mut r2);
    }
    if r1 > T::zero() && r1 < *max_r {
        return Some(r1);
    }
    if r2 > T::zero() && r2 < *max_r {
        return Some(r2);
    }
    None
}

/// The entry time of `a t^2 + 2 half_b t + c = 0` for a body that starts
/// outside (`c > 0`) and whose squared distance grows like `a >= 0`, given
/// the discriminant `disc = half_b^2 - a c`: the smaller root `c / q` with
/// `q = -half_b + sqrt(disc)`, computed without cancellation. `None` when the
/// body does not approach (`half_b >= 0`) or never reaches the feature
/// (`disc < 0`).
///
/// The caller computes `disc` from geometry rather than from the rounded
/// coefficients: `half_b^2` and `a c` are each of the order of the fourth
/// power of the sweep's length and cancel to something of the order of its
/// square, so subtracting them loses `u s^2` (Lagrange's identity gives the
/// cancellation-free forms used by [`super::sweep_robust`]). There is no
/// division by `a`, so a vanishing `a` (zero velocity, motion parallel to an
/// edge) needs no special case. Rounding: a few `u` relative in the time.
///
/// Non-finite inputs: a NaN `half_b` or `disc` gives `None` (no entry
/// is claimed from a meaningless discriminant). A `disc` that overflowed
/// to infinity (an edge longer than about `4e9` radii in `f32`, far
/// beyond the documented range) gives the time 0: a touch at the start,
/// which stops the body rather than letting it through. `c <= 0` (the
/// body already within reach) is the caller's case to handle first; given
/// one, the result is not an entry time.
#[must_use]
pub fn stable_entry_root<T: Real>(half_b: &T, c: &T, disc: &T) -> Option<T> {
    if !(*half_b < T::zero()) || !(*disc >= T::zero()) {
        return None;
    }
    let q = disc.sqrt() - half_b;
    Some(c.clone() / q)
}
