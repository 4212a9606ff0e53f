//! The robust response: what a game would ship.
//!
//! Per pass, starting from the eSpace position `p` (relative to the frame's
//! start, so far-from-origin coordinates keep their precision) with the
//! desired displacement `w`:
//!
//! 0. Start from the resting contacts: the triangles within `1 + 2 pad` of
//!    `p`, found by one scan at the end of the previous pass (or at the
//!    start of the frame). Those that `w` approaches join the set of planes
//!    met (step 3) before any sweep, with the normal the robust detection
//!    would give a contact at `t = 0`; a sweep would only find each of them
//!    again at `t = 0`. `w` is projected onto them (step 4).
//! 1. Sweep the unit sphere along `w` (robust detection by default).
//!    Nothing hit: move the whole way, done.
//! 2. Advance to the hit, stopping `pad` short *along the contact normal*:
//!    the advance is shortened by `pad / (-w . n)` (capped at the hit); if
//!    that leaves less than `pad / 2` of gap (a grazing or touching hit;
//!    a touch at `t = 0` counts as no gap) the
//!    body is pushed out along `n` to `pad`, never further than half the
//!    room to whatever lies behind it (so it centres in a slot narrower than
//!    `2 + 2 pad` instead of jamming). A body already within the resting
//!    band `[pad / 2, 2 pad]` of the contact does not move towards it: no
//!    creeping, and no toggling between neighbouring floats far from the
//!    origin.
//! 3. Add the contact normal to the set of planes met this pass. (The
//!    robust detection already gives an edge or vertex contact between
//!    coplanar or gently convex triangles, an internal edge of a tessellated
//!    surface, the face normal, so seams do not snag; see
//!    `world::Adjacency::active_features`.)
//! 4. Project the original displacement, scaled by the fraction of the
//!    frame left, onto the cone
//!    `{v : v . n_i >= 0 for every plane met}`: exactly, by trying the
//!    unconstrained move, each single plane and each pair's crease, and
//!    keeping the closest admissible candidate (zero if none: a corner).
//!    Planes the motion leaves do not constrain; a pair whose crease is
//!    shorter than `parallel_ulps * u` (parallel or coplanar planes) is
//!    never normalised or used. The projection then keeps none of its
//!    approach to the plane just hit (the cone admits `feasible_ulps * u`
//!    of it, more than the graze share of step 5).
//! 5. Repeat with the projected displacement. A triangle already met in
//!    this pass and touched again at the start of a sweep is skipped by
//!    the next sweep when the displacement approaches it by no more than
//!    the touching tolerance's share (`touch_ulps * u`, see
//!    [`crate::detect::DetectOptions`]) of the displacement still to go
//!    before projection (`w` times the fraction of the frame left): a
//!    displacement projected onto its plane approaches it only by the
//!    projection's rounding, a few `u` of that length however short the
//!    projection (fuzz finding F32), and meeting it again, sweep after
//!    sweep, would add nothing to the cone and freeze the body (fuzz
//!    finding F24). Over the sweep the body then nears it by at most that
//!    share, `16 u |w|`, less than the padding (`48 u s`, `s` at least the
//!    displacement's largest coordinate, so `|w| <= sqrt(3) s`), and the
//!    skin is restored at the end of the pass.
//!
//! A pass whose displacement is too long for the padding (thousands of
//! radii in `f32`) is slid in equal parts, each a pass of its own
//! ([`parts`]).
//!
//! Bound: at most [`RobustOptions::max_iterations`] sweeps per pass, or per
//! part of a pass slid in parts (plus one push-out sweep after a grazing
//! contact, not counted). Each sweep either
//! ends the pass or adds a plane; once three independent planes are met the
//! cone is a point and the pass stops (`Blocked`).
//!
//! Every pass ends with a scan (`settle`): the scan for the next pass's resting
//! contacts, which also restores the skin (a body left closer than
//! `1 + pad / 2` to a triangle is pushed out to `1 + pad`).
//!
//! Padding: `pad = padding_ulps * u * s * max(1, g / free_tilt) + position_ulps * u * |start|`,
//! capped at `max_padding`, where `u` is the unit roundoff, `s` the
//! magnitude of the relative coordinates the contact was computed from (the
//! distance to the triangle's nearest vertex, the displacement and the
//! position relative to the frame's start, at least one), `g` the tilt factor of the triangle's unit normal
//! ([`Candidate::tilt`]: `1 / sin` of its largest angle for the product of
//! rounded edges, so a distance to its plane is off by about `u g s`; `g <= 2` for any triangle whose
//! largest angle is at most 150 degrees, and no more than 4 for any taken
//! that way: a triangle whose shape factor exceeds 4, every flat cap among
//! them, takes its normal from its exact edges, whose tilt factor is about
//! 1 until `1 / sin` of its largest angle nears `1 / u`; for a contact on an edge or a
//! vertex, whose distance does not use the normal, the tilt's share
//! `padding_ulps * u * s * (max(1, g / free_tilt) - 1)` is capped at the
//! triangle's inradius squared over two, `side_excess`) and `|start|` the largest eSpace
//! coordinate of the frame's start
//! (which bounds the rounding of the final `start + displacement`). In `f32`
//! at the origin that is about `3e-6`, in `f64` about `5e-15`, at `1e5` in
//! `f32` the cap, `0.01` (the formula gives `0.024`; eSpace units).
//! Where the cap takes over, the final world position's rounding can
//! exceed `pad / 2`; the move then measures the rounded position again
//! and restores the skin from there.
//!
//! A body that starts embedded is first pushed out by the shortest
//! displacement that clears every triangle within reach (up to
//! `depenetration_rounds` rounds; where none clears it, it stays at the
//! best position measured, never deeper, and `Trace::embedded` says so).
//! A still body starts as a moving one does: pushed out if embedded, its
//! skin restored.

use super::{Frame, StopReason};
use crate::detect::{Candidate, DetectOptions, Detection, Hit, REACH_MARGIN, closest_point, proximity};
use crate::geom::{Feature, Triangle, Vec3, cross, dot, max_abs, norm, norm_squared, normalize, to_f64};
use crate::world::INTERNAL_EDGE_DEGREES;
use crate::{Error, Real};
use smallvec::SmallVec;
use std::borrow::Cow;

/// The robust response's tolerances. Distances are eSpace units (radius 1);
/// `*_ulps` fields are multiples of the backend's unit roundoff `u`.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
pub struct RobustOptions {
    /// Sweeps per pass at most (default 8).
    pub max_iterations: u32,
    /// Padding per unit of `u * s` (detection rounding; default 48, three
    /// times the detection's touching tolerance), times `g / free_tilt`
    /// for a triangle whose normal's tilt factor `g` exceeds `free_tilt`.
    pub padding_ulps: f64,
    /// The tilt factor `g` of a triangle's unit normal
    /// ([`Candidate::tilt`]: `1 / sin` of its largest angle, at most 4, for
    /// the product of rounded edges; about 1 for the exact edges' product
    /// that a flat cap's normal is) beyond which its padding grows in
    /// proportion to `g` (default 2: every triangle whose largest angle is
    /// at most 150 degrees keeps the plain padding).
    pub free_tilt: f64,
    /// Padding per unit of `u * |start|` (final-position rounding; default 4).
    pub position_ulps: f64,
    /// Upper bound of the padding (default 0.01). `48 u s` reaches it at
    /// very low precision, far from the origin, beside triangles larger
    /// than about `3.5e3` radii in `f32` (`1.9e12` in `f64`) and on pushes
    /// so long that even [`parts`] cannot bring them within it
    /// (`docs/findings.md`, "The robust response: known limits").
    pub max_padding: f64,
    /// Two planes whose normals' cross product is shorter than
    /// `parallel_ulps * u` count as parallel (default 1024).
    pub parallel_ulps: f64,
    /// A displacement counts as admissible for a plane when
    /// `v . n >= -feasible_ulps * u * |v|` (default 64); a remaining
    /// displacement shorter than `feasible_ulps * u` of the pass's is
    /// negligible. [`super::move_body`] refuses `feasible_ulps * u > 1/2`.
    pub feasible_ulps: f64,
    /// Push-out rounds for a body that starts embedded (default 8; each
    /// moves it at most about one radius, and a body that does not overlap
    /// anything costs one scan).
    pub depenetration_rounds: u32,
    /// The bound of the final world position's rounding, in eSpace, per
    /// unit of `u (m + 2 travel)` (`m` the start's eSpace magnitude,
    /// `travel` how far the body may have gone; default `sqrt(3)`, the
    /// bound derived for it: see the module docs). Where it can exceed half
    /// the least padding the skin is checked after the rounding and the
    /// band in which a body counts as resting is twice the bound wider.
    /// Lowering it below `sqrt(3)` voids that check; the lab's `Mpfr<256>`
    /// replay scales it with the other `*_ulps` fields, so that it rests
    /// in the run's band. [`super::move_body`] refuses
    /// `rounding_ulps * u > 1/2`: no rounding is larger.
    pub rounding_ulps: f64,
}

/// `Ok` unless one of the tolerances counted in units of `u` exceeds half
/// a unit in `T` (`x u > 1/2`):
/// - `rounding_ulps`: no precision of 2 bits or more (`u <= 1/4`) rounds
///   a vector by more than `sqrt(3) / 4` of its magnitude, so a larger
///   bound means no rounding and only lengthens the landing's unswept
///   pushes, to `pad + 2 R` (a review, session 29: `1e7` in `f32`, `0.6`
///   per unit, carried a body through a slot's wall; `1e300` gave an
///   infinite position);
/// - `feasible_ulps`: a share of the displacement's length, a tolerance
///   for the rounding of a few products; from 1 on the whole displacement
///   counts as negligible and every pass ends `Blocked` where it started,
///   even in empty space (a review, thirty-eighth session: `1e16` in
///   `f64`). The default, 64, passes down to 7 bits; below, the robust
///   response could not slide at all and is refused.
///
/// `parallel_ulps` is not bounded: the default, 1024, already makes every
/// pair of planes parallel below 10 bits (the precision dial's 8 bits
/// among them), and a larger value means no more than that: no crease is
/// slid along, the body stops where two planes meet. The products are the
/// same in the lab's replay, which scales the `*_ulps` fields by the ratio
/// of the unit roundoffs.
///
/// # Errors
/// [`Error::InvalidArgument`] naming the first field out of range.
#[inline]
pub(crate) fn check_rounding<T: Real>(opts: &RobustOptions) -> Result<(), Error> {
    let fields = [("rounding_ulps", opts.rounding_ulps), ("feasible_ulps", opts.feasible_ulps)];
    match fields.into_iter().find(|(_, x)| !(x * T::unit_roundoff() <= 0.5)) {
        None => Ok(()),
        Some((name, x)) => Err(ulps_too_large::<T>(name, x)),
    }
}

/// The error of [`check_rounding`].
#[cold]
fn ulps_too_large<T: Real>(name: &str, x: f64) -> Error {
    Error::InvalidArgument {
        what: format!("robust.{name}"),
        message: format!(
            "times the unit roundoff of {} it must be at most 1/2 (a tolerance for rounding, and no rounding is \
             larger), got {x} ({:e}); the defaults need at least 7 bits",
            T::name(),
            x * T::unit_roundoff()
        ),
    }
}

impl Default for RobustOptions {
    fn default() -> Self {
        RobustOptions {
            max_iterations: 8,
            padding_ulps: 48.0,
            free_tilt: 2.0,
            position_ulps: 4.0,
            max_padding: 0.01,
            parallel_ulps: 1024.0,
            feasible_ulps: 64.0,
            depenetration_rounds: 8,
            rounding_ulps: 3f64.sqrt(),
        }
    }
}

