//! A seeded random search for failures: scene families with random angles,
//! clearances, speeds and offsets, run in `f32` and `f64` through all three
//! responses. Every failure comes with the `sweepslide run` command that
//! reproduces it.
//!
//! Six kinds are looked for: penetration and NaN positions in every run,
//! jitter where the ideal is rest (corners, the dead end), and freezes,
//! drift off the ideal's line and wobble (a zigzag) where the ideal is a
//! slide (folds, creases, wedges, slots, the floors: tessellated, tilted
//! and messy), each judged by the lab's exact metrics. One trial in four
//! moves an ellipsoid instead of the scene's own body; it has no ideal
//! slide, so its runs are checked for all but freezes, drift and wobble.

use super::metrics::{DRIFT_THRESHOLD, JITTER_THRESHOLD, penetration};
use super::rng::Rng;
use super::runner::{FrameRecord, Precision, RunConfig, RunResult, run_all};
use super::scenes::{Scene, build};
use crate::Error;
use crate::respond::Response;
use crate::world::World;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

/// What went wrong in a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureKind {
    /// A frame ended with the body inside the geometry (exact check).
    Penetration,
    /// A frame ended at a NaN or infinite position.
    Nan,
    /// The body kept moving back and forth where it should rest (jitter
    /// above 1e-3 of the speed in a scene whose ideal is rest, with less net
    /// progress than half the path, still there in a run four times as
    /// long).
    Jitter,
    /// The body zigzagged where it should slide: in a scene with an ideal
    /// slide its wobble ([`super::metrics::wobble`]) over the last quarter
    /// exceeded [`JITTER_THRESHOLD`] plus what rounding its positions can
    /// give ([`WOBBLE_ROUNDING`]) beyond the least wobble of the other
    /// responses in the same trial and precision, and still did in a run
    /// four times as long.
    Wobble,
    /// The body stopped where it should slide: in a scene with an ideal
    /// slide it covered less than [`FREEZE`] of the ideal distance (the
    /// snag ratio), though each frame's ideal step was at least
    /// [`FREEZE_STEP`] times the unit roundoff of the position's largest
    /// coordinate, so the precision could have carried it.
    Freeze,
    /// The body left the ideal slide's line: once it slid as the ideal
    /// does, it drifted across it ([`super::metrics::drift`]) by
    /// [`DRIFT_THRESHOLD`] radii or more beyond what rounding its positions
    /// every frame can carry it ([`DRIFT_ROUNDING`]) and beyond the least
    /// drift of the other responses in the same trial and precision, while
    /// it stayed on the scene's surfaces, where the ideal holds.
    Drift,
}

/// One failure and how to reproduce it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Finding {
    /// The kind of failure.
    pub kind: FailureKind,
    /// Its size: the largest penetration, the NaN frame count, the jitter,
    /// the snag ratio of a freeze, or the drift in radii.
    pub value: f64,
    /// The run's metrics.
    pub result: RunResult,
    /// The command line that reproduces it.
    pub command: String,
}

/// What a search found, and what it tried.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Every failure, in trial order.
    pub findings: Vec<Finding>,
    /// How many trials each family had (`mesh:NAME` for a mesh's), by name.
    pub trials: BTreeMap<String, usize>,
    /// How many of them moved an ellipsoid.
    pub ellipsoids: usize,
}

/// One random trial: the scene as it runs, the command-line arguments
/// that build it, its family (`mesh:NAME` for a mesh's), whether its ideal
/// is rest, and whether it moves an ellipsoid.
#[derive(Clone, Debug)]
struct Trial {
    scene: Arc<Scene>,
    args: String,
    seed: u64,
    family: String,
    rest: bool,
    ellipsoid: bool,
}

/// Frames per trial.
const FRAMES: usize = 60;

/// `[x, y, z]` as the command line reads it back, bit for bit.
fn vec3_arg(a: [f64; 3]) -> String {
    format!("{:e},{:e},{:e}", a[0], a[1], a[2])
}

