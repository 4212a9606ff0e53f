//! Runs a scene with one response in one precision and measures it.

use super::metrics::{drift, jitter, penetrated, penetration, snag_ratio, wobble};
use super::scenes::{Scene, Steering};
use crate::detect::Detection;
use crate::geom::{Ellipsoid, Feature, Vec3, to_f64, vec3};
use crate::real::{MpfrDyn, with_precision};
use crate::respond::{Move, MoveOptions, Response, StopReason, move_body};
use crate::world::World;
use crate::{Error, Mpfr, Real};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::sync::Arc;
use std::time::Instant;

/// Precision of the reference run that decision flips are counted against,
/// for runs at up to half of it ([`reference_bits`]).
pub const REFERENCE_BITS: u32 = 256;

/// The precision of the replay a run at `precision` is compared with:
/// [`REFERENCE_BITS`], or twice the run's bits beyond 128, at most
/// [`MAX_BITS`](crate::real::MAX_BITS) (so a run beyond half of that is
/// replayed less than twice as finely, and one at `MAX_BITS` at its own
/// precision: its flips are then zero by construction). The replay's
/// tolerances are the run's in absolute terms (`same_tolerances`), so
/// its own rounding must lie far below them: a review (session 29) found
/// runs at 600 bits, compared with `Mpfr<256>`, flipping 4 to 6
/// decisions where their 256-bit runs flipped none.
#[must_use]
pub fn reference_bits(precision: Precision) -> u32 {
    REFERENCE_BITS.max(precision.bits().saturating_mul(2)).min(crate::real::MAX_BITS)
}

/// A floating-point backend chosen at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Precision {
    /// IEEE single precision.
    F32,
    /// IEEE double precision.
    F64,
    /// MPFR with this many bits of significand (2 or more).
    Mpfr(u32),
}

impl Precision {
    /// Parses `f32`, `f64`, `mpfrBITS` or `mpfr<BITS>`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for anything else, and
    /// [`Error::PrecisionOutOfRange`] for a precision MPFR cannot use.
    pub fn parse(s: &str) -> Result<Self, Error> {
        let lower = s.trim().to_ascii_lowercase();
        match lower.as_str() {
            "f32" => return Ok(Precision::F32),
            "f64" => return Ok(Precision::F64),
            _ => {}
        }
        let digits = lower.strip_prefix("mpfr").map(|d| d.trim_start_matches('<').trim_end_matches('>'));
        let bits: u32 = digits.and_then(|d| d.parse().ok()).ok_or_else(|| Error::InvalidArgument {
            what: format!("precision `{s}`"),
            message: "expected f32, f64 or mpfr<BITS> (for example mpfr53)".into(),
        })?;
        with_precision(bits, || ())?;
        Ok(Precision::Mpfr(bits))
    }

    /// Significand bits.
    #[must_use]
    pub fn bits(self) -> u32 {
        match self {
            Precision::F32 => 24,
            Precision::F64 => 53,
            Precision::Mpfr(b) => b,
        }
    }
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Precision::F32 => write!(f, "f32"),
            Precision::F64 => write!(f, "f64"),
            Precision::Mpfr(b) => write!(f, "mpfr{b}"),
        }
    }
}

/// One run to make.
#[derive(Clone, Debug)]
pub struct RunConfig {
    /// The scene (its defaults, possibly overridden, drive the run).
    pub scene: Arc<Scene>,
    /// The response.
    pub response: Response,
    /// The detection (`None`: the response's own).
    pub detection: Option<Detection>,
    /// The backend.
    pub precision: Precision,
    /// Seed of the motion program.
    pub seed: u64,
}

