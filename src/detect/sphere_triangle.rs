//! The unit sphere swept against one triangle: Fauerby's test as he wrote
//! it, and the robust one. Coordinates are eSpace (the body is the unit
//! sphere centred at `base`, moving by `vel` over `t` in `[0, 1]`).

use super::roots::{stable_entry_root, textbook_lowest_root};
use super::{Candidate, DetectOptions, Hit};
use crate::Real;
use crate::world::ActiveFeatures;

use crate::geom::{
    Feature, Plane, Triangle, Vec3, closest_point_on_sides, closest_point_on_triangle, cross, dot, max_abs, norm,
    norm_squared, normalize, normalize_near_unit,
};

/// Where and how a contact was found: the sphere centre and the contact
/// point at the time of touch (in the coordinates the test worked in) and
/// the normal to fall back on if they coincide.
struct Touch<T: Real> {
    t: T,
    point: Vec3<T>,
    centre: Vec3<T>,
    feature: Feature,
}

impl<T: Real> Touch<T> {
    /// The hit record; `origin` is added to the point to return it in the
    /// caller's coordinates (the normal is computed before, where the
    /// coordinates are small).
    fn into_hit(
        self,
        origin: Option<&Vec3<T>>,
        fallback: impl FnOnce() -> Vec3<T>,
        index: u32,
        overlapping: bool,
    ) -> Hit<T> {
        let normal = normalize_near_unit(&(&self.centre - &self.point)).unwrap_or_else(fallback);
        let point = match origin {
            Some(o) => self.point + o,
            None => self.point,
        };
        Hit { t: self.t, point, normal, feature: self.feature, triangle: index, started_overlapping: overlapping }
    }
}

/// Fauerby's `checkTriangle`, faithfully: back-face culling against the
/// normalised velocity, the plane interval `[t0, t1]` with his exact
/// `nv == 0` test, the face test with his sign-bit inside test, then the
/// three vertices and three edges with the textbook root finder. Defects are
/// kept: see [`textbook_lowest_root`] and [`fauerby_point_in_triangle`].
#[must_use]
pub fn sweep_fauerby<T: Real>(tri: &Triangle<T>, base: &Vec3<T>, vel: &Vec3<T>, index: u32) -> Option<Hit<T>> {
    let zero = T::zero();
    let one = T::one();
    // His PLANE(p1, p2, p3) normalises without a guard; his normalize()
    // divides by the length even when it is zero (NaN then fails the test
    // below, so a degenerate triangle or a zero velocity finds nothing).
    let raw = tri.unnormalized_normal();
    let plane = Plane::from_point_normal(&tri.a, raw.clone() / norm(&raw));
    let normalized_velocity = vel.clone() / norm(vel);
    if !(dot(&plane.normal, &normalized_velocity) <= zero) {
        return None; // isFrontFacingTo: only triangles facing the motion
    }
    let signed_dist = plane.signed_distance(base);
    let normal_dot_velocity = dot(&plane.normal, vel);
    let mut embedded = false;
    let (t0, t1);
    if normal_dot_velocity == zero {
        if signed_dist.abs() >= one {
            return None;
        }
        embedded = true;
        (t0, t1) = (zero.clone(), one.clone());
    } else {
        let mut a = (-one.clone() - &signed_dist) / &normal_dot_velocity;
        let mut b = (one.clone() - &signed_dist) / &normal_dot_velocity;
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        if a > one || b < zero {
            return None;
        }
        t0 = a.max(zero.clone()).min(one.clone());
        t1 = b.max(zero.clone()).min(one.clone());
    }
    let _ = t1; // Fauerby computes it but only the entry time is used.
    if !embedded {
        let plane_point = base - &plane.normal + vel * t0.clone();
        if fauerby_point_in_triangle(&plane_point, tri) {
            let overlapping = t0 == zero;
            let centre = base + vel * t0.clone();
            let touch = Touch { t: t0, point: plane_point, centre, feature: Feature::Face };
            return Some(touch.into_hit(None, || plane.normal.clone(), index, overlapping));
        }
    }
    let velocity_sq = norm_squared(vel);
    let mut t = one.clone();
    let mut found: Option<(Vec3<T>, Feature)> = None;
    for i in 0..3 {
        let p = tri.vertex(i);
        let b = T::c(2.0) * dot(vel, &(base - p));
        let c = norm_squared(&(p - base)) - &one;
        if let Some(root) = textbook_lowest_root(&velocity_sq, &b, &c, &t) {
            t = root;
            found = Some((p.clone(), Feature::Vertex(i as u8)));
        }
    }
    for i in 0..3 {
        let (p, q) = (tri.vertex(i), tri.vertex(i + 1));
        let edge = q - p;
        let base_to_vertex = p - base;
        let edge_sq = norm_squared(&edge);
        let edge_dot_velocity = dot(&edge, vel);
        let edge_dot_btv = dot(&edge, &base_to_vertex);
        let a = edge_sq.clone() * -velocity_sq.clone() + edge_dot_velocity.clone() * &edge_dot_velocity;
        let b =
            edge_sq.clone() * (T::c(2.0) * dot(vel, &base_to_vertex)) - T::c(2.0) * &edge_dot_velocity * &edge_dot_btv;
        let c = edge_sq.clone() * (one.clone() - norm_squared(&base_to_vertex)) + edge_dot_btv.clone() * &edge_dot_btv;
        if let Some(root) = textbook_lowest_root(&a, &b, &c, &t) {
            let f = (edge_dot_velocity * &root - &edge_dot_btv) / &edge_sq;
            if f >= zero && f <= one {
                t = root;
                found = Some((p + edge * f, Feature::Edge(i as u8)));
            }
        }
    }
    let (point, feature) = found?;
    let centre = base + vel * t.clone();
    let overlapping = t == zero;
    Some(Touch { t, point, centre, feature }.into_hit(None, || plane.normal.clone(), index, overlapping))
}

/// Fauerby's `checkPointInTriangle`: barycentric-like quantities
/// `x = d c - e b`, `y = e a - d b`, `z = x + y - (a c - b b)`, and "inside"
/// read off the IEEE sign bits: `z` negative while neither `x` nor `y` is.
/// No tolerance; `-0.0` counts as negative, `+0.0` as not, and a NaN with
/// its sign bit set as negative, exactly as the bit trick behaves.
#[must_use]
pub fn fauerby_point_in_triangle<T: Real>(point: &Vec3<T>, tri: &Triangle<T>) -> bool {
    let e10 = &tri.b - &tri.a;
    let e20 = &tri.c - &tri.a;
    let a = dot(&e10, &e10);
    let b = dot(&e10, &e20);
    let c = dot(&e20, &e20);
    let ac_bb = a.clone() * &c - b.clone() * &b;
    let vp = point - &tri.a;
    let d = dot(&vp, &e10);
    let e = dot(&vp, &e20);
    let x = d.clone() * &c - e.clone() * &b;
    let y = e * &a - d * &b;
    let z = x.clone() + &y - &ac_bb;
    z.is_sign_negative() && !(x.is_sign_negative() || y.is_sign_negative())
}