/// `word` as a POSIX shell reads it back: bare when it holds only
/// `[A-Za-z0-9_./-]` and does not start with `-`, else in single quotes
/// (each `'` written `'\''`). (A path that starts with `-` is printed
/// after `--mesh=`, where the command line does not take it for a flag.)
fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./-".contains(c);
    if !word.is_empty() && !word.starts_with('-') && word.chars().all(plain) {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', "'\\''"))
    }
}

/// `x` to four significant digits, as printed and read back.
fn four_digits(x: f64) -> f64 {
    format!("{x:.3e}").parse().expect("a formatted float parses")
}

/// One trial in four moves an ellipsoid inside the sphere of radius `r`
/// (its largest radius `r`), so it starts outside wherever that sphere
/// does.
fn ellipsoid(rng: &mut Rng, r: f64) -> Option<[f64; 3]> {
    rng.next_u64().is_multiple_of(4).then(|| {
        let radii = [(); 3].map(|()| 10f64.powf(rng.range(-1.0, 0.0)));
        let largest = radii.iter().fold(0f64, |m, &x| m.max(x));
        radii.map(|x| four_digits(r * x / largest))
    })
}

/// A trial of a built-in scene family.
fn builtin_trial(rng: &mut Rng, family: &str) -> Result<Trial, Error> {
    let (spec, rest) = match family {
        "corner" => (format!("corner:{:.2}", rng.range(5.0, 85.0)), true),
        "wedge" => (format!("wedge:{:.3}", 10f64.powf(rng.range(-0.3, 1.3))), false),
        "crease" => (format!("crease:{:.2}", rng.range(2.0, 75.0)), false),
        "fold" => (format!("fold:{:.3e}", 10f64.powf(rng.range(-3.0, 1.3))), false),
        "slot" => (format!("slot:{:.3e}", 10f64.powf(rng.range(-5.0, 0.0))), false),
        "tessellated-floor" => ("tessellated-floor:12".to_string(), false),
        "tilted-floor" => (format!("tilted-floor:{:.2}", rng.range(1.0, 60.0)), false),
        "messy-floor" => ("messy-floor:12".to_string(), false),
        _ => ("dead-end".to_string(), true),
    };
    let scene = build(&spec, 1)?;
    let speed = 10f64.powf(rng.range(-7.0, 0.7));
    let velocity = scene.velocity.map(|v| (v * speed) as f32 as f64);
    let offset = if rng.coin() {
        [0.0; 3]
    } else {
        let m = 10f64.powf(rng.range(1.0, 5.0));
        // `+ 0.0` turns a rounded `-0` into `0` (`-0e0` in the command).
        [rng.range(-m, m), rng.range(-m, m), rng.range(-m, m)].map(|x| x.round() + 0.0)
    };
    let radii = ellipsoid(rng, scene.radii[0]);
    // The sliding families' ideal slides, scaled with the velocity; an
    // ellipsoid has none (`Scene::with_radii`), so it is not checked for
    // freezes.
    let mut scene = scene.offset(offset, true)?.with_velocity(velocity);
    let mut args = format!("--scene {spec} --offset={} --velocity={}", vec3_arg(offset), vec3_arg(velocity));
    if let Some(radii) = radii {
        // Rounded to `f32` as the command line rounds a built-in scene's
        // inputs; printed as drawn.
        scene = scene.with_radii(radii.map(|x| x as f32 as f64));
        args += &format!(" --radii={}", vec3_arg(radii));
    }
    scene.frames = FRAMES;
    let ellipsoid = radii.is_some();
    Ok(Trial { scene: Arc::new(scene), args, seed: 1, family: family.to_string(), rest, ellipsoid })
}

/// A mesh the search moves bodies over: its default scene, its world for
/// the start's clearance, and its path.
struct SearchMesh {
    scene: Scene,
    world: World<f64>,
    path: PathBuf,
}