impl RobustOptions {
    /// What the padding of a triangle whose normal has tilt factor `tilt`
    /// ([`Candidate::tilt`]) is multiplied by: `max(1, tilt / free_tilt)`,
    /// and 1 for a triangle degenerate in the working precision (`tilt`
    /// infinite or NaN: no normal, distances to its sides only).
    #[must_use]
    pub fn tilt_factor(&self, tilt: f64) -> f64 {
        if tilt.is_finite() { (tilt / self.free_tilt).max(1.0) } else { 1.0 }
    }
}

/// The padding for a contact on candidate `c` at position `p` (see the
/// module docs): `s` is the largest of 1, the displacement, the distance
/// from `p` to the triangle's nearest vertex and `|p|`, the magnitudes that
/// the contact's distance was computed from (`p` and the triangle's
/// coordinates are relative to the frame's start, each rounded by about
/// `u` times its magnitude: a body that travels far in one frame meets
/// triangles whose relative coordinates are that far from zero; without
/// `|p|` a review found one that moved 84 radii in a frame, in `f32`,
/// resting 2.7e-6 radii inside a ramp). Where the contact is on the face
/// (`feature`, the part of the triangle its distance was measured to), the
/// padding of a triangle whose normal's tilt factor exceeds `free_tilt`
/// is multiplied by that factor over `free_tilt`
/// ([`RobustOptions::tilt_factor`]; since R33a a flat cap's normal comes
/// from its exact edges, its tilt factor about 1), because its unit normal's
/// direction carries errors of a few `u` times that factor, so the
/// distance to its plane, `s` from its nearest vertex, is off by as much
/// times `s` (fuzz finding F14). A contact on an edge or a vertex is
/// measured to the edge's line or the vertex, without the normal, and has
/// the plain padding plus at most [`side_excess`] (the inradius squared
/// over two: a foot on the face that the side tests, with the tilted
/// normal, placed outside it is measured to the nearest side instead).
/// Until the thirty-first session (R31a) edges and vertices had the face's
/// padding: a crack-filling sliver lying in a floor, whose padding is the
/// cap in `f32`, held a body `0.01` radii off its edges, which lie in the
/// floor, and a slow walk over it stopped or bobbed. A triangle degenerate
/// in this precision (no normal) keeps the plain padding.
///
/// `least_s` is `max(1, |p|)` ([`least_s`]), computed once by callers that
/// pad many triangles at one position. The padding is at most
/// `max_padding`; [`uncapped_padding`] is the same without that cap.
fn padding<T: Real>(
    start_magnitude: f64,
    least_s: f64,
    p: &Vec3<T>,
    w: &Vec3<T>,
    c: &Candidate<T>,
    feature: Feature,
    opts: &RobustOptions,
) -> T {
    T::c(uncapped_padding(start_magnitude, least_s, p, w, c, feature, opts).min(opts.max_padding))
}

/// [`padding`] before its cap `max_padding`: a bound, with the margin of
/// `padding_ulps` over the detection's touching tolerance, on the error of
/// the contact's distance, and so also of its closest point.
#[inline(always)]
fn uncapped_padding<T: Real>(
    start_magnitude: f64,
    least_s: f64,
    p: &Vec3<T>,
    w: &Vec3<T>,
    c: &Candidate<T>,
    feature: Feature,
    opts: &RobustOptions,
) -> f64 {
    let u = T::unit_roundoff();
    let tri = &c.triangle;
    let magnitude = |v: &Vec3<T>| max_abs(v, T::zero()).to_f64();
    let nearest = [&tri.a, &tri.b, &tri.c].into_iter().map(|v| magnitude(&(v - p))).fold(f64::INFINITY, f64::min);
    let s = magnitude(w).max(nearest).max(least_s);
    let plain = opts.padding_ulps * u * s;
    // The tilt never exceeds the shape factor: most triangles need no more.
    let tilted = if c.shape.to_f64() > opts.free_tilt { plain * (opts.tilt_factor(c.tilt()) - 1.0) } else { 0.0 };
    let tilt = if feature == Feature::Face || tilted == 0.0 { tilted } else { tilted.min(side_excess(c, u)) };
    plain + tilt + opts.position_ulps * u * start_magnitude
}

/// How much farther than the triangle a contact measured to its nearest
/// side can be, where the foot of the centre on the face lies inside the
/// triangle but the side tests, with a tilted normal, placed it outside:
/// the foot is then within the inradius `r` of the nearest side, and for a
/// centre at least 1 from the plane the side is farther than the face by at
/// most `r^2 / 2`. `r = |e0 x e1| / perimeter` is computed in `f64` from
/// the working precision's coordinates, plus `2 u` times their largest
/// magnitude for their rounding. A review of the first version of R31a,
/// which gave edges and vertices the plain padding alone, found spheres
/// pushed onto flat caps `1e5` to `1e7` long and `1e-4` high ending up to
/// `1.5e-6` inside in `f64` (`tests/regressions/respond_messy_levels.rs`).
fn side_excess<T: Real>(c: &Candidate<T>, u: f64) -> f64 {
    let [a, b, d] = [&c.triangle.a, &c.triangle.b, &c.triangle.c].map(to_f64);
    let (ab, ad) = (b - a, d - a);
    let perimeter = ab.norm() + (d - b).norm() + ad.norm();
    let far = [a, b, d].iter().map(|v| v.amax()).fold(0.0, f64::max);
    let r = ab.cross(&ad).norm() / perimeter + 2.0 * u * far;
    r * r / 2.0
}

/// The most parts [`parts`] splits a pass into.
pub const MAX_PARTS: usize = 1024;

/// How many equal parts [`crate::respond::move_body`] slides a pass of
/// eSpace displacement `w` in, each a pass of its own: 1 unless the
/// padding that `w`'s largest coordinate `m` calls for, `padding_ulps u m`,
/// exceeds half the cap `max_padding` (`m` beyond about `1.7e3` radii in
/// `f32`, `9.4e11` in `f64`, 6.8 at 16 bits, 1.7 at 14 bits); then the
/// fewest parts that keep it under half the cap, if at most
/// [`MAX_PARTS`] do (`m` up to about `1.8e6` radii in `f32`, `9.6e14` in
/// `f64`); beyond that `None`: no number of parts the move would take
/// keeps its guarantees, and [`crate::respond::move_body`] refuses the
/// pass (a probe, twenty-eighth session: unsplit, a push of `2e7` radii in
/// `f32` went through a wall and ended `2.5e6` radii away). Each part is
/// `w / n` (rounded once per coordinate: the parts' sum is off from `w` by
/// about `n u |w / n|`, one rounding of `w` itself). Precisions whose
/// padding is over half the cap for a displacement of one radius (13 bits
/// and fewer, below the robust response's range) are not split and not
/// refused: `Some(1)`.
///
/// The rounding of a sweep and the tolerances the slide scales with the
/// displacement's length (the cone's `feasible_ulps u |w|`, the touching
/// tolerance) grow with `|w|`; the padding grows with it only up to its
/// cap. A displacement thousands of radii long in one frame then outran
/// its padding: a probe (twenty-seventh session) found bodies pushed up
/// to `1.4e6` eSpace radii in one `f32` frame ending up to 0.69 radii
/// inside the walls of a closed box
/// (`tests/regressions/respond_hard_pushes.rs`).
///
/// A pass in `n` parts behaves as `n` shorter frames: each part starts
/// from the resting contacts the previous one left and pushes in `w`'s
/// direction again (a body that slides off the end of a wall goes on
/// around it, where one pass would have gone on along the wall's plane),
/// and costs up to a pass's work: up to `n` times one pass's sweeps and
/// scans over the frame's neighbourhood (a review measured 1.3 s for a
/// pass of 1,024 parts over the 69,451-triangle bunny, all of it within
/// reach, against 15 ms for one pass).
#[inline]
#[must_use]
pub fn parts<T: Real>(w: &Vec3<T>, opts: &RobustOptions) -> Option<usize> {
    let per_radius = part_padding_per_radius::<T>(opts);
    let needs = max_abs(w, T::zero()).to_f64() * per_radius;
    if needs > opts.max_padding && per_radius <= opts.max_padding {
        count_parts(needs / opts.max_padding)
    } else {
        Some(1)
    }
}

/// Twice the padding one eSpace radius of displacement calls for,
/// `2 padding_ulps u`: a part of length `m` (largest coordinate) needs at
/// most half the cap, `m <= max_padding / per_radius` ([`parts`]).
fn part_padding_per_radius<T: Real>(opts: &RobustOptions) -> f64 {
    2.0 * opts.padding_ulps * T::unit_roundoff()
}

/// [`Error::InvalidArgument`] for a pass (`what`: the velocity or the
/// gravity) whose eSpace displacement `w` even [`MAX_PARTS`] parts cannot
/// slide with the padding its rounding needs ([`parts`] is `None`).
pub(crate) fn too_long<T: Real>(what: &str, w: &Vec3<T>, opts: &RobustOptions) -> Error {
    let limit = MAX_PARTS as f64 * opts.max_padding / part_padding_per_radius::<T>(opts);
    Error::InvalidArgument {
        what: what.into(),
        message: format!(
            "measured in the body's radii, its largest coordinate ({:e}) is more than the robust response can slide \
             in one move in this precision ({limit:.2e}, in {MAX_PARTS} parts): split the motion into several moves, or \
             use a wider precision",
            max_abs(w, T::zero()).to_f64(),
        ),
    }
}

/// `ceil(ratio)` if at most [`MAX_PARTS`], else `None` ([`parts`]).
#[cold]
fn count_parts(ratio: f64) -> Option<usize> {
    let n = ratio.ceil();
    (n <= MAX_PARTS as f64).then_some(n as usize)
}

/// The least `s` of [`padding`] at `p`: `max(1, |p|)`.
fn least_s<T: Real>(p: &Vec3<T>) -> f64 {
    max_abs(p, T::zero()).to_f64().max(1.0)
}

/// Triangle `index` of the frame as a candidate in eSpace coordinates:
/// the neighbourhood's, or one mapped from the world should it not be
/// there.
fn candidate_e<'a, T: Real>(frame: &'a Frame<'_, T>, index: u32) -> Cow<'a, Candidate<T>> {
    match frame.hood.triangles.binary_search_by_key(&index, |c| c.index) {
        Ok(k) => Cow::Borrowed(&frame.hood.triangles[k]),
        Err(_) => {
            let w = frame.world.triangle(index);
            let to_e = |v: &Vec3<T>| frame.body.to_espace(&(v - &frame.hood.origin));
            Cow::Owned(Candidate::lone(index, Triangle::new(to_e(&w.a), to_e(&w.b), to_e(&w.c))))
        }
    }
}

/// The closest displacement to `w` that does not move into any of the
/// planes: `v . n_i >= 0` for every `n_i` (up to `feasible_ulps`).
#[must_use]
pub fn project_onto_cone<T: Real>(w: &Vec3<T>, normals: &[Vec3<T>], opts: &RobustOptions) -> Vec3<T> {
    let u = T::unit_roundoff();
    let tol = T::c(opts.feasible_ulps * u) * norm(w);
    let admissible = |v: &Vec3<T>| normals.iter().all(|n| dot(v, n) >= -tol.clone());
    if admissible(w) {
        return w.clone();
    }
    let closest = |candidates: &mut dyn Iterator<Item = Vec3<T>>| {
        candidates.filter(|v| admissible(v)).map(|v| (norm_squared(&(w - &v)), v)).fold(None, |best, (d, v)| match best
        {
            Some((bd, bv)) if bd <= d => Some((bd, bv)),
            _ => Some((d, v)),
        })
    };
    let mut singles = normals.iter().filter_map(|n| {
        let d = dot(w, n);
        (d < T::zero()).then(|| w - n * d)
    });
    let min_sin2 = T::c((opts.parallel_ulps * u).powi(2));
    let mut creases = normals.iter().enumerate().flat_map(|(i, a)| {
        normals[i + 1..].iter().filter_map(|b| {
            let c = crease(a, b);
            let c2 = norm_squared(&c);
            (c2 > min_sin2).then(|| {
                let along = dot(w, &c) / c2;
                c * along
            })
        })
    });
    let best = closest(&mut singles).or_else(|| closest(&mut creases));
    best.map_or_else(Vec3::zeros, |(_, v)| v)
}

