//! The invariants the fuzz targets assert, with their exact (MPFR) oracles.
//!
//! This file is shared: the fuzz crate compiles it as `sweepslide_fuzz::oracle`
//! and the root crate's `tests/fuzz_props.rs` includes it with `#[path]`, so
//! `cargo test` checks the very same invariants on proptest's inputs that
//! `cargo fuzz` checks on libFuzzer's. It depends on `sweepslide` (features
//! `mpfr` and `lab`) and `rug` only.
//!
//! # Sweep of one triangle (`check_sweep`)
//! The input (`f64` values) is rounded into the backend `T`; the robust
//! sweep runs on those values in `T` and in `Mpfr<256>` (the reference,
//! exactly the same numbers). Distances are judged exactly: MPFR at
//! [`PREC`] bits from the exact binary values, by a formula independent of
//! the crate's (distance to the plane when the projection falls inside the
//! triangle, else to the nearest edge segment). With `D(t)` the exact
//! distance from the centre `base + t vel` to the triangle and
//! `B = BOUND_ULPS * u * s * k` (see [`sweep_bound`]):
//!
//! 1. no panic, `t` in `[0, 1]`, a finite unit normal, a finite point;
//! 2. a hit at `t > 0` touches: `|D(t) - 1| <= B`; a hit at `t = 0`
//!    touches or overlaps: `D(0) <= 1 + B`;
//! 3. nothing is entered before the reported time (or before 1 without a
//!    hit): `min D over [0, t] >= min(1, D(0)) - B`;
//! 4. the backend agrees with the reference: both hit, the reference's
//!    `t_ref > 0` touches too (`|D(t_ref) - 1| <= B`) and nothing is entered
//!    before the later of `t` and `t_ref` (so both are first touches within
//!    the bound, however far apart a grazing contact lets them be), or
//!    exactly one of them hits and the exact path shows a near miss:
//!    `min D over [0, 1] >= min(1, D(0)) - B`.
//!
//! # Robust moves (`check_robust_moves`)
//! A body starting outside the geometry (exact penetration `<= 0`, inputs
//! that start inside are skipped) and moved frame after frame by the robust
//! response never gets a NaN or infinite position, never uses more than
//! [`iteration_bound`] collision checks in a frame, and never ends a frame
//! penetrating (`sweepslide::lab::metrics::penetration > 0`).
//!
//! # Range (inputs outside it are skipped, not failed)
//! Every coordinate (vertices, positions, velocities, in `f64` before and
//! in `T` after rounding) within `[-MAX_COORD, MAX_COORD]`; radii in
//! `[MIN_RADIUS, MAX_RADIUS]` with a largest/smallest ratio of at most
//! `MAX_RADIUS_RATIO`; for moves, the robust response's padding below its
//! cap ([`padding_in_range`]) and a start not squeezed within the padding
//! of two opposite triangles ([`Skip::StartsSqueezed`]), the frames checked
//! up to the first later one that starts squeezed in a slot
//! ([`SLOT_OPPOSED`]) and up to one that ends squeezed in a slot no deeper
//! than the skin ([`squeeze`]); for the sweep, a non-degenerate triangle with shape
//! factor `k = max |edge|^2 / |(b - a) x (c - a)|` at most `MAX_SHAPE`
//! (`k >= 2 / sqrt(3)`, equality for an equilateral triangle; `k = 1000`
//! is an angle of about 0.1 degrees).

// The checks are written `!(err <= bound)` on purpose: a NaN must fail.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use rug::Float;
use std::sync::Arc;
use sweepslide::detect::{Candidate, DetectOptions, Hit, sweep_robust};
use sweepslide::geom::{Ellipsoid, Triangle, Vec3, closest_point_on_triangle, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, RobustOptions, move_body, robust};
use sweepslide::world::{TriangleMesh, World};
use sweepslide::{Mpfr, Real};

/// Working precision of the exact checks (bits). The inputs are `f32` or
/// `f64` values of magnitude at most [`MAX_COORD`], so every quantity here
/// is exact to far below `1e-60` relative.
pub const PREC: u32 = 256;

/// The sweep bound in units of `u * s * k` (see [`sweep_bound`]).
pub const BOUND_ULPS: f64 = 64.0;

/// Largest absolute coordinate in range.
pub const MAX_COORD: f64 = 1e6;

/// Largest triangle shape factor in range for the sweep checks.
pub const MAX_SHAPE: f64 = 1e3;

/// Smallest radius in range.
pub const MIN_RADIUS: f64 = 1e-4;

/// Largest radius in range.
pub const MAX_RADIUS: f64 = 1e4;