/// A trial on a mesh: a sphere of 0.4% to 10% of the mesh's diagonal, or an
/// ellipsoid inside it, started 1% to 100% of its radius in front of a
/// random point of a random triangle (drawn again, up to 100 times, until
/// the exact distance to the whole mesh clears the sphere by 1% of its
/// radius, else above the mesh's box), pushed 1e-5 to 3 radii a frame in a
/// random direction and steered by the scene's random walk, with gravity
/// in half the trials, anywhere up to 1e4 radii from the mesh's own
/// coordinates. Only penetration and NaN are looked for.
///
/// In front, because a body inside a closed mesh meets the faces' backs,
/// which Fauerby's one-sided detection passes by design. Open meshes (the
/// bunny's holes, the teapot's rim) still let a body in; the lab tells
/// those frames apart only where every triangle a frame ends in was
/// entered from behind, and a body inside a solid also overlaps the next
/// face across an edge from its front side (culled by the motion's
/// direction, as designed, but counted), so a one-sided detection's
/// penetration on a mesh counts only in a run that never passed through a
/// back face.
fn mesh_trial(rng: &mut Rng, mesh: &SearchMesh) -> Result<Trial, Error> {
    let base = &mesh.scene;
    let r = four_digits(base.radii[0] * 10f64.powf(rng.range(-0.7, 0.7)));
    let sphere = Vector3::repeat(r);
    let clear = |p: &Vector3<f64>| penetration(&mesh.world, &sphere, p).is_none_or(|d| d <= -0.01 * r);
    let n = base.mesh.len() as u64;
    let start = (0..100)
        .find_map(|_| {
            let t = base.mesh.triangle((rng.next_u64() % n) as u32);
            let (u, v) = (rng.unit(), rng.unit());
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            let on = t.a + (t.b - t.a) * u + (t.c - t.a) * v;
            let normal = t.unnormalized_normal().try_normalize(0.0)?;
            let p = (on + normal * (r * (1.0 + 10f64.powf(rng.range(-2.0, 0.0))))).map(|x| x as f32 as f64);
            clear(&p).then_some(p)
        })
        .unwrap_or_else(|| {
            let b = base.mesh.bounds();
            Vector3::new(b.centre().x, b.max.y + 2.0 * r, b.centre().z).map(|x| x as f32 as f64)
        });
    let direction = loop {
        let d = Vector3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        if (0.01..=1.0).contains(&d.norm_squared()) {
            break d.normalize();
        }
    };
    let velocity: [f64; 3] = (direction * r * 10f64.powf(rng.range(-5.0, 0.5))).map(|x| x as f32 as f64).into();
    let gravity = if rng.coin() { [0.0; 3] } else { [0.0, -four_digits(r * 10f64.powf(rng.range(-4.0, -0.5))), 0.0] };
    let offset = if rng.coin() {
        [0.0; 3]
    } else {
        let m = r * 10f64.powf(rng.range(1.0, 4.0));
        [(); 3].map(|()| four_digits(rng.range(-m, m)))
    };
    let seed = 1 + rng.next_u64() % 1000;
    let drawn = ellipsoid(rng, r);
    let body = drawn.map_or_else(|| format!("--radius {r:e}"), |radii| format!("--radii={}", vec3_arg(radii)));
    let radii = drawn.unwrap_or([r; 3]);
    let scene = Scene { start: start.into(), velocity, gravity, radii, frames: FRAMES, ..base.clone() };
    // A mesh valid where it was given can collapse at an offset (triangles
    // smaller than the offset's rounding): the search names it rather than
    // searching a mesh other than the one given.
    let scene = scene.offset(offset, false).map_err(|e| Error::InvalidArgument {
        what: format!("--mesh={}", mesh.path.display()),
        message: format!("the search moves each mesh up to 1e4 radii from the origin, and at {} {e}", vec3_arg(offset)),
    })?;
    let args = format!(
        "--mesh={} --start={} --velocity={} --gravity={} {body} --offset={} --seed {seed}",
        shell_word(&mesh.path.to_string_lossy()),
        vec3_arg(start.into()),
        vec3_arg(velocity),
        vec3_arg(gravity),
        vec3_arg(offset)
    );
    let family = format!("mesh:{}", base.name);
    Ok(Trial { scene: Arc::new(scene), args, seed, family, rest: false, ellipsoid: drawn.is_some() })
}

