//! Detection: the earliest time a unit sphere moving along `vel` touches a
//! triangle, where, and on which feature.
//!
//! Two variants sit side by side in [`sphere_triangle`]: Fauerby's test as
//! he wrote it ([`Detection::Fauerby`], the baseline, defects included) and
//! the robust one ([`Detection::Robust`]). [`Neighbourhood`] maps a frame's
//! candidate triangles into eSpace once; [`earliest_hit`] runs a variant
//! over them and [`sweep_world`] does the whole query against a world.

pub mod roots;
pub mod sphere_triangle;

pub use sphere_triangle::{
    Proximity, closest_point, fauerby_point_in_triangle, proximity, sweep_fauerby, sweep_robust,
};

use sphere_triangle::{SweptBox, sweep_robust_with_speed};

use crate::error::not_negative;
use crate::geom::{
    Ellipsoid, Feature, Triangle, Vec3, cross, cross_of_edges, dot, is_finite, max_abs, norm, norm_squared,
};
use crate::world::{ActiveFeatures, INTERNAL_EDGE_DEGREES, World};
use crate::{Error, Real};
use smallvec::SmallVec;

/// Which sphere-vs-triangle test to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "lab", serde(rename_all = "lowercase"))]
pub enum Detection {
    /// Fauerby's test, faithful to his code (one-sided, textbook roots).
    Fauerby,
    /// The robust test ([`sweep_robust`]).
    Robust,
}

impl Detection {
    /// Runs this variant on one candidate. Fauerby's ignores the active
    /// features (every edge of his is a real edge) and `limit`; the robust
    /// one only reports a hit earlier than `limit` (the best so far), which
    /// lets it give up early on triangles that cannot win.
    #[must_use]
    pub fn sweep<T: Real>(
        self,
        c: &Candidate<T>,
        base: &Vec3<T>,
        vel: &Vec3<T>,
        opts: &DetectOptions,
        limit: Option<&T>,
    ) -> Option<Hit<T>> {
        match self {
            Detection::Fauerby => sweep_fauerby(&c.triangle, base, vel, c.index),
            Detection::Robust => sweep_robust(c, base, vel, opts, limit),
        }
    }

    /// The lowercase name used on the command line and in reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Detection::Fauerby => "fauerby",
            Detection::Robust => "robust",
        }
    }
}

/// Options of the robust detection (Fauerby's has none).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
pub struct DetectOptions {
    /// Treat both sides of every triangle as solid (default `true`). When
    /// `false`, a triangle whose plane has the sphere centre behind it is
    /// ignored, as with back-face culling.
    pub two_sided: bool,
    /// The touching tolerance in units of `u * s` (unit roundoff times the
    /// input magnitude, see [`sweep_robust`]); default 16. A sphere whose
    /// closest distance is within `1 +- tol` counts as touching at `t = 0`.
    pub touch_ulps: f64,
    /// How much a sweep that starts touching a triangle (within the
    /// touching tolerance, not overlapping it) must approach it to meet it at
    /// `t = 0`, in units of `u * |vel|`: the contact is met only when
    /// `-sep . vel > approach_ulps * u * |vel|` (`sep` its separating
    /// direction). Default 0: any approach. The robust response's push-outs
    /// use its [`crate::respond::RobustOptions::feasible_ulps`], so that a
    /// push along a wall the body touches is not stopped by the rounding of
    /// that wall's direction.
    pub approach_ulps: f64,
}

impl DetectOptions {
    /// Checks every field against its documented range ([`sweep_world`]
    /// and [`crate::respond::move_body`] do this first): `touch_ulps` and
    /// `approach_ulps` finite and not negative.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), Error> {
        not_negative("detect.touch_ulps", self.touch_ulps)?;
        not_negative("detect.approach_ulps", self.approach_ulps)
    }
}

impl Default for DetectOptions {
    fn default() -> Self {
        DetectOptions { two_sided: true, touch_ulps: 16.0, approach_ulps: 0.0 }
    }
}

/// A contact found by a sweep, in the coordinates of the query.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit<T: Real> {
    /// Time of first touch, in `[0, 1]` (fraction of the velocity).
    pub t: T,
    /// The touched point on the triangle.
    pub point: Vec3<T>,
    /// Unit contact normal, from the contact point towards the sphere centre
    /// at the time of touch.
    pub normal: Vec3<T>,
    /// The feature touched.
    pub feature: Feature,
    /// Index of the triangle in its mesh.
    pub triangle: u32,
    /// `true` when the sphere already overlapped the triangle at `t = 0`.
    pub started_overlapping: bool,
}

/// One frame's candidate triangles in eSpace, relative to an origin.
///
/// Robust code uses the frame's start as origin (coordinates stay small far
/// from the world origin); Fauerby's and Linahan's use the world origin, as
/// they did.
#[derive(Clone, Debug)]
pub struct Neighbourhood<T: Real> {
    /// World-space origin of the eSpace coordinates.
    pub origin: Vec3<T>,
    /// The candidates, by increasing index, in eSpace relative to `origin`
    /// (the first [`INLINE_CANDIDATES`] stored inline: a frame's
    /// neighbourhood costs no allocation).
    pub triangles: SmallVec<[Candidate<T>; INLINE_CANDIDATES]>,
}

