//! The lab's measurements (ALGORITHMS.md section 7), computed independently
//! of the code under test.
//!
//! Distances are computed with `rug` directly at [`judge_bits`] bits
//! (512, or `4 p + 64` for a run at `p` bits beyond 112) from the exact
//! binary values the run stored (vertices, position, radii), with a
//! formulation different from the detection's: the distance to the plane
//! when the projection falls inside the triangle (three orientation signs),
//! else the smallest distance to the three segments (clamped projection).
//! Both branches are continuous across edges and vertices, so points near
//! them are not misjudged. The differences of stored values and their
//! products up to the fourth degree (the plane distance's square) are
//! exact at that precision; the division by the radii, the segments'
//! clamped projections and the square root round, each by a relative
//! `2^-bits`. A reported distance `d` is then off by about `2^-(bits - 4)`
//! relative, and a penetration `1 - d` by as much absolute: at 512 bits
//! `1e-153`, far below the last bit of the `f64` it is reported in and
//! below the clearance any run up to 112 bits keeps (its padding is tens
//! of its own unit roundoffs); beyond 112 bits a run's clearances can be
//! smaller than that, hence the wider precision (a review, session 29,
//! found runs at 600 and 1,024 bits judged `1e-153` inside at 512 bits,
//! and clear at 4,096).

use crate::Real;
use crate::geom::Vec3;
use crate::world::World;
use rug::Float;

/// Precision of the exact computations, at least ([`judge_bits`]).
pub const EXACT_BITS: u32 = 512;

/// The precision the judge computes at for values of backend `T`:
/// [`EXACT_BITS`], or `4 p + 64` where that is more (`p = T::bits()`, more
/// than 112), so that the products of stored values it forms are exact and
/// its rounding stays far below the run's own.
#[must_use]
pub fn judge_bits<T: Real>() -> u32 {
    EXACT_BITS.max(T::bits().saturating_mul(4).saturating_add(64))
}

type V = [Float; 3];

/// The precision of `v`'s values (all three share it).
fn prec(v: &V) -> u32 {
    v[0].prec()
}

fn sub(a: &V, b: &V) -> V {
    [0, 1, 2].map(|i| Float::with_val(prec(a), &a[i] - &b[i]))
}

fn dot(a: &V, b: &V) -> Float {
    let mut s = Float::with_val(prec(a), &a[0] * &b[0]);
    s += &a[1] * &b[1];
    s += &a[2] * &b[2];
    s
}

fn cross(a: &V, b: &V) -> V {
    [
        Float::with_val(prec(a), &a[1] * &b[2] - &a[2] * &b[1]),
        Float::with_val(prec(a), &a[2] * &b[0] - &a[0] * &b[2]),
        Float::with_val(prec(a), &a[0] * &b[1] - &a[1] * &b[0]),
    ]
}

/// Squared distance from `p` to the segment `[a, b]`.
fn segment_distance_sq(p: &V, a: &V, b: &V) -> Float {
    let ab = sub(b, a);
    let ap = sub(p, a);
    let len2 = dot(&ab, &ab);
    let mut t = dot(&ap, &ab);
    if len2.is_zero() || t.is_sign_negative() {
        t = Float::new(prec(p));
    } else {
        t /= &len2;
        if t > 1 {
            t = Float::with_val(prec(p), 1);
        }
    }
    let d = [0, 1, 2].map(|i| Float::with_val(prec(p), &ap[i] - &t * &ab[i]));
    dot(&d, &d)
}

/// Squared distance from `p` to the triangle `a b c`, computed at the
/// precision of `p`'s values (all four exact at it: [`judge_bits`]).
#[must_use]
pub fn triangle_distance_sq(p: &V, a: &V, b: &V, c: &V) -> Float {
    let n = cross(&sub(b, a), &sub(c, a));
    let n2 = dot(&n, &n);
    let inside = !n2.is_zero()
        && [(a, b), (b, c), (c, a)].iter().all(|(u, v)| !dot(&n, &cross(&sub(v, u), &sub(p, u))).is_sign_negative());
    if inside {
        let h = dot(&n, &sub(p, a));
        return Float::with_val(prec(p), &h * &h) / n2;
    }
    let d = segment_distance_sq(p, a, b).min(&segment_distance_sq(p, b, c));
    d.min(&segment_distance_sq(p, c, a))
}