fn command(t: &Trial, response: Response, precision: Precision) -> String {
    format!("sweepslide run {} --frames {FRAMES} --response {} --precision {precision}", t.args, response.name())
}

/// A sliding run that covers less than this fraction of the ideal distance
/// froze.
pub const FREEZE: f64 = 0.5;

/// A freeze counts only where the ideal step per frame is at least this many
/// times the unit roundoff of the largest coordinate the run held (start or
/// end): rounding the position then moves it by at most `sqrt(3) / 64` of
/// the step per frame, far from the half that a freeze loses.
pub const FREEZE_STEP: f64 = 64.0;

/// The unit roundoff of `precision` times the largest coordinate of
/// `start` and `end`: how far rounding can move a position the run held,
/// per coordinate (the scale of [`FREEZE_STEP`] and [`DRIFT_ROUNDING`]).
fn position_rounding(start: &[f64; 3], end: &[f64; 3], precision: Precision) -> f64 {
    let largest = start.iter().chain(end).fold(0f64, |m, v| m.max(v.abs()));
    2f64.powi(-(precision.bits() as i32)) * largest
}

/// The last quarter of a trajectory's frames, at least `least` of them
/// (all where there are fewer).
fn last_quarter(frames: &[FrameRecord], least: usize) -> &[FrameRecord] {
    &frames[frames.len() - (frames.len() / 4).max(least).min(frames.len())..]
}

/// Whether a run's ideal step per frame is long enough for its precision to
/// carry, from `start` to `end` ([`FREEZE_STEP`]).
fn carried(ideal: &[f64; 3], start: &[f64; 3], end: &[f64; 3], precision: Precision) -> bool {
    // (A run that ends at NaN has no slide ratio; `f64::max` below would
    // pass over a NaN.)
    if !end.iter().all(|v| v.is_finite()) {
        return false;
    }
    let step = ideal.iter().map(|v| v * v).sum::<f64>().sqrt();
    step >= FREEZE_STEP * position_rounding(start, end, precision)
}

/// A drift counts only beyond this many unit roundoffs of the largest
/// coordinate the run held (start or end), in radii, per frame (and one
/// more): rounding a position moves it across the ideal by up to `sqrt(3)
/// u` of that coordinate, and a slide along a surface that does not push
/// back sideways (a floor, the line of a nearly flat fold) keeps every such
/// offset. A robust body in a fold of `0.05` degrees `2.7e4` from the
/// origin in `f32` drifted `0.04` radii in 60 frames that way (`1.1e-4` in
/// `f64`).
pub const DRIFT_ROUNDING: f64 = 2.0;

/// The drift a run's rounding can explain, in radii ([`DRIFT_ROUNDING`]):
/// over `frames` frames, for the largest coordinate of `start` and `end`
/// and the smallest of `radii`.
fn drift_rounding(radii: &[f64; 3], start: &[f64; 3], end: &[f64; 3], frames: usize, precision: Precision) -> f64 {
    let smallest_radius = radii.iter().copied().fold(f64::INFINITY, f64::min);
    DRIFT_ROUNDING * (frames + 1) as f64 * position_rounding(start, end, precision) / smallest_radius
}

/// How much more `value` (a drift, a wobble) is than the least of the
/// other responses' in the same trial and precision (`others`; those
/// without one left out, all of it where none has one). Exact collide-and-slide gives one
/// trajectory; what all three responses share is the scene's or the
/// precision's (a body that a push too slow to show above the positions'
/// rounding still lowers onto a floor `4.6e3` out in `f32`, drifting
/// `0.05` radii in all three), not a response's.
fn beyond_others(value: f64, others: impl Iterator<Item = Option<f64>>) -> f64 {
    value - others.flatten().reduce(f64::min).unwrap_or(0.0)
}

