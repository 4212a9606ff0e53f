//! A seeded random search for failures: scene families with random angles,
//! clearances, speeds and offsets, run in `f32` and `f64` through all three
//! responses. Every failure comes with the `sweepslide run` command that
//! reproduces it.
//!
//! Four kinds are looked for: penetration and NaN positions in every run,
//! jitter where the ideal is rest (corners, the dead end), freezes where
//! the ideal is a slide (folds, creases, wedges, slots, the tessellated
//! floors, level and tilted), each judged by the lab's exact metrics. One
//! trial in four moves an ellipsoid instead of the scene's sphere; it has no
//! ideal slide, so its runs are checked for all but freezes.

use super::rng::Rng;
use super::runner::{FrameRecord, Precision, RunConfig, RunResult, run_all};
use super::scenes::build;
use crate::Error;
use crate::respond::Response;
use serde::{Deserialize, Serialize};
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
    /// The body stopped where it should slide: in a scene with an ideal
    /// slide it covered less than [`FREEZE`] of the ideal distance (the
    /// snag ratio), though each frame's ideal step was at least
    /// [`FREEZE_STEP`] times the unit roundoff of the position's largest
    /// coordinate, so the precision could have carried it.
    Freeze,
}

/// One failure and how to reproduce it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Finding {
    /// The kind of failure.
    pub kind: FailureKind,
    /// Its size: the largest penetration, the NaN frame count, the jitter,
    /// or the snag ratio of a freeze.
    pub value: f64,
    /// The run's metrics.
    pub result: RunResult,
    /// The command line that reproduces it.
    pub command: String,
}

/// One random trial: a scene spec, where it is, how the body moves.
#[derive(Clone, Debug)]
struct Trial {
    spec: String,
    offset: [f64; 3],
    velocity: [f64; 3],
    /// An ellipsoid's radii, or `None` for the scene's own sphere.
    radii: Option<[f64; 3]>,
    frames: usize,
    rest: bool,
}

fn trial(rng: &mut Rng) -> Trial {
    let families = ["corner", "wedge", "crease", "fold", "slot", "dead-end", "tessellated-floor", "tilted-floor"];
    let family = families[(rng.next_u64() % families.len() as u64) as usize];
    let (spec, rest) = match family {
        "corner" => (format!("corner:{:.2}", rng.range(5.0, 85.0)), true),
        "wedge" => (format!("wedge:{:.3}", 10f64.powf(rng.range(-0.3, 1.3))), false),
        "crease" => (format!("crease:{:.2}", rng.range(2.0, 75.0)), false),
        "fold" => (format!("fold:{:.3e}", 10f64.powf(rng.range(-3.0, 1.3))), false),
        "slot" => (format!("slot:{:.3e}", 10f64.powf(rng.range(-5.0, 0.0))), false),
        "tessellated-floor" => ("tessellated-floor:12".to_string(), false),
        "tilted-floor" => (format!("tilted-floor:{:.2}", rng.range(1.0, 60.0)), false),
        _ => ("dead-end".to_string(), true),
    };
    let scene = build(&spec, 1).expect("search specs are valid");
    let speed = 10f64.powf(rng.range(-7.0, 0.7));
    let velocity = scene.velocity.map(|v| v * speed);
    let offset = if rng.coin() {
        [0.0; 3]
    } else {
        let m = 10f64.powf(rng.range(1.0, 5.0));
        // `+ 0.0` turns a rounded `-0` into `0` (`-0e0` in the command).
        [rng.range(-m, m), rng.range(-m, m), rng.range(-m, m)].map(|x| x.round() + 0.0)
    };
    // One trial in four moves an ellipsoid inside the scene's sphere (its
    // largest radius the sphere's), so it starts outside wherever the
    // sphere does; its radii have three significant digits, as printed.
    let radii = (rng.next_u64() % 4 == 0).then(|| {
        let r = [(); 3].map(|()| 10f64.powf(rng.range(-1.0, 0.0)));
        let largest = r.iter().fold(0f64, |m, &x| m.max(x));
        r.map(|x| format!("{:.3e}", scene.radii[0] * x / largest).parse().expect("a formatted float parses"))
    });
    Trial { spec, offset, velocity: velocity.map(|v| v as f32 as f64), radii, frames: 60, rest }
}

fn command(t: &Trial, response: Response, precision: Precision) -> String {
    let v = |a: [f64; 3]| format!("{:e},{:e},{:e}", a[0], a[1], a[2]);
    let radii = t.radii.map(|r| format!(" --radii={}", v(r))).unwrap_or_default();
    format!(
        "sweepslide run --scene {} --offset={} --velocity={}{radii} --frames {} --response {} --precision {precision}",
        t.spec,
        v(t.offset),
        v(t.velocity),
        t.frames,
        response.name()
    )
}

/// Jitter above this (of the speed) in a scene whose ideal is rest counts.
const JITTER: f64 = 1e-3;

/// A sliding run that covers less than this fraction of the ideal distance
/// froze.
pub const FREEZE: f64 = 0.5;