/// Largest ratio between an ellipsoid's radii in range.
pub const MAX_RADIUS_RATIO: f64 = 64.0;

/// Why an input was not checked (out of the documented range).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Skip {
    /// A coordinate beyond [`MAX_COORD`] (or not finite).
    OutOfRange,
    /// A degenerate triangle (zero area after rounding) or one with shape
    /// factor above [`MAX_SHAPE`].
    Degenerate,
    /// Radii outside the range, or rejected by `Ellipsoid::new`.
    BadBody,
    /// The mesh has no valid triangle.
    EmptyMesh,
    /// The body starts penetrating the geometry.
    StartsInside,
    /// The body starts squeezed: within the robust response's padding skin
    /// of two triangles on opposite sides of it (their closest points seen
    /// from the centre more than 90 degrees apart), as in a slot whose
    /// clearance is below twice the padding. No position then keeps the
    /// padding from both, and when the clearance is at the level of
    /// rounding (a zero-clearance slot) no representable position other
    /// than the start may lie outside both: the body cannot be moved
    /// without an exact penetration of the order of the coordinates'
    /// rounding. The skin is the padding of the first frame's passes,
    /// which grows with their displacement (docs/fuzzing.md, F3 and F27).
    StartsSqueezed,
    /// The robust response's padding would reach its cap
    /// (`RobustOptions::max_padding`): see [`padding_in_range`].
    PaddingCap,
    /// Beyond a limit set for a campaign by an environment variable
    /// (`SWEEPSLIDE_SWEEP_MAX_S`, see [`check_sweep`]).
    Excluded,
}

/// What a checked sweep measured, for the fuzz targets' statistics.
#[derive(Clone, Debug, Default)]
pub struct SweepStats {
    /// The backend reported a hit.
    pub hit: bool,
    /// The largest error met, in units of `u * s * k` (the assertions
    /// allow [`BOUND_ULPS`]).
    pub worst: f64,
}

// ------------------------------------------------------ exact geometry --

/// An exact 3-vector.
pub type X = [Float; 3];

fn xs(x: f64) -> Float {
    Float::with_val(PREC, x)
}

/// The exact value of a backend number.
fn xr<T: Real>(x: &T) -> Float {
    Float::with_val(PREC, x.to_rug())
}

fn xv<T: Real>(v: &Vec3<T>) -> X {
    [xr(&v[0]), xr(&v[1]), xr(&v[2])]
}

fn sub(a: &X, b: &X) -> X {
    [0, 1, 2].map(|i| Float::with_val(PREC, &a[i] - &b[i]))
}

fn add(a: &X, b: &X) -> X {
    [0, 1, 2].map(|i| Float::with_val(PREC, &a[i] + &b[i]))
}

fn scale(a: &X, s: &Float) -> X {
    [0, 1, 2].map(|i| Float::with_val(PREC, &a[i] * s))
}

fn dot(a: &X, b: &X) -> Float {
    let mut s = Float::with_val(PREC, &a[0] * &b[0]);
    s += Float::with_val(PREC, &a[1] * &b[1]);
    s += Float::with_val(PREC, &a[2] * &b[2]);
    s
}

fn cross(a: &X, b: &X) -> X {
    [
        Float::with_val(PREC, &a[1] * &b[2]) - Float::with_val(PREC, &a[2] * &b[1]),
        Float::with_val(PREC, &a[2] * &b[0]) - Float::with_val(PREC, &a[0] * &b[2]),
        Float::with_val(PREC, &a[0] * &b[1]) - Float::with_val(PREC, &a[1] * &b[0]),
    ]
}

fn norm(a: &X) -> Float {
    dot(a, a).sqrt()
}

/// Distance from `p` to the segment `[a, b]`.
fn dist_segment(p: &X, a: &X, b: &X) -> Float {
    let e = sub(b, a);
    let e2 = dot(&e, &e);
    if e2.is_zero() {
        return norm(&sub(p, a));
    }
    let s = dot(&sub(p, a), &e) / e2;
    let s = s.clamp(&xs(0.0), &xs(1.0));
    norm(&sub(p, &add(a, &scale(&e, &s))))
}

/// Exact distance from `p` to the triangle `t`: to its plane when the
/// projection of `p` lies inside (all three edge orientations agree with
/// the normal), else to the nearest edge segment.
#[must_use]
pub fn dist_triangle(p: &X, t: &[X; 3]) -> Float {
    let n = cross(&sub(&t[1], &t[0]), &sub(&t[2], &t[0]));
    let n2 = dot(&n, &n);
    let inside = !n2.is_zero()
        && (0..3).all(|i| {
            let (a, b) = (&t[i], &t[(i + 1) % 3]);
            dot(&cross(&sub(b, a), &sub(p, a)), &n) >= 0
        });
    if inside {
        return (dot(&sub(p, &t[0]), &n) / n2.sqrt()).abs();
    }
    (0..3).map(|i| dist_segment(p, &t[i], &t[(i + 1) % 3])).min_by(|a, b| a.total_cmp(b)).expect("three edges")
}