/// The metrics of one run. Field names are the lab's public contract
/// (`sweepslide run --json`, `results.json`): fields are added, never
/// renamed. A NaN or infinite value (a faithful response's position) is
/// written as the string `"NaN"`, `"inf"` or `"-inf"`
/// ([`super::json_float`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// Scene name.
    pub scene: String,
    /// Response name.
    pub response: String,
    /// Detection name.
    pub detection: String,
    /// Precision name.
    pub precision: String,
    /// Seed of the motion program.
    pub seed: u64,
    /// Frames run.
    pub frames: usize,
    /// The motion program: `constant` or `random_walk` (a steered path
    /// bends, which the jitter metric also scores).
    pub motion: String,
    /// Largest exact penetration over the frames (0 if never inside).
    #[serde(with = "super::json_float::number")]
    pub max_penetration: f64,
    /// Frames that ended with the body inside the geometry.
    pub penetrating_frames: usize,
    /// First frame (0-based) that ended inside the geometry.
    pub first_penetrating_frame: Option<usize>,
    /// Penetrating frames that entered every triangle they end inside of
    /// from behind (its centre behind the triangle's plane at the start of
    /// the frame it entered it, moving along its front normal in one of
    /// that frame's passes, so that Fauerby's detection culled it;
    /// [`super::metrics::Penetrated::from_behind`]): for
    /// Fauerby's one-sided detection (and so the faithful responses) the
    /// semantics of a triangle solid from the front only, not a failure;
    /// for a two-sided detection, penetrations like any other.
    pub back_face_frames: usize,
    /// Largest exact penetration into a triangle not entered from behind
    /// over the frames (0 if none).
    #[serde(with = "super::json_float::number")]
    pub max_front_penetration: f64,
    /// Jitter over the last quarter of the frames (NaN, written `"NaN"` in
    /// JSON, for a run with NaN frames: not computable).
    #[serde(with = "super::json_float::number")]
    pub jitter: f64,
    /// Wobble over the same frames ([`super::metrics::wobble`]): how much
    /// the step went back and forth from frame to frame, which a sliding
    /// body's jitter barely shows (NaN, written `"NaN"`, where jitter is).
    #[serde(with = "super::json_float::number")]
    pub wobble: f64,
    /// Largest number of collision checks in one frame (the freeze metric).
    pub max_iterations: u32,
    /// Largest number of collision checks in one pass of a frame (the
    /// velocity's or the gravity's).
    pub max_pass_iterations: u32,
    /// Mean collision checks per frame.
    pub mean_iterations: f64,
    /// Frames that stopped at the response's cap (Fauerby's depth cap,
    /// Linahan's third plane, the robust iteration budget).
    pub capped_frames: usize,
    /// Frames whose position was NaN or infinite (the run stops at the
    /// first; the rest of the frames count too).
    pub nan_frames: usize,
    /// Frames the robust response began inside geometry it could not push
    /// the body out of ([`crate::respond::Trace::embedded`]: a slot
    /// narrower than the body, a closed cavity); the move went on from the
    /// best position the push-out measured. Zero for the faithful
    /// responses, which do not push out (zero in `runs.json` files written
    /// before the count existed).
    #[serde(default)]
    pub embedded_frames: usize,
    /// Frames whose contact decisions (hit or not, triangle, feature)
    /// differ from the same frame replayed from the same start at
    /// [`reference_bits`] (`Mpfr<256>` for runs up to 128 bits).
    pub decision_flips: usize,
    /// Frames whose sliding constraints differ from that replay: another
    /// number of contacts, or a contact normal more than 1e-3 rad away.
    /// Neither count contains the other: ties between coplanar triangles (a
    /// touch exactly on a shared edge) count in `decision_flips` but not
    /// here, while the same edge or vertex met at a position rounded
    /// elsewhere gives another normal, counted here only.
    pub plane_flips: usize,
    /// Position after the last frame.
    #[serde(with = "super::json_float::triple")]
    pub final_position: [f64; 3],
    /// Snag ratio where the scene has an ideal slide (1 = no snag).
    #[serde(with = "super::json_float::optional")]
    pub snag: Option<f64>,
    /// Drift where the scene has an ideal slide: how far, in radii, the
    /// net displacement leaves the ideal slide's line
    /// ([`super::metrics::drift`]; absent in `runs.json` files written
    /// before it was measured).
    #[serde(default, with = "super::json_float::optional")]
    pub drift: Option<f64>,
    /// Wall-clock nanoseconds per `move_body` call: the run's moves again,
    /// back to back from their recorded starts, three times over; the
    /// least of the three means (a single pass could be slowed a
    /// hundredfold by a cold cache or the other jobs of a loaded machine).
    pub ns_per_move: f64,
    /// Triangles of the scene degenerate once rounded into the run's
    /// precision ([`World::degenerate_in_backend`]): they collided as the
    /// segments or points they became, not as the triangles the scene gave
    /// (zero in `runs.json` files written before the count existed).
    #[serde(default)]
    pub degenerate_triangles: usize,
    /// The scene's world units per metre ([`Scene::units_per_meter`]),
    /// which sets the faithful responses' `eps` (1 in `runs.json` files
    /// written before it was recorded, as every run then used).
    #[serde(default = "one")]
    pub units_per_meter: f64,
    /// The body's radii in world units: penetration, clearance and the
    /// final position are in world units for a sphere, and penetration in
    /// radii (eSpace) for an ellipsoid; these convert between them (absent
    /// in `runs.json` files written before they were recorded).
    /// Always finite (a body's radii are checked), so written as plain
    /// numbers.
    #[serde(default)]
    pub radii: Option<[f64; 3]>,
}

