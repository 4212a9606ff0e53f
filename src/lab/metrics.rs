//! The lab's measurements (ALGORITHMS.md section 7), computed independently
//! of the code under test.
//!
//! Distances are computed with `rug` directly at [`EXACT_BITS`] bits from
//! the exact binary values the run stored (vertices, position, radii), with
//! a formulation different from the detection's: the distance to the plane
//! when the projection falls inside the triangle (three orientation signs),
//! else the smallest distance to the three segments (clamped projection).
//! Both branches are continuous across edges and vertices, so points near
//! them are not misjudged. Every operation rounds at 512 bits, so each
//! reported value (an `f64`) is the exact one up to a relative error of
//! about `2^-500`, far below the last bit of the `f64` it is reported in.

use crate::Real;
use crate::geom::Vec3;
use crate::world::World;
use rug::Float;

/// Precision of the exact computations.
pub const EXACT_BITS: u32 = 512;

type V = [Float; 3];

fn f(x: &Float) -> Float {
    Float::with_val(EXACT_BITS, x)
}

fn sub(a: &V, b: &V) -> V {
    [0, 1, 2].map(|i| Float::with_val(EXACT_BITS, &a[i] - &b[i]))
}

fn dot(a: &V, b: &V) -> Float {
    let mut s = Float::with_val(EXACT_BITS, &a[0] * &b[0]);
    s += &a[1] * &b[1];
    s += &a[2] * &b[2];
    s
}

fn cross(a: &V, b: &V) -> V {
    [
        Float::with_val(EXACT_BITS, &a[1] * &b[2] - &a[2] * &b[1]),
        Float::with_val(EXACT_BITS, &a[2] * &b[0] - &a[0] * &b[2]),
        Float::with_val(EXACT_BITS, &a[0] * &b[1] - &a[1] * &b[0]),
    ]
}

/// Squared distance from `p` to the segment `[a, b]`.
fn segment_distance_sq(p: &V, a: &V, b: &V) -> Float {
    let ab = sub(b, a);
    let ap = sub(p, a);
    let len2 = dot(&ab, &ab);
    let mut t = dot(&ap, &ab);
    if len2.is_zero() || t.is_sign_negative() {
        t = Float::new(EXACT_BITS);
    } else {
        t /= &len2;
        if t > 1 {
            t = Float::with_val(EXACT_BITS, 1);
        }
    }
    let d = [0, 1, 2].map(|i| Float::with_val(EXACT_BITS, &ap[i] - &t * &ab[i]));
    dot(&d, &d)
}

/// Squared distance from `p` to the triangle `a b c` (all exact at
/// [`EXACT_BITS`]).
#[must_use]
pub fn triangle_distance_sq(p: &V, a: &V, b: &V, c: &V) -> Float {
    let n = cross(&sub(b, a), &sub(c, a));
    let n2 = dot(&n, &n);
    let inside = !n2.is_zero()
        && [(a, b), (b, c), (c, a)].iter().all(|(u, v)| !dot(&n, &cross(&sub(v, u), &sub(p, u))).is_sign_negative());
    if inside {
        let h = dot(&n, &sub(p, a));
        return Float::with_val(EXACT_BITS, &h * &h) / n2;
    }
    let d = segment_distance_sq(p, a, b).min(&segment_distance_sq(p, b, c));
    d.min(&segment_distance_sq(p, c, a))
}

fn exact<T: Real>(v: &Vec3<T>) -> V {
    [0, 1, 2].map(|i| f(&v[i].to_rug()))
}

/// How far beyond the radius [`penetration`] looks, in eSpace units: it
/// reports the exact (negative) penetration of a body clear of the mesh
/// by at most this much, the clearance of a body resting on it.
pub const PENETRATION_REACH: f64 = 0.05;