/// The shape factor `max |edge|^2 / |(b - a) x (c - a)|` (infinite for a
/// degenerate triangle).
#[must_use]
pub fn shape_factor(t: &[X; 3]) -> f64 {
    let area2 = norm(&cross(&sub(&t[1], &t[0]), &sub(&t[2], &t[0])));
    if area2.is_zero() {
        return f64::INFINITY;
    }
    let longest = (0..3)
        .map(|i| dot(&sub(&t[(i + 1) % 3], &t[i]), &sub(&t[(i + 1) % 3], &t[i])))
        .fold(xs(0.0), |m, x| if x > m { x } else { m });
    (longest / area2).to_f64()
}

/// An exact sphere path and triangle.
struct Path {
    base: X,
    vel: X,
    tri: [X; 3],
}

impl Path {
    /// Exact distance from the centre at time `t` to the triangle.
    fn dist(&self, t: &Float) -> Float {
        dist_triangle(&add(&self.base, &scale(&self.vel, t)), &self.tri)
    }

    /// The minimum of the (convex) distance over `[lo, hi]`, by
    /// golden-section search to a relative width of `1e-15` (the distance
    /// is convex along a line, so this finds its minimum; its value is off
    /// by far less than any bound used here).
    fn min_dist(&self, lo: f64, hi: f64) -> Float {
        let g = (5f64.sqrt() - 1.0) / 2.0;
        let f = |t: f64| self.dist(&xs(t));
        let mut best = f(lo).min(&f(hi));
        let (mut a, mut b) = (lo, hi);
        let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
        let (mut fc, mut fd) = (f(c), f(d));
        for _ in 0..80 {
            if !(b - a > 1e-15 * hi.abs().max(1e-300)) {
                break;
            }
            if fc < fd {
                b = d;
                d = c;
                fd = fc.clone();
                c = b - g * (b - a);
                fc = f(c);
            } else {
                a = c;
                c = d;
                fc = fd.clone();
                d = a + g * (b - a);
                fd = f(d);
            }
        }
        for v in [fc, fd, f((a + b) / 2.0)] {
            if v < best {
                best = v;
            }
        }
        best
    }
}

fn in_range(v: &[f64; 3]) -> bool {
    v.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORD)
}

fn in_range_t<T: Real>(v: &Vec3<T>) -> bool {
    v.iter().all(|x| x.is_finite() && x.to_f64().abs() <= MAX_COORD)
}

/// The unit of the sweep bound, `u * s * k`: `u` the backend's unit
/// roundoff, `s = max(1, |p_i - base|_inf, |vel|_inf)` the magnitude of the
/// relative inputs (eSpace, sphere radius 1), `k = max(1, shape factor)`.
#[must_use]
pub fn sweep_bound<T: Real>(base: &Vec3<T>, vel: &Vec3<T>, tri: &Triangle<T>, shape: f64) -> f64 {
    let s = [&tri.a, &tri.b, &tri.c]
        .into_iter()
        .flat_map(|p| (0..3).map(move |i| (p[i].to_f64() - base[i].to_f64()).abs()))
        .chain((0..3).map(|i| vel[i].to_f64().abs()))
        .fold(1.0, f64::max);
    T::unit_roundoff() * s * shape.max(1.0)
}

/// The robust sweep of the unit sphere at `base` moving by `vel` against
/// one lone triangle, in backend `T`.
pub fn robust_sweep<T: Real>(base: &Vec3<T>, vel: &Vec3<T>, tri: &Triangle<T>) -> Option<Hit<T>> {
    let c = Candidate::lone(0, tri.clone());
    sweep_robust(&c, base, vel, &DetectOptions::default(), None)
}

fn to<T: Real, U: Real>(v: &Vec3<T>) -> Vec3<U> {
    v.map(|x| U::from_rug(&x.to_rug()))
}

/// The largest `s` checked, from `SWEEPSLIDE_SWEEP_MAX_S` (unset: no
/// limit). A campaign can set it to keep exploring the rest of the range
/// while a failure at large `s` is open.
fn max_s() -> f64 {
    static MAX_S: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    *MAX_S.get_or_init(|| {
        std::env::var("SWEEPSLIDE_SWEEP_MAX_S").ok().and_then(|v| v.parse().ok()).unwrap_or(f64::INFINITY)
    })
}