/// The default of [`RunResult::units_per_meter`].
fn one() -> f64 {
    1.0
}

impl RunResult {
    /// Whether the run's detection is one-sided (Fauerby's: it culls the
    /// triangles whose front does not face the motion).
    #[must_use]
    pub fn one_sided(&self) -> bool {
        self.detection == Detection::Fauerby.name()
    }

    /// The penetrating frames and the deepest penetration that count
    /// against the run: for a one-sided detection those not entered from
    /// behind (`back_face_frames` are its semantics), for a two-sided one
    /// all of them.
    #[must_use]
    pub fn counted_penetration(&self) -> (usize, f64) {
        if self.one_sided() {
            (self.penetrating_frames - self.back_face_frames, self.max_front_penetration)
        } else {
            (self.penetrating_frames, self.max_penetration)
        }
    }
}

/// Per-frame values, kept for plots and `--trace`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameRecord {
    /// Frame index.
    pub frame: usize,
    /// Position after the frame.
    #[serde(with = "super::json_float::triple")]
    pub position: [f64; 3],
    /// Exact penetration after the frame (`None`: nothing within reach).
    #[serde(with = "super::json_float::optional")]
    pub penetration: Option<f64>,
    /// Whether the frame ended inside only triangles it entered from
    /// behind (see [`RunResult::back_face_frames`]).
    pub from_behind: bool,
    /// Collision checks this frame.
    pub iterations: u32,
    /// Why the frame's last pass stopped.
    pub stop: StopReason,
    /// Whether the decisions differed from the replay ([`reference_bits`]).
    pub flip: bool,
    /// Whether the robust response could not push the body out of the
    /// geometry it began the frame in ([`RunResult::embedded_frames`]).
    #[serde(default)]
    pub embedded: bool,
}

/// A run's metrics and its frames.
#[derive(Clone, Debug)]
pub struct RunOutput {
    /// The metrics.
    pub result: RunResult,
    /// One record per frame.
    pub frames: Vec<FrameRecord>,
    /// The triangles degenerate in the run's precision
    /// ([`World::degenerate_in_backend`]; [`RunResult::degenerate_triangles`]
    /// counts them), for a user to be told which.
    pub degenerate: Vec<u32>,
}

/// The contact decisions of a move: triangle and feature of each contact.
fn decisions<T: Real>(m: &Move<T>) -> Vec<(u32, Feature)> {
    m.trace.contacts.iter().map(|c| (c.hit.triangle, c.hit.feature)).collect()
}

/// Whether two moves met different sliding constraints: another number of
/// contacts, or normals more than `1e-3` rad apart (compared in `f64`).
fn planes_differ<T: Real, U: Real>(a: &Move<T>, b: &Move<U>) -> bool {
    a.trace.contacts.len() != b.trace.contacts.len()
        || a.trace.contacts.iter().zip(&b.trace.contacts).any(|(x, y)| {
            let (n, m) = (to_f64(&x.plane_normal), to_f64(&y.plane_normal));
            !((n - m).norm() <= 1e-3)
        })
}

/// `v` in the replay's backend `R`, at its precision (call within
/// `R::with_bits` for [`MpfrDyn`]).
fn to_reference<T: Real, R: Real>(v: &Vec3<T>) -> Vec3<R> {
    v.map(|x| R::from_rug(&x.to_rug()))
}

fn is_capped(stop: StopReason) -> bool {
    matches!(stop, StopReason::DepthCap | StopReason::ThirdPlane | StopReason::IterationCap)
}