/// The exact penetration of a body with `radii` centred at `position` into
/// the triangles of `world`: `1 - d` with `d` the exact eSpace distance from
/// the centre to the mesh (coordinates divided by the radii at 512 bits),
/// multiplied by the radius for a sphere (so it is in world units) and left
/// in eSpace units for an ellipsoid. Positive means inside the geometry,
/// negative is minus the clearance; `None` when no triangle comes within
/// `1 + PENETRATION_REACH` of the centre (eSpace: clear by more than
/// that) or the position is not finite.
///
/// Every triangle within that distance is examined (its box is rounded
/// outward, in `f64`). Until the eighteenth session the box reached `1e-6` beyond the radius, and a negative
/// value could come from a far triangle of a BVH leaf while a nearer one
/// lay outside the box (a review found -7.05 where the clearance was
/// 8.5e-6); positive values were exact.
#[must_use]
pub fn penetration<T: Real>(world: &World<T>, radii: &Vec3<T>, position: &Vec3<T>) -> Option<f64> {
    let near = Near::at(world, radii, position)?;
    near.depth(near.triangles.iter().map(|(_, _, d2)| d2))
}

/// A triangle a body is inside of: exact eSpace distance from the centre
/// below 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Penetrated {
    /// The triangle's index in the world.
    pub triangle: u32,
    /// Its penetration, as [`penetration`] measures it.
    pub depth: f64,
    /// Whether the frame's start centre lay strictly behind the
    /// triangle's plane: on the side opposite to `(b - a) x (c - a)` (in
    /// eSpace, the sign computed at [`EXACT_BITS`] bits; `false` for a
    /// zero-area triangle, which has no back). Fauerby's one-sided
    /// detection culls a triangle by the direction of motion instead (a
    /// motion along its front normal); a body behind a plane that comes
    /// to the triangle moves along that normal, so what this side marks is
    /// culled there too, though the converse need not hold (a body in
    /// front that moves away from the plane and reaches the triangle over
    /// an edge is culled but marked as a front entry, counted against the
    /// response).
    pub start_behind: bool,
}

/// Every triangle a body that moved from `start` to `end` is inside of at
/// `end` (empty when none, or when either is not finite).
///
/// Whether a body entered a triangle from behind is decided by the side
/// its centre was on in the frame where it entered, not later: a body deep
/// inside can carry its centre through the plane. The lab's runner keeps
/// that side from frame to frame ([`crate::lab::RunResult::back_face_frames`]).
#[must_use]
pub fn penetrated<T: Real>(world: &World<T>, radii: &Vec3<T>, start: &Vec3<T>, end: &Vec3<T>) -> Vec<Penetrated> {
    let Some(near) = Near::at(world, radii, end).filter(|_| start.iter().all(Real::is_finite)) else {
        return Vec::new();
    };
    let s = near.to_espace(start);
    near.triangles
        .iter()
        .filter(|(_, _, d2)| *d2 < 1)
        .map(|(t, [a, b, c], d2)| {
            let side = dot(&cross(&sub(b, a), &sub(c, a)), &sub(&s, a));
            Penetrated {
                triangle: *t,
                depth: near.depth(std::iter::once(d2)).unwrap_or(0.0),
                start_behind: side.is_sign_negative() && !side.is_zero(),
            }
        })
        .collect()
}

/// The triangles within reach of a body's centre, in eSpace at
/// [`EXACT_BITS`] bits, with their squared distances to it.
struct Near {
    radii: V,
    triangles: Vec<(u32, [V; 3], Float)>,
}

impl Near {
    /// Every triangle within `1 + PENETRATION_REACH` (eSpace) of
    /// `position`, and perhaps a few beyond; `None` when there is none or
    /// the position is not finite.
    ///
    /// The box they must meet is computed in `f64` and rounded outward
    /// (in `T`, `position - radii` rounds to nearest, and far from the
    /// origin a box that rounds inward by half a unit in the last place,
    /// 0.004 at 1e5 in `f32`, could miss a triangle that a body has sunk
    /// into).
    fn at<T: Real>(world: &World<T>, radii: &Vec3<T>, position: &Vec3<T>) -> Option<Near> {
        if !position.iter().all(Real::is_finite) {
            return None;
        }
        let centre = [0, 1, 2].map(|i| position[i].to_f64());
        // The radii and centre as `f64` are rounded to nearest (for `MpfrDyn`
        // and `Mpfr` beyond 53 bits): a relative `f64::EPSILON` covers them.
        let half = |i: usize| {
            radii[i].to_f64() * (1.0 + PENETRATION_REACH) * (1.0 + 4.0 * f64::EPSILON) + centre[i].abs() * f64::EPSILON
        };
        let min = nalgebra::Vector3::from_fn(|i, _| (centre[i] - half(i)).next_down());
        let max = nalgebra::Vector3::from_fn(|i, _| (centre[i] + half(i)).next_up());
        let mut candidates = Vec::new();
        world.candidates_f64(&min, &max, &mut candidates);
        if candidates.is_empty() {
            return None;
        }
        let mut near = Near { radii: exact(radii), triangles: Vec::with_capacity(candidates.len()) };
        let p = near.to_espace(position);
        for t in candidates {
            let tri = world.triangle(t);
            let corners = [&tri.a, &tri.b, &tri.c].map(|v| near.to_espace(v));
            let d2 = triangle_distance_sq(&p, &corners[0], &corners[1], &corners[2]);
            near.triangles.push((t, corners, d2));
        }
        Some(near)
    }