/// The robust sweep: the earliest `t` in `[0, 1]` at which the unit sphere
/// centred at `base + t vel` touches `tri`.
///
/// * All arithmetic is done on `tri - base` (relative coordinates), so the
///   error depends on the distances involved, not on how far from the
///   origin the scene lies.
/// * A sphere that already touches or overlaps the triangle at `t = 0`
///   (closest distance `<= 1 + tol`) is reported at `t = 0` with the
///   separating normal `sep` (closest point to centre) if and only if the
///   motion approaches that point: `-sep . vel > 0` when overlapping
///   (`dist < 1 - tol`), `-sep . vel > opts.approach_ulps * u * |vel|` when
///   touching (default 0; see [`DetectOptions::approach_ulps`]). Otherwise
///   there is no hit: the distance to the (convex) triangle is convex along
///   the motion, so it does not decrease (or, with `approach_ulps`, by at
///   most `approach_ulps * u * |vel|` over the sweep). The exit time is
///   never reported.
/// * Face: plane distance taken from the vertex nearest the centre; the
///   contact point is inside when all three edge orientations are
///   non-negative, judged in the coordinate plane most nearly parallel to
///   the triangle (two products per side; see `side_outside`). At a
///   grazing angle the plane's time is accurate in distance but not along
///   the track, so a contact point found outside is clipped: the hit is
///   the earliest moment, among those where the plane distance is within
///   `tol` of 1, at which the centre's projection is inside the triangle
///   (see `face_window`); otherwise the edge tests decide, which agree to
///   second order.
/// * An edge contact's direction is projected across the edge (at the
///   start a second time, after the perpendicular's own projection): off
///   by about `u` along the edge (a slide along the edge then keeps its
///   distance), by `u s` only as a turn about it (fuzz finding F35).
/// * Edges and vertices: squared-distance quadratics from cross products
///   (`|e x (t v - p)|^2 = |e|^2`, no cancellation of `|e|^2 |v|^2` against
///   `(e.v)^2`), their discriminants from Lagrange's identity (no
///   cancellation of fourth powers of the sweep length), solved by
///   [`stable_entry_root`] and only when the body starts outside the
///   feature.
/// * No exact float equality decides anything. The touching tolerance is
///   `tol = opts.touch_ulps * u * s`, `u` the unit roundoff and
///   `s = max(1, |q|_inf)` the magnitude of the point `q` the distance is
///   measured from (the vertex nearest the centre for the face, the nearer
///   endpoint for an edge, the vertex itself), all relative to `base`.
/// * The quick rejections come first, with a fixed margin of `1e-3` radii
///   beyond 1 plus their own rounding: a candidate whose box lies beyond
///   that is no hit even where `tol` is wider (`s` above about `1e3` in
///   `f32`, `6e11` in `f64`) and [`proximity`] calls it touching. The box's
///   coordinates are differences of stored values, far more accurate
///   there than a distance taken from a vertex `s` away; the touching rule
///   above holds for the candidates they pass.
///
/// * A sphere *touching* an inactive (internal) edge or vertex at `t = 0`,
///   as `active` says, is judged and reported with the face normal: on a
///   seam of a tessellated surface the exact contact normal is the face
///   normal, and the rounded one must not stop a body sliding along it.
///   Only where the centre is over the face, though (the geometric
///   direction within 60 degrees of the face normal): beside the edge, near
///   the face's plane, the face normal is no contact direction (fuzz
///   finding F20), and the geometric one is kept. A contact reached
///   during the sweep (`t > 0`) keeps its geometric normal, the right
///   constraint on a gently convex fold (the body rides over it); where a
///   neighbour's face is reached at the same time up to rounding (a flat
///   seam hit head-on), [`crate::detect::earliest_hit`] takes that face.
///
/// Ties: face before edges before vertices, lower feature index first.
///
/// The first rejection is the candidate's box against the box the sphere
/// sweeps, axis by axis relative to `base`; a caller with many triangles
/// goes through [`crate::detect::earliest_hit`] or
/// [`crate::detect::sweep_world`], which test the boxes against a swept box
/// and ball computed once per sweep.
///
/// Inputs must be finite (this kernel does not check, to stay cheap:
/// [`crate::detect::sweep_world`] and [`crate::respond::move_body`] do,
/// and return [`crate::Error::NonFinite`]); with a NaN or infinite input
/// the answer is meaningless.
#[must_use]
pub fn sweep_robust<T: Real>(
    c: &Candidate<T>,
    base: &Vec3<T>,
    vel: &Vec3<T>,
    opts: &DetectOptions,
    limit: Option<&T>,
) -> Option<Hit<T>> {
    if box_misses_sweep(c, base, vel) {
        return None;
    }
    sweep_robust_with_speed(c, base, vel, &norm(vel), opts, limit)
}

/// Whether the candidate's box lies outside the box swept by the unit
/// sphere from `base` by `vel` on some axis `i`, judged relative to `base`:
/// `lo_i - base_i > max(vel_i, 0) + r_i` or
/// `hi_i - base_i < min(vel_i, 0) - r_i` with `r_i = reach + 4 u |vel_i|`.
/// Each side is one or two rounded operations; where they nearly agree
/// (`|lo_i - base_i|` about `|vel_i| + 1`) their roundings add up to a few
/// `u (|vel_i| + 1)`, which the `4 u |vel_i|` and the margin of [`reach`]
/// cover. Cheaper than building a [`SweptBox`] for one candidate: no square
/// root, no magnitude of the coordinates, no ball.
#[inline]
fn box_misses_sweep<T: Real>(c: &Candidate<T>, base: &Vec3<T>, vel: &Vec3<T>) -> bool {
    let zero = T::zero();
    let margin = T::c(4.0 * T::unit_roundoff());
    // Every axis and both sides are evaluated, without a branch between
    // them: a hit passes all six tests, and one branch is cheaper.
    let outside = |i: usize| {
        let v = &vel[i];
        let r = reach::<T>() + margin.clone() * v.clone().abs();
        (c.lo[i].clone() - &base[i] > v.clone().max(zero.clone()) + &r)
            | (c.hi[i].clone() - &base[i] < v.clone().min(zero.clone()) - r)
    };
    outside(0) | outside(1) | outside(2)
}

/// The region the unit sphere swept from `base` by `vel` can touch, for the
/// first, cheapest rejection of a candidate: the box around the swept sphere
/// and the ball around the whole sweep (centre `base + vel / 2`, radius
/// `|vel| / 2 + 1`), both grown by [`reach`] plus `8 u` times the largest
/// coordinate involved (the rounding of the box corners and of the
/// candidate-box distance). Computed once per sweep by
/// [`crate::detect::earliest_hit`]: a candidate whose box misses either is
/// out.
pub(crate) struct SweptBox<T: Real> {
    lo: Vec3<T>,
    hi: Vec3<T>,
    mid: Vec3<T>,
    ball_sq: T,
    /// `|vel|`.
    pub(crate) speed: T,
}

/// The radius plus the margin every quick rejection of the robust sweep
/// keeps (far larger than the rounding of the estimates it guards).
fn reach<T: Real>() -> T {
    T::c(1.0 + 1e-3)
}

impl<T: Real> SweptBox<T> {
    pub(crate) fn new(base: &Vec3<T>, vel: &Vec3<T>) -> Self {
        let end = base + vel;
        let magnitude = max_abs(&end, max_abs(base, T::zero()));
        let reach = reach::<T>() + T::c(8.0 * T::unit_roundoff()) * magnitude;
        let lo = Vec3::from_fn(|i, _| base[i].clone().min(end[i].clone()) - &reach);
        let hi = Vec3::from_fn(|i, _| base[i].clone().max(end[i].clone()) + &reach);
        let mid = base + vel * T::c(0.5);
        let speed = norm(vel);
        let ball = speed.clone() * T::c(0.5) + reach;
        SweptBox { lo, hi, mid, ball_sq: ball.clone() * ball, speed }
    }