/// `opts` for the replay in `R` at `bits`: every tolerance counted in units of
/// the unit roundoff (the robust detection's touching and approach tolerances, the robust
/// response's padding, admissibility and parallel-plane tolerances, and the
/// final rounding's bound, which widens the resting band far from the
/// origin) scaled
/// from `u` of `T` to `u` of the reference, so the replay decides with the
/// same absolute tolerances as the run, only without its rounding. (With
/// its own, far smaller tolerances, a body the run holds in the resting
/// band would be, for the replay, a body a hair away that must sweep to
/// the contact first: a flip that no rounding caused.)
fn same_tolerances<T: Real, R: Real>(opts: &MoveOptions, bits: u32) -> Result<MoveOptions, Error> {
    let k = T::unit_roundoff() / R::with_bits(bits, R::unit_roundoff)?;
    let mut o = opts.clone();
    o.detect.touch_ulps *= k;
    o.detect.approach_ulps *= k;
    let r = &mut o.robust;
    for x in
        [&mut r.padding_ulps, &mut r.position_ulps, &mut r.parallel_ulps, &mut r.feasible_ulps, &mut r.rounding_ulps]
    {
        *x *= k;
    }
    Ok(o)
}

/// Runs `cfg` in backend `T`, replayed in `R` at `ref_bits` bits.
fn run_in<T: Real, R: Real>(cfg: &RunConfig, ref_bits: u32) -> Result<RunOutput, Error> {
    let scene = &*cfg.scene;
    let frames = scene.frames;
    if !(1..=MAX_FRAMES).contains(&frames) {
        return Err(Error::InvalidArgument {
            what: "frames".into(),
            message: format!("a run has 1 to {MAX_FRAMES} frames, got {frames}"),
        });
    }
    // A finite input that `T` cannot hold is named as such (as a
    // non-finite position or push it was reported as given infinite: a
    // review, session 36).
    let scripted = match &scene.motion {
        super::scenes::Motion::Scripted { velocities } => velocities.as_slice(),
        _ => &[],
    };
    let inputs = [("start", &scene.start), ("gravity", &scene.gravity), ("velocity", &scene.velocity)];
    let inputs = inputs.into_iter().chain(scripted.iter().map(|v| ("a scripted velocity", v)));
    for (what, v) in inputs {
        if let Some(x) = v.iter().find(|x| x.is_finite() && !T::from_f64(**x).is_finite()) {
            return Err(Error::InvalidArgument {
                what: what.into(),
                message: format!("{x:e} rounds to infinity in {}", T::name()),
            });
        }
    }
    let world = World::<T>::new(scene.mesh.clone())?;
    let body = Ellipsoid::<T>::new(scene.radii)?;
    let (reference, ref_body) = R::with_bits(ref_bits, || -> Result<_, Error> {
        Ok((world.converted::<R>()?, Ellipsoid::from_radii(to_reference::<T, R>(body.radii()))?))
    })??;
    let mut opts = MoveOptions::new(cfg.response);
    opts.detection = cfg.detection;
    opts.fauerby.units_per_meter = scene.units_per_meter;
    opts.linahan.very_close_distance = opts.fauerby.very_close_distance();
    opts.validate()?;
    let eps = opts.linahan.very_close_distance;
    let rounded = T::c(eps);
    if cfg.response != Response::Robust && (rounded.is_zero() || !rounded.is_finite()) {
        return Err(Error::InvalidArgument {
            what: format!("units per metre {:e}", scene.units_per_meter),
            message: format!(
                "the faithful responses' eps, 5e-5 times it ({eps:.3e} eSpace units), rounds to {} in {}",
                if rounded.is_zero() { "zero" } else { "infinity" },
                T::name()
            ),
        });
    }
    let ref_opts = same_tolerances::<T, R>(&opts, ref_bits)?;
    let gravity: Vec3<T> = vec3(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let has_gravity = scene.gravity != [0.0; 3];
    // The first push (a scripted case may start at rest and move later).
    let first_push = std::iter::once(&scene.velocity).chain(scripted).find(|v| **v != [0.0; 3]);
    if first_push.is_none() && !has_gravity {
        return Err(Error::ZeroVelocity);
    }
    // A motion given that this precision rounds to none would run as a
    // body at rest.
    let vanishes = |v: &[f64; 3]| *v != [0.0; 3] && vec3::<T>(v[0], v[1], v[2]).iter().all(|x| x.is_zero());
    let motions = std::iter::once(("velocity", &scene.velocity)).chain(scripted.iter().map(|v| ("velocity", v)));
    if let Some((what, v)) = motions.chain([("gravity", &scene.gravity)]).find(|(_, v)| vanishes(v)) {
        return Err(Error::InvalidArgument {
            what: what.into(),
            message: format!("{v:?} rounds to zero in {}", T::name()),
        });
    }
    let mut steering = Steering::new(scene, cfg.seed);
    let start: Vec3<T> = vec3(scene.start[0], scene.start[1], scene.start[2]);
    let mut p = start.clone();
    let mut positions = vec![p.clone()];
    let mut records = Vec::with_capacity(frames);
    let (mut iterations_sum, mut max_iterations, mut max_pass) = (0u64, 0u32, 0u32);
    // Each frame's displacement, for the timing after the run.
    let mut velocities = Vec::with_capacity(frames);
    let (mut penetrating, mut first_pen, mut max_pen) = (0usize, None, 0.0f64);
    let (mut back_face, mut max_front) = (0usize, 0.0f64);
    // The triangles the body ended the last frame inside of, and whether it
    // entered each from behind.
    let mut inside: Vec<(u32, bool)> = Vec::new();
    let (mut capped, mut flips, mut plane_flips, mut nan_frames) = (0usize, 0usize, 0usize, 0usize);
    let mut embedded = 0usize;
    let mut moves = 0usize;
    for k in 0..frames {
        let v = steering.next(scene);
        let vel: Vec3<T> = vec3(v[0], v[1], v[2]);
        let grav = has_gravity.then_some(&gravity);
        let m = move_body(&world, &body, &p, &vel, grav, &opts)?;
        moves += 1;
        let finite = m.position.iter().all(Real::is_finite);
        let replay = R::with_bits(ref_bits, || {
            move_body(
                &reference,
                &ref_body,
                &to_reference(&p),
                &to_reference(&vel),
                has_gravity.then(|| to_reference(&gravity)).as_ref(),
                &ref_opts,
            )
        })??;
        let flip = decisions(&m) != decisions(&replay);
        flips += usize::from(flip);
        plane_flips += usize::from(planes_differ(&m, &replay));
        iterations_sum += u64::from(m.trace.iterations);
        max_iterations = max_iterations.max(m.trace.iterations);
        max_pass = max_pass.max(m.trace.pass_iterations);
        capped += usize::from(is_capped(m.trace.stop));
        embedded += usize::from(m.trace.embedded);
        let pen = if finite { penetration(&world, body.radii(), &m.position) } else { None };
        let mut from_behind = false;
        if let Some(d) = pen.filter(|d| *d > 0.0) {
            penetrating += 1;
            first_pen.get_or_insert(k);
            max_pen = max_pen.max(d);
            // Each triangle keeps the side the body entered it from while
            // the body stays inside it.
            let passes: Vec<&Vec3<T>> = std::iter::once(&vel).chain(grav).collect();
            let now = penetrated(&world, body.radii(), &p, &m.position, &passes);
            let entered: Vec<(u32, bool)> = now
                .iter()
                .map(|t| {
                    let kept = inside.iter().find(|(i, _)| *i == t.triangle).map(|(_, behind)| *behind);
                    (t.triangle, kept.unwrap_or(t.from_behind))
                })
                .collect();
            let front = now.iter().zip(&entered).filter(|(_, (_, behind))| !behind).map(|(t, _)| t.depth);
            // (`now` cannot be empty when `d > 0`; if it were, the frame
            // would count as a front penetration, not be hidden.)
            match front.reduce(f64::max).or(now.is_empty().then_some(d)) {
                None => {
                    from_behind = true;
                    back_face += 1;
                }
                Some(f) => max_front = max_front.max(f),
            }
            inside = entered;
        } else {
            inside.clear();
        }
        records.push(FrameRecord {
            frame: k,
            position: [0, 1, 2].map(|i| m.position[i].to_f64()),
            penetration: pen,
            from_behind,
            iterations: m.trace.iterations,
            stop: m.trace.stop,
            flip,
            embedded: m.trace.embedded,
        });
        p = m.position;
        positions.push(p.clone());
        velocities.push(vel);
        if !finite {
            nan_frames = frames - k;
            break;
        }
    }
    // Timed apart from the run: every frame's move again from its recorded
    // start, back to back, so that the time is the move's own. Timed inside
    // the loop, each move came after the `Mpfr<256>` replay and the
    // metrics of the frame before, which had evicted its code and data and
    // retrained the branch predictors: the robust response on the two
    // triangles of `floor` took about 1,250 ns per move there in `f32`
    // and Fauerby's 570 ns, against about 510 and 310 ns here.
    // The least of three passes: one pass alone was seen 100 times slower
    // than the same run's next seed on a loaded machine (a review, session
    // 39).
    let grav = has_gravity.then_some(&gravity);
    let mut ns = u128::MAX;
    for _ in 0..3 {
        let clock = Instant::now();
        for (start, vel) in positions.iter().zip(&velocities) {
            std::hint::black_box(move_body(&world, &body, start, vel, grav, &opts)?);
        }
        ns = ns.min(clock.elapsed().as_nanos());
    }
    let speed = {
        let v = first_push.unwrap_or(&scene.gravity);
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    };
    let degenerate = world.degenerate_in_backend();
    let result = RunResult {
        scene: scene.name.clone(),
        response: cfg.response.name().to_string(),
        detection: opts.effective_detection().name().to_string(),
        precision: cfg.precision.to_string(),
        seed: cfg.seed,
        frames,
        motion: match scene.motion {
            super::scenes::Motion::Constant => "constant".to_string(),
            super::scenes::Motion::RandomWalk { .. } => "random_walk".to_string(),
            super::scenes::Motion::Scripted { .. } => "scripted".to_string(),
        },
        max_penetration: max_pen,
        penetrating_frames: penetrating,
        first_penetrating_frame: first_pen,
        back_face_frames: back_face,
        max_front_penetration: max_front,
        jitter: jitter(&positions, speed),
        wobble: wobble(&positions, speed),
        max_iterations,
        max_pass_iterations: max_pass,
        mean_iterations: iterations_sum as f64 / moves.max(1) as f64,
        capped_frames: capped,
        nan_frames,
        embedded_frames: embedded,
        decision_flips: flips,
        plane_flips,
        final_position: [0, 1, 2].map(|i| p[i].to_f64()),
        snag: scene.ideal.and_then(|ideal| snag_ratio(&start, &p, ideal, frames)),
        drift: scene.ideal.and_then(|ideal| drift(&positions, ideal, scene.radii)),
        ns_per_move: ns as f64 / moves.max(1) as f64,
        degenerate_triangles: degenerate.len(),
        units_per_meter: scene.units_per_meter,
        radii: Some(scene.radii),
    };
    Ok(RunOutput { result, frames: records, degenerate })
}

/// The most frames one run plays (every frame's position and record is
/// kept, and replayed in `Mpfr<256>` or finer: a million frames take minutes and
/// about 100 MB).
pub const MAX_FRAMES: usize = 1_000_000;

/// Runs one configuration.
///
/// # Errors
/// Bad scene parameters ([`Error::InvalidRadius`], [`Error::ZeroVelocity`]
/// when no frame pushes and there is no gravity, [`Error::NonFinite`],
/// [`Error::InvalidArgument`] for a number of frames outside
/// `1..=`[`MAX_FRAMES`]) or an unusable precision.
pub fn run(cfg: &RunConfig) -> Result<RunOutput, Error> {
    let reference = reference_bits(cfg.precision);
    match cfg.precision {
        Precision::F32 => run_in::<f32, Mpfr<REFERENCE_BITS>>(cfg, reference),
        Precision::F64 => run_in::<f64, Mpfr<REFERENCE_BITS>>(cfg, reference),
        Precision::Mpfr(bits) if reference == REFERENCE_BITS => {
            with_precision(bits, || run_in::<MpfrDyn, Mpfr<REFERENCE_BITS>>(cfg, reference))?
        }
        Precision::Mpfr(bits) => with_precision(bits, || run_in::<MpfrDyn, MpfrDyn>(cfg, reference))?,
    }
}

/// Runs every configuration on `jobs` threads (0: one per core; never
/// more than there are configurations). The
/// results come back in the order of `configs` and do not depend on the
/// number of threads (each run is sequential and self-contained); only
/// `ns_per_move` varies between runs. `done` is called after each run.
///
/// # Errors
/// [`Error::InvalidArgument`] if the thread pool cannot be created.
pub fn run_all(
    configs: &[RunConfig],
    jobs: usize,
    done: &(dyn Fn(&RunConfig) + Sync),
) -> Result<Vec<Result<RunOutput, Error>>, Error> {
    // More threads than runs would only cost their start-up.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(if jobs == 0 { 0 } else { jobs.min(configs.len().max(1)) })
        .build()
        .map_err(|e| Error::InvalidArgument { what: "jobs".into(), message: e.to_string() })?;
    Ok(pool.install(|| {
        configs
            .par_iter()
            .map(|c| {
                let out = run(c);
                done(c);
                out
            })
            .collect()
    }))
}