/// A freeze counts only where the ideal step per frame is at least this many
/// times the unit roundoff of the largest coordinate the run held (start or
/// end): rounding the position then moves it by at most `sqrt(3) / 64` of
/// the step per frame, far from the half that a freeze loses.
pub const FREEZE_STEP: f64 = 64.0;

/// Whether a run's ideal step per frame is long enough for its precision to
/// carry, from `start` to `end` ([`FREEZE_STEP`]).
fn carried(ideal: &[f64; 3], start: &[f64; 3], end: &[f64; 3], precision: Precision) -> bool {
    // (A run that ends at NaN has no slide ratio; `f64::max` below would
    // pass over a NaN.)
    if !end.iter().all(|v| v.is_finite()) {
        return false;
    }
    let step = ideal.iter().map(|v| v * v).sum::<f64>().sqrt();
    let largest = start.iter().chain(end).fold(0f64, |m, v| m.max(v.abs()));
    step >= FREEZE_STEP * 2f64.powi(-(precision.bits() as i32)) * largest
}

/// Whether the last quarter of a trajectory goes back and forth (its net
/// displacement is less than half its path) rather than progressing, say
/// along a ramp in steps of the float spacing far from the origin, which the
/// jitter formula also scores.
fn back_and_forth(frames: &[FrameRecord]) -> bool {
    let tail = &frames[frames.len() - (frames.len() / 4).max(2).min(frames.len())..];
    let at = |f: &FrameRecord| nalgebra::Vector3::from(f.position);
    let path: f64 = tail.windows(2).map(|w| (at(&w[1]) - at(&w[0])).norm()).sum();
    let net = (at(&tail[tail.len() - 1]) - at(&tail[0])).norm();
    net < 0.5 * path
}

/// A short run may end while a slow body is still arriving, whose bent path
/// looks like jitter; a jitter finding counts only if a run four times as
/// long still shows it.
fn confirm_jitter(cfg: &RunConfig) -> Result<bool, Error> {
    let mut scene = (*cfg.scene).clone();
    scene.frames *= 4;
    let longer = RunConfig { scene: Arc::new(scene), ..cfg.clone() };
    Ok(super::runner::run(&longer)?.result.jitter > JITTER)
}

/// Runs `trials` random trials from `seed` on `jobs` threads and returns
/// every failure, in trial order.
///
/// # Errors
/// A scene that cannot be built at its random offset, a run that fails
/// (naming its command), or a thread-pool failure.
pub fn search(seed: u64, trials: usize, jobs: usize) -> Result<Vec<Finding>, Error> {
    let mut rng = Rng::new(seed);
    let mut plan = Vec::new();
    for _ in 0..trials {
        let t = trial(&mut rng);
        // The sliding families' ideal slides, scaled with the velocity.
        // An ellipsoid has no ideal slide (`Scene::with_radii`), so no freeze.
        let mut scene = build(&t.spec, 1)?.offset(t.offset, true)?.with_velocity(t.velocity);
        if let Some(radii) = t.radii {
            scene = scene.with_radii(radii);
        }
        scene.frames = t.frames;
        let scene = Arc::new(scene);
        for precision in [Precision::F32, Precision::F64] {
            for response in Response::ALL {
                plan.push((
                    t.clone(),
                    RunConfig { scene: scene.clone(), response, detection: None, precision, seed: 1 },
                ));
            }
        }
    }
    let configs: Vec<RunConfig> = plan.iter().map(|(_, c)| c.clone()).collect();
    let outputs = run_all(&configs, jobs, &|_| {})?;
    let mut findings = Vec::new();
    for ((t, cfg), out) in plan.iter().zip(outputs) {
        // A run that fails is a defect of the search (its scenes are valid
        // input), reported with the command that reproduces it.
        let out = out.map_err(|e| Error::InvalidArgument {
            what: format!("search run `{}`", command(t, cfg.response, cfg.precision)),
            message: e.to_string(),
        })?;
        let r = out.result;
        let mut found = |kind, value: f64| {
            findings.push(Finding { kind, value, result: r.clone(), command: command(t, cfg.response, cfg.precision) });
        };
        // Not a frame that a one-sided detection passes by design (it
        // ends inside only triangles it entered from behind).
        let (penetrating, depth) = r.counted_penetration();
        if penetrating > 0 {
            found(FailureKind::Penetration, depth);
        }
        if r.nan_frames > 0 {
            found(FailureKind::Nan, r.nan_frames as f64);
        }
        if t.rest && r.jitter > JITTER && back_and_forth(&out.frames) && confirm_jitter(cfg)? {
            found(FailureKind::Jitter, r.jitter);
        }
        if let (Some(snag), Some(ideal)) = (r.snag, &cfg.scene.ideal)
            && snag < FREEZE
            && carried(ideal, &cfg.scene.start, &r.final_position, cfg.precision)
        {
            found(FailureKind::Freeze, snag);
        }
    }
    Ok(findings)
}