    /// Whether the candidate's box lies wholly outside the swept box or the
    /// ball around the sweep.
    #[inline]
    pub(crate) fn misses(&self, c: &Candidate<T>) -> bool {
        // Every test is evaluated, without a branch between them (one
        // branch, taken for most candidates, predicts better than seven).
        let outside = |i: usize| (c.lo[i] > self.hi[i]) | (c.hi[i] < self.lo[i]);
        outside(0) | outside(1) | outside(2) | (c.box_distance_sq(&self.mid) > self.ball_sq)
    }
}

/// [`sweep_robust`] given `speed = |vel|` (as [`norm`] rounds it), for a
/// caller that computed it once per sweep.
pub(crate) fn sweep_robust_with_speed<T: Real>(
    c: &Candidate<T>,
    base: &Vec3<T>,
    vel: &Vec3<T>,
    speed: &T,
    opts: &DetectOptions,
    limit: Option<&T>,
) -> Option<Hit<T>> {
    let zero = T::zero();
    let one = T::one();
    let index = c.index;
    // A hit must come before `limit` (an earlier triangle's hit) or, with
    // none yet, within the frame.
    let wins = |t: &T| limit.map_or(*t <= one, |l| t < l);
    let reach = reach::<T>();
    // Quick rejection from the precomputed normal and vertex a alone: the
    // centre stays farther than 1 from the plane on one side for the whole
    // sweep. The margin covers this estimate's rounding (the unit normal's
    // direction is off by a few `u k`, `k` the shape factor, and each dot
    // product by a few `u` times its terms) and the touching tolerance, so
    // nothing rejected here could touch; it is tight enough that a body
    // resting on a surface (a padding of a few hundred `u` away) and moving
    // along or away from it rejects the surface's triangles here.
    let from_a = base - &c.triangle.a;
    let scale = max_abs(&from_a, one.clone()) + speed;
    let clear = one.clone() + T::c((opts.touch_ulps + 16.0) * T::unit_roundoff()) * &c.shape * scale;
    if let Some(n) = &c.normal {
        let d0 = dot(n, &from_a);
        let d1 = d0.clone() + dot(n, vel);
        let (lo, hi) = if d0 < d1 { (d0, d1) } else { (d1, d0) };
        if lo > clear || hi < -clear.clone() || (!opts.two_sided && hi < zero) {
            return None;
        }
    }
    let rel = c.triangle.relative_to(base);
    let p = [&rel.a, &rel.b, &rel.c];
    // Edges from the given vertices, not from `rel` (see `Candidate::edges`).
    let edges = &c.edges;
    let mut normal = c.normal.clone();
    let dist_sq = [norm_squared(p[0]), norm_squared(p[1]), norm_squared(p[2])];
    let nearest = nearest_vertex(&dist_sq);

    // Which side the centre (the origin, now) is on, from the nearest vertex.
    let mut plane_dist = zero.clone();
    if let Some(n) = normal.as_mut() {
        plane_dist = -dot(n, p[nearest]);
        if plane_dist < zero {
            if !opts.two_sided {
                return None;
            }
            *n = -n.clone();
            plane_dist = -plane_dist;
        }
        // Quick rejection: the sphere stays clear of the whole plane, or
        // reaches it too late to beat `limit`.
        let nv = dot(n, vel);
        if plane_dist.clone() + nv.clone().min(zero.clone()) > clear {
            return None;
        }
        if plane_dist > clear && nv < zero && !wins(&((plane_dist.clone() - &clear) / -nv)) {
            return None;
        }
    }

    // Face interior: the plane reached with the contact point inside.
    let face_hit = || {
        let plane = SeenPlane { n: normal.as_ref()?, dist: &plane_dist, from: p[nearest], speed };
        face_contact(c, &rel, &plane, base, vel, opts.touch_ulps, &wins)
    };
    // Clear of the plane by more than the margin, the body cannot be
    // touching anything now: a face hit needs no closest point.
    let clear_of_plane = plane_dist > clear;
    if clear_of_plane && let Some(hit) = face_hit() {
        return Some(hit);
    }

    // The centre moves at most `|vel|`, and at most `l |vel|` before the
    // best time `l` so far, so a triangle farther than `1 + l |vel|` cannot
    // win: this rejects most near misses before the edge and vertex
    // quadratics. The margin covers the rounding of the closest point
    // below: Ericson's face coordinates are quotients of differences of
    // products of dot products `d_i` (each up to `|e| far`, `|e|` the
    // longest edge), off by about `u (|e| far)^2 / |(b - a) x (c - a)|^2`,
    // which moves the point by `|e|` times that: `u far k` times the lever
    // `max(1, k far / |e|)`, `k` the shape factor. The lever is about 1 for
    // a well-shaped triangle near the body and large for a long sliver
    // seen from far along it (a 600 x 0.6 strip from 34 units along it put
    // the point 5.4 away where it is 1.5 in `f32`, and the body fell
    // through: tests/regressions/detect_long_slivers.rs).
    let far = max_abs(p[2], max_abs(p[1], max_abs(p[0], one.clone())));
    // The face normal, or for a degenerate triangle the direction against
    // the motion: the fallback direction of a contact.
    let face_normal = || normal.clone().unwrap_or_else(|| -vel.clone());
    let longest = c.edge_sq.iter().fold(T::zero(), |m, l| m.max(l.clone())).sqrt();
    let lever = (c.shape.clone() * &far / longest).max(one.clone());
    let slack = T::c(64.0 * T::unit_roundoff()) * &far * &c.shape;
    // Before `limit` (an earlier triangle's hit) the centre has moved at
    // most `limit |vel|`.
    let travel = limit.map_or_else(|| speed.clone(), |l| l.clone().min(one.clone()) * speed);
    let gap_bound = (one.clone() + travel) * &reach + slack.clone() * lever;
    let gap_bound_sq = gap_bound.clone() * gap_bound;
    if clear_of_plane && limit.is_none() {
        // Not touching now, the distance serves only that rejection, and
        // with no earlier hit its bound is loose (`1 + |vel|`): the distance
        // to the triangle's box, a lower bound, rejects nearly as much for
        // a fraction of the closest point's cost (after an earlier hit the
        // bound is tight and the exact distance is worth its cost: the box
        // alone cost a frame move 1.4% more instructions, and the box for
        // every body not within `near` of it, 2.8%). Its terms
        // `lo_i - base_i` are `rel`'s smallest coordinates, rounded the
        // same way, so it is the distance to `rel`'s box to within the
        // rounding of its squares and sum.
        if c.box_distance_sq(base) > gap_bound_sq {
            return None;
        }
    } else {
        // The closest point now, for the rejection and for a touch at the
        // start (decided only near distance 1): distance and separating
        // direction computed per feature, from the nearest point that
        // defines it, so both carry errors of order u * |that point| only.
        // Near the plane, a centre whose projection the side tests place
        // inside the triangle is over its face, at the plane distance:
        // Ericson's point, a quotient of products, can be off by `u k far`
        // times the lever (0.59 radii on a 40 x 0.05 strip in `f32`, and a
        // sphere started 0.1 inside it passed through: a review), where the
        // side tests are orientations of the edges, exact but for `u`.
        let (closest, feature) = if c.long_lever && !clear_of_plane {
            long_lever_closest(c, &rel, normal.as_ref().map(|n| n * -plane_dist.clone()))
        } else {
            closest_point_on_triangle(&Vec3::zeros(), &rel)
        };
        let closest_sq = norm_squared(&closest);
        if closest_sq > gap_bound_sq {
            return None;
        }
        // Only a point this near decides a touch at the start (with the
        // plain margin: the lever widens only the rejection above, since a
        // point the face coordinates put far off is not near, and the
        // sweep's own tests below find the contact; a tiny triangle far
        // away, whose lever is huge, would otherwise be judged by its
        // plane distance alone).
        let near = reach.clone() + &slack;
        if closest_sq <= near.clone() * near {
            let local = Local { p, c, face: normal.as_ref(), plane_dist: &plane_dist, nearest };
            let (dist, sep, tol) = local.separation(&closest, feature, &face_normal(), opts);
            if dist <= one.clone() + &tol {
                // Touching: approached by more than `opts.approach_ulps`;
                // overlapping: by any amount.
                let overlapping = dist < one.clone() - &tol;
                // Overlapping, only the approach's sign decides, and only
                // the motion across the edge's line counts: the same in
                // exact arithmetic, since the direction is perpendicular
                // to the edge. Motion along the edge would carry the
                // direction's error along it into the sign: `u |from| /
                // dist` for the perpendicular from the line before it was
                // projected across the edge a second time (fuzz finding
                // F21), and still `u` times the tilt for the face normal
                // that stands in for an inactive edge (a review: a flat
                // cap's inactive edge, overlapped and sunk into at `2.5e-5`
                // per frame, read as receding).
                let approach = match feature {
                    Feature::Edge(i) if overlapping => {
                        let i = usize::from(i);
                        -dot(&sep, &across(vel, &edges[i], &c.edge_sq[i]))
                    }
                    _ => -dot(&sep, vel),
                };
                let approached = if overlapping {
                    approach > zero
                } else {
                    approach > T::c(opts.approach_ulps * T::unit_roundoff()) * speed
                };
                if approached && wins(&zero) {
                    return Some(Hit {
                        t: zero,
                        point: closest + base,
                        normal: sep,
                        feature,
                        triangle: index,
                        started_overlapping: overlapping,
                    });
                }
                return None;
            }
        }
    }
    if !clear_of_plane && let Some(hit) = face_hit() {
        return Some(hit);
    }

    // Edges, then vertices: the earliest entry time within [0, 1]; on a tie
    // the feature found first stays.
    //
    // The unit ball around a vertex lies inside the unit cylinder around
    // either edge's line, so a body that starts outside that cylinder
    // reaches the vertex no earlier than the cylinder: a vertex is solved
    // for only if neither of its edges rules it out. An edge rules out both
    // of its vertices when its cylinder is never entered, or entered too
    // late to win, or entered over the edge itself (the edge is hit first);
    // entered beyond one end, it rules out the other end (to reach that one
    // the centre would cross the slab of the near end inside the cylinder,
    // touching the near end first), and both only when a touch on the edge
    // is found there that wins (a touch that `edge_beyond_end` finds after
    // the near end was reached proves nothing about it). What this skips
    // is decided on rounded quantities, but only where the vertex would be
    // reached within a rounding of the edge's own entry time.
    let mut best: Option<Touch<T>> = None;
    let better = |t: &T, best: &Option<Touch<T>>| match best {
        None => wins(t),
        Some(b) => *t < b.t,
    };
    // Bit `v` set: vertex `v` is still to be solved for.
    let mut vertex_open = 0b111u8;
    for (i, e) in edges.iter().enumerate() {
        let ends = [i, (i + 1) % 3];
        // The line through the edge from its nearer end `a`: the distance
        // to it is then computed from coordinates of the size of that
        // distance, not of the far end (a long edge reaching far away would
        // carry its far end's rounding into the cross products; fuzz
        // finding F15). Along the edge, `f` is measured from `a`: the edge
        // spans `[lo, lo + 1]`.
        let from_end = dist_sq[ends[1]] < dist_sq[ends[0]];
        let a = p[ends[usize::from(from_end)]];
        let lo = if from_end { -one.clone() } else { zero.clone() };
        let e2 = c.edge_sq[i].clone();
        // The quadratic is formed from `a` across the edge, the same in
        // exact arithmetic (`m` is perpendicular to `e`): the rounded `m`
        // has a component of `u |e| |vel|` along `e`, which `m . a` took
        // times `a`'s reach along the edge (a review: in `f32` a sweep
        // along an edge whose nearer end lay 600 radii along it got a
        // negative discriminant and missed the edge, `3.6e-3` deep by the
        // end; `f64` missed entries 500 times its padding deep).
        let a_across = across(a, e, &e2);
        let m = cross(e, vel);
        let k = cross(e, &a_across);
        let c = norm_squared(&k) - &e2;
        if !(c > zero) {
            continue;
        }
        // disc = (m.k)^2 - |m|^2 c = |e|^2 (|m|^2 - (m.a)^2) by Lagrange's
        // identity, since m x k = e (m . a): no fourth powers cancel.
        let det = dot(&m, &a_across);
        let m2 = norm_squared(&m);
        let disc = e2.clone() * (m2.clone() - det.clone() * &det);
        let entry = EdgeEntry { e2, m2, half_b: -dot(&m, &k), c, disc };
        let Some(t) = stable_entry_root(&entry.half_b, &entry.c, &entry.disc).filter(|t| better(t, &best)) else {
            vertex_open &= !(1 << ends[0] | 1 << ends[1]);
            continue;
        };
        let f = dot(&(&(vel * t.clone()) - a), e) / &entry.e2;
        let hi = lo.clone() + &one;
        // Entered beyond an end: maybe within rounding of it, or at a
        // grazing angle (see `edge_beyond_end`).
        // A touch on the edge (at an end, or over the band) that comes too
        // late to win rules out only the far end: the near one may be
        // reached before it (fuzz finding F26: a band touch after the end
        // of the sweep ruled out the vertex reached half way).
        let (t, f) = if f < lo || f > hi {
            let magnitude = far.clone() + speed;
            let touch = edge_beyond_end(e, a, vel, &entry, (&t, &f), (&lo, &hi), &magnitude, opts.touch_ulps);
            let Some(touch) = touch.filter(|(t, _)| better(t, &best)) else {
                vertex_open &= !(1 << if f < lo { ends[1] } else { ends[0] });
                continue;
            };
            touch
        } else {
            (t, f)
        };
        vertex_open &= !(1 << ends[0] | 1 << ends[1]);
        let centre = vel * t.clone();
        best = Some(Touch { t, point: a + e * f, centre, feature: Feature::Edge(i as u8) });
    }
    let v2 = norm_squared(vel);
    for (i, v) in p.iter().enumerate() {
        if vertex_open & 1 << i == 0 {
            continue;
        }
        let c = norm_squared(*v) - &one;
        if !(c > zero) {
            continue;
        }
        // disc = (vel.v)^2 - |vel|^2 c = |vel|^2 - |vel x v|^2 (Lagrange).
        let disc = v2.clone() - norm_squared(&cross(vel, *v));
        let Some(t) = stable_entry_root(&-dot(vel, *v), &c, &disc) else {
            continue;
        };
        if better(&t, &best) {
            let centre = vel * t.clone();
            best = Some(Touch { t, point: (*v).clone(), centre, feature: Feature::Vertex(i as u8) });
        }
    }
    let mut hit = best?.into_hit(Some(base), face_normal, index, false);
    if let Feature::Edge(i) = hit.feature {
        // Across the edge, as `separation` takes it at the start (fuzz
        // finding F35): `centre - point` is off by `u` of the centre's
        // distance from the edge's nearer end, along the edge too.
        let i = usize::from(i);
        hit.normal = normalize_near_unit(&across(&hit.normal, &edges[i], &c.edge_sq[i])).unwrap_or(hit.normal);
    }
    Some(hit)
}