fn exact<T: Real>(v: &Vec3<T>) -> V {
    [0, 1, 2].map(|i| Float::with_val(judge_bits::<T>(), v[i].to_rug()))
}

/// How far beyond the radius [`penetration`] looks, in eSpace units: it
/// reports the exact (negative) penetration of a body clear of the mesh
/// by at most this much, the clearance of a body resting on it.
pub const PENETRATION_REACH: f64 = 0.05;

/// The exact penetration of a body with `radii` centred at `position` into
/// the triangles of `world`: `1 - d` with `d` the exact eSpace distance from
/// the centre to the mesh (coordinates divided by the radii at
/// [`judge_bits`] bits),
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
    /// Whether the body entered it from behind as Fauerby's one-sided
    /// detection passes through a triangle: the frame's start centre lay
    /// strictly behind the triangle's plane (on the side opposite to `(b -
    /// a) x (c - a)`), and the displacement of one of the frame's passes
    /// points along that front normal, so that the detection culled the
    /// triangle (`isFrontFacingTo` fails: `n . v > 0`). Both signs are
    /// computed exactly in eSpace at [`judge_bits`] bits; `false` for a
    /// zero-area triangle, which has no back.
    ///
    /// The side alone is not enough (a review, thirty-eighth session): a
    /// body beside a triangle, behind its plane's extension, that moves
    /// into its edge along the plane (`n . v = 0`) is not culled, and in
    /// `f32` `1e5` out Fauerby's and Linahan's responses went `0.54` radii
    /// into it, excused as entered from behind, while its mirror image, in
    /// front, counted. Looked at per pass, not per sweep: a later sweep of
    /// a pass slides along another direction, which the lab does not see,
    /// so an entry in a slid sweep that faced the triangle, or in the other
    /// pass, can still be excused where one pass's displacement culled it.
    pub from_behind: bool,
}

/// Every triangle a body that moved from `start` to `end` is inside of at
/// `end` (empty when none, or when either is not finite), with whether it
/// entered each from behind ([`Penetrated::from_behind`]) by the frame's
/// `passes` (its velocity and gravity, world space; zero ones cull
/// nothing).
///
/// Whether a body entered a triangle from behind is decided in the frame
/// where it entered, not later: a body deep inside can carry its centre
/// through the plane. The lab's runner keeps that verdict from frame to
/// frame ([`crate::lab::RunResult::back_face_frames`]).
#[must_use]
pub fn penetrated<T: Real>(
    world: &World<T>,
    radii: &Vec3<T>,
    start: &Vec3<T>,
    end: &Vec3<T>,
    passes: &[&Vec3<T>],
) -> Vec<Penetrated> {
    let Some(near) = Near::at(world, radii, end).filter(|_| start.iter().all(Real::is_finite)) else {
        return Vec::new();
    };
    let s = near.to_espace(start);
    let passes: Vec<V> = passes.iter().map(|v| near.to_espace(v)).collect();
    near.triangles
        .iter()
        .filter(|(_, _, d2)| *d2 < 1)
        .map(|(t, [a, b, c], d2)| {
            let normal = cross(&sub(b, a), &sub(c, a));
            let side = dot(&normal, &sub(&s, a));
            let behind = side.is_sign_negative() && !side.is_zero();
            let culled = passes.iter().any(|v| dot(&normal, v) > 0);
            Penetrated {
                triangle: *t,
                depth: near.depth(std::iter::once(d2)).unwrap_or(0.0),
                from_behind: behind && culled,
            }
        })
        .collect()
}