/// The crease direction `a x b` of two unit normals, computed as
/// `a x (b - a)` where they are within 90 degrees of each other and as
/// `a x (b + a)` beyond: the same in exact arithmetic. `b - a` (or `b + a`)
/// is then a difference of nearly equal numbers, exact or nearly so, and
/// the crease's error is `u` relative to its length `sin theta`; `a x b`
/// itself subtracts products of size 1 and is off by `u` absolute, a
/// direction error of `u / sin theta`. Along the fold of a shallow valley
/// or ridge (`theta` below about `1e-3`) that error made the crease
/// motion fail the cone's admissibility test against both faces, and a
/// body pushed along the fold stopped dead (`Blocked`), in `f64` in about
/// a third of such pushes (a directed probe, twenty-third session).
#[inline(always)]
fn crease<T: Real>(a: &Vec3<T>, b: &Vec3<T>) -> Vec3<T> {
    if dot(a, b) >= T::zero() { cross(a, &(b - a)) } else { cross(a, &(b + a)) }
}

/// The start of a pass from `p` by `w`: meets the resting contacts (see
/// [`settle`]) as the pass's first sweeps would, without sweeping, and
/// returns `w` projected onto them.
///
/// A sweep from within the resting band finds the contact it approaches
/// soonest (gap over approach speed, ties to the lower triangle index) at
/// once, with no advance; the next sweep, along the projected displacement,
/// the next one it still approaches, and so on. This replays that sequence
/// on the contacts' distances and normals ([`proximity`]): the contacts met
/// are those the sweeps would have met, in the same order, and a contact
/// the projected motion no longer approaches (another triangle of the same
/// plane, a wall the slide leaves) is not met.
fn meet_resting<T: Real>(frame: &mut Frame<'_, T>, p: &Vec3<T>, w: &Vec3<T>, opts: &RobustOptions) -> Vec3<T> {
    let zero = T::zero();
    frame.seeds.clear();
    // Each seed's candidate, for the rule below.
    let mut candidates: SmallVec<[usize; 8]> = SmallVec::new();
    for &k in &frame.resting {
        let c = &frame.hood.triangles[k];
        if let Some(near) = proximity(c, p, frame.detect) {
            frame.seeds.push((c.index, near));
            candidates.push(k);
        }
    }
    drop_hidden_features(frame, &candidates, opts);
    let tol = T::c(opts.feasible_ulps * T::unit_roundoff()) * norm(w);
    let mut remaining = w.clone();
    loop {
        let mut soonest: Option<(usize, T, u8)> = None;
        for (k, (_, near)) in frame.seeds.iter().enumerate() {
            let approach = -dot(&remaining, &near.normal);
            if !(approach > tol) {
                continue;
            }
            // Sooner by more than the distance's touching tolerance wins.
            // Within it, a tie: as in the sweep, a face beats an edge, an
            // edge a vertex, and the lower triangle index (met first) the
            // rest (on a seam of a tessellated surface, the neighbour's
            // edge and the face the body stands over are equally near).
            let time = (near.dist.clone() - T::one()).max(zero.clone()) / &approach;
            let margin = near.tol.clone() / approach;
            let rank = match near.feature {
                Feature::Face => 0,
                Feature::Edge(_) => 1,
                Feature::Vertex(_) => 2,
            };
            let wins = soonest.as_ref().is_none_or(|(_, best, best_rank)| {
                time.clone() + &margin < *best || (!(time.clone() - &margin > *best) && rank < *best_rank)
            });
            if wins {
                soonest = Some((k, time, rank));
            }
        }
        let Some((k, _, _)) = soonest else { return remaining };
        let (triangle, near) = frame.seeds.remove(k);
        let overlapping = near.dist < T::one() - &near.tol;
        let normal = near.normal.clone();
        let hit = Hit {
            t: zero.clone(),
            point: near.point,
            normal: near.normal,
            feature: near.feature,
            triangle,
            started_overlapping: overlapping,
        };
        frame.record(hit, normal.clone());
        frame.planes.push(normal);
        frame.met.push(triangle);
        remaining = project_onto_cone(w, &frame.planes, opts);
    }
}

/// Drops from `frame.seeds` (with their candidates' positions in the
/// neighbourhood, `candidates`) every edge or vertex contact whose feature
/// lies on or behind the plane of a face contact, one whose closest point
/// lies on its face, so that the centre is over it: every point of that
/// feature is then at least as far from the centre, wherever it moves on
/// the face's side, as the plane is, and the sweeps never meet it before
/// the face. Met as a resting contact, its direction (from the feature to
/// the centre) is tilted off the face's normal by the centre's offset
/// along the plane over the distance, and the cone of the two is their
/// crease: an active seam in a flat surface (a T-junction, a tile or a
/// sliver beside a shared edge, a face given twice, the underside of a
/// thin plate) stopped a body walking over it (a directed probe, thirtieth
/// session: `f32` at the origin beside a sliver, and `1e4` from it on
/// T-junctions, where the padding, and so the band within which resting
/// contacts are met, grows with the coordinates). Internal edges already
/// take the face's normal there ([`proximity`]).
///
/// Rounded: a feature vertex `v` counts as on the plane when
/// `n . (v - q) <= tol + feasible_ulps u max(|v - q|, 1)` (`n`, `q` and
/// `tol` the face contact's normal, closest point and distance tolerance),
/// the tolerance of the face's distance plus the rounding of the normal
/// over the lever `|v - q|`. A feature wrongly dropped costs no more than
/// a resting contact not met: the sweeps still meet it if the motion
/// comes within touching distance, and the skin is restored after the pass.
fn drop_hidden_features<T: Real>(frame: &mut Frame<'_, T>, candidates: &[usize], opts: &RobustOptions) {
    let faces: SmallVec<[usize; 4]> =
        (0..frame.seeds.len()).filter(|&j| frame.seeds[j].1.feature == Feature::Face).collect();
    if faces.is_empty() || faces.len() == frame.seeds.len() {
        return;
    }
    let ulps = T::c(opts.feasible_ulps * T::unit_roundoff());
    let hidden = |j: usize| {
        let (tri, feature) = (&frame.hood.triangles[candidates[j]].triangle, frame.seeds[j].1.feature);
        faces.iter().any(|&f| {
            let face = &frame.seeds[f].1;
            tri.feature_on_or_behind(feature, &face.normal, &face.point, &face.tol, &ulps)
        })
    };
    let keep: SmallVec<[bool; 8]> = (0..frame.seeds.len()).map(|j| !hidden(j)).collect();
    let mut k = 0;
    frame.seeds.retain(|_| {
        k += 1;
        keep[k - 1]
    });
}

/// Moves `p` out along the unit `normal` by up to `want`, but no further
/// than to the middle of the room between the contact behind (`gap` away)
/// and whatever lies ahead. The sweep looks `2 want + gap` ahead, further
/// than the push, so an obstacle exactly `want` away is seen rather than
/// lost to rounding at the end of the sweep.
///
/// The look-ahead sweep ignores a touched triangle that the push only
/// grazes (approaching it by less than `feasible_ulps * u` of its length,
/// [`DetectOptions::approach_ulps`]): pushed out of one wall of a corner
/// along the next, the body must not be stopped by the rounding of that
/// next wall's direction (fuzz finding F12).
fn push_out<T: Real>(
    frame: &Frame<'_, T>,
    p: Vec3<T>,
    normal: &Vec3<T>,
    want: T,
    gap: &T,
    opts: &RobustOptions,
) -> Vec3<T> {
    let look = T::c(2.0) * &want + gap;
    let d = normal * look.clone();
    let detect = DetectOptions { approach_ulps: opts.feasible_ulps, ..frame.detect.clone() };
    let delta = match frame.hood.earliest_hit(Detection::Robust, &p, &d, &detect) {
        None => want,
        Some(h) => {
            let room = h.t * &look;
            ((room - gap) * T::c(0.5)).max(T::zero()).min(want)
        }
    };
    p + normal * delta
}

/// One sliding pass from eSpace `p` by eSpace `w`.
///
/// The displacement of every iteration is the *original* `w`, scaled by the
/// fraction of the frame still left, projected onto all planes met so far,
/// less any approach it keeps, within the cone's tolerance, to the plane
/// just hit (R23d). Projecting the already-projected leftover instead
/// would let a second plane push the body out of the first one's plane,
/// which is exactly Fauerby's jitter in obtuse corners.
pub(crate) fn slide<T: Real>(frame: &mut Frame<'_, T>, mut p: Vec3<T>, w: Vec3<T>, opts: &RobustOptions) -> Vec3<T> {
    let zero = T::zero();
    let w_len = norm(&w);
    // A pass whose squared length underflows `T` is too short to measure,
    // and moves as a zero one ([`crate::respond::move_body`]; a review,
    // session 36: it ended as `Blocked`).
    if w_len.is_zero() {
        return p;
    }
    let negligible = T::c(opts.feasible_ulps * T::unit_roundoff()) * &w_len;
    let mut time_left = T::one();
    frame.planes.clear();
    frame.met.clear();
    let mut remaining = meet_resting(frame, &p, &w, opts);
    // Triangles met earlier in the pass that a sweep from `p` along
    // `remaining` only grazes (see `grazes_met`): the next sweep skips them.
    let mut grazed: SmallVec<[u32; 8]> = SmallVec::new();
    for _ in 0..opts.max_iterations {
        if !(norm(&remaining) > negligible) {
            frame.trace.stop = StopReason::Blocked;
            return settle(frame, p, opts);
        }
        let Some(hit) = frame.check_collision_skipping(&p, &remaining, &grazed) else {
            frame.trace.stop = StopReason::Free;
            return settle(frame, p + remaining, opts);
        };
        if grazes_met(frame, &hit, &p, &remaining, &w_len, &time_left, opts) {
            grazed.push(hit.triangle);
            continue;
        }
        grazed.clear();
        let candidate = candidate_e(frame, hit.triangle);
        let pad = padding(frame.start_magnitude, least_s(&p), &p, &remaining, &candidate, hit.feature, opts);
        // The gap to the contact along its normal now. Within the resting
        // band [pad / 2, 2 pad] the body neither creeps closer nor is pushed
        // out, so rounding cannot make it toggle between neighbouring floats.
        let approach = -dot(&remaining, &hit.normal);
        let gap_now = hit.t.clone() * approach.clone().max(zero.clone());
        let t_move = if approach > zero && gap_now > T::c(2.0) * &pad {
            (hit.t.clone() - pad.clone() / &approach).max(zero.clone())
        } else {
            zero.clone()
        };
        p += &remaining * t_move.clone();
        let gap = (hit.t.clone() - &t_move) * approach.max(zero.clone());
        if gap < pad.clone() * T::c(0.5) {
            p = push_out(frame, p, &hit.normal, pad - &gap, &gap, opts);
        }
        let n = hit.normal.clone();
        frame.met.push(hit.triangle);
        frame.record(hit, n.clone());
        frame.planes.push(n.clone());
        time_left *= T::one() - t_move;
        remaining = project_onto_cone(&(&w * time_left.clone()), &frame.planes, opts);
        // The cone admits a displacement that approaches a plane by up to
        // `feasible_ulps * u` of its length, but the next sweep meets the
        // plane just hit again once it is approached by more than the
        // graze share (`touch_ulps * u`, `grazes_met`): a displacement
        // between the two met it sweep after sweep without moving, to the
        // iteration cap (a directed probe: a unit sphere on an `f32`
        // floor pushed 100 radii along it and `3.5e-4` into it stayed
        // put; bowls of shallow faces alike). It keeps none of its
        // approach to the plane just hit.
        let approach = dot(&remaining, &n);
        if approach < zero {
            remaining -= &n * approach;
        }
    }
    frame.trace.stop = StopReason::IterationCap;
    settle(frame, p, opts)
}