/// Whether every frame of a trajectory's last quarter ended on the scene's
/// surfaces, clear of them by at most half of [`DRIFT_THRESHOLD`] plus
/// `rounding` (radii): a scene's ideal slide holds only there. The
/// search's pushes, up to five times the scene's own, carry a body past
/// the end of a 12-cell floor, where it falls and every response
/// "drifted" alike; a body that left its surface by less than that cannot
/// have drifted the threshold by leaving it. The frames' penetration is in
/// world units for a sphere (of radius `radii[0]`) and in radii for an
/// ellipsoid ([`penetration`]).
fn on_surfaces(frames: &[FrameRecord], radii: &[f64; 3], rounding: f64) -> bool {
    let unit = if radii.iter().all(|r| *r == radii[0]) { radii[0] } else { 1.0 };
    last_quarter(frames, 1).iter().all(|f| f.penetration.is_some_and(|p| -p / unit <= 0.5 * DRIFT_THRESHOLD + rounding))
}

/// Whether the last quarter of a trajectory goes back and forth (its net
/// displacement is less than half its path) rather than progressing, say
/// along a ramp in steps of the float spacing far from the origin, which the
/// jitter formula also scores.
fn back_and_forth(frames: &[FrameRecord]) -> bool {
    let tail = last_quarter(frames, 2);
    let at = |f: &FrameRecord| nalgebra::Vector3::from(f.position);
    let path: f64 = tail.windows(2).map(|w| (at(&w[1]) - at(&w[0])).norm()).sum();
    let net = (at(&tail[tail.len() - 1]) - at(&tail[0])).norm();
    net < 0.5 * path
}

/// A short run may end while a slow body is still arriving, whose bent path
/// looks like jitter (or whose landing's bounce looks like wobble): a
/// finding counts only if a run four times as long still shows it,
/// `still` of that run's result.
fn confirm(cfg: &RunConfig, still: impl Fn(&RunResult) -> bool) -> Result<bool, Error> {
    let mut scene = (*cfg.scene).clone();
    scene.frames *= 4;
    let longer = RunConfig { scene: Arc::new(scene), ..cfg.clone() };
    Ok(still(&super::runner::run(&longer)?.result))
}

/// A wobble counts only beyond this many unit roundoffs of the largest
/// coordinate the run held, over the speed: each step difference spans
/// three rounded positions, each off by up to `sqrt(3) u` of that
/// coordinate, so rounding alone can give up to about `2 sqrt(3)`
/// ([`super::metrics::wobble`] halves the total variation); twice that.
pub const WOBBLE_ROUNDING: f64 = 7.0;

/// The most trials one search runs: a million trials are six million
/// runs, days on two cores.
pub const MAX_TRIALS: usize = 1_000_000;

/// Trials drawn, run and judged together: a trial holds its scene (a
/// messy floor's mesh among them, tens of kilobytes), so a search keeps
/// one chunk's scenes at a time, whatever its trial count.
const CHUNK_TRIALS: usize = 1_000;