/// How many candidates a [`Neighbourhood`] holds without allocating: a
/// body walking on a tessellated surface gathers about 9 (the terrain of
/// `docs/performance.md`, cells as wide as the body's radius).
pub const INLINE_CANDIDATES: usize = 16;

/// A triangle of a mesh ready for detection, with what every sweep of a
/// frame would otherwise recompute: its unit normal and its box.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate<T: Real> {
    /// Its index in the mesh.
    pub index: u32,
    /// Its vertices, in the coordinates of the query.
    pub triangle: Triangle<T>,
    /// Its active edges and vertices ([`ActiveFeatures::ALL`] for a lone
    /// triangle).
    pub active: ActiveFeatures,
    /// Unit front normal, the direction of `(b - a) x (c - a)`, computed as
    /// the cross product of the two shorter edges (those meeting at the
    /// largest angle), `None` if the triangle is degenerate in this
    /// precision. Each edge is rounded by `u` of its length, which tilts the
    /// product by about `u |e_i| |e_j| / |e_i x e_j|`: for the two shorter
    /// edges that is `1 / sin` of the largest angle
    /// ([`Candidate::angle_factor`]), about 1 for any triangle but a flat
    /// cap (an obtuse sliver), whereas a pair with the longest edge of a
    /// needle would give its shape factor. Beyond the shape factor
    /// [`ACCURATE_SHAPE`] (every flat cap) the product is that of the exact
    /// edges instead ([`Candidate::accurate_normal`]), tilted by a few `u`,
    /// and `None` where that is zero (the vertices exactly collinear);
    /// except for triangles whose doubled area is below `16 / u^2` times
    /// the smallest normal value (`5e-23` in `f32`), where the exact
    /// product would round into gradual underflow.
    pub normal: Option<Vec3<T>>,
    /// Whether [`Candidate::normal`] is the product of the exact edges
    /// ([`cross_of_edges`]), taken for a triangle whose shape factor exceeds
    /// [`ACCURATE_SHAPE`]: its tilt is then a few `u` whatever the
    /// triangle's angles ([`Candidate::tilt`]).
    pub accurate_normal: bool,
    /// Lower corner of its box.
    pub lo: Vec3<T>,
    /// Upper corner of its box.
    pub hi: Vec3<T>,
    /// Its edges `b - a`, `c - b`, `a - c`, from the vertices as given: the
    /// difference of two nearby floats is rounded relative to the edge's own
    /// length, whereas vertices relative to a sweep's start carry errors of
    /// order `u |vertex - base|`, which can exceed a small triangle far from
    /// the start (a fast body) and destroy its shape.
    pub edges: [Vec3<T>; 3],
    /// Their squared lengths `|edges[i]|^2` (rounded as [`norm_squared`]
    /// rounds them).
    pub edge_sq: [T; 3],
    /// Shape factor `k = max |edge|^2 / |(b - a) x (c - a)|` (at least
    /// `2 / sqrt(3)`; large for a sliver, infinite when degenerate in this
    /// precision or, for a sliver, exactly): the closest point of a triangle is computed with an error
    /// of order `u k` times the coordinates, so the rejections that use it
    /// widen their margin by `k`.
    pub shape: T,
    /// Whether Ericson's closest point can carry a long lever near the
    /// body: a sliver (`shape` above 4) or a triangle shorter than the
    /// body's radius (every side below 1). Where it can, the robust
    /// detection and response take the foot on the plane when the side
    /// tests place it inside ([`crate::detect::closest_point`]).
    pub long_lever: bool,
}

/// The doubled area below which a candidate keeps the product of its
/// rounded edges: `2^4 / u^2` times the smallest normal value. Below it the
/// exact product's fused multiply-adds can round into gradual underflow,
/// and its error is no longer `u^2` of the edges' product (a review: in
/// `f32`, caps `1e-15` radii across were tilted `6,500` times more than
/// the exact product's tilt factor says). `2^-74`, about `5e-23`, in
/// `f32`; `2^-912` in `f64`; no floor for MPFR.
fn exact_product_floor<T: Real>() -> f64 {
    let u = T::unit_roundoff();
    16.0 * T::min_positive_normal() / (u * u)
}

/// The unit normal along `raw` (a product of two edges), the shape factor
/// for the squared longest edge `longest`, and `|raw|`; no normal and an
/// infinite shape factor where `|raw|` is zero or not finite. As
/// `normalize(raw)`, without taking the norm twice. (A product by one
/// reciprocal would save two quotients, but its extra `2u` per component
/// flipped a tie between two walls in the lab's
/// `linahan-nan-narrow-slot-diagonal` case, in `f32` and `Mpfr<24>`.)
#[inline(always)]
fn normal_and_shape<T: Real>(raw: &Vec3<T>, longest: T) -> (Option<Vec3<T>>, T, T) {
    let area2 = norm_without_overflow(raw);
    let has_area = area2 > T::zero() && area2.is_finite();
    let normal = has_area.then(|| raw.map(|x| x / &area2));
    let shape = if has_area { longest / &area2 } else { T::c(f64::INFINITY) };
    (normal, shape, area2)
}

