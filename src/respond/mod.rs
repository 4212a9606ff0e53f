//! Collision response: where the body ends up this frame.
//!
//! One entry point, [`move_body`], runs any of three responses over any
//! detection variant and any [`Real`] backend:
//!
//! * [`Response::Fauerby`]: Fauerby's recursive `collideWithWorld` (the
//!   paper's Table I), faithful, defects included ([`fauerby`]).
//! * [`Response::Linahan`]: Linahan's iterative `sphere_sweep` (Table II),
//!   faithful ([`linahan`]).
//! * [`Response::Robust`]: our successor ([`robust`]).
//!
//! Defaults follow the papers: Fauerby's and Linahan's responses run on
//! Fauerby's detection, the robust response on the robust detection; any
//! combination can be chosen with [`MoveOptions::detection`].

mod batch;
pub mod fauerby;
pub mod linahan;
pub mod robust;

pub use batch::{BodyMove, move_bodies};
pub use fauerby::FauerbyOptions;
pub use linahan::LinahanOptions;
pub use robust::RobustOptions;

use crate::detect::{
    DetectOptions, Detection, Hit, Neighbourhood, Proximity, REACH_MARGIN, Reach, check_finite, check_in_radii,
    earliest_hit, espace_magnitude,
};
use crate::error::{count, not_negative, out_of_range, positive};
use crate::geom::{Ellipsoid, Vec3, norm};
use crate::world::World;
use crate::{Error, Real};
use smallvec::SmallVec;

/// Which collision response to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "lab", serde(rename_all = "lowercase"))]
pub enum Response {
    /// Fauerby's recursive response (Table I), faithful to the original,
    /// defects included: a baseline for study, not for a game. Its
    /// one-sided detection lets a body into a triangle from behind or over
    /// a culled edge, it jitters in corners and freezes in wedges
    /// (`docs/findings.md`).
    Fauerby,
    /// Linahan's iterative response (Table II), as published: a baseline
    /// for study. On Fauerby's detection it still enters triangles in
    /// `f32`, and its crease of two parallel planes is NaN
    /// (`docs/findings.md`).
    Linahan,
    /// The robust response of this crate: the one to use.
    Robust,
}

impl Response {
    /// All three, in the order reports list them.
    pub const ALL: [Response; 3] = [Response::Fauerby, Response::Linahan, Response::Robust];

    /// The detection the response's paper used: Fauerby's for Fauerby and
    /// Linahan (who kept it unchanged), the robust one for Robust.
    #[must_use]
    pub fn default_detection(self) -> Detection {
        match self {
            Response::Fauerby | Response::Linahan => Detection::Fauerby,
            Response::Robust => Detection::Robust,
        }
    }

    /// The lowercase name used on the command line and in reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Response::Fauerby => "fauerby",
            Response::Linahan => "linahan",
            Response::Robust => "robust",
        }
    }
}

/// Everything that tunes a move. Distances are in eSpace units (the body's
/// radii are 1) unless a field says otherwise.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
pub struct MoveOptions {
    /// The response to run.
    pub response: Response,
    /// The detection to run it on; `None` for the response's own
    /// ([`Response::default_detection`]).
    pub detection: Option<Detection>,
    /// Options of the robust detection.
    pub detect: DetectOptions,
    /// Fauerby's constants.
    pub fauerby: FauerbyOptions,
    /// Linahan's constants.
    pub linahan: LinahanOptions,
    /// The robust response's tolerances.
    pub robust: RobustOptions,
}

impl MoveOptions {
    /// Default options for `response`.
    #[must_use]
    pub fn new(response: Response) -> Self {
        MoveOptions {
            response,
            detection: None,
            detect: DetectOptions::default(),
            fauerby: FauerbyOptions::default(),
            linahan: LinahanOptions::default(),
            robust: RobustOptions::default(),
        }
    }

    /// The detection that will run.
    #[must_use]
    pub fn effective_detection(&self) -> Detection {
        self.detection.unwrap_or_else(|| self.response.default_detection())
    }