/// Whether `hit`, from a sweep along `remaining`, is a contact (at the
/// start or later in the sweep) with a triangle already met in this pass
/// that the motion approaches by no more than the detection's touching
/// tolerance's share of `reach`, the length of the displacement still to
/// go before its projection onto the planes met (`w_len * time_left`: the
/// pass's displacement `w` scaled by the fraction of the frame left;
/// `touch_ulps * u * reach`; fuzz findings F24, F32; R25a). Not an
/// overlap: a body already deeper than the touching tolerance must not sink
/// further (fuzz finding F31).
///
/// A displacement projected onto a triangle's plane still approaches it by
/// the projection's rounding, a few `u` of the unprojected length (of
/// `reach`, not of the projection: a gravity projected onto a floor tilted
/// by `4e-8` keeps `4e-8` of its length, and the rounding was `5e-9` of
/// that, F32), and the detection meets a touch at any approach (at a
/// grazing angle also through the face test's window, whose tolerance
/// grows with the speed). Met again, the triangle adds nothing to the
/// cone, the projection is the same, and so is the next sweep's answer,
/// until the iteration cap: the body freezes. A contact later in the sweep
/// freezes it as well: so grazing an approach leaves no room for a padding
/// before it, and the body does not advance (R25a: in a slot exactly as
/// wide as the body, the next triangles of both walls, met where the
/// body's closest points cross their diagonals at an approach of `1e-16`
/// from the rounding of an edge normal, were met in turn to the iteration
/// cap, frame after frame, in `f32` and `f64`). Skipping the triangle for
/// the next sweep (from the same position, along the same motion) is safe:
/// the distance to a convex triangle is convex along the motion, at least
/// 1 before the contact and falling at most at the rate of the approach
/// after it, so over the sweep the body nears it by at most `approach (1 -
/// t)`, and the skin is restored at the end of the pass. At the start that
/// is the touching tolerance's share; for a contact later in the sweep the
/// skip also needs it below half the triangle's padding (R25b: the share
/// grows with the push, and pushed 2,450 radii into a shallow bowl a body
/// that skipped such a re-hit, `2.3e-3` against a padding of `3e-6`, sank
/// into the triangle until another stopped the sweep, and every later
/// sweep met it overlapping, to the iteration cap).
fn grazes_met<T: Real>(
    frame: &Frame<'_, T>,
    hit: &Hit<T>,
    p: &Vec3<T>,
    remaining: &Vec3<T>,
    w_len: &T,
    time_left: &T,
    opts: &RobustOptions,
) -> bool {
    if hit.started_overlapping || !frame.met.contains(&hit.triangle) {
        return false;
    }
    let approach = -dot(remaining, &hit.normal);
    !(approach > T::c(frame.detect.touch_ulps * T::unit_roundoff()) * (w_len.clone() * time_left))
        && (hit.t <= T::zero() || {
            // Later in the sweep, the body must also near the triangle by
            // less than half its padding over the rest of the sweep.
            let candidate = candidate_e(frame, hit.triangle);
            let pad = padding(frame.start_magnitude, least_s(p), p, remaining, &candidate, hit.feature, opts);
            !(approach * (T::one() - &hit.t) > pad * T::c(0.5))
        })
}

/// The end of a pass (and the start of the first): restores the skin and
/// finds the resting contacts, in one scan of the neighbourhood.
///
/// * Every triangle closer than `1 + 2 pad` is a resting contact, kept in
///   [`Frame::resting`]. The next pass starts constrained by those its
///   displacement approaches, with the normal the robust sweep would
///   report for a contact at `t = 0` ([`proximity`]), instead of spending a
///   sweep on finding each again.
/// * A sweep may legitimately end a hair from a surface it did not reach,
///   closer than the final rounding of the position can guarantee: if the
///   nearest triangle is closer than `1 + pad / 2`, the body is pushed out
///   along its separating direction to `1 + pad` (room permitting, as
///   [`push_out`]) and the scan is repeated there.
///
/// Boxes and planes at distance `1 + 2 max_padding` (plus the band) or
/// more are skipped with one box distance or dot product each.
fn settle<T: Real>(frame: &mut Frame<'_, T>, p: Vec3<T>, opts: &RobustOptions) -> Vec3<T> {
    let nearest = scan_resting(frame, &p, opts);
    restore_skin(frame, p, nearest, opts)
}

/// How many times [`restore_skin`] pushes a body out before it lets the
/// position stand: one per wall of a corner (a sweep can leave a body
/// touching three mutually perpendicular walls at once, and each push
/// moves it away from one).
const SKIN_ROUNDS: usize = 3;

/// The push-out of [`settle`], given the scan's nearest triangle: while the
/// nearest triangle is closer than `1 + pad / 2`, push out along its
/// separating direction ([`push_out`]) and scan again, at most
/// [`SKIN_ROUNDS`] times; a push that cannot move the body (no room behind
/// it) ends the rounds.
fn restore_skin<T: Real>(
    frame: &mut Frame<'_, T>,
    mut p: Vec3<T>,
    mut nearest: Option<Nearest<T>>,
    opts: &RobustOptions,
) -> Vec3<T> {
    for _ in 0..SKIN_ROUNDS {
        let Some(near) = nearest.as_ref().filter(|n| n.short()) else { return p };
        let gap = near.dist.clone() - T::one();
        let Some(dir) = normalize(&(&p - &near.point)) else { break };
        let pushed = push_out(frame, p.clone(), &dir, near.pad.clone() - &gap, &gap.max(T::zero()), opts);
        if pushed == p {
            break;
        }
        p = pushed;
        nearest = scan_resting(frame, &p, opts);
    }
    skin_in_crease(frame, p, nearest, opts)
}

/// The end of [`restore_skin`] where pushes along one normal at a time
/// left the skin short: in a crease the push out of one wall along its
/// normal runs into the other at once (fuzz finding F34 left a body
/// `6.9e-12` inside a huge triangle whose padding, `9.4e-10`, it was short
/// of, in an acute crease with a floor that stopped every push). Up to
/// [`SKIN_ROUNDS`] times the body moves by [`crease_push`]: every triangle
/// short of half its padding is pushed to its full padding, and no other
/// comes nearer than its own (or nearer at all, if it already is); where
/// no push does both (a slot narrower than the paddings: its walls ask
/// for opposite pushes) the body stays. Of the positions measured, the
/// best ([`Nearest::beats`]) is kept. Without a short skin it costs
/// nothing.
#[cold]
fn skin_in_crease<T: Real>(
    frame: &mut Frame<'_, T>,
    mut p: Vec3<T>,
    nearest: Option<Nearest<T>>,
    opts: &RobustOptions,
) -> Vec3<T> {
    let Some(mut best) = nearest.filter(Nearest::short).map(|n| (n, p.clone())) else { return p };
    let mut limits = SmallVec::new();
    for _ in 0..SKIN_ROUNDS {
        if !limits_at(frame, &p, &T::zero(), Limits::Skin, opts, &mut limits, None) {
            break;
        }
        let Some(push) = crease_push(&mut limits, opts) else { break };
        let pushed = &p + push;
        if pushed == p {
            break;
        }
        p = pushed;
        let Some(near) = scan_resting(frame, &p, opts) else { return p };
        let short = near.short();
        if near.beats(&best.0) {
            best = (near, p.clone());
        }
        if !short {
            break;
        }
    }
    if best.1 != p {
        // The resting contacts must be those of the position kept.
        scan_resting(frame, &best.1, opts);
    }
    best.1
}

/// The world position of the eSpace position `p` (relative to the frame's
/// `origin`), with the skin checked after its final rounding when that
/// rounding could undo it.
///
/// `from_espace(p) + origin` rounds each world coordinate `x_i` by up to
/// `u |x_i|` and the product `r_i p_i` by `u r_i |p_i|`: in eSpace at most
/// `R = sqrt(3) u (m + 2 |p|)` for a start of eSpace magnitude `m`. The
/// padding keeps a resting body `pad / 2` clear, and `pad` is at least
/// `min(max_padding, (position_ulps m + padding_ulps) u)` (its terms with
/// `s >= 1` and a tilt factor `>= 1`). When `R` reaches half of that (far
/// from the origin, where the padding is capped: in `f32` from about
/// `5e4` radii on; or a displacement of more than about `0.077 m + 5.9`
/// radii in one frame) the rounded position is measured again (its
/// difference to the origin is exact by Sterbenz's lemma for a move within
/// a factor two of the origin's coordinates, then one product: within
/// `2u |p|`) and, where a triangle lies closer than `1 + pad / 2`, moved by
/// the shortest push that leaves every triangle within reach `1 + pad + R`
/// away ([`land_checked`]). `|p|` is bounded by `reach`, the frame's
/// reach radius (eSpace), plus the depenetration pushes. From a quarter
/// of it to half, the rounding is chosen in a crease ([`off_contacts`]).
/// Otherwise the check costs a few operations.
#[inline(always)]
pub(crate) fn land<T: Real>(
    frame: &mut Frame<'_, T>,
    p: &Vec3<T>,
    origin: &Vec3<T>,
    reach: f64,
    opts: &RobustOptions,
) -> Result<Vec3<T>, Error> {
    let (rounding, least_pad) =
        rounding_and_least_pad::<T>(frame.start_magnitude, reach + frame.trace.depenetration, opts);
    let d = frame.body.from_espace(p);
    Ok(if rounding >= 0.5 * least_pad {
        let world = d + origin;
        land_checked(frame, world, origin, rounding, opts)?
    } else if rounding >= 0.25 * least_pad {
        // From a quarter of the least padding on, rounded to nearest frame
        // after frame, a body sliding along a crease can walk into it by
        // rounding (each frame's step rounded the same way, up to `R`
        // towards a wall), faster than the skin's restoring pushes,
        // themselves rounded, carry it back out (a review, session 36: an
        // ellipsoid `2.9e4` radii out in `f32`, pushed along the crease of
        // a floor and a ceiling meeting at 22 degrees, ended `2.9e-4` radii
        // inside the ceiling every 40 frames). From half on, the skin is
        // checked after the rounding instead.
        off_contacts(frame, &d, origin, rounding, opts)
    } else {
        d + origin
    })
}

/// How far beyond the radii (eSpace) a frame whose final rounding's bound
/// is `rounding` (`R`, [`final_rounding`]) gathers around the body's path:
/// [`REACH_MARGIN`] plus what the skin's checks add, in
/// `(SKIN_ROUNDS + 2) (max_padding + 5 R)`. The resting scans look
/// `2 max_padding + 2 R` beyond the radius ([`scan_resting`], the band),
/// and [`land_checked`] pushes at most [`SKIN_ROUNDS`] times by `pad + 2 R'`
/// and measures every triangle within `1 + pad + R'` of where it goes,
/// with `R' = R + 2 u |p| <= (1 + 2 / sqrt(3)) R` (`|p| <= m + travel`),
/// below `2.2 R`. Where the rounding is a radius or more (an `f32` body
/// ten times narrower than it is tall, a million units out), the margin
/// of `1.05` had left the floor under the pushed positions ungathered: a
/// still body touching a floor was pushed half a radius through it (a
/// review, session 39).
pub(crate) fn skin_margin(rounding: f64, opts: &RobustOptions) -> f64 {
    REACH_MARGIN + (SKIN_ROUNDS + 2) as f64 * (opts.max_padding + 5.0 * rounding)
}