/// The triangles within reach of a body's centre, in eSpace at
/// [`judge_bits`] bits, with their squared distances to it.
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
        let pen = Float::with_val(d.prec(), 1 - &d);
        let r = &self.radii;
        let sphere = r[0] == r[1] && r[1] == r[2];
        Some(if sphere { (pen * &r[0]).to_f64() } else { pen.to_f64() })
    }

    fn to_espace<T: Real>(&self, v: &Vec3<T>) -> V {
        let v = exact(v);
        [0, 1, 2].map(|i| Float::with_val(prec(&v), &v[i] / &self.radii[i]))
    }
}

/// The positions that bound the last `K = max(1, n / 4)` of the `n`
/// displacements of `positions` (`K + 1` of them, none without a
/// displacement), exact at [`judge_bits`]: the window of [`jitter`] and
/// [`wobble`]. `None` when a position is NaN or infinite.
fn exact_tail<T: Real>(positions: &[Vec3<T>]) -> Option<Vec<V>> {
    if positions.iter().any(|p| !p.iter().all(Real::is_finite)) {
        return None;
    }
    let n = positions.len().saturating_sub(1);
    let first = if n == 0 { positions.len() } else { positions.len() - 1 - (n / 4).max(1) };
    Some(positions[first..].iter().map(exact).collect())
}

/// Jitter above this counts as jitter (a tenth of a percent of the speed):
/// the threshold of the report's claims and of the random search.
pub const JITTER_THRESHOLD: f64 = 1e-3;

/// Jitter over the last `K = max(1, n / 4)` displacements `d_k` of the
/// trajectory `positions` (frame 0 first): `(sum |d_k| - |sum d_k|) / (K
/// speed)`. Zero for straight motion or rest, positive when the body
/// wiggles. Displacements are taken exactly ([`judge_bits`]) so that rounding of
/// far-from-origin coordinates does not show up as jitter. The exact value
/// is never negative (the triangle inequality); the rounded difference of
/// path and net can round a few units of `2^-bits` of the path below zero
/// for straight motion, and is clamped at zero. Zero without a displacement
/// or a speed; NaN (not computable, and so not zero) when a position is
/// NaN or infinite.
#[must_use]
pub fn jitter<T: Real>(positions: &[Vec3<T>], speed: f64) -> f64 {
    let Some(exact_tail) = exact_tail(positions) else { return f64::NAN };
    let k = exact_tail.len().saturating_sub(1);
    if k == 0 || !(speed > 0.0) {
        return 0.0;
    }
    let norm = |d: &V| dot(d, d).sqrt();
    let mut path = Float::new(judge_bits::<T>());
    for w in exact_tail.windows(2) {
        path += norm(&sub(&w[1], &w[0]));
    }
    let net = norm(&sub(&exact_tail[k], &exact_tail[0]));
    let j = Float::with_val(judge_bits::<T>(), path - net) / (k as f64 * speed);
    j.to_f64().max(0.0)
}

/// Wobble over the same window as [`jitter`], the last `K = max(1, n /
/// 4)` displacements `d_k`: `(sum_k |d_{k+1} - d_k| - |d_K - d_1|) / (2 K
/// speed)`, how much the step changed from frame to frame beyond a
/// steady change (the total variation of the steps less their net
/// change). Zero for a body at rest or moving by a constant step, and for
/// one whose step changes steadily (slowing down, stopping or turning
/// without turning back); positive when the step goes back and forth.
/// Halved so that a body at rest toggling between two points `a` apart
/// scores about `a / speed`, as [`jitter`] does.
///
/// [`jitter`] (the shared definition, `docs/error-analysis.md`) measures the
/// path's excess over the net displacement, which for a sliding body grows
/// with the square of a sideways wobble: a slide of step `s` that zigzags
/// by `a` across its direction every frame scores about `a^2 / (2 s
/// speed)` there, and `a / speed` here. A review (thirty-eighth session)
/// found Fauerby's response zigzagging by +-2.5 degrees every frame along
/// `fold:5` in `f64` with a jitter of `6.7e-4`, below
/// [`JITTER_THRESHOLD`]; its wobble is `3.0e-2`.
///
/// Computed at [`judge_bits`] from the stored positions (the steps and
/// their differences exact, the norms rounded by a relative `2^-bits`);
/// the rounded difference is clamped at zero as [`jitter`]'s is. Zero
/// with fewer than two steps or without a speed; NaN when a position is
/// NaN or infinite.
#[must_use]
pub fn wobble<T: Real>(positions: &[Vec3<T>], speed: f64) -> f64 {
    let Some(tail) = exact_tail(positions) else { return f64::NAN };
    let k = tail.len().saturating_sub(1);
    if k < 2 || !(speed > 0.0) {
        return 0.0;
    }
    let steps: Vec<V> = tail.windows(2).map(|w| sub(&w[1], &w[0])).collect();
    let norm = |d: &V| dot(d, d).sqrt();
    let mut variation = Float::new(judge_bits::<T>());
    for w in steps.windows(2) {
        variation += norm(&sub(&w[1], &w[0]));
    }
    let net = norm(&sub(&steps[k - 1], &steps[0]));
    let w = Float::with_val(judge_bits::<T>(), variation - net) / (2.0 * k as f64 * speed);
    w.to_f64().max(0.0)
}