/// [`Candidate::long_lever`] for shape factor `shape` and squared sides
/// `edge_sq`.
#[inline(always)]
fn long_lever<T: Real>(shape: &T, edge_sq: &[T; 3]) -> bool {
    *shape > T::c(4.0) || edge_sq.iter().all(|l| *l < T::one())
}

/// `|v|`, or where the squares overflow (a triangle's doubled area beyond
/// about `1.8e19` in `f32`, `1.3e154` in `f64`, sides beyond about `4e9`
/// and `1e77` radii) the norm of `v` scaled by its largest coordinate.
/// Left infinite, a large triangle had no normal and no face, and a sweep
/// onto it found nothing (a review).
#[inline(always)]
fn norm_without_overflow<T: Real>(v: &Vec3<T>) -> T {
    let n = norm(v);
    if n.is_finite() || !is_finite(v) {
        return n;
    }
    let m = max_abs(v, T::zero());
    norm(&v.map(|x| x / &m)) * m
}

impl<T: Real> Candidate<T> {
    /// A candidate from a triangle of a mesh.
    #[must_use]
    pub fn new(index: u32, triangle: Triangle<T>, active: ActiveFeatures) -> Self {
        let (lo, hi) = triangle.bounds();
        let mut candidate = Self::with_bounds(index, triangle, active, lo, hi);
        if candidate.accurate_normal {
            candidate.take_exact_normal();
        }
        candidate
    }

    /// Replaces the normal and the shape factor by those of the product of
    /// the exact edges ([`cross_of_edges`]) other than the longest; no
    /// normal, and an infinite shape factor, where that product is zero
    /// (the vertices collinear). For the candidates [`Candidate::with_bounds`]
    /// marks [`Candidate::accurate_normal`].
    #[cold]
    #[inline(never)]
    fn take_exact_normal(&mut self) {
        let (a, b, c) = (&self.triangle.a, &self.triangle.b, &self.triangle.c);
        let [l0, l1, l2] = &self.edge_sq;
        // `(x, y, z)` with `y - x` and `z - y` the two edges after the
        // longest, in cyclic order, as `with_bounds` chose them.
        let (longest, [x, y, z]) = if l0 >= l1 && l0 >= l2 {
            (l0, [b, c, a])
        } else if l1 >= l2 {
            (l1, [c, a, b])
        } else {
            (l2, [a, b, c])
        };
        (self.normal, self.shape, _) = normal_and_shape(&cross_of_edges(x, y, z), longest.clone());
        self.long_lever = long_lever(&self.shape, &self.edge_sq);
    }

    /// [`Candidate::new`] given the triangle's box `[lo, hi]` (as
    /// [`Triangle::bounds`] computes it), when the caller has it already,
    /// but with the rounded edges' normal: where it marks
    /// [`Candidate::accurate_normal`], the candidate is final only after
    /// [`Candidate::take_exact_normal`].
    /// Always inlined, so that the gather writes the candidate once, where
    /// it lives: called, the triangle went through the stack with narrow
    /// stores read back by wide loads (a store-forwarding stall) and the
    /// result was copied (`docs/performance.md`, History, session 17).
    #[inline(always)]
    fn with_bounds(index: u32, triangle: Triangle<T>, active: ActiveFeatures, lo: Vec3<T>, hi: Vec3<T>) -> Self {
        let (a, b, c) = (&triangle.a, &triangle.b, &triangle.c);
        let edges = [b - a, c - b, a - c];
        let edge_sq = [norm_squared(&edges[0]), norm_squared(&edges[1]), norm_squared(&edges[2])];
        let [l0, l1, l2] = edge_sq.clone();
        // The two edges after the longest, in cyclic order: their cross
        // product is `(b - a) x (c - a)` in exact arithmetic.
        let (raw, longest) = if l0 >= l1 && l0 >= l2 {
            (cross(&edges[1], &edges[2]), l0)
        } else if l1 >= l2 {
            (cross(&edges[2], &edges[0]), l1)
        } else {
            (cross(&edges[0], &edges[1]), l2)
        };
        let (normal, shape, area2) = normal_and_shape(&raw, longest);
        // A flat cap's product of rounded edges is tilted by a few `u g`
        // (`Candidate::tilt`); beyond the shape factor `ACCURATE_SHAPE`
        // (`g` is at most `k`) the normal is to come from the exact edges
        // ([`Candidate::take_exact_normal`]), after the gather's loop: a
        // call in the loop, even one never made, cost the terrain's moves
        // 5% more instructions.
        let accurate = normal.is_some() && shape > T::c(ACCURATE_SHAPE) && area2 > T::c(exact_product_floor::<T>());
        let long_lever = long_lever(&shape, &edge_sq);
        Candidate {
            index,
            triangle,
            active,
            normal,
            accurate_normal: accurate,
            lo,
            hi,
            edges,
            edge_sq,
            shape,
            long_lever,
        }
    }