/// Checks the sweep invariants (module docs) for the unit sphere at `base`
/// moving by `vel` against `tri`, all rounded into `T` first.
///
/// Inputs with `s` above `SWEEPSLIDE_SWEEP_MAX_S` (if set) are skipped.
///
/// # Errors
/// A description of the first violated invariant, with the numbers.
pub fn check_sweep<T: Real>(
    base: [f64; 3],
    vel: [f64; 3],
    tri: [[f64; 3]; 3],
) -> Result<Result<SweepStats, Skip>, String> {
    if !(in_range(&base) && in_range(&vel) && tri.iter().all(in_range)) {
        return Ok(Err(Skip::OutOfRange));
    }
    let p = |a: &[f64; 3]| vec3::<T>(a[0], a[1], a[2]);
    let (b, v) = (p(&base), p(&vel));
    let t = Triangle::new(p(&tri[0]), p(&tri[1]), p(&tri[2]));
    if !(in_range_t(&b) && in_range_t(&v) && [&t.a, &t.b, &t.c].iter().all(|x| in_range_t(x))) {
        return Ok(Err(Skip::OutOfRange));
    }
    let path = Path { base: xv(&b), vel: xv(&v), tri: [xv(&t.a), xv(&t.b), xv(&t.c)] };
    let shape = shape_factor(&path.tri);
    if !(shape <= MAX_SHAPE) {
        return Ok(Err(Skip::Degenerate));
    }
    let name = T::name();
    let unit = sweep_bound(&b, &v, &t, shape);
    if unit / T::unit_roundoff() / shape.max(1.0) > max_s() {
        return Ok(Err(Skip::Excluded));
    }
    let bound = BOUND_ULPS * unit;
    let mut stats = SweepStats::default();
    let mut note = |err: f64| stats.worst = stats.worst.max(err / unit);

    // Never panics (the fuzz harness catches a panic); the reference runs
    // on exactly the same values.
    let hit = robust_sweep(&b, &v, &t);
    let reference = robust_sweep::<Mpfr<256>>(&to(&b), &to(&v), &Triangle::new(to(&t.a), to(&t.b), to(&t.c)));

    let one = xs(1.0);
    let d0 = path.dist(&xs(0.0));
    let floor = if d0 < one { d0.clone() } else { one.clone() };
    let describe = || format!("{name}: base {base:?} vel {vel:?} tri {tri:?} -> hit {hit:?}, reference {reference:?}");

    // 1. The record itself.
    if let Some(h) = &hit {
        let th = h.t.to_f64();
        if !(0.0..=1.0).contains(&th) {
            return Err(format!("t = {th} outside [0, 1]; {}", describe()));
        }
        let n = h.normal.iter().map(|x| x.to_f64().powi(2)).sum::<f64>().sqrt();
        if !((n - 1.0).abs() <= 8.0 * T::unit_roundoff()) {
            return Err(format!("|normal| = {n}; {}", describe()));
        }
        if !h.point.iter().all(Real::is_finite) {
            return Err(format!("non-finite contact point; {}", describe()));
        }
        if h.started_overlapping && th != 0.0 {
            return Err(format!("started_overlapping with t = {th}; {}", describe()));
        }
    }

    // 2. A reported hit touches.
    let end = match &hit {
        Some(h) if h.t.to_f64() > 0.0 => {
            let err = (path.dist(&xr(&h.t)) - &one).to_f64().abs();
            note(err);
            if !(err <= bound) {
                return Err(format!("|D(t) - 1| = {err:e} > bound {bound:e} ({} u*s*k); {}", err / unit, describe()));
            }
            h.t.to_f64()
        }
        Some(_) => {
            let gap = (d0.clone() - &one).to_f64();
            note(gap.max(0.0));
            if !(gap <= bound) {
                return Err(format!("hit at t = 0 but D(0) - 1 = {gap:e} > bound {bound:e}; {}", describe()));
            }
            0.0
        }
        None => 1.0,
    };

    // 3. Nothing entered before.
    if end > 0.0 {
        let dip = (floor.clone() - path.min_dist(0.0, end)).to_f64().max(0.0);
        note(dip);
        if !(dip <= bound) {
            return Err(format!(
                "the path dips {dip:e} (> bound {bound:e}) below min(1, D(0)) before t = {end}; {}",
                describe()
            ));
        }
    }

    // 4. Agreement with the reference, in a well-conditioned form: a
    // reference hit at `t_ref > 0` touches too, and nothing is entered
    // before the later of the two times (so both are first touches up to
    // the bound, however far apart a grazing contact puts them); exactly
    // one hit: the exact path shows a near miss.
    match (&hit, &reference) {
        (Some(h), Some(r)) => {
            let tr = r.t.to_f64();
            if tr > 0.0 {
                let err = (path.dist(&xr(&r.t)) - &one).to_f64().abs();
                note(err);
                if !(err <= bound) {
                    return Err(format!("the reference's |D(t_ref) - 1| = {err:e} > bound {bound:e}; {}", describe()));
                }
            }
            let later = tr.max(h.t.to_f64());
            if later > end {
                let dip = (floor.clone() - path.min_dist(0.0, later)).to_f64().max(0.0);
                note(dip);
                if !(dip <= bound) {
                    return Err(format!(
                        "the path dips {dip:e} (> bound {bound:e}) below min(1, D(0)) before t_ref = {tr}; {}",
                        describe()
                    ));
                }
            }
        }
        (Some(_), None) | (None, Some(_)) => {
            let depth = (floor - path.min_dist(0.0, 1.0)).to_f64().max(0.0);
            note(depth);
            if !(depth <= bound) {
                return Err(format!(
                    "hit/miss differs from Mpfr<256> and the path goes {depth:e} (> bound {bound:e}) deep; {}",
                    describe()
                ));
            }
        }
        (None, None) => {}
    }
    stats.hit = hit.is_some();
    Ok(Ok(stats))
}