/// Two contact normals whose cross product's squared length exceeds this
/// (`sin^2` of their angle: about 0.6 degrees) make a crease for
/// [`off_contacts`].
const CREASE_SIN_SQ: f64 = 1e-4;

/// `origin + d` (world space), each coordinate rounded to one of its two
/// neighbouring values of `T`: to nearest, unless the move's contacts
/// ([`super::Trace::contacts`]) make a crease (two normals more than
/// [`CREASE_SIN_SQ`] apart) and that moves the body towards the plane of
/// one of them and another choice does not; then the choice nearest to
/// `origin + d` of those that move it towards none, or, where every choice
/// does, the one that moves it least towards the worst. Only a choice
/// within the bound `rounding` (`R`, eSpace) of `origin + d` is taken, and
/// only where every triangle within reach keeps half its padding there or
/// its thinnest skin is thicker than the nearest's (one or two scans, in
/// the frames that take another choice than the nearest): a triangle the
/// body did not touch can lie nearer than `R` (a first version moved a
/// coordinate by up to an ulp and carried a body into the far wall of a
/// slot `8.8e-4` radii wider than itself). Where rounding to nearest
/// returns the body to `origin`, its start, it stays there. The rounding
/// errors are measured as `(w - origin) - d`, whose first difference is
/// exact where `w` and `origin` lie within a factor two of each other
/// (Sterbenz) and is otherwise within `u |w|` of the one the bound allows.
fn off_contacts<T: Real>(
    frame: &mut Frame<'_, T>,
    d: &Vec3<T>,
    origin: &Vec3<T>,
    rounding: f64,
    opts: &RobustOptions,
) -> Vec3<T> {
    let nearest = d + origin;
    // A body the rounding returns to its start does not walk: the nearest
    // keeps it at rest (choosing another value there, a first version set
    // bodies at rest in creases creeping along them: a review).
    if nearest == *origin {
        return nearest;
    }
    let contacts = &frame.trace.contacts;
    // Along one plane the skin's restoring push, along its normal, is not
    // undone by the rounding; only between two planes (a crease, a
    // corner) does it sit mostly across the steps the rounding keeps.
    let crease = contacts.iter().enumerate().any(|(i, a)| {
        contacts[i + 1..].iter().any(|b| norm_squared(&cross(&a.hit.normal, &b.hit.normal)) > T::c(CREASE_SIN_SQ))
    });
    if !crease {
        return nearest;
    }
    let error = |w: &Vec3<T>| frame.body.to_espace(&((w - origin) - d));
    // The most the rounding error `e` moves the body towards a contact's
    // plane (negative: towards it).
    let worst = |e: &Vec3<T>| contacts.iter().map(|c| dot(&c.hit.normal, e)).reduce(Real::min);
    let e0 = error(&nearest);
    let Some(w0) = worst(&e0) else { return nearest };
    if !(w0 < T::zero()) {
        return nearest;
    }
    let bound_sq = T::c(rounding * rounding);
    let mut best = (w0.clone(), norm_squared(&e0), nearest.clone());
    for mask in 1..8u8 {
        let flips = |i: usize| mask & (1 << i) != 0;
        if (0..3).any(|i| flips(i) && e0[i].is_zero()) {
            continue;
        }
        let w =
            Vec3::from_fn(|i, _| if flips(i) { nearest[i].next_toward(e0[i] < T::zero()) } else { nearest[i].clone() });
        let e = error(&w);
        let e_sq = norm_squared(&e);
        if !(e_sq <= bound_sq) {
            continue;
        }
        let Some(we) = worst(&e) else { continue };
        let better = match (!(we < T::zero()), !(best.0 < T::zero())) {
            (true, false) => true,
            (true, true) => e_sq < best.1,
            (false, false) => we > best.0,
            (false, true) => false,
        };
        if better {
            best = (we, e_sq, w);
        }
    }
    // The choice may approach a triangle it did not touch by up to `R`:
    // kept where every triangle within reach keeps half its padding there
    // ([`scan_resting`]), or else where it measures better than the
    // nearest ([`Nearest::beats`]).
    if best.2 == nearest {
        return nearest;
    }
    let at = |w: &Vec3<T>| frame.body.to_espace(&(w - origin));
    let (q, q0) = (at(&best.2), at(&nearest));
    match scan_resting(frame, &q, opts) {
        Some(near) if near.short() => match scan_resting(frame, &q0, opts) {
            Some(near0) if !near.beats(&near0) => nearest,
            _ => best.2,
        },
        _ => best.2,
    }
}

/// The bound `R = sqrt(3) u (m + 2 travel)` of the final rounding's shift
/// in eSpace ([`land`]; `sqrt(3)` is [`RobustOptions::rounding_ulps`]) for
/// a start of eSpace magnitude `m` and a position at most `travel` from
/// it, where it can exceed half the least padding
/// `min(max_padding, (position_ulps m + padding_ulps) u)`; `None` where it
/// cannot.
pub(crate) fn final_rounding<T: Real>(m: f64, travel: f64, opts: &RobustOptions) -> Option<f64> {
    let (rounding, least_pad) = rounding_and_least_pad::<T>(m, travel, opts);
    (rounding >= 0.5 * least_pad).then_some(rounding)
}

/// The largest bound `R = sqrt(3) u (m + 2 travel)` of the final
/// position's rounding (in radii, for a start of eSpace magnitude `m` and
/// a frame reaching `travel`; [`RobustOptions::rounding_ulps`]) a robust
/// move accepts: half a radius, where a coordinate of the
/// position rounds by about a third of the radius. Beyond it the gap the
/// response keeps cannot be held: a review (session 39) found `f32`
/// ellipsoids ten times narrower than tall touching a floor a million
/// units out (`R` about one radius) pushed through it by the push that
/// restores the skin, since a triangle's side within half its padding
/// (then over two radii) is not trusted.
pub const MAX_FINAL_ROUNDING: f64 = 0.5;

/// `Ok` unless the final rounding's bound `R = sqrt(3) u (m + 2 travel)`
/// ([`final_rounding`] with the derived factor `sqrt(3)`, whatever
/// [`RobustOptions::rounding_ulps`] says: the rounding itself, not the
/// tolerance for it) for a start of eSpace magnitude `m` and a frame
/// reaching `travel` exceeds [`MAX_FINAL_ROUNDING`]: in `f32` a start
/// beyond about `4.8e6` radii from the origin (`2.6e15` in `f64`), or a
/// move that reaches that far.
///
/// # Errors
/// [`Error::InvalidArgument`] naming the position, as described.
pub(crate) fn check_final_rounding<T: Real>(m: f64, travel: f64) -> Result<(), Error> {
    let rounding = 3f64.sqrt() * T::unit_roundoff() * (m + 2.0 * travel);
    if rounding <= MAX_FINAL_ROUNDING {
        return Ok(());
    }
    Err(Error::InvalidArgument {
        what: "position".into(),
        message: format!(
            "measured in the body's radii it lies {m:.3e} from the origin and the move reaches {travel:.3e}, where {} \
             rounds a position by up to {rounding:.3} radii, more than {MAX_FINAL_ROUNDING}: the robust response cannot \
             keep its gap from the geometry there; move the world's origin nearer the body, or use a wider precision",
            T::name()
        ),
    })
}

/// The final rounding's bound `R = rounding_ulps u (m + 2 travel)` and
/// the least padding `min(max_padding, (position_ulps m + padding_ulps)
/// u)` ([`final_rounding`], [`land`]).
fn rounding_and_least_pad<T: Real>(m: f64, travel: f64, opts: &RobustOptions) -> (f64, f64) {
    let u = T::unit_roundoff();
    let rounding = opts.rounding_ulps * u * (m + 2.0 * travel);
    (rounding, opts.max_padding.min((opts.position_ulps * m + opts.padding_ulps) * u))
}

/// [`land`] where the rounding `R` could undo the skin: measure the
/// rounded position again; while a triangle lies closer than `1 + pad /
/// 2`, move by the shortest push that leaves every triangle within reach
/// `1 + pad + R'` away (`R'` = `R` plus the measurement's `2u |p|`), at
/// most `pad + 2 R'` long, round, and measure again, at most
/// [`SKIN_ROUNDS`] times; of the positions measured, the first clear one,
/// or else the one with the widest gap (never a worse one than the
/// rounding gave: a push in a tight space, unswept, can meet what it was
/// not near, and a review found longer pushes carrying bodies 0.7 radii
/// into a duct's ceiling). The resting band is `2 R` wider in such frames
/// ([`super::Frame::band`]), so a body pushed out to `1 + pad + R` rests
/// there in the next frame instead of falling back.
/// The candidates are gathered again first where the depenetration pushes
/// made `R` larger than the frame's margin allowed for ([`skin_margin`]).
///
/// # Errors
/// As [`super::Frame::regather`].
#[cold]
fn land_checked<T: Real>(
    frame: &mut Frame<'_, T>,
    mut world: Vec3<T>,
    origin: &Vec3<T>,
    rounding: f64,
    opts: &RobustOptions,
) -> Result<Vec3<T>, Error> {
    let body = frame.body;
    let margin = skin_margin(rounding, opts);
    if margin > frame.margin {
        frame.margin = margin;
        frame.regather(&body.to_espace(&(&world - origin)))?;
    }
    // The measurement's own error, `2u |p|`, on top of the rounding.
    let extra =
        T::c(rounding) + T::c(2.0 * T::unit_roundoff()) * max_abs(&body.to_espace(&(&world - origin)), T::zero());
    let mut limits = SmallVec::new();
    let mut best: Option<(Nearest<T>, Vec3<T>)> = None;
    for round in 0..=SKIN_ROUNDS {
        let q = body.to_espace(&(&world - origin));
        let Some(near) = scan_resting(frame, &q, opts) else { return Ok(world) };
        if !near.short() {
            return Ok(world);
        }
        let longest = near.pad.clone() + T::c(2.0) * &extra;
        if best.as_ref().is_none_or(|(b, _)| near.beats(b)) {
            best = Some((near, world.clone()));
        }
        // Clear limits are always complete.
        let _ = limits_at(frame, &q, &extra, Limits::Clear, opts, &mut limits, None);
        if round == SKIN_ROUNDS || limits.is_empty() {
            break;
        }
        world = body.from_espace(&(q + shortest_push(&mut limits, &longest, opts))) + origin;
    }
    Ok(best.map_or(world, |(_, w)| w))
}

/// The triangle whose skin is thinnest at a position, from
/// [`scan_resting`]: the one whose gap `dist - 1` falls furthest below half
/// its own padding (the nearest one where the paddings are alike; a huge
/// triangle far from its vertices has a far wider padding than a small one
/// in the same plane: fuzz finding F34 left a body beside two such
/// coplanar triangles `1.9e-13` clear of the small one, its own padding
/// kept, and `6.9e-12` inside the huge one, whose padding of `9.4e-10` the
/// skin check never looked at; F34 is still open, since the push out of
/// the huge one then runs into the floor of the crease they form).
struct Nearest<T: Real> {
    /// Its distance.
    dist: T,
    /// Its closest point.
    point: Vec3<T>,
    /// Its padding.
    pad: T,
    /// Its skin, `dist - pad / 2` (what the choice of this triangle
    /// minimises).
    skin: T,
    /// The least distance of any triangle scanned (an overlap when below 1).
    closest: T,
}