    /// `1 / sin` of the largest angle, `|e_i| |e_j| / |e_i x e_j|` for the
    /// two shorter edges (1 for a right triangle, `2 / sqrt(3)` for an
    /// equilateral one, large only for a flat cap; infinite when
    /// degenerate), in `f64`. Where the product of the squared sides
    /// leaves `f64`'s range (sides beyond about `1e51` or below `1e-51`
    /// radii) the two shorter sides' lengths are multiplied instead (a
    /// review, session 29: the product overflowed, and a flat cap `1e60`
    /// radii wide lost its tilt's padding).
    #[must_use]
    pub fn angle_factor(&self) -> f64 {
        let [l0, l1, l2] = [0, 1, 2].map(|i| self.edge_sq[i].to_f64());
        let longest = l0.max(l1).max(l2);
        let shape = self.shape.to_f64();
        if !(longest > 0.0 && shape < f64::INFINITY) {
            return f64::INFINITY;
        }
        // `|e_i|^2 |e_j|^2 = l0 l1 l2 / longest` and `shape = longest / |e_i x e_j|`.
        let product = l0 * l1 * l2 / longest;
        let sides = if product.is_normal() {
            product.sqrt()
        } else {
            let mut l = [l0, l1, l2];
            l.sort_by(f64::total_cmp);
            l[0].sqrt() * l[1].sqrt()
        };
        sides * shape / longest
    }

    /// The tilt factor of [`Candidate::normal`]: its direction is off by a
    /// few `u` times this, and so is a distance to the plane per unit of
    /// lever arm. For the product of the rounded edges it is the angle
    /// factor `g` ([`Candidate::angle_factor`]); for the exact edges'
    /// product ([`Candidate::accurate_normal`]) `1 + 32 u g` (or `g` where
    /// smaller): about 1 for a flat cap until `g` nears `1 / u`. Infinite
    /// when degenerate.
    #[must_use]
    pub fn tilt(&self) -> f64 {
        let g = self.angle_factor();
        if self.accurate_normal { g.min(1.0 + ACCURATE_TILT_ULPS * T::unit_roundoff() * g) } else { g }
    }

    /// A bound of [`Candidate::tilt`] in the working precision: the shape
    /// factor `k` (the tilt factor never exceeds it; no square root), or,
    /// where the normal is the exact edges' product (slivers alone), the
    /// tilt factor itself: `1 + 32 u k` can exceed it many times over for
    /// a cap whose apex lies near one end. Between 1 and `k`.
    #[inline]
    #[must_use]
    pub fn tilt_bound(&self) -> T {
        if self.accurate_normal {
            // `tilt` is computed in `f64`: where the squared sides leave its
            // range (MPFR triangles below about `1e-162` or beyond `1e154`
            // radii) it can come out 0, infinite or NaN, and `k` stands in
            // (a review: a NaN window missed the face).
            let tilt = T::c(self.tilt());
            if tilt >= T::one() && tilt <= self.shape {
                return tilt;
            }
        }
        self.shape.clone()
    }

    /// The squared distance from `p` to this candidate's box (zero inside):
    /// a lower bound of the squared distance to the triangle, cheap enough to
    /// reject a candidate before any per-triangle work. Rounded: each axis's
    /// excess is one subtraction (error `u` times the larger coordinate),
    /// so callers compare it against a bound carrying that much slack.
    #[inline]
    #[must_use]
    pub fn box_distance_sq(&self, p: &Vec3<T>) -> T {
        box_distance_sq(&self.lo, &self.hi, p)
    }

    /// A lone triangle (every edge and vertex active).
    #[must_use]
    pub fn lone(index: u32, triangle: Triangle<T>) -> Self {
        Self::new(index, triangle, ActiveFeatures::ALL)
    }
}

/// The shape factor ([`Candidate::shape`]) beyond which a candidate's
/// normal is the product of its exact edges ([`cross_of_edges`]): the tilt
/// factor `g` never exceeds the shape factor, so below it the plain
/// product's tilt is at most a few `u` times 4, and the terrain's
/// triangles (shape factor about 2) never pay for the exact one.
pub const ACCURATE_SHAPE: f64 = 4.0;

/// The exact edges' product is off in direction by at most about
/// `3u + 50 u^2 g` ([`cross_of_edges`]), `u` times `3 (1 + 17 u g)`,
/// against a few `u g` for the rounded edges': its tilt factor is taken
/// as `1 + ACCURATE_TILT_ULPS u g` (or `g` where that is smaller).
const ACCURATE_TILT_ULPS: f64 = 32.0;

/// How far beyond the radii a gather reaches, in radii (eSpace units):
/// room for paddings and small push-outs, far above any rounding of the
/// box distances that decide what is gathered.
pub const REACH_MARGIN: f64 = 1.05;

/// The region a body can touch: the points of the world box `[min, max]`
/// within eSpace distance `radius` of the world point `centre` (an
/// ellipsoid around it, with the body's proportions).
///
/// A frame whose centre travels a path of eSpace length `L` from `c`
/// touches only triangles within `L + 1` of `c`: slides project eSpace
/// displacements, so they never lengthen the path (its box is the ball's).
/// A straight sweep touches only triangles within 1 of its segment: the
/// segment's box grown by the radii, intersected with the ball around its
/// midpoint (a long sweep's box stays narrow across the motion).
#[derive(Clone, Debug, PartialEq)]
pub struct Reach<T: Real> {
    /// Lower corner of the world box.
    pub min: Vec3<T>,
    /// Upper corner of the world box.
    pub max: Vec3<T>,
    /// World-space centre of the ball.
    pub centre: Vec3<T>,
    /// eSpace radius of the ball.
    pub radius: T,
}