// ---------------------------------------------------------------- moves --

/// One frame's displacements (world space): the velocity and an optional
/// gravity pass.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameInput {
    /// The pushing displacement.
    pub velocity: [f64; 3],
    /// The gravity displacement (second pass), if any.
    pub gravity: Option<[f64; 3]>,
}

/// A move scenario: a soup, a body, a start and frames (all `f64`, rounded
/// into the backend when run).
#[derive(Clone, Debug, PartialEq)]
pub struct MoveCase {
    /// The triangles, by their corners.
    pub triangles: Vec<[[f64; 3]; 3]>,
    /// The body's radii (all equal for a sphere).
    pub radii: [f64; 3],
    /// The body's centre at the start.
    pub start: [f64; 3],
    /// The frames, in order.
    pub frames: Vec<FrameInput>,
}

/// How a response failed in a frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure {
    /// A NaN or infinite position.
    NonFinite,
    /// `move_body` returned an error.
    Error(String),
    /// The frame ended inside the geometry by this much (exact; world
    /// units for a sphere, eSpace units for an ellipsoid).
    Penetration(f64),
    /// More collision checks than [`iteration_bound`] allows.
    Iterations {
        /// Checks used.
        used: u32,
        /// The bound.
        bound: u32,
    },
}

impl Failure {
    /// A short name of the kind of failure.
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Failure::NonFinite => "nan",
            Failure::Error(_) => "error",
            Failure::Penetration(_) => "penetration",
            Failure::Iterations { .. } => "iterations",
        }
    }
}

/// A failure in a given frame, with the state it started from.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameFailure {
    /// Index of the frame (0 first).
    pub frame: usize,
    /// The body's centre at the start of that frame (in the backend,
    /// converted to `f64` exactly for `f32`/`f64`).
    pub from: [f64; 3],
    /// The centre it ended at.
    pub to: [f64; 3],
    /// What went wrong.
    pub failure: Failure,
}

/// The world, body and start of a case in backend `T`, or why it is out
/// of range.
pub struct Prepared<T: Real> {
    /// The world.
    pub world: World<T>,
    /// The body.
    pub body: Ellipsoid<T>,
    /// The start, rounded into `T`.
    pub start: Vec3<T>,
}

/// Whether the padding the robust response computes stays below its cap
/// for every frame of `case` in `T`:
/// `position_ulps u P + padding_ulps u S f <= max_padding` (defaults 4, 48
/// and 0.01; `src/respond/robust.rs`) for every triangle, with, in eSpace
/// (coordinates divided by the radii), `P` the largest coordinate any frame
/// can start from (`|start|` plus the total travel), `S` the largest
/// distance from there to one of the triangle's vertices, or of a
/// displacement, at least 1, and `f` its tilt factor
/// ([`RobustOptions::tilt_factor`], from its normal's tilt in `T`). Where
/// the cap binds (in `f32`, `P` beyond about `4e4` radii or `S f` beyond
/// about `3e3` radii), the padding no longer covers the rounding the
/// response itself says it must cover, and non-penetration is not claimed.
#[must_use]
pub fn padding_in_range<T: Real>(case: &MoveCase) -> bool {
    let opts = RobustOptions::default();
    let u = T::unit_roundoff();
    let e = |v: &[f64; 3]| (0..3).map(|i| (v[i] / case.radii[i]).abs()).fold(0.0, f64::max);
    let travel: f64 = case.frames.iter().map(|f| e(&f.velocity) + f.gravity.as_ref().map_or(0.0, e)).sum();
    let reach = e(&case.start) + travel;
    let worst = espace_triangles(case, &case.start).fold(travel.max(1.0), |worst, tri| {
        let far = [&tri.a, &tri.b, &tri.c].iter().map(|v| v.amax()).fold(0.0, f64::max);
        worst.max((far + travel).max(1.0) * tilt_factor::<T>(&opts, &tri))
    });
    opts.position_ulps * u * reach + opts.padding_ulps * u * worst <= opts.max_padding
}