/// `v` less its component along `e` (`e2` its squared length): the part of
/// `v` across the line of `e`.
#[inline(always)]
fn across<T: Real>(v: &Vec3<T>, e: &Vec3<T>, e2: &T) -> Vec3<T> {
    v - e * (dot(v, e) / e2)
}

/// The entry of the unit sphere moving by `vel` into the unit cylinder
/// around an edge's line (through its nearer end `a`, along `e`):
/// `m2 t^2 + 2 half_b t + c = 0` is `|e|^2` times the squared distance to
/// the line less 1, with `m = e x vel`, `k = e x a'`, `c = |k|^2 - |e|^2`,
/// `half_b = -(m . k)` and the discriminant from Lagrange's identity,
/// `disc = |e|^2 (|m|^2 - (m . a')^2)`, where `a'` is `a` less its
/// component along `e` (equal in exact arithmetic; the rounded `m`'s
/// component along `e` then meets no reach along the edge; see
/// [`sweep_robust`]).
struct EdgeEntry<T: Real> {
    /// `|e|^2`.
    e2: T,
    /// `|e x vel|^2`.
    m2: T,
    /// Half the linear coefficient.
    half_b: T,
    /// The constant coefficient (positive: the body starts outside).
    c: T,
    /// The discriminant.
    disc: T,
}