impl<T: Real> Reach<T> {
    /// The reach of a frame starting at `position` (world space) whose
    /// displacements (world space, slid or not) are `moves`: radius
    /// [`REACH_MARGIN`] plus the sum of their eSpace lengths, centred on
    /// `position` itself (no rounding), the radius grown by `4 u` of
    /// itself for its own rounding.
    #[must_use]
    pub fn of_frame(body: &Ellipsoid<T>, position: &Vec3<T>, moves: &[&Vec3<T>]) -> Self {
        Self::of_frame_within(body, position, moves, REACH_MARGIN)
    }

    /// [`Reach::of_frame`] with `margin` radii (eSpace) instead of
    /// [`REACH_MARGIN`]: the robust response reaches farther where the
    /// final rounding of a position can undo its skin
    /// ([`crate::respond::robust`]'s `skin_margin`).
    #[must_use]
    pub fn of_frame_within(body: &Ellipsoid<T>, position: &Vec3<T>, moves: &[&Vec3<T>], margin: f64) -> Self {
        let length = moves.iter().fold(T::zero(), |r, m| r + norm(&body.to_espace(m)));
        let radius = T::c(margin) + length;
        let radius = radius.clone() + radius * T::c(4.0 * T::unit_roundoff());
        Reach::around(body, position, &Vec3::zeros(), &radius.clone(), position.clone(), radius)
    }

    /// The reach of one straight sweep from `position` by `velocity`: every
    /// point within [`REACH_MARGIN`] (eSpace) of the segment. The ball is
    /// centred on the segment's midpoint, rounded in world coordinates: its
    /// radius is grown by that rounding (`u` per coordinate of the
    /// midpoint, in eSpace; a review found `f32` sweeps a million radii
    /// from the origin missing the wall they end on, the rounding being
    /// more than the margin).
    #[must_use]
    pub fn of_sweep(body: &Ellipsoid<T>, position: &Vec3<T>, velocity: &Vec3<T>) -> Self {
        let half = velocity * T::c(0.5);
        let centre = position + &half;
        let u = T::unit_roundoff();
        let half_e = norm(&body.to_espace(&half));
        let off = max_abs(&body.to_espace(&centre), half_e.clone()) * T::c(4.0 * 3f64.sqrt() * u);
        let radius = half_e + T::c(REACH_MARGIN);
        let radius = radius.clone() + radius * T::c(4.0 * u) + off;
        Reach::around(body, position, velocity, &T::c(REACH_MARGIN), centre, radius)
    }

    /// The reach with the box around the segment from `position` by
    /// `velocity`, grown by `by` radii and by the rounding of its corners
    /// (`4 u` times the magnitudes each corner sums, per axis, so a corner
    /// computed in `T` never cuts into the margin: far from the origin half
    /// an ulp of the position can exceed it).
    fn around(body: &Ellipsoid<T>, position: &Vec3<T>, velocity: &Vec3<T>, by: &T, centre: Vec3<T>, radius: T) -> Self {
        let end = position + velocity;
        let margin = T::c(4.0 * T::unit_roundoff());
        let grow = Vec3::from_fn(|i, _| {
            let g = body.radii()[i].clone() * by;
            let sum = position[i].clone().abs() + velocity[i].clone().abs() + &g;
            g + margin.clone() * sum
        });
        let min = Vec3::from_fn(|i, _| position[i].clone().min(end[i].clone()) - &grow[i]);
        let max = Vec3::from_fn(|i, _| position[i].clone().max(end[i].clone()) + &grow[i]);
        Reach { min, max, centre, radius }
    }
}

impl<T: Real> Neighbourhood<T> {
    /// An empty neighbourhood with eSpace coordinates relative to `origin`.
    #[must_use]
    pub fn new(origin: Vec3<T>) -> Self {
        Neighbourhood { origin, triangles: SmallVec::new() }
    }