/// The triangles of `case` in eSpace relative to the position `at`, in
/// `f64`.
fn espace_triangles<'a>(case: &'a MoveCase, at: &'a [f64; 3]) -> impl Iterator<Item = Triangle<f64>> + 'a {
    let e = |v: &[f64; 3]| {
        vec3::<f64>((v[0] - at[0]) / case.radii[0], (v[1] - at[1]) / case.radii[1], (v[2] - at[2]) / case.radii[2])
    };
    case.triangles.iter().map(move |t| Triangle::new(e(&t[0]), e(&t[1]), e(&t[2])))
}

/// The robust response's padding factor for `tri` (eSpace, relative to
/// the start), from its normal's tilt computed in `T` as the response
/// computes it ([`Candidate::tilt`]).
fn tilt_factor<T: Real>(opts: &RobustOptions, tri: &Triangle<f64>) -> f64 {
    let t = |v: &Vec3<f64>| vec3::<T>(v.x, v.y, v.z);
    opts.tilt_factor(Candidate::lone(0, Triangle::new(t(&tri.a), t(&tri.b), t(&tri.c))).tilt())
}

/// The robust padding at the position `at` (world) at the start of frame
/// `frame`, in eSpace units, for a contact on the triangle `tri` (eSpace,
/// relative to `at`): as the response computes it
/// (`src/respond/robust.rs`, `padding`), with `s` the largest of 1, the
/// distance to the triangle's nearest vertex and the frame's displacements
/// (largest coordinates; a pass's padding grows with its displacement, fuzz
/// finding F27), times its tilt factor, and the `position_ulps u |at|`
/// term; capped.
fn skin<T: Real>(case: &MoveCase, at: &[f64; 3], frame: usize, tri: &Triangle<f64>) -> f64 {
    let opts = RobustOptions::default();
    let u = T::unit_roundoff();
    let amax = |v: &[f64; 3]| (0..3).map(|i| (v[i] / case.radii[i]).abs()).fold(0.0, f64::max);
    let moved = case.frames.get(frame).map_or(0.0, |f| amax(&f.velocity).max(f.gravity.as_ref().map_or(0.0, amax)));
    let nearest = [&tri.a, &tri.b, &tri.c].iter().map(|v| v.amax()).fold(f64::INFINITY, f64::min);
    let s = nearest.max(moved).max(1.0);
    (opts.padding_ulps * u * s * tilt_factor::<T>(&opts, tri) + opts.position_ulps * u * amax(at)).min(opts.max_padding)
}

/// The factor the squeeze test ([`Skip::StartsSqueezed`]) widens the
/// padding skin by: an eighth, six `u s` of the skin's `48 u s`, for the
/// rounding of its `f64` distances.
pub const SQUEEZE_MARGIN: f64 = 1.125;

/// Whether the position `at` (world), at the start of frame `frame`, lies
/// within the padding skin (the padding the response would keep from each,
/// [`skin`]) of two triangles whose closest points, seen from the centre,
/// are in directions `d_1`, `d_2` with `d_1 . d_2 < -opposed |d_1| |d_2|`
/// (`opposed = 0` for the start, [`Skip::StartsSqueezed`]:
/// on opposite sides; [`SLOT_OPPOSED`] for a later frame), in eSpace and
/// `f64`. This is a classification of the input, not a
/// measurement: the distances here carry a few `u s` of `f64` rounding
/// against a skin of `48 u s`, so the skin is widened by
/// [`SQUEEZE_MARGIN`] and a start within rounding of its edge counts as
/// squeezed (fuzz finding F22: a sphere `0.9991` skins from one wall of a
/// zero-clearance slot and touching the other, classified free by the
/// rounding of `1 + skin`, was then squeezed for the response).
fn squeezed<T: Real>(case: &MoveCase, at: &[f64; 3], frame: usize, opposed: f64) -> bool {
    squeeze::<T>(case, at, frame, opposed).is_some()
}