/// For the robust test's edges: the touch `(t', f')` (`f'` the position
/// along the edge, in `[lo, hi]`) when the unit cylinder around the line
/// through `a` along `e` is entered at time `t` at a position `f` beyond an
/// end, the sphere moving by `vel`, as the caller's `entry` found it;
/// `magnitude` is `far + |vel|` (the largest relative coordinate plus the
/// speed). (A vertex hit enters both of the vertex's edges' cylinders
/// beyond it, so this is common: about 0.8 calls per hit of the random
/// hits that `benches/detect.rs` times.)
///
/// * **Within rounding of the end** (fuzz finding F18). The position
///   comes from `centre - a`, whose terms carry a few `u` of `magnitude`:
///   an entry within `position = 8 u magnitude` of an end counts as on the
///   edge, at that end (the sphere then touches the edge within
///   `position^2 / 2`). For a triangle smaller than that (a tiny one far
///   from the start, in `f32`) the position says nothing.
/// * **At a grazing angle** (finding F19). The entry time is accurate in
///   distance but not along the edge (`u s` over the approach rate
///   `sqrt(disc) / |e|^2`, times the speed along the edge): an entry
///   computed beyond an end may really be on the edge, and a sphere moving
///   away from that end then sinks into the edge unseen. Over the *band*
///   where the distance to the line is within the touching tolerance
///   `tol = touch_ulps u magnitude` of 1 while entering (from the entry of
///   the cylinder of radius `1 + tol` to that of radius `1 - tol`, or the
///   exit of the first when the second is never entered), the position
///   along the edge is linear in time; the earliest moment of the band at
///   which it is on the edge is a touch within `tol`, and before it nothing
///   of the edge (its ends included) was entered by more than `tol`. The
///   band is at most `2 tol |e|^2 / sqrt(inner)` long (`inner` the
///   discriminant for radius `1 - tol`; the distance's rate is smallest at
///   the band's end), and the position moves at most `|vel| / |e|` per
///   unit time, so an entry farther beyond the end than that is ruled out
///   without solving for the band.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn edge_beyond_end<T: Real>(
    e: &Vec3<T>,
    a: &Vec3<T>,
    vel: &Vec3<T>,
    entry: &EdgeEntry<T>,
    (t, f): (&T, &T),
    (lo, hi): (&T, &T),
    magnitude: &T,
    touch_ulps: f64,
) -> Option<(T, T)> {
    let zero = T::zero();
    let EdgeEntry { e2, m2, half_b, c, disc } = entry;
    let excess = if f < lo { lo.clone() - f } else { f.clone() - hi };
    let excess_sq = excess.clone() * excess;
    let position = T::c(8.0 * T::unit_roundoff()) * magnitude;
    if excess_sq.clone() * e2 <= position.clone() * position {
        return Some((t.clone(), f.clone().max(lo.clone()).min(hi.clone())));
    }
    let tol = T::c(touch_ulps * T::unit_roundoff()) * magnitude;
    let two_tol = tol.clone() * T::c(2.0);
    let tol_sq = tol.clone() * &tol;
    // For radius 1 - tol and 1 + tol: c and disc shift by e2 (1 - r^2).
    let shrink = e2.clone() * (two_tol.clone() - &tol_sq);
    let inner = disc.clone() - m2.clone() * &shrink;
    if inner > zero && excess_sq * &inner > two_tol.clone() * &two_tol * e2 * norm_squared(vel) {
        return None;
    }
    let grow = e2.clone() * (two_tol + tol_sq);
    let outer_c = c.clone() - &grow;
    let outer_disc = disc.clone() + m2.clone() * &grow;
    let start = if outer_c > zero { stable_entry_root(half_b, &outer_c, &outer_disc)? } else { zero.clone() };
    let end = if inner > zero {
        stable_entry_root(half_b, &(c.clone() + shrink), &inner)?
    } else {
        (outer_disc.sqrt() - half_b) / m2
    };
    // f(t') = f + (t' - t) (vel . e) / e2, within [lo, hi].
    let rate = dot(vel, e) / e2;
    let (enter, leave) = if rate > zero {
        (t.clone() + (lo.clone() - f) / &rate, t.clone() + (hi.clone() - f) / &rate)
    } else if rate < zero {
        (t.clone() + (hi.clone() - f) / &rate, t.clone() + (lo.clone() - f) / &rate)
    } else {
        return None;
    };
    let from = start.max(enter);
    if !(from <= end.min(leave)) {
        return None;
    }
    // The position at `from` is taken afresh, as the caller took `f`, not
    // from the linear model: `f + (from - t) rate` carries `u` times the
    // terms' size, which for a fast sphere (`rate` of order `|vel| / |e|`)
    // moves the contact point along the edge and tilts the contact normal
    // by as much (fuzz finding F23: `2.9e-11` for a sphere at `1e6` radii
    // per frame).
    let at = (dot(&(&(vel * from.clone()) - a), e) / e2).max(lo.clone()).min(hi.clone());
    Some((from, at))
}