    /// Checks every field against its documented range ([`move_body`] does
    /// this first): tolerances finite and not negative, `max_padding` in
    /// `(0, 1)`, `free_tilt` and Fauerby's `units_per_meter` positive, and
    /// the counts (`max_iterations` at least 1) at most [`MAX_ROUNDS`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), Error> {
        let r = &self.robust;
        self.detect.validate()?;
        not_negative("robust.padding_ulps", r.padding_ulps)?;
        not_negative("robust.position_ulps", r.position_ulps)?;
        not_negative("robust.parallel_ulps", r.parallel_ulps)?;
        not_negative("robust.feasible_ulps", r.feasible_ulps)?;
        not_negative("robust.rounding_ulps", r.rounding_ulps)?;
        not_negative("linahan.very_close_distance", self.linahan.very_close_distance)?;
        positive("robust.free_tilt", r.free_tilt)?;
        positive("fauerby.units_per_meter", self.fauerby.units_per_meter)?;
        if !(r.max_padding > 0.0 && r.max_padding < 1.0) {
            return Err(out_of_range("robust.max_padding", format!("must lie in (0, 1) radii, got {}", r.max_padding)));
        }
        count("robust.max_iterations", r.max_iterations, 1)?;
        count("robust.depenetration_rounds", r.depenetration_rounds, 0)?;
        count("fauerby.max_depth", self.fauerby.max_depth, 1)
    }
}

/// The most sweeps, push-out rounds or recursion levels any option may ask
/// for (the defaults are 5 to 8): a bound on one move's work.
pub const MAX_ROUNDS: u32 = 1024;

/// Why a pass of the response stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "lab", serde(rename_all = "snake_case"))]
pub enum StopReason {
    /// The last sweep hit nothing: the remaining motion was completed.
    Free,
    /// The remaining motion became too short to continue (Fauerby's
    /// `veryCloseDistance` test).
    Exhausted,
    /// Fauerby's recursion depth cap was reached.
    DepthCap,
    /// Linahan's third plane: motion stops at the near point.
    ThirdPlane,
    /// The robust solve left no admissible motion (a corner or dead end).
    Blocked,
    /// The robust response used its whole sweep budget.
    IterationCap,
    /// Nothing to do: zero velocity and gravity, or, for the robust
    /// response, ones so short that their squared lengths in radii
    /// underflow `T` (below about `3.7e-23` radii in `f32`, `2.2e-162` in
    /// `f64`), which it cannot measure.
    ZeroVelocity,
}

/// One contact met during a move.
///
/// In eSpace (coordinates divided by the body's radii), as the response
/// worked: the hit's `point` relative to the move's start position for the
/// robust response (to the world origin for the faithful ones), so that in
/// world space it is `start + body.from_espace(&point)` (or
/// `body.from_espace(&point)`); its `normal` in world space is
/// [`Ellipsoid::normal_from_espace`]. For a sphere the normals agree; for a
/// flat ellipsoid they do not (a slope test on the eSpace normal would be
/// wrong). A world-space sweep, a ground probe for instance, is
/// [`crate::detect::sweep_world`].
#[derive(Clone, Debug, PartialEq)]
pub struct Contact<T: Real> {
    /// The detection's hit, in the eSpace coordinates the response used.
    pub hit: Hit<T>,
    /// The sliding-plane normal the response used (eSpace, unit or NaN for
    /// the faithful responses where their arithmetic produces NaN).
    pub plane_normal: Vec3<T>,
}

/// What happened during a move.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace<T: Real> {
    /// Collision checks run (calls to the world query), all passes together.
    pub iterations: u32,
    /// The most collision checks of one pass (the velocity's or the
    /// gravity's; of one part, where the robust response slides a long
    /// pass in parts, [`robust::parts`]).
    pub pass_iterations: u32,
    /// The contacts met, in order (the first four stored inline: a move
    /// that meets no more allocates nothing).
    pub contacts: SmallVec<[Contact<T>; 4]>,
    /// Why the last pass (the last part of a pass slid in parts,
    /// [`robust::parts`]) stopped.
    pub stop: StopReason,
    /// The total length (eSpace) of the pushes with which the robust
    /// response moved the body out of geometry it started embedded in
    /// (zero when it did not), the skin's pushes right after them
    /// included; the body's net displacement can be shorter.
    pub depenetration: f64,
    /// Whether the robust response could not push a body that started
    /// embedded out: after its push-out some triangle's computed distance
    /// was still below 1 (a slot narrower than the body, a closed cavity).
    /// The move then went on from the best position the push-out measured,
    /// never deeper than the start. Always `false` for the faithful
    /// responses, which do not push out.
    pub embedded: bool,
}