/// The snag ratio: displacement achieved along the ideal slide direction
/// divided by the ideal displacement (`frames * |ideal|`); 1 means no snag.
#[must_use]
pub fn snag_ratio<T: Real>(start: &Vec3<T>, end: &Vec3<T>, ideal_per_frame: [f64; 3], frames: usize) -> Option<f64> {
    let ideal = ideal_per_frame.map(|x| Float::with_val(judge_bits::<T>(), x));
    let len = dot(&ideal, &ideal).sqrt();
    if len.is_zero() || frames == 0 || !end.iter().all(Real::is_finite) {
        return None;
    }
    let moved = sub(&exact(end), &exact(start));
    let along = dot(&moved, &ideal) / len.clone();
    Some((along / (len * frames as f64)).to_f64())
}

/// Drift above this counts as leaving the ideal slide's line (a hundredth
/// of a radius, the robust response's largest padding `max_padding`): the
/// threshold of the report's claim.
pub const DRIFT_THRESHOLD: f64 = 1e-2;

/// How closely a frame's displacement must match the ideal slide's for the
/// body to count as sliding as the ideal does ([`drift`]), relative to the
/// ideal's length, beyond the rounding of the positions and of the step
/// itself ([`STEADY_STEP_ULPS`]). Tight, because an approach slower than
/// this counts as drift: near `26.57` degrees a crease's push creeps along
/// its slope towards the valley at a rate that vanishes with the
/// difference of angles, and at `1e-3` such a creep showed as `1.9e-2`
/// radii of drift in every response. At `1e-4` a creep needs 100 radii of
/// travel to reach the report's threshold ([`DRIFT_THRESHOLD`]); the
/// report's and the search's runs travel at most 30. Not tighter: a
/// scene's surfaces, their vertices rounded to `f32` coordinates, are bent
/// off the ideal's direction by about `1e-5`, and at `1e-6` no frame of
/// any response's runs along `fold:0.01` (in `f32`), or along the tilted
/// floor at `(1e3, 2e3, -1e3)` from 53 bits on, counted as sliding.
pub const STEADY_TOLERANCE: f64 = 1e-4;

/// The most rounding of the positions, relative to the ideal step, with
/// which a frame still counts as sliding as the ideal does ([`drift`]):
/// beyond it the precision does not carry the step, and any step of about
/// its size would pass the test (a search's body falling onto a fold
/// `4e4` out in `f32`, `0.012` of rounding against a step of `0.0116`,
/// counted as sliding from the first frame and drifted `0.48` radii).
pub const STEADY_ROUNDING: f64 = 0.5;

/// The rounding a response's own arithmetic leaves in a step that slides
/// as the ideal does (a projection, a crease's direction, eSpace and back),
/// in units of the run's unit roundoff times the step's length: part of
/// [`drift`]'s tolerance, well above what a few roundings give.
pub const STEADY_STEP_ULPS: f64 = 64.0;