    /// Replaces the candidates with the triangles of `world` that may lie
    /// within `reach`, mapped to eSpace relative to `self.origin`, by
    /// increasing index: those of the BVH's
    /// leaves that meet the reach's box whose own eSpace box lies within the
    /// reach's radius of its centre. Every triangle within reach is among
    /// them; a few outside the box may be too (the sweeps reject them).
    ///
    /// Rounded: the box distance is computed from the rounded eSpace
    /// vertices with an error of order `u` times their coordinates (relative
    /// to `origin`), far below the [`REACH_MARGIN`] that every reach carries
    /// beyond the unit radius; the world box and ball handed to the BVH are
    /// widened for the conversion to `f64` by [`World::each_candidate`].
    /// That holds from about 10 bits of precision on. Below, the margin
    /// itself rounds away (`1.05` is `1` in 2 to 4 bits) and the touching
    /// tolerance exceeds it: in `Mpfr<2>` to `Mpfr<6>` a review found
    /// random sweeps through the world missing triangles that the same
    /// sweep against the triangle alone hits (none from 8 bits on), part of
    /// why the robust response's guarantees need about 16 bits.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming a gathered triangle whose sides,
    /// measured in the body's radii, are too long for `T`: their squares
    /// overflow (beyond about `1.8e19` radii in `f32`, `1.3e154` in
    /// `f64`), so no distance to the triangle could be computed and every
    /// test would miss it.
    pub fn gather(&mut self, world: &World<T>, body: &Ellipsoid<T>, reach: &Reach<T>) -> Result<(), Error> {
        let origin = &self.origin;
        let to_e = |v: &Vec3<T>| body.to_espace(&(v - origin));
        let centre = to_e(&reach.centre);
        let radius_sq = reach.radius.clone() * &reach.radius;
        // The BVH's leaves hold several triangles and its bounds are rounded
        // outward; the distance of each triangle's own eSpace box keeps only
        // those within reach, and only they pay for a candidate's normal,
        // edges and shape.
        // Indices first, sorted, so that candidates are built in place in
        // their final order.
        let mut indices: SmallVec<[u32; 2 * INLINE_CANDIDATES]> = SmallVec::new();
        world.each_candidate(&reach.min, &reach.max, Some((&reach.centre, body.radii(), &reach.radius)), |t| {
            indices.push(t);
        });
        indices.sort_unstable();
        self.triangles.clear();
        for t in indices {
            let w = world.corners(t);
            let triangle = Triangle::new(to_e(w[0]), to_e(w[1]), to_e(w[2]));
            let (lo, hi) = triangle.bounds();
            if box_distance_sq(&lo, &hi, &centre) <= radius_sq {
                self.triangles.push(Candidate::with_bounds(t, triangle, world.mesh().active(t), lo, hi));
            }
        }
        // A finite shape factor implies finite sides: only a triangle
        // without one (degenerate or overflowing) is looked at further.
        // On an error no candidate is left (those after it would still wait
        // for their exact normals).
        let overflowing = self.triangles.iter_mut().find_map(|c| {
            if c.accurate_normal {
                c.take_exact_normal();
            }
            (!(c.shape.is_finite() || c.edge_sq.iter().all(Real::is_finite))).then_some(c.index)
        });
        match overflowing {
            None => Ok(()),
            Some(index) => {
                self.triangles.clear();
                Err(Error::InvalidArgument {
                    what: format!("triangle {index}"),
                    message: "measured in the body's radii, its sides are too long for this precision (their \
                              squares overflow): split it into smaller triangles, or use a wider precision"
                        .into(),
                })
            }
        }
    }

    /// The earliest hit of the unit sphere at `base` moving by `vel` (both in
    /// this neighbourhood's eSpace coordinates) over all its triangles.
    #[must_use]
    pub fn earliest_hit(
        &self,
        detection: Detection,
        base: &Vec3<T>,
        vel: &Vec3<T>,
        opts: &DetectOptions,
    ) -> Option<Hit<T>> {
        earliest_hit(detection, &self.triangles, base, vel, opts)
    }
}