impl<T: Real> Nearest<T> {
    /// Whether the gap falls short of half the padding: the skin to
    /// restore.
    fn short(&self) -> bool {
        self.dist.clone() - T::one() < self.pad.clone() * T::c(0.5)
    }

    /// Whether the position this scan measured is better than `other`'s,
    /// for the pushes that keep the best position they measured: one that
    /// overlaps nothing (`closest >= 1`) beats one that overlaps, less
    /// overlap beats more, and without overlap the thicker skin (`dist -
    /// pad / 2` of the thinnest) wins. (Judged on the skin alone, a push
    /// into one wall of a slot narrower than twice the other's padding
    /// would count as progress.)
    fn beats(&self, other: &Self) -> bool {
        let one = T::one();
        match (self.closest >= one, other.closest >= one) {
            (true, true) => self.skin > other.skin,
            (clear, other_clear) if clear != other_clear => clear,
            _ => self.closest > other.closest,
        }
    }
}

/// Fills [`Frame::resting`] with the triangles within `1 + 2 pad + band`
/// of `p` (by their position in the neighbourhood; `band` is
/// [`Frame::band`], zero unless the final rounding can undo the skin) and
/// returns the one with the thinnest skin within `1 + 2 max_padding +
/// band` ([`Nearest`]). The scan reaches as far as the band can, `2 pad`
/// being at most `2 max_padding`: until the thirty-seventh session it
/// stopped at `1 + max_padding + band`, and where a padding exceeds half
/// its cap (from about `2.1e4` radii out in `f32`, or beside triangles
/// thousands of radii long) the triangles between the two were no resting
/// contacts; the sweeps met them one by one without moving the body (they
/// lay within the resting band), and in the notch of `docs/findings.md`,
/// "A sawtooth in tight notches far out in `f32`", gravity slid a body
/// along one of three walls it rested against as if the other two were
/// not there. The widening costs 1.6-1.8% of the terrain replay's
/// instructions.
fn scan_resting<T: Real>(frame: &mut Frame<'_, T>, p: &Vec3<T>, opts: &RobustOptions) -> Option<Nearest<T>> {
    let one = T::one();
    let reach = one.clone() + T::c(2.0 * opts.max_padding) + &frame.band;
    let reach_sq = reach.clone() * &reach;
    let mut nearest: Option<Nearest<T>> = None;
    let s = least_s(p);
    frame.resting.clear();
    for (k, c) in frame.hood.triangles.iter().enumerate() {
        if beyond(c, p, &reach, &reach_sq) {
            continue;
        }
        let (point, feature) = closest_point(c, p);
        // Squared, so that the square root is taken only within reach (the
        // cutoff moves by the rounding of `reach^2`: a contact at the very
        // edge of a band as wide as the cap allows can fall beyond it, and
        // is then met by the sweeps as any triangle outside the band).
        let dist_sq = norm_squared(&(p - &point));
        if !(dist_sq < reach_sq) {
            continue;
        }
        let dist = dist_sq.sqrt();
        let pad = padding(frame.start_magnitude, s, p, &Vec3::zeros(), c, feature, opts);
        if dist <= one.clone() + T::c(2.0) * &pad + &frame.band {
            frame.resting.push(k);
        }
        let skin = dist.clone() - pad.clone() * T::c(0.5);
        match nearest.as_mut() {
            None => nearest = Some(Nearest { closest: dist.clone(), dist, point, pad, skin }),
            Some(b) => {
                if dist < b.closest {
                    b.closest = dist.clone();
                }
                if skin < b.skin {
                    (b.dist, b.point, b.pad, b.skin) = (dist, point, pad, skin);
                }
            }
        }
    }
    nearest
}

/// The start of a robust move, still or moving: [`depenetrate`] if the
/// body starts embedded, then [`settle`] (the skin, and the resting
/// contacts for the first pass). The scan that finds the resting contacts
/// also tells whether anything is nearer than 1, so a body that starts
/// free costs one scan.
///
/// A still body starts as a moving one does, but is moved to restore its
/// skin only where the push restores it: one only checked for an
/// overlap stayed inside a triangle it overlapped by less than the
/// rounding of its distance (a directed probe, R24b: `1.2e-4` radii in
/// `f32` at `5,800` radii from the origin, where the plane test computed
/// `1.0000153`), which the skin, wider than that rounding, clears.
///
/// Every push of the start counts in [`Trace::depenetration`](super::Trace::depenetration) where the
/// body started embedded (the skin's pushes after the push-out as well:
/// the final rounding's bound takes the travel from it, [`land`]), and the
/// candidates are gathered again when the pushes together pass the
/// gather's margin. Where the push-out could not clear the body,
/// [`Trace::embedded`](super::Trace::embedded) says so.
///
/// # Errors
/// As [`Neighbourhood::gather`](crate::detect::Neighbourhood::gather), for
/// the candidates gathered again after a long push-out.
pub(crate) fn start<T: Real>(
    frame: &mut Frame<'_, T>,
    p: Vec3<T>,
    moving: bool,
    opts: &RobustOptions,
) -> Result<Vec3<T>, Error> {
    let nearest = scan_resting(frame, &p, opts);
    if !nearest.as_ref().is_some_and(|n| n.closest < T::one()) {
        if moving || !nearest.as_ref().is_some_and(Nearest::short) {
            return Ok(restore_skin(frame, p, nearest, opts));
        }
        // A still body moves only where that restores its skin: in a slot
        // narrower than its walls' paddings the skin cannot be restored,
        // and each still frame's centring push, rounding noise of one
        // sign, crept it along by `5e-12` frame after frame (a review).
        let pushed = restore_skin(frame, p.clone(), nearest, opts);
        let whole = !scan_resting(frame, &pushed, opts).is_some_and(|n| n.short());
        return Ok(if whole { pushed } else { p });
    }
    let (pushed, since_gather) = depenetrate(frame, p, opts)?;
    let settled = settle(frame, pushed.clone(), opts);
    let skin = norm(&(&settled - &pushed)).to_f64();
    frame.trace.depenetration += skin;
    if since_gather + skin > REACH_MARGIN - 1.0 {
        frame.regather(&settled)?;
    }
    frame.trace.embedded = least_distance(frame, &settled).is_some();
    Ok(settled)
}

/// Pushes a body that starts embedded out of the geometry, in up to
/// `depenetration_rounds` rounds; returns where it ends and how far it
/// was pushed since the candidates were last gathered.
///
/// A round runs while some triangle is nearer than 1 ([`least_distance`])
/// and moves the body by [`shortest_push`] over the limits of every
/// triangle within `1 + max_padding` ([`limits_at`]; its simpler limits'
/// push where that leaves nothing nearer than 1): flat walls are
/// cleared in one round, a wedge along its bisector (where a push out of
/// one wall at a time, the method until the nineteenth session, drives the
/// body into the other and left one started 0.1 inside a 20 degree wedge
/// 0.16 inside after four rounds). A push that takes the body beyond the
/// margin of the gathered candidates gathers them again before the next
/// round, so a triangle first within reach after the push counts too.
///
/// Where the rounds cannot clear the body (a slot narrower than it, a
/// closed cavity) it ends at the best position measured, the one whose
/// nearest triangle is farthest, never deeper than it started: the last
/// round's position ping-ponged between a slot's walls, and a body 0.25
/// inside a slot of 1.5 radii ended 0.5 inside (a directed probe, R24a).
fn depenetrate<T: Real>(
    frame: &mut Frame<'_, T>,
    mut p: Vec3<T>,
    opts: &RobustOptions,
) -> Result<(Vec3<T>, f64), Error> {
    let mut since_gather = 0.0;
    let (mut limits, mut simpler) = (SmallVec::new(), SmallVec::new());
    // The best position measured: its nearest triangle's distance, the
    // position, the pushes since the gather then, and the gather's number.
    let (mut best, mut gathers) = (None::<(T, Vec3<T>, f64, u32)>, 0);
    for round in 0..=opts.depenetration_rounds {
        let Some(closest) = least_distance(frame, &p) else { return Ok((p, since_gather)) };
        if best.as_ref().is_none_or(|b| closest > b.0) {
            best = Some((closest, p.clone(), since_gather, gathers));
        }
        if round == opts.depenetration_rounds {
            break;
        }
        // Clear limits are always complete.
        let _ = limits_at(frame, &p, &T::zero(), Limits::Clear, opts, &mut limits, Some(&mut simpler));
        let longest = T::c(MAX_PUSH + opts.max_padding);
        // The simpler limits' push where it clears the body, else all of
        // them (see `limits_at`).
        let simple = (!simpler.is_empty()).then(|| shortest_push(&mut simpler, &longest, opts));
        let push = match simple.filter(|push| least_distance(frame, &(&p + push)).is_none()) {
            Some(push) => push,
            None => shortest_push(&mut limits, &longest, opts),
        };
        let length = norm(&push).to_f64();
        frame.trace.depenetration += length;
        since_gather += length;
        p += push;
        if since_gather > REACH_MARGIN - 1.0 {
            frame.regather(&p)?;
            since_gather = 0.0;
            gathers += 1;
        }
    }
    let Some((_, q, since, gathered)) = best else { return Ok((p, since_gather)) };
    if q == p {
        return Ok((p, since_gather));
    }
    if gathered != gathers {
        frame.regather(&q)?;
        return Ok((q, 0.0));
    }
    Ok((q, since))
}

/// The distance from `p` to the nearest candidate nearer than 1 (an
/// overlap), or `None` if there is none.
fn least_distance<T: Real>(frame: &Frame<'_, T>, p: &Vec3<T>) -> Option<T> {
    let one = T::one();
    let mut least: Option<T> = None;
    for c in &frame.hood.triangles {
        // A box or plane at distance 1 or more cannot hold an overlap.
        if beyond(c, p, &one, &one) {
            continue;
        }
        let dist_sq = norm_squared(&(p - closest_point(c, p).0));
        if dist_sq < one && least.as_ref().is_none_or(|l| dist_sq < *l) {
            least = Some(dist_sq);
        }
    }
    least.map(|d| d.sqrt())
}

/// Whether candidate `c`'s box or plane lies `reach` or more from `p`
/// (`reach_sq` its square): then so does the triangle. The cheap tests
/// the scans run before a closest point.
#[inline]
fn beyond<T: Real>(c: &Candidate<T>, p: &Vec3<T>, reach: &T, reach_sq: &T) -> bool {
    c.box_distance_sq(p) >= *reach_sq || c.normal.as_ref().is_some_and(|n| dot(n, &(p - &c.triangle.a)).abs() >= *reach)
}

/// A limit on a push: `(need, n)`, the distance `need` a body must gain
/// along the unit direction `n`.
type Limit<T> = (T, Vec3<T>);

/// What the limits of [`limits_at`] ask for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Limits {
    /// Every triangle within reach must end `1 + pad + extra` away.
    Clear,
    /// The limits of [`skin_in_crease`], for a push at most `max_padding /
    /// 2` long: a triangle short of its skin (nearer than `1 + pad / 2`)
    /// must end `1 + pad` away; any other must not come nearer than
    /// `1 + pad`, nor nearer at all if it already is (its need is at most
    /// 0). They are not to be trusted where a triangle whose padding is
    /// capped could be within reach: its distance and direction are off by
    /// more than the padding, and so may be the gain a push seems to make
    /// (in `f32` a wall with vertices `8.8e5` radii away, measured beyond
    /// reach, was `6.5e-4` inside after a push towards it); a triangle
    /// counts wherever that error, its [`uncapped_padding`], could put it
    /// within reach, and on either side of a one-sided triangle. An
    /// uncapped triangle's closest point is off by well under its padding,
    /// so its direction by under `pad` radians, and a push of at most
    /// `max_padding / 2` gains at most `pad max_padding / 2` less than it
    /// seems to: a hundredth of the half padding the limits keep in hand.
    Skin,
}