    /// The penetration for the least of the squared distances `d2`
    /// (`None` when there is none or it lies beyond the reach).
    fn depth<'a>(&self, d2: impl Iterator<Item = &'a Float>) -> Option<f64> {
        let d = d2.min_by(|a, b| a.total_cmp(b))?.clone().sqrt();
        if d > 1.0 + PENETRATION_REACH {
            return None;
        }
        let pen = Float::with_val(EXACT_BITS, 1 - d);
        let r = &self.radii;
        let sphere = r[0] == r[1] && r[1] == r[2];
        Some(if sphere { (pen * &r[0]).to_f64() } else { pen.to_f64() })
    }

    fn to_espace<T: Real>(&self, v: &Vec3<T>) -> V {
        let v = exact(v);
        [0, 1, 2].map(|i| Float::with_val(EXACT_BITS, &v[i] / &self.radii[i]))
    }
}

/// Jitter over the last `K = max(1, n / 4)` displacements `d_k` of the
/// trajectory `positions` (frame 0 first): `(sum |d_k| - |sum d_k|) / (K
/// speed)`. Zero for straight motion or rest, positive when the body
/// wiggles. Displacements are taken exactly (512 bits) so that rounding of
/// far-from-origin coordinates does not show up as jitter. The exact value
/// is never negative (the triangle inequality); the 512-bit difference of
/// path and net can round a few units of `2^-512` of the path below zero
/// for straight motion, and is clamped at zero. Zero without a displacement
/// or a speed; NaN (not computable, and so not zero) when a position is
/// NaN or infinite.
#[must_use]
pub fn jitter<T: Real>(positions: &[Vec3<T>], speed: f64) -> f64 {
    let n = positions.len().saturating_sub(1);
    if positions.iter().any(|p| !p.iter().all(Real::is_finite)) {
        return f64::NAN;
    }
    if n == 0 || !(speed > 0.0) {
        return 0.0;
    }
    let k = (n / 4).max(1);
    let tail = &positions[positions.len() - 1 - k..];
    let exact_tail: Vec<V> = tail.iter().map(exact).collect();
    let norm = |d: &V| dot(d, d).sqrt();
    let mut path = Float::new(EXACT_BITS);
    for w in exact_tail.windows(2) {
        path += norm(&sub(&w[1], &w[0]));
    }
    let net = norm(&sub(&exact_tail[k], &exact_tail[0]));
    let j = Float::with_val(EXACT_BITS, path - net) / (k as f64 * speed);
    j.to_f64().max(0.0)
}

/// The snag ratio: displacement achieved along the ideal slide direction
/// divided by the ideal displacement (`frames * |ideal|`); 1 means no snag.
#[must_use]
pub fn snag_ratio<T: Real>(start: &Vec3<T>, end: &Vec3<T>, ideal_per_frame: [f64; 3], frames: usize) -> Option<f64> {
    let ideal = exact(&crate::geom::vec3::<crate::Mpfr<EXACT_BITS>>(
        ideal_per_frame[0],
        ideal_per_frame[1],
        ideal_per_frame[2],
    ));
    let len = dot(&ideal, &ideal).sqrt();
    if len.is_zero() || frames == 0 || !end.iter().all(Real::is_finite) {
        return None;
    }
    let moved = sub(&exact(end), &exact(start));
    let along = dot(&moved, &ideal) / len.clone();
    Some((along / (len * frames as f64)).to_f64())
}