/// The robust test's face contact: the unit sphere at the origin (the
/// sweep's start, `rel` the triangle relative to it) moving by `vel`
/// reaches `plane` with the contact point inside the triangle, at a time
/// that `wins`. (A function, not a closure: the robust test tries it in
/// two places, before the closest point for a body clear of the plane and
/// after it otherwise, and a closure's captures cost more than its
/// arguments. Kept out of line: inlined into the closure that calls it,
/// it cost the terrain replay's frame move 0.7% more instructions.)
///
/// The plane's time `t_p = (plane.dist - 1) / -(n . vel)` is accurate in
/// distance but not along the track: at a grazing angle its error, `u s g'`
/// over `|n . vel|` (`s` the magnitude of the vertex the plane distance is
/// measured from, `g'` a bound of the normal's tilt factor,
/// [`Candidate::tilt_bound`]; [`SeenPlane::tol`]), moves the
/// contact point by `|vel| / |n . vel|` times that (fuzz findings F16,
/// F17 and F38). So when the contact point at `t_p` is outside the
/// triangle, the face is still touched if, at some moment of the window
/// where the centre's plane distance is within the touching tolerance
/// `tol = touch_ulps u s g'` of 1, the centre's projection is inside: the
/// earliest such moment is the hit (see [`face_window`]).
#[inline(never)]
fn face_contact<T: Real>(
    c: &Candidate<T>,
    rel: &Triangle<T>,
    plane: &SeenPlane<'_, T>,
    base: &Vec3<T>,
    vel: &Vec3<T>,
    touch_ulps: f64,
    wins: &impl Fn(&T) -> bool,
) -> Option<Hit<T>> {
    let (zero, one) = (T::zero(), T::one());
    let n = plane.n;
    let nv = dot(n, vel);
    if !(nv < zero) {
        return None;
    }
    if !(*plane.dist > one) {
        return face_entered_touching(c, rel, plane, base, vel, nv, touch_ulps, wins);
    }
    let t = (plane.dist.clone() - &one) / -nv.clone();
    // A plane reached after the frame is not met in it.
    if !(t <= one) {
        return None;
    }
    let contact = vel * t.clone() - n;
    let tol = plane.tol(c, touch_ulps);
    // The window below can move the contact earlier by `tol / |nv|`: only a
    // plane reached too late even then cannot beat `limit` (judged at `t`
    // itself, `limit` pruned grazing contacts the window would have moved
    // ahead of it, and the earliest hit depended on the candidates' order:
    // a review).
    if !wins(&(t.clone() - tol.clone() / -nv.clone())) {
        return None;
    }
    // Orientation against the triangle's own winding normal (not the
    // side-flipped `n`), so back faces are found too.
    let winding = c.normal.as_ref().unwrap_or(n);
    let (t, contact) = match side_outside(c, rel, winding, &contact) {
        None if wins(&t) => (t, contact),
        None => return None,
        Some(outside) => {
            let window = Window { t, nv, tol };
            if window.rules_out(&outside, c, vel) {
                return None;
            }
            let t = face_window(c, rel, winding, vel, &contact, &window)?;
            if !wins(&t) {
                return None;
            }
            let contact = vel * t.clone() - n;
            (t, contact)
        }
    };
    Some(face_hit(c, n, t, contact, base))
}

/// A side of a triangle that a point lies outside of, as [`side_outside`]
/// judged it.
struct Outside<T: Real> {
    /// Which side (edge `i`, from vertex `i` to vertex `i + 1`).
    side: usize,
    /// The size of the point's orientation in the coordinate plane: `|e_i|`
    /// times its distance to the side's line times `|winding[k]|`, which is
    /// between `1 / sqrt 3` and 1.
    by: T,
}

/// The first side of the triangle that the contact point `contact`
/// (relative to the sweep's start, as `rel`) lies outside of, if any,
/// judged in the coordinate plane most nearly parallel to the triangle:
/// each side's orientation is the component along the normal's largest
/// coordinate `k` of `e_i x (contact - p_i)`, two products instead of the
/// nine of a triple product with `winding` (the triangle's unit normal),
/// its sign taken against `winding[k]`, which is at least `1 / sqrt 3` in
/// size. For a point in the plane both are `winding[k]` times the same
/// value; a point off the plane by `delta` (the contact point is, by
/// rounding) moves it by at most `sqrt 3 delta |e_i|`, a rounding of the
/// point's own size. A point judged outside goes to [`Window::rules_out`]
/// and, unless it is far outside, to [`face_window`], which works in three
/// dimensions and finds the earliest moment, within the touching
/// tolerance, at which it is inside.
#[inline]
fn side_outside<T: Real>(
    c: &Candidate<T>,
    rel: &Triangle<T>,
    winding: &Vec3<T>,
    contact: &Vec3<T>,
) -> Option<Outside<T>> {
    let p = [&rel.a, &rel.b, &rel.c];
    // `(i1, i2)` follow `k` cyclically, so that `e[i1] d[i2] - e[i2] d[i1]`
    // is the `k` component of `e x d`. Written out per axis so that every
    // index is a constant.
    let outside_along = |k: usize, i1: usize, i2: usize| {
        let w = &winding[k];
        (0..3).find_map(|i| {
            let e = &c.edges[i];
            let o =
                e[i1].clone() * (contact[i2].clone() - &p[i][i2]) - e[i2].clone() * (contact[i1].clone() - &p[i][i1]);
            (o.clone() * w < T::zero()).then(|| Outside { side: i, by: o.abs() })
        })
    };
    let [x, y, z] = [0, 1, 2].map(|k| winding[k].clone().abs());
    if x >= y && x >= z {
        outside_along(0, 1, 2)
    } else if y >= z {
        outside_along(1, 2, 0)
    } else {
        outside_along(2, 0, 1)
    }
}

/// The face hit of candidate `c` at time `t`, `contact` relative to the
/// sweep's start `base`, with the normal `n` turned towards the centre.
#[inline]
fn face_hit<T: Real>(c: &Candidate<T>, n: &Vec3<T>, t: T, contact: Vec3<T>, base: &Vec3<T>) -> Hit<T> {
    Hit {
        t,
        point: contact + base,
        normal: n.clone(),
        feature: Feature::Face,
        triangle: c.index,
        started_overlapping: false,
    }
}

/// For [`face_contact`], when the centre already lies within 1 of the plane
/// (`plane_dist <= 1`), beside the triangle (a touch of the triangle at the
/// start was ruled out before), approaching it (`nv = n . vel < 0`): the
/// face contact at which the centre's projection enters the triangle while
/// the plane distance is still within the touching tolerance
/// `tol = touch_ulps u s g'` of 1 ([`SeenPlane::tol`]),
/// if it does (fuzz finding F29: a sphere `1.5e-14` inside the plane of a
/// triangle beside it slid into the triangle unseen, its edges'
/// discriminants, at tangency, rounded negative). The window is
/// `[0, t_hi]`, `t_hi` the time the plane distance falls to `1 - tol`; see
/// [`face_window`].
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn face_entered_touching<T: Real>(
    c: &Candidate<T>,
    rel: &Triangle<T>,
    plane: &SeenPlane<'_, T>,
    base: &Vec3<T>,
    vel: &Vec3<T>,
    nv: T,
    touch_ulps: f64,
    wins: &impl Fn(&T) -> bool,
) -> Option<Hit<T>> {
    let zero = T::zero();
    let n = plane.n;
    let reach = plane.dist.clone() - T::one() + plane.tol(c, touch_ulps);
    if !(reach > zero) {
        return None;
    }
    let contact = -n.clone();
    let winding = c.normal.as_ref().unwrap_or(n);
    let window = Window { t: zero, nv, tol: reach };
    if side_outside(c, rel, winding, &contact).is_some_and(|outside| window.rules_out(&outside, c, vel)) {
        return None;
    }
    let t = face_window(c, rel, winding, vel, &contact, &window)?;
    if !wins(&t) {
        return None;
    }
    let contact = vel * t.clone() - n;
    Some(face_hit(c, n, t, contact, base))
}

/// A candidate's plane as the robust test sees it from the sweep's start:
/// what [`face_contact`] and [`face_entered_touching`] work from.
struct SeenPlane<'a, T: Real> {
    /// The unit normal, turned towards the centre.
    n: &'a Vec3<T>,
    /// The centre's distance to the plane, from the vertex nearest it.
    dist: &'a T,
    /// That vertex, relative to the start.
    from: &'a Vec3<T>,
    /// The sweep's speed `|vel|`.
    speed: &'a T,
}