/// Where a limit of [`limits_at`] came from.
enum Source<T: Real> {
    /// The closest point lies on the face: the limit is along the face's
    /// normal, and `p` lies this far from the plane along it.
    Face(T),
    /// The closest point lies on an edge or a vertex: the limit is along
    /// `p` minus that point. With the triangle's unit front normal and
    /// `p`'s distance from its plane along it, where it has a normal.
    Point(Option<(Vec3<T>, T)>),
    /// Anything else (`p` on the triangle's boundary, or behind a
    /// one-sided triangle's edge).
    Other,
}

/// Replaces `limits` with those of every triangle within
/// `1 + max_padding + extra` of `p` (wider for [`Limits::Skin`]): the unit
/// direction that separates `p` from the triangle's closest point (the
/// face's normal, towards `p`, and the distance to its plane if that point
/// lies on the face, the front normal where `p` lies within half the
/// triangle's padding behind it; the front normal when triangles are one-sided and `p`
/// is behind the plane of one it overlaps, which pushes it through to the
/// front; one-sided triangles it is behind and does not overlap set no
/// limit) and the distance to gain along it: to lie `1 + pad + extra`
/// away, or as `kind` says. Returns whether the limits can be trusted:
/// always for [`Limits::Clear`]; for [`Limits::Skin`] not where a
/// triangle whose padding is capped could be within reach (the limits are
/// then left incomplete).
///
/// With `simpler`, it also receives a simpler set, for the push-out
/// (empty where it would be the same): a triangle whose closest point is
/// an edge or vertex sets no limit where it lies behind the plane of a
/// triangle `p` is over, as that one's limit faces (every vertex at most
/// half its own uncapped padding plus `feasible_ulps u m` in front of it,
/// `m` the vertex's largest coordinate relative to `p`): clearing that
/// plane clears it; and one that does not lie behind it but whose own
/// plane is within [`INTERNAL_EDGE_DEGREES`] of parallel to it asks
/// instead that `p` clear its own plane, on `p`'s side (on the face's
/// where `p` lies within half the triangle's padding of it), which clears
/// the triangle too. The edge's own limit, a half-space along the
/// direction from the edge, asks for a push away from the edge that the
/// plane may not need: a review (session 29) found a body whose centre
/// started on a flat floor, `0.18` radii beside the seam of its two
/// triangles, pushed out `0.64` radii sideways as well as up, and on
/// turned tessellated floors far from the origin, whose rounded vertices
/// lie a little off each other's planes, up to 1.4 radii sideways. But
/// the simpler set asks for more than needed where the neighbour is a
/// real step beside `p` (clearing its whole plane, where a push off its
/// edge would do) and, with a neighbour whose vertices lie far, can
/// count a raise of up to its padding as lying in the plane: a second
/// review found bodies pushed into a ceiling over a step, or left inside
/// a huge sheet raised `1.65e-3` radii, and stuck there. So
/// [`depenetrate`] takes the simpler set's push only where it clears the
/// body, and the full set's otherwise.
fn limits_at<T: Real>(
    frame: &Frame<'_, T>,
    p: &Vec3<T>,
    extra: &T,
    kind: Limits,
    opts: &RobustOptions,
    limits: &mut SmallVec<[Limit<T>; 8]>,
    simpler: Option<&mut SmallVec<[Limit<T>; 8]>>,
) -> bool {
    let one = T::one();
    let reach = one.clone() + T::c(opts.max_padding) + extra;
    let tiny = T::c(opts.feasible_ulps * T::unit_roundoff());
    let s = least_s(p);
    // The face's padding for every limit: a gap below is a distance to the
    // plane wherever `p` is over the face or behind it.
    let raw_padding =
        |c: &Candidate<T>| uncapped_padding(frame.start_magnitude, s, p, &Vec3::zeros(), c, Feature::Face, opts);
    limits.clear();
    // Per limit: its triangle, its uncapped padding and where it came from.
    type From<'a, T> = (&'a Candidate<T>, f64, Source<T>);
    let mut from: SmallVec<[From<'_, T>; 8]> = SmallVec::new();
    // The limit that asks for `gap` along `n` to become `1 + pad + extra`
    // (relaxed as [`Limits::Skin`] says).
    let limit = |gap: T, n: Vec3<T>, raw_pad: f64| -> Limit<T> {
        let pad = T::c(raw_pad.min(opts.max_padding));
        let short = gap.clone() - &one < pad.clone() * T::c(0.5);
        let need = one.clone() + pad + extra - gap;
        let relaxed = kind == Limits::Skin && !short;
        (if relaxed { need.min(T::zero()) } else { need }, n)
    };
    for c in &frame.hood.triangles {
        let tri = &c.triangle;
        // A skin limit is set wherever the distance's error could put the
        // triangle within reach.
        let widened = (kind == Limits::Skin).then(|| raw_padding(c));
        let reach = widened.map_or_else(|| reach.clone(), |w| reach.clone() + T::c(w));
        if beyond(c, p, &reach, &(reach.clone() * &reach)) {
            continue;
        }
        let (q, feature) = closest_point(c, p);
        let dist = norm(&(p - &q));
        if !(dist < reach) {
            continue;
        }
        let raw_pad = widened.unwrap_or_else(|| raw_padding(c));
        if kind == Limits::Skin && raw_pad >= opts.max_padding {
            return false;
        }
        let front = normalize(&tri.unnormalized_normal());
        let side = front.as_ref().map(|f| dot(f, &(p - &tri.a)));
        // `gap`: how far `p` lies along `n` from the triangle.
        let (gap, n, source) = match (front, side) {
            (Some(f), Some(side)) if side < T::zero() && !frame.detect.two_sided => {
                if !(dist < one) {
                    continue;
                }
                let source = if feature == Feature::Face { Source::Face(side.clone()) } else { Source::Other };
                (side, f, source)
            }
            // Over the face the plane's normal is the direction: `p - q`
            // is off by the closest point's error in the plane too, and
            // on or near the plane of a triangle whose vertices are far
            // it is mostly that error and points sideways. Within half
            // the padding of the plane, where the side is not to be
            // trusted, the front normal decides (as for a point on the
            // face), so that a body barely behind a wall of a slot too
            // narrow for it leaves the way the front says, not into the
            // slot.
            (Some(f), Some(side)) if feature == Feature::Face => {
                if side < -T::c(raw_pad / 2.0) {
                    (-side.clone(), -f, Source::Face(-side))
                } else {
                    (side.clone(), f, Source::Face(side))
                }
            }
            (front, side) if dist > tiny => (dist.clone(), (p - &q) / dist, Source::Point(front.zip(side))),
            (Some(f), _) => (T::zero(), f, Source::Other),
            (None, _) => continue,
        };
        limits.push(limit(gap, n, raw_pad));
        if simpler.is_some() {
            from.push((c, raw_pad, source));
        }
    }
    let Some(simpler) = simpler else { return true };
    simpler.clear();
    // The limits of the faces `p` is over: direction and gap.
    let faces: SmallVec<[(Vec3<T>, T); 4]> = limits
        .iter()
        .zip(&from)
        .filter_map(|((_, n), (_, _, source))| match source {
            Source::Face(gap) => Some((n.clone(), gap.clone())),
            _ => None,
        })
        .collect();
    if faces.is_empty() {
        return true;
    }
    let rounding = T::c(opts.feasible_ulps * T::unit_roundoff());
    let flat = T::c(INTERNAL_EDGE_DEGREES.to_radians().cos());
    // Whether `c` lies behind the plane a face's limit asks `p` to clear.
    let behind = |c: &Candidate<T>, raw_pad: f64, (n, gap): &(Vec3<T>, T)| {
        [&c.triangle.a, &c.triangle.b, &c.triangle.c].into_iter().all(|v| {
            let rel = v - p;
            dot(n, &rel) + gap <= T::c(raw_pad / 2.0) + rounding.clone() * max_abs(&rel, T::one())
        })
    };
    // A triangle's own unit normal, towards `p` (as a face's limit where
    // `p` lies within half the padding of its plane and the triangle has
    // two sides), where it is within `INTERNAL_EDGE_DEGREES` of a face's
    // limit.
    let parallel = |(f, side): &(Vec3<T>, T), raw_pad: f64| {
        let tied = frame.detect.two_sided && side.clone().abs() <= T::c(raw_pad / 2.0);
        let towards = if side.is_sign_negative() { -f.clone() } else { f.clone() };
        faces.iter().find_map(|(m, _)| {
            if dot(&towards, m) >= flat {
                Some(towards.clone())
            } else if tied && -dot(&towards, m) >= flat {
                Some(-towards.clone())
            } else {
                None
            }
        })
    };
    let mut changed = false;
    for (l, (c, raw_pad, source)) in limits.iter().zip(&from) {
        let Source::Point(front) = source else {
            simpler.push(l.clone());
            continue;
        };
        if faces.iter().any(|f| behind(c, *raw_pad, f)) {
            changed = true;
            continue;
        }
        match front.as_ref().and_then(|f| parallel(f, *raw_pad)) {
            Some(n) => {
                changed = true;
                simpler.push(limit(dot(&n, &(p - &c.triangle.a)), n, *raw_pad));
            }
            None => simpler.push(l.clone()),
        }
    }
    if !changed {
        simpler.clear();
    }
    true
}

/// The longest push one round may make, in radii: the most the body's
/// own size spans. A longer least-norm push (the limits are half-spaces,
/// the triangles behind them finite: in a narrow crack the push that
/// clears both planes lies far along the bisector, beyond where the walls
/// end, and a review found one of 400 radii leaving a closed room) is
/// shortened to it, and the next round, with the candidates gathered
/// again, decides from there. No round can then carry the body through a
/// wall it was not already within `1 + max_padding` of (a one-sided
/// triangle it overlaps from behind it pushes through to the front, as
/// intended).
const MAX_PUSH: f64 = 1.0;

/// The push for `limits` (their deepest [`DEPENETRATION_LIMITS`]): the
/// shortest that satisfies them all ([`least_push`]), or the deepest
/// one's alone if none does, at most `longest`.
fn shortest_push<T: Real>(limits: &mut SmallVec<[Limit<T>; 8]>, longest: &T, opts: &RobustOptions) -> Vec3<T> {
    limits.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap_or(std::cmp::Ordering::Equal));
    limits.truncate(DEPENETRATION_LIMITS);
    let Some((need, n)) = limits.first() else { return Vec3::zeros() };
    let push = least_push(limits, opts).unwrap_or_else(|| n * need.clone());
    let length = norm(&push);
    if length > *longest { push * (longest.clone() / length) } else { push }
}