/// The earliest hit over `triangles`: smallest `t`, ties to the lowest
/// triangle index. The robust variant prunes each candidate with the best
/// time so far, which keeps ties exact for candidates given in increasing
/// index order, as [`Neighbourhood`] keeps them. The answer depends on the
/// order given only within the touching tolerance: a grazing face contact
/// pruned by an earlier triangle's time can leave the same triangle's edge
/// contact a few `u s k` later (a review measured 138 of a million grazing
/// pairs in `f32`, each within `9.5 u s k`; before the face contact's
/// pruning considered its window, about 4,500).
///
/// One exception, robust only: an inactive (internal) edge or vertex met at
/// `t > 0`, or an active one lying on or behind the face's plane (the seam
/// of a flat surface that is no shared edge: a T-junction, a face given
/// twice; R30b), and the face of a triangle around it, met within the touching
/// tolerance of the same time (`touch_ulps u s` over the speed, `s` the
/// contact point's magnitude), give that face's hit at the earlier of the
/// two times, if the face's normal lies within the internal-edge angle of
/// the feature's direction, the face is local to the feature (it shares a
/// vertex of it, or its contact point is near), and the feature's
/// direction does not lie between its own triangle's normal and the
/// face's (the bottom of a valley, where it is the constraint). On a flat seam hit head-on the two
/// tie up to rounding, and the edge's geometric direction is tilted by the
/// square root of the distance the rounding hides, not by a rounding: as
/// the slide's plane it carried the rest of a push sideways (a review,
/// twenty-eighth session: `0.014` radii along a wall after a push of 200
/// radii in `f32`, `tests/regressions/respond_seam_hits.rs`). Where no
/// face is met so soon (the ridge of a gently convex fold hit head-on) the
/// edge's direction is the constraint and stays.
#[must_use]
pub fn earliest_hit<'a, T: Real + 'a>(
    detection: Detection,
    triangles: impl IntoIterator<Item = &'a Candidate<T>>,
    base: &Vec3<T>,
    vel: &Vec3<T>,
    opts: &DetectOptions,
) -> Option<Hit<T>> {
    let mut best: Option<(Hit<T>, &'a Candidate<T>)> = None;
    // The robust sweeps' pruning time: the best time, or past it by the
    // window within which a face would stand in for the best hit.
    let mut limit: Option<T> = None;
    let swept = SweptBox::new(base, vel);
    for c in triangles {
        let hit = match detection {
            Detection::Fauerby => sweep_fauerby(&c.triangle, base, vel, c.index),
            Detection::Robust if swept.misses(c) => None,
            Detection::Robust => sweep_robust_with_speed(c, base, vel, &swept.speed, opts, limit.as_ref()),
        };
        let Some(h) = hit else { continue };
        let next = match best.take() {
            None => (h, c),
            Some((b, bc)) => match seam_face(detection, (&b, bc), (&h, c), base, &swept.speed, opts) {
                Some(face) => face,
                None if h.t < b.t || (h.t == b.t && h.triangle < b.triangle) => (h, c),
                None => (b, bc),
            },
        };
        limit = Some(match seam_window(detection, &next.0, base, &swept.speed, opts) {
            Some(w) => next.0.t.clone() + w,
            None => next.0.t.clone(),
        });
        best = Some(next);
    }
    best.map(|(h, _)| h)
}

/// For a robust hit `h` on an edge or vertex at `t > 0`, the window of
/// time within which a face of a triangle around that feature may stand
/// in for it ([`seam_face`] decides): the touching
/// tolerance `opts.touch_ulps u s` (`s` the magnitude of the contact point
/// relative to `base`, at least 1) over the speed `speed`. `None` for any
/// other hit.
fn seam_window<T: Real>(
    detection: Detection,
    h: &Hit<T>,
    base: &Vec3<T>,
    speed: &T,
    opts: &DetectOptions,
) -> Option<T> {
    let seam = detection == Detection::Robust && h.feature != Feature::Face && h.t > T::zero();
    seam.then(|| {
        let s = max_abs(&(&h.point - base), T::one());
        T::c(opts.touch_ulps * T::unit_roundoff()) * s / speed
    })
}

/// The face hit that stands in for a seam hit ([`earliest_hit`]): of the
/// two hits `a` and `b` (each with its candidate), one a face and the
/// other an edge or vertex met at `t > 0` within [`seam_window`]
/// of it, inactive or lying on or behind the face's plane (each of its
/// vertices `v` with `n . (v - q) <= d + touch_ulps u max(|v - q|, 1)`,
/// `n` and `q` the face hit's normal and point, `d` the window as a
/// distance: the seam of a flat surface that is no shared edge, such as a
/// T-junction, where the neighbour's edge tied with the face and its
/// tilted direction slid landings sideways by up to `5.8e-4` radii in
/// `f32` and a push into a doubled wall `0.014` radii along it; a directed
/// probe, thirtieth session, R30b), the face's hit (its point and normal)
/// at the earlier of the two
/// times, if the face is local to the feature and its normal lies within
/// the default internal-edge angle ([`INTERNAL_EDGE_DEGREES`], not a
/// mesh's own) of the feature's direction (a wall met at a corner beside a
/// seam keeps its own hit) and the feature's direction does not lie
/// between its triangle's normal and the face's ([`between_faces`]). Local: its triangle shares a vertex of the
/// feature (bit for bit: candidates of one neighbourhood are mapped from
/// the same world vertices; an edge met at its end ties with the faces
/// around that end), or its contact point lies within `2 sqrt(2 d)` of
/// the feature's, `d` the window as a distance (a tie leaves the centre
/// up to `sqrt(2 d)` beside the feature, and on a mesh finer than that
/// the face under it can be a few triangles away).
fn seam_face<'a, T: Real>(
    detection: Detection,
    a: (&Hit<T>, &'a Candidate<T>),
    b: (&Hit<T>, &'a Candidate<T>),
    base: &Vec3<T>,
    speed: &T,
    opts: &DetectOptions,
) -> Option<(Hit<T>, &'a Candidate<T>)> {
    let ((face, fc), (seam, sc)) = match (a.0.feature, b.0.feature) {
        (Feature::Face, Feature::Face) => return None,
        (Feature::Face, _) => (a, b),
        (_, Feature::Face) => (b, a),
        _ => return None,
    };
    let window = seam_window(detection, seam, base, speed, opts)?;
    let around = [&fc.triangle.a, &fc.triangle.b, &fc.triangle.c];
    // Or its contact point within twice the offset the tie allows: on a
    // mesh finer than that offset the face under the centre can lie a few
    // triangles from the feature met.
    let shares = seam.feature.corners().any(|k| around.contains(&sc.triangle.vertex(k)))
        || norm_squared(&(&face.point - &seam.point)) <= T::c(8.0) * &window * speed;
    let aligned = dot(&seam.normal, &face.normal) >= T::c(INTERNAL_EDGE_DEGREES.to_radians().cos());
    let near = face.t <= seam.t.clone() + &window && seam.t <= face.t.clone() + &window;
    // An active feature only where it lies on or behind the face's plane
    // (up to the window as a distance and the rounding of the normal over
    // the lever): a seam of a flat surface that is no shared edge.
    let hidden = || {
        let ulps = T::c(opts.touch_ulps * T::unit_roundoff());
        sc.triangle.feature_on_or_behind(seam.feature, &face.normal, &face.point, &(window.clone() * speed), &ulps)
    };
    let inactive = !sphere_triangle::is_active(seam.feature, sc.active);
    (shares && aligned && near && !between_faces(seam, sc, face) && (inactive || hidden()))
        .then(|| (Hit { t: face.t.clone().min(seam.t.clone()), ..face.clone() }, fc))
}

/// Whether the direction of the seam hit `seam` (of candidate `sc`) lies
/// strictly between its own triangle's normal and the normal of the face
/// hit `face` (both turned towards the centre): the contact directions of
/// a fold's bottom or top, such as the bisector of a shallow valley hit
/// head-on, where either face's normal alone would slide the body across
/// the fold (a review of R28a: 0.44 radii across a 1-degree valley in
/// `f32`, against 0.01 with the edge's direction). On a flat seam the two
/// normals coincide and no direction lies between them.
fn between_faces<T: Real>(seam: &Hit<T>, sc: &Candidate<T>, face: &Hit<T>) -> bool {
    let Some(own) = &sc.normal else { return false };
    let own = if dot(own, &seam.normal) < T::zero() { -own.clone() } else { own.clone() };
    dot(&cross(&own, &seam.normal), &cross(&seam.normal, &face.normal)) > T::zero()
}

/// The squared distance from `p` to the box `[lo, hi]` (zero inside); each
/// axis's excess is one rounded subtraction.
#[inline]
fn box_distance_sq<T: Real>(lo: &Vec3<T>, hi: &Vec3<T>, p: &Vec3<T>) -> T {
    let zero = T::zero();
    (0..3).fold(zero.clone(), |sum, i| {
        let excess = (lo[i].clone() - &p[i]).max(p[i].clone() - &hi[i]).max(zero.clone());
        sum + excess.clone() * excess
    })
}

/// Sweeps `body` from `position` by `velocity` (world space) through the
/// whole `world` and returns the earliest hit, in world space: `point` on
/// the triangle, `normal` the unit surface normal there (the eSpace normal
/// mapped back), `t` the fraction of `velocity`.
///
/// # Errors
/// [`Error::InvalidArgument`] for options out of range
/// ([`DetectOptions::validate`]); [`Error::NonFinite`] for a non-finite
/// position or velocity; [`Error::InvalidArgument`] if, measured in the
/// body's radii, the position or the velocity is not representable in `T`
/// ([`check_in_radii`]), or a triangle within reach is too large
/// ([`Neighbourhood::gather`]).
pub fn sweep_world<T: Real>(
    world: &World<T>,
    body: &Ellipsoid<T>,
    position: &Vec3<T>,
    velocity: &Vec3<T>,
    detection: Detection,
    opts: &DetectOptions,
) -> Result<Option<Hit<T>>, Error> {
    opts.validate()?;
    check_finite("position", position)?;
    check_finite("velocity", velocity)?;
    let origin = match detection {
        Detection::Robust => position.clone(),
        Detection::Fauerby => Vec3::zeros(),
    };
    let reach = Reach::of_sweep(body, position, velocity);
    check_in_radii(espace_magnitude(body, position), &reach)?;
    let mut hood = Neighbourhood::new(origin.clone());
    hood.gather(world, body, &reach)?;
    let base = body.to_espace(&(position - &origin));
    let vel = body.to_espace(velocity);
    Ok(hood.earliest_hit(detection, &base, &vel, opts).map(|h| Hit {
        point: body.from_espace(&h.point) + &origin,
        normal: body.normal_from_espace(&h.normal),
        ..h
    }))
}

/// The largest absolute eSpace coordinate of world point `p`, in `f64`.
#[must_use]
pub fn espace_magnitude<T: Real>(body: &Ellipsoid<T>, p: &Vec3<T>) -> f64 {
    max_abs(&body.to_espace(p), T::zero()).to_f64()
}

/// [`Error::InvalidArgument`] unless, measured in the body's radii, the
/// position (`position_magnitude`, see [`espace_magnitude`]) and the
/// length of the motion (in `reach`'s radius) are representable in `T`:
/// beyond, a length squared is infinite and no response can work (the
/// robust one would stop, the faithful ones give NaN).
///
/// # Errors
/// As described.
pub fn check_in_radii<T: Real>(position_magnitude: f64, reach: &Reach<T>) -> Result<(), Error> {
    if reach.radius.is_finite() && position_magnitude.is_finite() {
        return Ok(());
    }
    Err(Error::InvalidArgument {
        what: "move".into(),
        message: format!(
            "measured in the body's radii, the displacement ({:e}) or the position ({position_magnitude:e}) \
             overflows this precision: move in smaller steps or use a wider precision",
            (reach.radius.clone() - T::c(REACH_MARGIN)).to_f64(),
        ),
    })
}

/// [`Error::NonFinite`] if a coordinate of `v` is NaN or infinite.
///
/// # Errors
/// As described.
pub fn check_finite<T: Real>(what: &str, v: &Vec3<T>) -> Result<(), Error> {
    if is_finite(v) {
        return Ok(());
    }
    let value = v.iter().map(Real::to_f64).find(|x| !x.is_finite()).unwrap_or(f64::NAN);
    Err(Error::NonFinite { what: what.to_string(), value })
}

/// Fauerby's `nearestDistance`: how far along `vel` the hit lies.
#[must_use]
pub fn hit_distance<T: Real>(hit: &Hit<T>, vel: &Vec3<T>) -> T {
    hit.t.clone() * norm(vel)
}