impl<T: Real> SeenPlane<'_, T> {
    /// The touching tolerance of `dist` for candidate `c`,
    /// `touch_ulps u s g'`: `s` is the largest coordinate of `from` and 1,
    /// plus the speed, and `g'` a bound of the normal's tilt factor
    /// ([`Candidate::tilt_bound`]: the shape factor `k`, without a square
    /// root, or the tilt factor of a normal from the exact edges). The plane
    /// distance is the unit normal's dot product with the vertex: rounded
    /// by `u` times its size, and off by that size times the normal's
    /// tilt ([`Candidate::tilt`]); the speed covers the contact point's
    /// rounding (`|vel t - n| <= 1 + |vel|`). Measured by the contact point
    /// alone (`u` times about 1), the window was too narrow for the plane's
    /// time: in a huge triangle's plane, its nearest vertex `1.5e3` away,
    /// that time came out `2.4e-5` late, the contact point `1.4e-6` beyond a
    /// side that the exact one lies `1.1e-7` inside, and the face was
    /// missed (fuzz finding F38); a flat cap (`k = 458`) crossed at `1e-7`
    /// of a grazing angle was missed the same way until the tilt was
    /// added. With `k` itself for every triangle (F38's fix until R33b) a
    /// flat cap's window reached radii beyond its sides (`k = 2.8e4`, 390
    /// radii from the start: 10 radii), and a body sliding along a wall
    /// onto a cap's long edge met its face a radius past the edge, already
    /// a radius deep (R33b). At most `44 u s' k` for the sweep checks'
    /// magnitude `s'` (`docs/fuzzing.md`), within their bound of `64 u s'
    /// k`.
    fn tol(&self, c: &Candidate<T>, touch_ulps: f64) -> T {
        T::c(touch_ulps * T::unit_roundoff()) * (max_abs(self.from, T::one()) + self.speed) * c.tilt_bound()
    }
}

/// Where a face contact may lie in time: the plane's time `t`, the
/// approach speed `nv = n . vel < 0`, and the tolerance `tol` on the
/// plane distance; the window is `|t' - t| <= tol / |nv|`.
struct Window<T: Real> {
    t: T,
    nv: T,
    tol: T,
}

impl<T: Real> Window<T> {
    /// Whether a contact point outside a side as [`side_outside`] found it
    /// stays outside over the whole window, so that [`face_window`] need
    /// not run: within the window the projection moves at most
    /// `tol |vel| / |nv|`, and a point is beyond the side's line by
    /// `o / |e_i|` or more, `o` the size of its orientation in the
    /// coordinate plane (at most the three-dimensional one, which is
    /// `|e_i|` times the distance, for a point in the plane; the contact
    /// point is off it by its rounding, a few `u s`, far below `tol`). For
    /// an edge or vertex hit the face's contact point is outside, and most
    /// face tests end here.
    fn rules_out(&self, outside: &Outside<T>, c: &Candidate<T>, vel: &Vec3<T>) -> bool {
        let Window { nv, tol, .. } = self;
        let o = &outside.by;
        o.clone() * o * nv * nv > tol.clone() * tol * norm_squared(vel) * &c.edge_sq[outside.side]
    }
}

/// For [`face_contact`], when the contact point at the plane's time is
/// outside the triangle: the earliest time of the window (clipped to
/// `t >= 0`) at which the centre's projection onto the plane is inside the
/// triangle, if any. `contact` is the contact point at the window's `t`,
/// `winding` the triangle's unit normal (callers first try
/// [`Window::rules_out`]).
///
/// Over the window the plane distance stays within `tol` (plus its own
/// rounding, a few `u s`) of 1 and decreases, so a hit at the earliest
/// time the projection is inside touches within `tol`, and nothing was
/// entered before by more than `tol`. Each side's orientation is linear in
/// time, `o_i(t') = o_i(t) + (t' - t) d_i` with
/// `d_i = (e_i x vel) . winding`: the projection is inside from
/// `t - o_i / d_i` on where `d_i > 0`, until then where `d_i < 0` (`o_i`
/// is `|e_i|` times the signed distance to the side's line).
#[cold]
#[inline(never)]
fn face_window<T: Real>(
    c: &Candidate<T>,
    rel: &Triangle<T>,
    winding: &Vec3<T>,
    vel: &Vec3<T>,
    contact: &Vec3<T>,
    window: &Window<T>,
) -> Option<T> {
    let zero = T::zero();
    let Window { t, nv, tol } = window;
    let p = [&rel.a, &rel.b, &rel.c];
    let orientation = |i: usize| dot(&cross(&c.edges[i], &(contact - p[i])), winding);
    let half = tol.clone() / -nv.clone();
    let mut lo = (t.clone() - &half).max(zero.clone());
    let mut hi = t.clone() + half;
    for (i, e) in c.edges.iter().enumerate() {
        let o = orientation(i);
        let d = dot(&cross(e, vel), winding);
        if d > zero {
            lo = lo.max(t.clone() - o / d);
        } else if d < zero {
            hi = hi.min(t.clone() - o / d);
        } else if o < zero {
            return None;
        }
    }
    (lo <= hi).then_some(lo)
}

/// A candidate seen from the sphere's centre: its vertices relative to the
/// centre and what the robust test derives from them first.
struct Local<'a, T: Real> {
    /// The vertices minus the centre.
    p: [&'a Vec3<T>; 3],
    /// The candidate (its edges, their squared lengths, its active
    /// features).
    c: &'a Candidate<T>,
    /// The unit normal turned towards the centre (`None`: degenerate).
    face: Option<&'a Vec3<T>>,
    /// The centre's distance to the plane, from the nearest vertex.
    plane_dist: &'a T,
    /// Which vertex is nearest the centre.
    nearest: usize,
}

impl<T: Real> Local<'_, T> {
    /// The distance from the centre to the triangle, the separating
    /// direction (from the closest point `closest` on `feature` to the
    /// centre; the face normal `face_normal` for an inactive edge or vertex
    /// when the centre is over the face)
    /// and the touching tolerance. Distance and direction are computed per
    /// feature, from the nearest point that defines it, so both carry errors
    /// of order `u` times that point's magnitude `s` (an edge's direction
    /// only as a turn about the edge: along the edge it is off by `u`,
    /// F35); the tolerance is `opts.touch_ulps * u * max(1, s)`.
    fn separation(
        &self,
        closest: &Vec3<T>,
        feature: Feature,
        face_normal: &Vec3<T>,
        opts: &DetectOptions,
    ) -> (T, Vec3<T>, T) {
        let p = &self.p;
        let (dist, sep, local) = match (feature, self.face) {
            (Feature::Face, Some(n)) => (self.plane_dist.clone(), n.clone(), p[self.nearest]),
            (Feature::Edge(i), _) => {
                let (a, b, e) = (p[i as usize], p[(i as usize + 1) % 3], &self.c.edges[i as usize]);
                let (from, e) = if norm_squared(a) <= norm_squared(b) { (a, e.clone()) } else { (b, -e.clone()) };
                let perp = across(&(-from), &e, &self.c.edge_sq[i as usize]);
                // Once more: `perp`, the difference of two vectors of the
                // size of `from`, is off by `u |from|` in every direction,
                // along the edge too, and a slide along the edge (a crease
                // with a parallel face) carries that component into the
                // distance, `u |from|` per radius slid: 1.5e-4 radii into
                // an `f32` ledge after a 97-radius slide (fuzz finding
                // F35). Projected again, its part along the edge is off by
                // about `u` (more only within `u |from|` of the line, where
                // the direction is rounding noise anyway); what is left is
                // a turn about the edge, which a slide along it does not
                // feel.
                let perp = across(&perp, &e, &self.c.edge_sq[i as usize]);
                let d = norm(&perp);
                let sep = normalize(&perp).unwrap_or_else(|| face_normal.clone());
                (d, sep, from)
            }
            _ => {
                let d = norm(closest);
                let sep = normalize(&-closest.clone()).unwrap_or_else(|| face_normal.clone());
                (d, sep, p[self.nearest])
            }
        };
        // The face normal stands in for an inactive feature's direction
        // only where the centre is over the face, within 60 degrees of its
        // normal: on a seam or a gently convex fold the sphere touches the
        // neighbouring face too, and their normals agree within the fold's
        // angle. Beside the edge, near the plane (the outside of a sheet
        // folded flat onto itself, fuzz finding F20), the face normal is
        // no contact direction at all: a push away from the edge would be
        // judged to approach the face by the rounding of its direction.
        let over_face = dot(&sep, face_normal) > T::c(0.5);
        let sep = if is_active(feature, self.c.active) || !over_face { sep } else { face_normal.clone() };
        let tol = T::c(opts.touch_ulps * T::unit_roundoff()) * max_abs(local, T::one());
        (dist, sep, tol)
    }
}