/// The outcome of [`move_body`].
#[derive(Clone, Debug, PartialEq)]
pub struct Move<T: Real> {
    /// Where the body's centre ends up (world space).
    pub position: Vec3<T>,
    /// How it got there.
    pub trace: Trace<T>,
}

/// `v / |v|` without a guard, as Fauerby's and Linahan's code normalise: a
/// zero vector gives NaN, which the faithful responses must keep.
pub(crate) fn unguarded_normalize<T: Real>(v: &Vec3<T>) -> Vec3<T> {
    v / norm(v)
}

/// One frame's shared state: the candidate triangles in eSpace and the
/// trace being written.
pub(crate) struct Frame<'w, T: Real> {
    pub world: &'w World<T>,
    pub body: &'w Ellipsoid<T>,
    pub detection: Detection,
    pub detect: &'w DetectOptions,
    pub hood: Neighbourhood<T>,
    pub trace: Trace<T>,
    /// This frame's displacements (velocity, gravity), world space.
    pub moves: [Vec3<T>; 2],
    /// The largest eSpace coordinate of the frame's start, for the robust
    /// padding (computed once per frame).
    pub start_magnitude: f64,
    /// The robust response's resting contacts at the current position, by
    /// their position in `hood`, found at the end of each pass for the next.
    pub resting: SmallVec<[usize; 16]>,
    /// How far beyond the radii (eSpace) the frame's gathers reach around
    /// the body's path: [`crate::detect::REACH_MARGIN`], or, for the robust
    /// response where the final rounding can undo the skin, as far as its
    /// scans and pushes then look (`robust::skin_margin`).
    pub margin: f64,
    /// How much wider than `2 pad` the robust response's resting band is:
    /// twice the final rounding's bound where that rounding can exceed
    /// `pad / 2` (`robust::final_rounding`), else zero.
    pub band: T,
    /// The robust response's planes met in the current pass (a buffer kept
    /// across passes).
    pub planes: SmallVec<[Vec3<T>; 8]>,
    /// The triangles whose contacts gave [`Frame::planes`], in the same
    /// order (see `robust::slide`).
    pub met: SmallVec<[u32; 8]>,
    /// The robust response's resting contacts not met yet at the start of
    /// a pass (triangle index and proximity; a buffer kept across passes).
    pub seeds: SmallVec<[(u32, Proximity<T>); 8]>,
}

impl<T: Real> Frame<'_, T> {
    /// Runs the collision query: the earliest hit of the unit sphere at
    /// `base` moving by `vel`, counted as one iteration.
    pub fn check_collision(&mut self, base: &Vec3<T>, vel: &Vec3<T>) -> Option<Hit<T>> {
        self.trace.iterations += 1;
        self.hood.earliest_hit(self.detection, base, vel, self.detect)
    }

    /// [`Frame::check_collision`] without the triangles in `skip` (by
    /// index).
    pub fn check_collision_skipping(&mut self, base: &Vec3<T>, vel: &Vec3<T>, skip: &[u32]) -> Option<Hit<T>> {
        if skip.is_empty() {
            return self.check_collision(base, vel);
        }
        self.trace.iterations += 1;
        let kept = self.hood.triangles.iter().filter(|c| !skip.contains(&c.index));
        earliest_hit(self.detection, kept, base, vel, self.detect)
    }

    /// Gathers the candidates again for eSpace position `p` (after a
    /// push-out moved the body beyond the gathered box's margin): all
    /// within the frame's reach of `p`, found as those within that reach
    /// plus `|p|` of the frame's start. The start is the neighbourhood's
    /// origin, held exactly, where `p` in world coordinates would be
    /// rounded, far from the origin by more than the reach's margin (a
    /// review).
    ///
    /// # Errors
    /// As [`Neighbourhood::gather`].
    pub fn regather(&mut self, p: &Vec3<T>) -> Result<(), Error> {
        let pushed = self.body.from_espace(p);
        let moves = [&self.moves[0], &self.moves[1], &pushed];
        let reach = Reach::of_frame_within(self.body, &self.hood.origin, &moves, self.margin);
        self.hood.gather(self.world, self.body, &reach)
    }

    /// Records a contact.
    pub fn record(&mut self, hit: Hit<T>, plane_normal: Vec3<T>) {
        self.trace.contacts.push(Contact { hit, plane_normal });
    }
}