/// The push for the limits of [`skin_in_crease`] ([`Limits::Skin`]): the
/// shortest that satisfies the deepest [`DEPENETRATION_LIMITS`]
/// ([`least_push`]), if it meets every limit within `feasible_ulps * u`
/// of the largest need or of its own length, and is at most `max_padding
/// / 2` long; `None` if not.
///
/// The check is tighter than [`least_push`]'s, whose tolerance grows with
/// the coefficients of a nearly singular pair or triple: two limits from
/// coplanar triangles of one wall, `5e-6` radians apart in `f32`, passed
/// its parallel test on the rounding of `1 - c^2` and gave a push of
/// rounding noise, `4.8e-3` long, that a tolerance of `7.5e-3` let move
/// the body `1.4e-3` towards a triangle it was to leave (a review). Unlike
/// [`shortest_push`] it never falls back to the deepest limit alone, nor
/// shortens a push: the limits hold for the push that meets them, not for
/// a part of it (shortened pushes took bodies up to `3.3e-3` into walls in
/// 20 of 300 narrow `f32` slots), and in a slot narrower than its walls'
/// paddings (their limits ask for opposite pushes) the deepest limit
/// alone would drive the body towards the other wall.
///
/// Why such a push keeps the limits: the distance to a triangle is convex,
/// so a push `d` gains at least `n . d` on a triangle whose exact
/// separating direction is `n` (the computed one is off by under `pad`
/// radians: [`Limits::Skin`]); a triangle beyond the limits' reach
/// `1 + max_padding` stays `1 + max_padding / 2` away, outside its skin.
fn crease_push<T: Real>(limits: &mut SmallVec<[Limit<T>; 8]>, opts: &RobustOptions) -> Option<Vec3<T>> {
    limits.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap_or(std::cmp::Ordering::Equal));
    let solved = limits.len().min(DEPENETRATION_LIMITS);
    let push = least_push(&limits[..solved], opts)?;
    let length = norm(&push);
    let scale = limits.iter().fold(length.clone(), |m, (need, _)| m.max(need.abs()));
    let tol = T::c(opts.feasible_ulps * T::unit_roundoff()) * scale;
    let meets_all = limits.iter().all(|(need, n)| dot(n, &push) >= need.clone() - &tol);
    (meets_all && length <= T::c(0.5 * opts.max_padding)).then_some(push)
}

/// The most limits one round solves for (the deepest ones; the next round
/// sees the rest): the push is chosen among the solutions of every one,
/// two and three of them, `O(k^3)` candidates.
const DEPENETRATION_LIMITS: usize = 8;

/// The shortest displacement `d` with `n_i . d >= need_i` for every limit
/// `(need_i, n_i)` (unit `n_i`); `None` if no candidate satisfies them all
/// (limits that contradict each other, or are parallel within
/// `parallel_ulps`).
///
/// The least-norm point of a polyhedron lies on a face where one, two or
/// three of its limits hold with equality (in three dimensions at most
/// three independent ones bind), and is the least-norm point of that
/// face's affine hull: `n_i need_i` for one, the solution in the span of
/// `n_i, n_j` for two ([`consider_pair`]), and Cramer's rule for three.
/// Every such point that satisfies all limits is a candidate and the
/// shortest one is the answer. A candidate, a sum of terms (`a_i n_i`, or
/// [`consider_pair`]'s), is computed with an error of a few `u` times the
/// sum of its terms' lengths (large for nearly parallel limits: in a 2
/// degree wedge they are 800 times the overlap), so a limit counts as
/// satisfied up to `feasible_ulps * u * (max |need| + that sum)`,
/// relative to the push, not to the body's radius: the needs are a padding
/// or an overlap, and a tolerance of `u` radii would exceed the padding (a
/// fuzz input in `f32` found a push towards the floor by `6e-7` radii
/// passing for one `3e-6` away from it).
fn least_push<T: Real>(limits: &[(T, Vec3<T>)], opts: &RobustOptions) -> Option<Vec3<T>> {
    let u = T::c(opts.feasible_ulps * T::unit_roundoff());
    let scale = limits.iter().fold(T::zero(), |m, (need, _)| m.max(need.abs()));
    let min_sin2 = T::c((opts.parallel_ulps * T::unit_roundoff()).powi(2));
    let mut best: Option<(T, Vec3<T>)> = None;
    let mut consider = |d: Vec3<T>, weight: T| {
        let tol = u.clone() * (scale.clone() + weight);
        if limits.iter().all(|(need, n)| dot(n, &d) >= need.clone() - &tol) {
            let length = norm_squared(&d);
            if best.as_ref().is_none_or(|(shortest, _)| length < *shortest) {
                best = Some((length, d));
            }
        }
    };
    for (i, (bi, ni)) in limits.iter().enumerate() {
        consider(ni * bi.clone(), bi.abs());
        for (j, (bj, nj)) in limits.iter().enumerate().skip(i + 1) {
            // `sin^2` of the pair's angle from their crease (`crease`),
            // not `1 - c^2`: for two normals equal up to rounding `c`
            // can round to one ulp below 1, and `1 - c^2` to `2 u`, which
            // passed the parallel test and gave coefficients of `1 / u`
            // whose rounding noise, within the tolerance they widen,
            // pushed a body out of a floor the wrong way, into it (fuzz
            // finding F37).
            if norm_squared(&crease(ni, nj)) > min_sin2 {
                consider_pair(ni, bi, nj, bj, &mut consider);
            }
            for (bk, nk) in &limits[j + 1..] {
                let (jk, ki, ij) = (cross(nj, nk), cross(nk, ni), cross(ni, nj));
                let det = dot(ni, &jk);
                if det.clone() * &det > min_sin2 {
                    let weight = (bi.abs() + bj.abs() + bk.abs()) / det.abs();
                    consider((jk * bi.clone() + ki * bj.clone() + ij * bk.clone()) / det, weight);
                }
            }
        }
    }
    best.map(|(_, d)| d)
}

/// The least-norm `d` with `ni . d = bi` and `nj . d = bj` (two limits of
/// [`least_push`] that are not parallel), passed to `consider` with the
/// size of its terms, which bounds its rounding.
///
/// Solved in the basis of `s = ni + nj` and `t = ni - nj`, whose Gram
/// matrix is nearly diagonal (`s . t = |ni|^2 - |nj|^2`, zero for unit
/// normals): `s . d = bi + bj` and `t . d = bi - bj`. The difference `t`
/// of two nearly parallel normals is nearly exact (as in [`crease`]), so
/// `|t|^2` is off by `u` relative, where the Gram system in `ni, nj`
/// divides by `1 - c^2` off by `u` absolute; and the normals' lengths,
/// one within a few `u` but not exactly, enter through `s . t` rather
/// than being taken as 1. With the unit-length form, a pair a few
/// thousandths of a radian apart missed both its limits by fifty times
/// the tolerance and no push was found (a review, R24d: in about 70% of
/// 20,000 such pairs in `f64`, 37% before F37).
fn consider_pair<T: Real>(ni: &Vec3<T>, bi: &T, nj: &Vec3<T>, bj: &T, consider: &mut impl FnMut(Vec3<T>, T)) {
    let (s, t) = (ni + nj, ni - nj);
    let (ss, tt, st) = (norm_squared(&s), norm_squared(&t), dot(&s, &t));
    let (sum, diff) = (bi.clone() + bj, bi.clone() - bj);
    let det = ss.clone() * &tt - st.clone() * &st;
    let a = (sum.clone() * &tt - st.clone() * &diff) / det.clone();
    let b = (diff * &ss - st * sum) / det;
    let weight = a.abs() * ss.sqrt() + b.abs() * tt.sqrt();
    consider(s * a + t * b, weight);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two limits `5.5e-3` radians apart with nearly equal needs, from a
    /// review of F37's fix (R24d): the pair's solution from the unit-length
    /// Gram system missed both by `8.2e-18` against a tolerance of
    /// `1.6e-19`, and no push was found.
    #[test]
    fn least_push_of_nearly_parallel_limits_meets_both() {
        let limits: Vec<(f64, Vec3<f64>)> = [
            (1.1244590213796508e-5, [0.7949812743988114, -0.5653629679806764, -0.2199306431385188]),
            (1.124435330481498e-5, [0.8001910092431135, -0.5595777137873537, -0.21579418657370297]),
        ]
        .into_iter()
        .map(|(need, n)| (need, Vec3::new(n[0], n[1], n[2])))
        .collect();
        let push = least_push(&limits, &RobustOptions::default()).expect("the pair's solution meets both");
        for (need, n) in &limits {
            assert!(dot(n, &push) >= need - 1e-18, "{push:?} misses ({need}, {n:?})");
        }
        assert!(norm(&push) < 1.2e-5, "{push:?} is not the least push");
    }

    /// Fuzz finding F37 (twenty-third session, `move_robust`, `f32`): the
    /// limits of a still body touching, from below, a floor of coincident
    /// triangles beside planes half a degree off it. Every limit asks for
    /// a push down (`-y`); two floor normals equal up to rounding made
    /// `1 - c^2` one ulp's worth, and the pair's solution, rounding noise
    /// `1.5e-5` long pointing up, was accepted within the tolerance its
    /// huge coefficients widened, and pushed the body into the floor.
    #[test]
    fn least_push_of_limits_equal_up_to_rounding_meets_them() {
        let limits: Vec<(f32, Vec3<f32>)> = [
            (7.688_999e-6, [2.793_968e-9, -1.0, 1.862_645_4e-9]),
            (7.688_999e-6, [-1.816_079_2e-7, -1.0, 9.126_962e-8]),
            (-2.884_864_8e-5, [0.008_544_739, -0.999_963_46, 0.0]),
            (1.478_791_2e-4, [0.0, -1.0, 0.0]),
            (-3.099_441_5e-6, [0.008_544_739, -0.999_963_46, 0.0]),
            (-3.099_441_5e-6, [0.008_544_739, -0.999_963_46, 0.0]),
            (7.688_999e-6, [0.0, -1.0, 0.0]),
            (-1.026_392e-4, [-0.003_188_387, -0.999_889_7, 0.014_510_738]),
        ]
        .into_iter()
        .map(|(need, n)| (need, Vec3::new(n[0], n[1], n[2])))
        .collect();
        let push = least_push(&limits, &RobustOptions::default()).expect("a push down meets them all");
        for (need, n) in &limits {
            assert!(dot(n, &push) >= need - 1e-6, "{push:?} misses ({need}, {n:?})");
        }
    }

    /// A review's finding (twenty-first session): [`least_push`] solves a
    /// pair of limits whose directions differ by rounding noise (its
    /// parallel test sees the rounding of `1 - c^2`) and accepts the noise
    /// within a tolerance that grows with the pair's huge coefficients, so
    /// [`crease_push`] must check every limit itself. Random sets of two to
    /// four nearly parallel limits in `f32` (`1e-7` to `1e-5` radians
    /// apart, needs within the `0.005` of a push): every push it returns
    /// meets every limit within its own tolerance.
    #[test]
    fn crease_push_meets_every_limit_it_was_given() {
        let opts = RobustOptions::default();
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut accepted = 0;
        for _ in 0..20_000 {
            let base = [uniform() - 0.5, uniform() - 0.5, uniform() - 0.5];
            let mut limits: SmallVec<[Limit<f32>; 8]> = SmallVec::new();
            for _ in 0..2 + (uniform() * 3.0) as usize {
                let angle = 10f64.powf(-7.0 + 2.0 * uniform());
                let tilt = [uniform() - 0.5, uniform() - 0.5, uniform() - 0.5];
                let v = Vec3::<f32>::from_fn(|i, _| (base[i] + angle * tilt[i]) as f32);
                let Some(n) = normalize(&v) else { continue };
                limits.push((((uniform() - 0.5) * 0.01) as f32, n));
            }
            let Some(push) = crease_push(&mut limits.clone(), &opts) else { continue };
            accepted += 1;
            let scale = limits.iter().fold(norm(&push), |m, (need, _)| m.max(need.abs()));
            let tol = (opts.feasible_ulps * f32::unit_roundoff()) as f32 * scale;
            for (need, n) in &limits {
                assert!(dot(n, &push) >= need - tol, "push {push:?} misses ({need:e}, {n:?}) by more than {tol:e}");
            }
        }
        assert!(accepted > 1_000, "only {accepted} pushes accepted");
    }
}