/// Runs `trials` random trials from `seed` on `jobs` threads and returns
/// every failure, in trial order. The trials draw from nine built-in scene
/// families and, where `meshes` names any OBJ files, a tenth: bodies moved
/// over those meshes (without meshes the draws are those of the nine
/// alone, so a seed finds what it found before meshes were offered).
/// `note` gets each mesh file's load notes
/// ([`crate::world::TriangleMesh::load_notes`]: skipped faces, ignored
/// statements) as it is read, before any run.
///
/// # Errors
/// [`Error::InvalidArgument`] for a trial count outside `1..=`
/// [`MAX_TRIALS`]; a mesh that cannot be loaded, a scene that cannot be
/// built at its random offset, a run that fails (naming its command), or
/// a thread-pool failure.
pub fn search(
    seed: u64,
    trials: usize,
    jobs: usize,
    meshes: &[PathBuf],
    note: &dyn Fn(&str),
) -> Result<Outcome, Error> {
    if !(1..=MAX_TRIALS).contains(&trials) {
        return Err(Error::InvalidArgument {
            what: "trials".into(),
            message: format!("a search runs 1 to {MAX_TRIALS} trials, got {trials}"),
        });
    }
    let meshes = meshes
        .iter()
        .map(|path| {
            // A finding's command names the mesh: a name that is not text
            // would print as another.
            if path.to_str().is_none() {
                return Err(Error::InvalidArgument {
                    what: path.display().to_string(),
                    message: "the search prints each mesh's path in its commands; this one is not valid UTF-8".into(),
                });
            }
            let scene = Scene::from_obj(path)?;
            scene.mesh.load_notes(&path.display().to_string()).iter().for_each(|l| note(l));
            let world = World::new(scene.mesh.clone())?;
            Ok(SearchMesh { scene, world, path: path.clone() })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let families =
        ["corner", "wedge", "crease", "fold", "slot", "dead-end", "tessellated-floor", "tilted-floor", "messy-floor"];
    let count = families.len() as u64 + u64::from(!meshes.is_empty());
    let mut rng = Rng::new(seed);
    let mut outcome = Outcome { findings: Vec::new(), trials: BTreeMap::new(), ellipsoids: 0 };
    let mut drawn = 0;
    while drawn < trials {
        let chunk = CHUNK_TRIALS.min(trials - drawn);
        let mut plan = Vec::with_capacity(chunk * 2 * Response::ALL.len());
        for _ in 0..chunk {
            let family = (rng.next_u64() % count) as usize;
            let t = match families.get(family) {
                Some(family) => builtin_trial(&mut rng, family)?,
                None => {
                    let mesh = &meshes[(rng.next_u64() % meshes.len() as u64) as usize];
                    mesh_trial(&mut rng, mesh)?
                }
            };
            *outcome.trials.entry(t.family.clone()).or_default() += 1;
            outcome.ellipsoids += usize::from(t.ellipsoid);
            for precision in [Precision::F32, Precision::F64] {
                for response in Response::ALL {
                    plan.push((
                        t.clone(),
                        RunConfig { scene: t.scene.clone(), response, detection: None, precision, seed: t.seed },
                    ));
                }
            }
        }
        judge(&plan, jobs, &mut outcome.findings)?;
        drawn += chunk;
    }
    Ok(outcome)
}

/// Runs a chunk's `plan` (each trial's runs, every response of one
/// precision after another) and adds its failures to `findings`, in the
/// plan's order.
fn judge(plan: &[(Trial, RunConfig)], jobs: usize, findings: &mut Vec<Finding>) -> Result<(), Error> {
    let configs: Vec<RunConfig> = plan.iter().map(|(_, c)| c.clone()).collect();
    let outputs = run_all(&configs, jobs, &|_| {})?;
    // Each trial's drift in each precision, for every response (the plan
    // runs them one after the other): the others' least is the control of
    // a response's drift ([`beyond_others`]).
    let drifts: Vec<Option<f64>> = outputs.iter().map(|o| o.as_ref().ok().and_then(|o| o.result.drift)).collect();
    let wobbles: Vec<Option<f64>> =
        outputs.iter().map(|o| o.as_ref().ok().map(|o| o.result.wobble).filter(|w| !w.is_nan())).collect();
    for (i, ((t, cfg), out)) in plan.iter().zip(outputs).enumerate() {
        // A run that fails is a defect of the search (its scenes are valid
        // input), reported with the command that reproduces it.
        let out = out.map_err(|e| Error::InvalidArgument {
            what: format!("search run `{}`", command(t, cfg.response, cfg.precision)),
            message: e.to_string(),
        })?;
        let r = out.result;
        let group = i - i % Response::ALL.len();
        let mut found = |kind, value: f64| {
            findings.push(Finding { kind, value, result: r.clone(), command: command(t, cfg.response, cfg.precision) });
        };
        // Not a frame that a one-sided detection passes by design (it
        // ends inside only triangles it entered from behind); on a mesh,
        // not a run that passed through a back face at all ([`mesh_trial`]).
        let (penetrating, depth) = r.counted_penetration();
        let on_mesh = t.family.starts_with("mesh:");
        if penetrating > 0 && !(on_mesh && r.one_sided() && r.back_face_frames > 0) {
            found(FailureKind::Penetration, depth);
        }
        if r.nan_frames > 0 {
            found(FailureKind::Nan, r.nan_frames as f64);
        }
        if t.rest
            && r.jitter > JITTER_THRESHOLD
            && back_and_forth(&out.frames)
            && confirm(cfg, |r| r.jitter > JITTER_THRESHOLD)?
        {
            found(FailureKind::Jitter, r.jitter);
        }
        if let (Some(snag), Some(ideal)) = (r.snag, &cfg.scene.ideal)
            && snag < FREEZE
            && carried(ideal, &cfg.scene.start, &r.final_position, cfg.precision)
        {
            found(FailureKind::Freeze, snag);
        }
        if cfg.scene.ideal.is_some() && !t.rest {
            // The speed the run's wobble is relative to (its first push).
            let push = if cfg.scene.velocity == [0.0; 3] { &cfg.scene.gravity } else { &cfg.scene.velocity };
            let speed = push.iter().map(|v| v * v).sum::<f64>().sqrt();
            let rounding =
                WOBBLE_ROUNDING * position_rounding(&cfg.scene.start, &r.final_position, cfg.precision) / speed;
            let others = (group..group + Response::ALL.len()).filter(|&j| j != i).map(|j| wobbles[j]);
            let limit = JITTER_THRESHOLD + rounding;
            if beyond_others(r.wobble, others) > limit && confirm(cfg, |r| r.wobble > limit)? {
                found(FailureKind::Wobble, r.wobble);
            }
        }
        let rounding = drift_rounding(&cfg.scene.radii, &cfg.scene.start, &r.final_position, r.frames, cfg.precision);
        let others = (group..group + Response::ALL.len()).filter(|&j| j != i).map(|j| drifts[j]);
        if let Some(drift) = r.drift
            && beyond_others(drift, others) >= DRIFT_THRESHOLD + rounding
            && on_surfaces(&out.frames, &cfg.scene.radii, rounding)
        {
            found(FailureKind::Drift, drift);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{beyond_others, shell_word};

    /// A drift is judged against the least of the others' (those that
    /// have one), or against none where no other response has one.
    #[test]
    fn a_drift_counts_beyond_the_least_other_drift() {
        assert_eq!(beyond_others(0.05, [Some(0.048), None].into_iter()), 0.05 - 0.048);
        assert_eq!(beyond_others(0.05, [Some(0.01), Some(0.03)].into_iter()), 0.05 - 0.01);
        assert_eq!(beyond_others(0.07, [None, None].into_iter()), 0.07);
    }

    /// A review's finding (twenty-sixth session): a mesh path with a space
    /// printed bare, and the command split there in a shell.
    #[test]
    fn a_printed_path_reads_back_through_a_shell() {
        for path in ["/a/b-c_d.obj", "m dir/fandisk.obj", "it's.obj", "-flag.obj", "", "$HOME/x;rm -rf y.obj"] {
            let out =
                std::process::Command::new("sh").arg("-c").arg(format!("printf %s {}", shell_word(path))).output();
            let out = out.expect("sh runs");
            assert_eq!(String::from_utf8_lossy(&out.stdout), path, "{}", shell_word(path));
        }
        assert_eq!(shell_word("/a/b-c_d.obj"), "/a/b-c_d.obj");
    }
}