/// [`Error::InvalidArgument`] if a coordinate of `v` carries a precision
/// other than the thread's ([`Real::own_bits`]: an [`crate::MpfrDyn`] value
/// made under another [`crate::real::with_precision`]); arithmetic would
/// round at the mixed operands' precisions and the tolerances would not
/// match them.
fn check_precision<T: Real>(what: &str, v: &Vec3<T>) -> Result<(), Error> {
    match v.iter().find_map(|x| x.own_bits().filter(|b| *b != T::bits())) {
        None => Ok(()),
        Some(bits) => Err(Error::InvalidArgument {
            what: what.into(),
            message: format!(
                "holds {bits}-bit values, but this thread computes at {} bits (with_precision): values of \
                 different precisions do not mix",
                T::bits()
            ),
        }),
    }
}

/// One pass of the response from eSpace `p` by eSpace `w`; notes its
/// collision checks in [`Trace::pass_iterations`].
fn pass<T: Real>(frame: &mut Frame<'_, T>, p: Vec3<T>, w: Vec3<T>, options: &MoveOptions) -> Vec3<T> {
    let before = frame.trace.iterations;
    let p = match options.response {
        Response::Fauerby => fauerby::collide_and_slide(frame, p, w, &options.fauerby),
        Response::Linahan => linahan::sphere_sweep(frame, p, w, &options.linahan),
        Response::Robust => robust::slide(frame, p, w, &options.robust),
    };
    frame.trace.pass_iterations = frame.trace.pass_iterations.max(frame.trace.iterations - before);
    p
}