/// Where the unit sphere centred at `base` stands against a candidate now.
#[derive(Clone, Debug, PartialEq)]
pub struct Proximity<T: Real> {
    /// Distance from the centre to the triangle.
    pub dist: T,
    /// Unit separating direction, from the triangle towards the centre, as
    /// the robust sweep reports it for a contact at `t = 0` (the face normal
    /// on an inactive edge or vertex with the centre over the face).
    pub normal: Vec3<T>,
    /// The closest point of the triangle (in the caller's coordinates).
    pub point: Vec3<T>,
    /// The feature it lies on.
    pub feature: Feature,
    /// The touching tolerance of this distance (see [`sweep_robust`]).
    pub tol: T,
}

/// The distance and separating direction between the unit sphere at `base`
/// and candidate `c`, computed as [`sweep_robust`] decides a contact at
/// `t = 0` (relative to `base`, per feature): `None` when `c` is one-sided
/// (`opts.two_sided` false) and `base` lies behind it. Always inlined, as
/// [`closest_point_on_triangle`], for the same stall on its result.
#[must_use]
#[inline(always)]
pub fn proximity<T: Real>(c: &Candidate<T>, base: &Vec3<T>, opts: &DetectOptions) -> Option<Proximity<T>> {
    let zero = T::zero();
    let rel = c.triangle.relative_to(base);
    let p = [&rel.a, &rel.b, &rel.c];
    let nearest = nearest_vertex(&p.map(norm_squared));
    let mut face = c.normal.clone();
    let mut plane_dist = zero.clone();
    if let Some(n) = face.as_mut() {
        plane_dist = -dot(n, p[nearest]);
        if plane_dist < zero {
            if !opts.two_sided {
                return None;
            }
            *n = -n.clone();
            plane_dist = -plane_dist;
        }
    }
    let (closest, feature) = if c.long_lever {
        long_lever_closest(c, &rel, face.as_ref().map(|n| n * -plane_dist.clone()))
    } else {
        closest_point_on_triangle(&Vec3::zeros(), &rel)
    };
    let face_normal = face.clone().unwrap_or_else(|| normalize(&-closest.clone()).unwrap_or_else(Vec3::zeros));
    let local = Local { p, c, face: face.as_ref(), plane_dist: &plane_dist, nearest };
    let (dist, normal, tol) = local.separation(&closest, feature, &face_normal, opts);
    Some(Proximity { dist, normal, point: closest + base, feature, tol })
}

/// The point of candidate `c` closest to `p`, and the feature it lies on:
/// [`closest_point_on_triangle`] (Ericson's), or, for a candidate whose
/// lever can be long ([`Candidate::long_lever`]), the foot of `p` on the
/// plane where the side tests (the orientations of the candidate's edges
/// with the foot, seen along its normal) place it inside the triangle, and
/// else the nearest point of its three sides.
///
/// Rounded: the foot is `p` moved along the candidate's unit normal by the
/// distance to the plane through the vertex nearest `p` (errors of order
/// `u` times that vertex's distance, the normal's tilt times the same
/// lever), and each side test is an orientation of an edge, off by `u`
/// times the distance to that edge's start. Ericson's face coordinates are
/// quotients of differences of products, off by `u k far` times the lever
/// `k far / |e|` (`k` the shape factor, `far` the distance to the
/// vertices, `|e|` the longest edge): 0.59 radii for a centre 0.9 above a
/// 40 x 0.05 strip in `f32`, where the foot is exact to `u` (a review).
/// The sides' points are projections on the edges, off by a few `u` times
/// the distance. Ericson's is kept where the lever is short: within the
/// reach of a contact (`far` at most `|e| + 1.05`), the lever is at most
/// `4 (1 + 1.05)`, about 8, and the point off by at most `u k^2 far^2 /
/// |e|`, some 70 `u` (the terrain's triangles, `k` about 1.2 and `|e|`
/// about 1, stay near 5 `u`), and Ericson's alone is cheaper.
/// Always inlined, as [`closest_point_on_triangle`] is.
#[must_use]
#[inline(always)]
pub fn closest_point<T: Real>(c: &Candidate<T>, p: &Vec3<T>) -> (Vec3<T>, Feature) {
    if !c.long_lever {
        return closest_point_on_triangle(p, &c.triangle);
    }
    let rel = c.triangle.relative_to(p);
    let corners = [&rel.a, &rel.b, &rel.c];
    let foot = c.normal.as_ref().map(|n| n * dot(n, corners[nearest_vertex(&corners.map(norm_squared))]));
    let (q, feature) = long_lever_closest(c, &rel, foot);
    (q + p, feature)
}

/// The closest point to the origin of a long-lever candidate (vertices
/// `rel` relative to the origin) given the origin's foot on its plane
/// (`None` without a normal): the foot where the side tests place it
/// inside the triangle, else the nearest point of its sides. Ericson's face
/// coordinates are never used: with the foot just outside a long side they
/// put the point up to 2.7 radii off on a strip of shape factor 990 in
/// `f32`, where the sides' points are off by a few `u` times the distance
/// (a review of the first version, which fell back on them).
fn long_lever_closest<T: Real>(c: &Candidate<T>, rel: &Triangle<T>, foot: Option<Vec3<T>>) -> (Vec3<T>, Feature) {
    let inside = |f: &Vec3<T>| c.normal.as_ref().is_some_and(|winding| side_outside(c, rel, winding, f).is_none());
    match foot.filter(inside) {
        Some(f) => (f, Feature::Face),
        None => closest_point_on_sides(&Vec3::zeros(), rel),
    }
}

/// The index of the vertex nearest the origin, given their squared
/// distances (the first on a tie).
fn nearest_vertex<T: Real>(dist_sq: &[T; 3]) -> usize {
    (0..3).min_by(|&i, &k| dist_sq[i].partial_cmp(&dist_sq[k]).unwrap_or(std::cmp::Ordering::Equal)).unwrap_or(0)
}

/// Whether a contact on `feature` keeps its own normal (an active edge or
/// vertex, or the face) or takes the face normal (an internal one).
pub(crate) fn is_active(feature: Feature, active: ActiveFeatures) -> bool {
    match feature {
        Feature::Face => true,
        Feature::Edge(i) => active.edge(i),
        Feature::Vertex(i) => active.vertex(i),
    }
}