/// The drift: how far, in radii, the body leaves the line of the ideal
/// slide once it slides as the ideal does. Its window starts at the first
/// frame whose displacement matches the ideal one within
/// [`STEADY_TOLERANCE`] plus [`STEADY_STEP_ULPS`] `u` of its length, once
/// each coordinate's difference is reduced by the rounding of the two
/// positions, `2 u` times the sum of their magnitudes in that coordinate
/// (`u` the run's unit roundoff: far from the origin in `f32` a position
/// cannot move by exactly the ideal), where that rounding is at most
/// [`STEADY_ROUNDING`] of the step: before it the body approaches the surfaces it will
/// slide along (a crease's slopes, a wedge's apex, the floor it falls on),
/// and moving across the ideal is what it should do. From there to the end
/// the drift is the length of the net displacement's component across the
/// ideal direction, both measured in eSpace (world coordinates divided by
/// `radii`, where an ellipsoid's slide is projected): zero for a slide
/// straight along the ideal, whatever its length; for a body turned aside
/// by a seam how far it went astray; for one that sinks or rises as it
/// slides the height it changed. The snag ratio ([`snag_ratio`]) measures
/// the other component, along the ideal, over the whole run. `None`
/// without an ideal slide or positive radii, where a position is not
/// finite, or where no frame moves as the ideal does (the body never
/// settled into the slide, the snag ratio says how far it got, or its
/// positions' rounding is too coarse to tell).
///
/// Computed at [`judge_bits`] from the stored positions: the across
/// component is the cross product of the displacement and the ideal, both
/// scaled by the products of the other two radii instead of divided by
/// their own (exact at that precision for `f32` and `f64` values, so a
/// slide exactly along the ideal drifts by exactly zero), then divided by
/// the ideal's scaled length and the radii's product: a relative
/// `2^-bits` or so.
#[must_use]
pub fn drift<T: Real>(positions: &[Vec3<T>], ideal_per_frame: [f64; 3], radii: [f64; 3]) -> Option<f64> {
    let bits = judge_bits::<T>();
    let finite = positions.iter().all(|p| p.iter().all(Real::is_finite));
    if !finite || !radii.iter().all(|r| *r > 0.0 && r.is_finite()) {
        return None;
    }
    let ideal = ideal_per_frame.map(|x| Float::with_val(bits, x));
    let ideal_len = dot(&ideal, &ideal).sqrt().to_f64();
    if ideal_len == 0.0 {
        return None;
    }
    // Exact positions only where they are looked at: frame by frame until
    // the first that slides as the ideal does, then the last.
    let steady = (1..positions.len()).find(|&f| {
        let off = sub(&sub(&exact(&positions[f]), &exact(&positions[f - 1])), &ideal);
        let rounding = [0, 1, 2]
            .map(|i| 2.0 * T::unit_roundoff() * (positions[f][i].to_f64().abs() + positions[f - 1][i].to_f64().abs()));
        let beyond_rounding = [0, 1, 2].map(|i| (off[i].to_f64().abs() - rounding[i]).max(0.0));
        let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let tolerance = (STEADY_TOLERANCE + STEADY_STEP_ULPS * T::unit_roundoff()) * ideal_len;
        norm(rounding) <= STEADY_ROUNDING * ideal_len && norm(beyond_rounding) <= tolerance
    })?;
    let scale = [0, 1, 2].map(|i| Float::with_val(bits, radii[(i + 1) % 3]) * radii[(i + 2) % 3]);
    let scaled = |v: &V| -> V { [0, 1, 2].map(|i| Float::with_val(bits, &v[i] * &scale[i])) };
    let moved = scaled(&sub(&exact(positions.last()?), &exact(&positions[steady - 1])));
    let ideal = scaled(&ideal);
    let across = cross(&moved, &ideal);
    let volume = Float::with_val(bits, &scale[0] * radii[0]);
    Some((dot(&across, &across).sqrt() / dot(&ideal, &ideal).sqrt() / volume).to_f64())
}