/// [`squeezed`], and if so, the widened skin of the nearest of the
/// triangles within it: the depth up to which a frame that *ends* squeezed
/// in a slot is out of range, not failed (fuzz findings F32, F33). The slot
/// is then narrower than twice the padding, and the padding is what covers
/// the response's errors in the distances it keeps (`48 u s`, three times
/// the detection's touching tolerance, and the final rounding of the
/// position): with no room for it on both sides the response centres
/// between the walls and can promise nothing finer. A body deeper than the
/// skin of the triangle it is in was not stopped by anything the padding
/// accounts for, and fails, in a slot too. What this gives up: a detection
/// defect whose only symptom is a depth under the skin in such a slot
/// (fuzz finding F26 on the ninth session's code, `4.1e-15` against a skin
/// of `1.8e-14`) is left to the sweep checks and its regression test.
fn squeeze<T: Real>(case: &MoveCase, at: &[f64; 3], frame: usize, opposed: f64) -> Option<f64> {
    let centre = Vec3::<f64>::zeros();
    let near: Vec<(Vec3<f64>, f64, f64)> = espace_triangles(case, at)
        .filter_map(|tri| {
            let (q, _) = closest_point_on_triangle(&centre, &tri);
            let d = centre - q;
            let (n, skin) = (d.norm(), SQUEEZE_MARGIN * skin::<T>(case, at, frame, &tri));
            (n < 1.0 + skin).then_some((d, n, skin))
        })
        .collect();
    let opposite = near
        .iter()
        .enumerate()
        .any(|(i, (a, na, _))| near[i + 1..].iter().any(|(b, nb, _)| a.dot(b) < -opposed * na * nb));
    let nearest = near.iter().min_by(|x, y| x.1.total_cmp(&y.1))?;
    opposite.then_some(nearest.2)
}

/// How nearly opposite (the cosine of the angle between the directions to
/// their closest points, negated) two triangles within the padding skin of
/// a body at the start of a later frame must be for it to count as
/// squeezed: within about 5 degrees of opposite, the walls of a slot, or of
/// a slot whose wall ends beside the body (fuzz findings F28: a body that
/// slid into a zero-clearance slot whose walls are `2e-7` from parallel,
/// where the crease of the two walls' planes carries `u / 2e-7` of
/// direction error, ended `1e-14` inside one; F30: in `f32`, a body `2.6e-5`
/// from both walls of a slot, one of them met at its edge, `1` degree from
/// opposite, ended `0.2` ulp inside). Narrower than the start's test, which
/// counts any two triangles on opposite sides: a body resting in a groove
/// or a wedge of more than 5 degrees, within the padding of both walls,
/// can still back out of it, and stays checked. A classification, not a
/// bound.
pub const SLOT_OPPOSED: f64 = 0.996;

/// Rounds a case into `T` and checks its range and its start.
///
/// # Errors
/// The reason the case is out of range (see [`Skip`]).
pub fn prepare<T: Real>(case: &MoveCase) -> Result<Prepared<T>, Skip> {
    let all_in_range = case.triangles.iter().flatten().all(in_range)
        && in_range(&case.start)
        && case.frames.iter().all(|f| in_range(&f.velocity) && f.gravity.as_ref().is_none_or(in_range));
    if !all_in_range {
        return Err(Skip::OutOfRange);
    }
    let (lo, hi) = case.radii.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    if !(lo >= MIN_RADIUS && hi <= MAX_RADIUS && hi <= MAX_RADIUS_RATIO * lo) {
        return Err(Skip::BadBody);
    }
    if !padding_in_range::<T>(case) {
        return Err(Skip::PaddingCap);
    }
    let body = Ellipsoid::<T>::new(case.radii).map_err(|_| Skip::BadBody)?;
    let mut vertices = Vec::with_capacity(case.triangles.len() * 3);
    let mut indices = Vec::with_capacity(case.triangles.len());
    for t in &case.triangles {
        let i = vertices.len() as u32;
        vertices.extend_from_slice(t);
        indices.push([i, i + 1, i + 2]);
    }
    let mesh = TriangleMesh::new_skipping_invalid(vertices, indices).map_err(|_| Skip::EmptyMesh)?;
    let world = World::<T>::new(Arc::new(mesh)).expect("the mesh fits the backend");
    let start = vec3::<T>(case.start[0], case.start[1], case.start[2]);
    if !in_range_t(&start) {
        return Err(Skip::OutOfRange);
    }
    match penetration(&world, body.radii(), &start) {
        Some(p) if p > 0.0 => return Err(Skip::StartsInside),
        // `penetration` gives `None` when nothing lies within
        // `PENETRATION_REACH` of the body, but the skin may reach further
        // (fuzz finding F25).
        _ if squeezed::<T>(case, &case.start, 0, 0.0) => {
            return Err(Skip::StartsSqueezed);
        }
        _ => {}
    }
    Ok(Prepared { world, body, start })
}