/// Moves `body` from `position` by `velocity` (world space, this frame's
/// displacement) through `world`, then, if given, by `gravity` in a second
/// pass (Fauerby's scheme, used by all three responses).
///
/// Zero velocity and gravity are valid (a body at rest): the position is
/// returned unchanged except that the robust response still pushes a body
/// that starts embedded out of the geometry, and one closer to a triangle
/// than half its padding out to its skin where that push restores it (a
/// body left there by rounding, or placed there). The robust response
/// takes a velocity or gravity whose squared length in radii underflows
/// `T` (shorter than about `3.7e-23` radii in `f32`, `2.2e-162` in `f64`)
/// as zero: it cannot measure it (its trace's stop says
/// [`StopReason::ZeroVelocity`] where neither pass is left).
///
/// # Errors
/// [`Error::InvalidArgument`] for options out of range
/// ([`MoveOptions::validate`], and `robust.rounding_ulps` or `feasible_ulps` beyond `1 / (2u)`
/// in `T`); [`Error::NonFinite`] if the position,
/// velocity or gravity has a NaN or
/// infinite coordinate; [`Error::InvalidArgument`] if, measured in the
/// body's radii (eSpace), the displacements' length is not representable
/// in `T` (its square overflows: beyond about `1.8e19` radii in `f32`,
/// `1.3e154` in `f64`) or a coordinate of the position is not (beyond
/// `T`'s largest value; the robust response works relative to the start,
/// so a position that large is usable), if for the robust response the
/// velocity or the gravity is longer than [`robust::parts`] can slide
/// (beyond about `1.8e6` radii along an axis in `f32`, `9.6e14` in `f64`,
/// in one move), if a triangle within reach is too
/// long for `T` ([`Neighbourhood::gather`]), or if an [`crate::MpfrDyn`]
/// input (position, velocity, gravity, the body's radii or the world's
/// vertices) was made at another precision than the thread's
/// ([`Real::own_bits`]). Never panics; the faithful responses may return a
/// NaN position where their arithmetic does (that is what the lab counts).
pub fn move_body<T: Real>(
    world: &World<T>,
    body: &Ellipsoid<T>,
    position: &Vec3<T>,
    velocity: &Vec3<T>,
    gravity: Option<&Vec3<T>>,
    options: &MoveOptions,
) -> Result<Move<T>, Error> {
    options.validate()?;
    robust::check_rounding::<T>(&options.robust)?;
    check_finite("position", position)?;
    check_finite("velocity", velocity)?;
    let zero = Vec3::zeros();
    let gravity = gravity.unwrap_or(&zero);
    check_finite("gravity", gravity)?;
    let vertex = world.corners(0)[0];
    for (what, v) in [("position", position), ("velocity", velocity), ("gravity", gravity)]
        .into_iter()
        .chain([("body", body.radii()), ("world", vertex)])
    {
        check_precision(what, v)?;
    }
    let origin = match options.response {
        Response::Robust => position.clone(),
        Response::Fauerby | Response::Linahan => Vec3::zeros(),
    };
    let mut reach = Reach::of_frame(body, position, &[velocity, gravity]);
    let trace = Trace {
        iterations: 0,
        pass_iterations: 0,
        contacts: SmallVec::new(),
        stop: StopReason::ZeroVelocity,
        depenetration: 0.0,
        embedded: false,
    };
    let moves = [velocity.clone(), gravity.clone()];
    let start_magnitude = espace_magnitude(body, position);
    check_in_radii(start_magnitude, &reach)?;
    // Where the final rounding can undo the robust response's skin, its
    // resting band is twice the rounding's bound wider and the gathers
    // reach as far as the scans and the pushes that restore the skin look.
    let travel = reach.radius.to_f64();
    let rounding = match options.response {
        Response::Robust => {
            robust::check_final_rounding::<T>(start_magnitude, travel)?;
            robust::final_rounding::<T>(start_magnitude, travel, &options.robust)
        }
        Response::Fauerby | Response::Linahan => None,
    };
    let margin = rounding.map_or(REACH_MARGIN, |r| robust::skin_margin(r, &options.robust));
    if margin > REACH_MARGIN {
        reach = Reach::of_frame_within(body, position, &[velocity, gravity], margin);
    }
    let mut frame = Frame {
        world,
        body,
        detection: options.effective_detection(),
        detect: &options.detect,
        hood: Neighbourhood::new(origin.clone()),
        trace,
        moves,
        start_magnitude,
        resting: SmallVec::new(),
        margin,
        band: T::c(2.0 * rounding.unwrap_or(0.0)),
        planes: SmallVec::new(),
        met: SmallVec::new(),
        seeds: SmallVec::new(),
    };
    frame.hood.gather(world, body, &reach)?;
    // Each pass in eSpace with the number of equal parts it is slid in:
    // the robust response slides a displacement too long for its padding
    // in parts ([`robust::parts`]) and refuses one too long for any.
    let mut passes: SmallVec<[(Vec3<T>, usize); 2]> = SmallVec::new();
    for (what, vel) in [("velocity", velocity), ("gravity", gravity)] {
        if vel.iter().all(T::is_zero) {
            continue;
        }
        let vel_e = body.to_espace(vel);
        let parts = match options.response {
            Response::Robust => {
                robust::parts(&vel_e, &options.robust).ok_or_else(|| robust::too_long(what, &vel_e, &options.robust))?
            }
            Response::Fauerby | Response::Linahan => 1,
        };
        passes.push((vel_e, parts));
    }
    let start = body.to_espace(&(position - &origin));
    let mut p = start.clone();
    let still = |v: &Vec3<T>| v.iter().all(T::is_zero);
    if options.response == Response::Robust {
        p = robust::start(&mut frame, p, !(still(velocity) && still(gravity)), &options.robust)?;
    }
    for (vel_e, parts) in passes {
        let piece = if parts == 1 {
            vel_e
        } else {
            let n = T::c(parts as f64);
            vel_e.map(|x| x / &n)
        };
        for _ in 1..parts {
            p = pass(&mut frame, p, piece.clone(), options);
        }
        p = pass(&mut frame, p, piece, options);
    }
    let position = if p == start {
        position.clone()
    } else if options.response == Response::Robust {
        robust::land(&mut frame, &p, &origin, travel, &options.robust)?
    } else {
        body.from_espace(&p) + &origin
    };
    Ok(Move { position, trace: frame.trace })
}