/// The most collision checks the robust response may run in one frame of
/// `body`: `RobustOptions::max_iterations` per pass (one pass per non-zero
/// displacement, velocity then gravity, each slid in
/// [`sweepslide::respond::robust::parts`] parts, a pass each; one part
/// except for displacements of thousands of radii in `f32`; a pass too long
/// for any number of parts counts one, its move being refused). `src/respond/robust.rs`: every
/// sweep of `slide` counts one iteration and its loop runs at most
/// `max_iterations` times; the push-out sweeps (after a grazing contact,
/// and restoring the skin after a free move) and the depenetration at the
/// start of the move are not collision checks and are not counted.
#[must_use]
pub fn iteration_bound<T: Real>(body: &Ellipsoid<T>, velocity: &Vec3<T>, gravity: &Vec3<T>) -> u32 {
    let opts = RobustOptions::default();
    let passes: usize = [velocity, gravity]
        .iter()
        .filter(|v| v.iter().any(|x| *x != T::zero()))
        .map(|v| robust::parts(&body.to_espace(v), &opts).unwrap_or(1))
        .sum();
    passes as u32 * opts.max_iterations
}

fn f64s<T: Real>(v: &Vec3<T>) -> [f64; 3] {
    [v[0].to_f64(), v[1].to_f64(), v[2].to_f64()]
}

/// Plays the frames of `case` with `response` from its prepared start in
/// backend `T`, and returns the first failed frame (`None`: every frame
/// ended finite and outside the geometry; for the robust response also
/// within the iteration bound). Stops at the first failure, and for the
/// robust response before the first later frame that starts squeezed in
/// a slot (the body has moved into a slot narrower than twice the padding,
/// [`SLOT_OPPOSED`]: out of range from there on, as a squeezed start is),
/// or after a frame that ends squeezed in a slot no deeper than the skin
/// of the triangle it is in ([`squeeze`]; out of range for the same
/// reason).
#[must_use]
pub fn play<T: Real>(case: &MoveCase, prepared: &Prepared<T>, response: Response) -> Option<FrameFailure> {
    let options = MoveOptions::new(response);
    let mut pos = prepared.start.clone();
    for (k, frame) in case.frames.iter().enumerate() {
        let vel = vec3::<T>(frame.velocity[0], frame.velocity[1], frame.velocity[2]);
        let gravity = frame.gravity.map(|g| vec3::<T>(g[0], g[1], g[2]));
        let zero = Vec3::<T>::zeros();
        let bound = iteration_bound(&prepared.body, &vel, gravity.as_ref().unwrap_or(&zero));
        let fail = |failure: Failure, to: [f64; 3]| Some(FrameFailure { frame: k, from: f64s(&pos), to, failure });
        if response == Response::Robust && k > 0 && squeezed::<T>(case, &f64s(&pos), k, SLOT_OPPOSED) {
            return None;
        }
        let moved = match move_body(&prepared.world, &prepared.body, &pos, &vel, gravity.as_ref(), &options) {
            Ok(m) => m,
            Err(e) => return fail(Failure::Error(e.to_string()), [f64::NAN; 3]),
        };
        let to = f64s(&moved.position);
        if !moved.position.iter().all(Real::is_finite) {
            return fail(Failure::NonFinite, to);
        }
        if response == Response::Robust && moved.trace.iterations > bound {
            return fail(Failure::Iterations { used: moved.trace.iterations, bound }, to);
        }
        if let Some(p) = penetration(&prepared.world, prepared.body.radii(), &moved.position)
            && p > 0.0
        {
            let sphere = case.radii[0] == case.radii[1] && case.radii[1] == case.radii[2];
            let depth = if sphere { p / case.radii[0] } else { p };
            if response == Response::Robust
                && squeeze::<T>(case, &to, k, SLOT_OPPOSED).is_some_and(|skin| depth <= skin)
            {
                return None;
            }
            return fail(Failure::Penetration(p), to);
        }
        pos = moved.position;
    }
    None
}

/// Checks the robust-move invariants (module docs) on `case` in `T`.
///
/// # Errors
/// The failed frame, described with the case's values.
pub fn check_robust_moves<T: Real>(case: &MoveCase) -> Result<Result<(), Skip>, String> {
    let prepared = match prepare::<T>(case) {
        Ok(p) => p,
        Err(skip) => return Ok(Err(skip)),
    };
    match play(case, &prepared, Response::Robust) {
        None => Ok(Ok(())),
        Some(f) => Err(format!("{}: robust response failed: {f:?}\ncase: {case:?}", T::name())),
    }
}
