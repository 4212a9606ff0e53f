//! Built-in scenes and OBJ scenes, each with sensible defaults for the body
//! and its motion.
//!
//! Every coordinate of a built-in scene (vertices, start, velocities, the
//! body's radii: `room`'s were not until the twenty-sixth session) is
//! rounded to the nearest `f32` when the scene is built, so `f32`, `f64` and
//! every MPFR precision of 24 bits or more see exactly the same geometry
//! and inputs: differences between runs come from arithmetic alone. OBJ
//! scenes keep the file's values; each backend then rounds them itself (and
//! the metrics use the rounded values that backend stored).

use super::rng::Rng;
use crate::Error;
use crate::world::TriangleMesh;
use nalgebra::{Rotation3, Unit, Vector3};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// How the pushing velocity evolves from frame to frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Motion {
    /// The same velocity every frame.
    Constant,
    /// A player steering: every frame the horizontal (x, z) direction turns
    /// by a seeded uniform angle in `[-turn_deg, turn_deg]`; the horizontal
    /// speed and the vertical component stay.
    RandomWalk {
        /// Largest turn per frame, in degrees.
        turn_deg: f64,
    },
    /// A recorded velocity per frame (a fuzz case); frames beyond the
    /// list repeat its last velocity.
    Scripted {
        /// The pushing displacement of each frame, in order.
        velocities: Vec<[f64; 3]>,
    },
}

/// A scene: geometry plus the default body and motion.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Name (with its parameter, e.g. `wedge:1`).
    pub name: String,
    /// One line saying what it shows.
    pub description: String,
    /// The triangles.
    pub mesh: Arc<TriangleMesh>,
    /// Start of the body's centre.
    pub start: [f64; 3],
    /// The body's radii (equal for a sphere).
    pub radii: [f64; 3],
    /// Pushing displacement per frame.
    pub velocity: [f64; 3],
    /// Gravity displacement per frame (second pass; zero for none).
    pub gravity: [f64; 3],
    /// Default number of frames.
    pub frames: usize,
    /// How the velocity evolves.
    pub motion: Motion,
    /// The displacement per frame of an ideal, frictionless slide (for the
    /// snag metric), where one is known.
    pub ideal: Option<[f64; 3]>,
    /// World units per metre, Fauerby's `unitsPerMeter` (1 unless set):
    /// the faithful responses' `eps`, Fauerby's `veryCloseDistance` and
    /// Linahan's `very_close_dist`, is `5e-5 * units_per_meter` eSpace
    /// units ([`crate::respond::FauerbyOptions::very_close_distance`]). The
    /// robust response has no such constant.
    pub units_per_meter: f64,
}

/// The built-in scenes: name, parameter meaning, description.
pub const BUILTIN: &[(&str, &str, &str)] = &[
    ("floor", "", "flat floor of two large triangles; the body slides along it while pressing down"),
    (
        "tessellated-floor",
        "cells per side (40)",
        "flat floor of many coplanar triangles with seeded random diagonals; internal edges everywhere",
    ),
    (
        "tilted-floor",
        "tilt in degrees (20)",
        "the tessellated floor, 24 cells per side, turned and tilted about a slanting axis (tilted at all, no coordinate is zero); the body slides along it while pressing in",
    ),
    (
        "corner",
        "ramp angle in degrees (45)",
        "the paper's Fig. 2: an obtuse corner between a floor and a ramp, body pushed down into it",
    ),
    (
        "wedge",
        "angle in degrees (10)",
        "the paper's Fig. 4: an acute wedge, body pushed into its apex with a free direction along the edge",
    ),
    (
        "crease",
        "slope in degrees (30)",
        "a V-shaped valley; the body pushes down into it and along it (below 26.57 degrees, where tan = 1/2, the push climbs the far slope instead)",
    ),
    (
        "fold",
        "fold angle in degrees (0.01)",
        "a valley folded along a slanting line (no axis-aligned normals), shallow by default; the body pushes into it and along it",
    ),
    ("dead-end", "", "three perpendicular planes (floor and two walls); the body pushes into the corner"),
    ("staircase", "steps (20)", "stairs of 0.15 rise and 0.6 run; a 0.5 sphere walks up with gravity"),
    (
        "terrain",
        "grid cells per side (64)",
        "seeded heightfield; a 0.5 sphere steered by a random walk at 5 m/s, 60 Hz, with gravity",
    ),
    ("soup", "triangles (200)", "seeded random triangle soup; the body wanders through it"),
    (
        "room",
        "",
        "a small level: floor, walls, pillars and ramps; an ellipsoid character steered by a random walk with gravity",
    ),
    (
        "messy-floor",
        "tiles per side (24)",
        "a level floor of unit tiles with the flaws of game levels (T-junctions, faces given twice, decals, crack-filling slivers, near-welded tiles); an ellipsoid character walks over it with gravity",
    ),
    (
        "slot",
        "clearance g (0.01)",
        "two parallel walls 2 + g apart; the body slides along the slot pressing into one wall",
    ),
];

/// The keys of a finding file written by the `compare_responses` fuzz
/// target: the case under `case`, and what failed.
const FINDING_KEYS: [&str; 9] = ["case", "target", "response", "precision", "kind", "failure", "frame", "from", "to"];

/// The names of the built-in scenes.
#[must_use]
pub fn builtin_names() -> Vec<&'static str> {
    BUILTIN.iter().map(|b| b.0).collect()
}

/// Rounds to the nearest `f32` (see the module docs).
fn q(x: f64) -> f64 {
    x as f32 as f64
}

fn q3(v: [f64; 3]) -> [f64; 3] {
    v.map(q)
}

/// Collects triangles, orienting each so its front faces a given direction.
#[derive(Default)]
struct Builder {
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

impl Builder {
    fn vertex(&mut self, v: [f64; 3]) -> u32 {
        self.vertices.push(q3(v));
        (self.vertices.len() - 1) as u32
    }

    /// A triangle whose front (counter-clockwise) side faces `facing`.
    fn tri(&mut self, a: [f64; 3], b: [f64; 3], c: [f64; 3], facing: [f64; 3]) {
        let (va, vb, vc) = (Vector3::from(a), Vector3::from(b), Vector3::from(c));
        let n = (vb - va).cross(&(vc - va));
        let (b, c) = if n.dot(&Vector3::from(facing)) < 0.0 { (c, b) } else { (b, c) };
        let ids = [self.vertex(a), self.vertex(b), self.vertex(c)];
        self.triangles.push(ids);
    }

    /// A planar quad `a b c d` (in order around it), split along `a c`.
    fn quad(&mut self, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], facing: [f64; 3]) {
        self.tri(a, b, c, facing);
        self.tri(a, c, d, facing);
    }

    /// An axis-aligned box without its bottom face, outward-facing.
    fn open_box(&mut self, lo: [f64; 3], hi: [f64; 3]) {
        let [x0, y0, z0] = lo;
        let [x1, y1, z1] = hi;
        self.quad([x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1], [0.0, 1.0, 0.0]);
        self.quad([x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1], [-1.0, 0.0, 0.0]);
        self.quad([x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1], [1.0, 0.0, 0.0]);
        self.quad([x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0], [0.0, 0.0, -1.0]);
        self.quad([x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1], [0.0, 0.0, 1.0]);
    }

    fn mesh(self) -> Result<Arc<TriangleMesh>, Error> {
        TriangleMesh::new(self.vertices, self.triangles).map(Arc::new)
    }
}

const UP: [f64; 3] = [0.0, 1.0, 0.0];

/// A scene skeleton with the given mesh and defaults; fields are then
/// adjusted by the builders below.
fn scene(name: String, description: &str, mesh: Arc<TriangleMesh>) -> Scene {
    Scene {
        name,
        description: description.to_string(),
        mesh,
        start: [0.0; 3],
        radii: [1.0; 3],
        velocity: [0.0; 3],
        gravity: [0.0; 3],
        frames: 200,
        motion: Motion::Constant,
        ideal: None,
        units_per_meter: 1.0,
    }
}

/// Builds a scene by name, `name` or `name:parameter` (see [`BUILTIN`]),
/// with `seed` for the seeded ones.
///
/// # Errors
/// [`Error::InvalidArgument`] for an unknown name or a parameter that is not
/// a number or is out of range.
pub fn build(spec: &str, seed: u64) -> Result<Scene, Error> {
    let (name, param) = match spec.split_once(':') {
        Some((n, p)) => {
            let value: f64 = p.parse().map_err(|_| bad(spec, format!("parameter `{p}` is not a number")))?;
            if !value.is_finite() {
                return Err(bad(spec, "parameter must be finite".to_string()));
            }
            (n, Some(value))
        }
        None => (spec, None),
    };
    let (_, meaning, description) = BUILTIN
        .iter()
        .find(|b| b.0 == name)
        .copied()
        .ok_or_else(|| bad(spec, format!("unknown scene (built-in scenes: {})", builtin_names().join(", "))))?;
    if meaning.is_empty() && param.is_some() {
        return Err(bad(spec, "this scene takes no parameter".to_string()));
    }
    let label = |default: f64| format!("{name}:{}", param.unwrap_or(default));
    let in_range = |lo: f64, hi: f64, default: f64| -> Result<f64, Error> {
        let v = param.unwrap_or(default);
        if (lo..=hi).contains(&v) { Ok(v) } else { Err(bad(spec, format!("parameter must lie in [{lo}, {hi}]"))) }
    };
    // A count: a whole number in range (never truncated).
    let count = |lo: f64, hi: f64, default: f64| -> Result<usize, Error> {
        let v = in_range(lo, hi, default)?;
        if v.fract() == 0.0 { Ok(v as usize) } else { Err(bad(spec, "parameter must be a whole number".to_string())) }
    };
    let mut b = Builder::default();
    let mut rng = Rng::new(seed);
    let s = match name {
        "floor" => {
            b.quad([-50.0, 0.0, -50.0], [-50.0, 0.0, 50.0], [50.0, 0.0, 50.0], [50.0, 0.0, -50.0], UP);
            let mut s = scene(name.to_string(), description, b.mesh()?);
            s.start = [-20.0, 1.05, 0.0];
            s.velocity = [0.1, -0.02, 0.0];
            s.ideal = Some([0.1, 0.0, 0.0]);
            s.frames = 300;
            s
        }
        "tessellated-floor" | "tilted-floor" => {
            // The tilted floor: 24 cells per side, turned in its plane and
            // then tilted about a slanting horizontal axis, so that no
            // coordinate or normal component is zero: its vertices round
            // (bending its internal edges by up to `u` of their
            // coordinates), and so does every slide along it, where the
            // level floor's are exact.
            let (n, turn, default) = if name == "tilted-floor" {
                let tilt = in_range(0.0, 60.0, 20.0)?.to_radians();
                let level = Rotation3::from_axis_angle(&Vector3::y_axis(), 0.7);
                let axis = Unit::new_normalize(Vector3::new(1.0, 0.0, 2.0));
                (24, Rotation3::from_axis_angle(&axis, tilt) * level, 20.0)
            } else {
                (count(1.0, 1000.0, 40.0)?, Rotation3::identity(), 40.0)
            };
            let t = |v: [f64; 3]| -> [f64; 3] { (turn * Vector3::from(v)).into() };
            let half = n as f64 / 2.0;
            for i in 0..n {
                for k in 0..n {
                    let (x0, z0) = (i as f64 - half, k as f64 - half);
                    let c = [[x0, 0.0, z0], [x0 + 1.0, 0.0, z0], [x0 + 1.0, 0.0, z0 + 1.0], [x0, 0.0, z0 + 1.0]].map(t);
                    if rng.coin() {
                        b.quad(c[0], c[1], c[2], c[3], t(UP));
                    } else {
                        b.quad(c[1], c[2], c[3], c[0], t(UP));
                    }
                }
            }
            let mut s = scene(label(default), description, b.mesh()?);
            s.start = t([-half * 0.8, 1.05, -half * 0.3]);
            s.velocity = t([0.1, -0.02, 0.037]);
            s.ideal = Some(t([0.1, 0.0, 0.037]));
            s.frames = (6 * n).min(300);
            s
        }
        "corner" => {
            let a = in_range(1.0, 89.0, 45.0)?.to_radians();
            b.quad([0.0, 0.0, -20.0], [0.0, 0.0, 20.0], [20.0, 0.0, 20.0], [20.0, 0.0, -20.0], UP);
            let h = 20.0 * a.tan();
            b.quad([-20.0, h, -20.0], [-20.0, h, 20.0], [0.0, 0.0, 20.0], [0.0, 0.0, -20.0], [a.sin(), a.cos(), 0.0]);
            let mut s = scene(label(45.0), description, b.mesh()?);
            // 2.5 above the ramp along its normal, wherever the angle.
            s.start = [-1.5 + 2.5 * a.sin(), 1.5 * a.tan() + 2.5 * a.cos(), 0.0];
            s.velocity = [-0.05, -0.1, 0.0];
            s
        }
        "wedge" => {
            let theta = in_range(0.5, 89.0, 10.0)?.to_radians();
            let apex = 1.0 / (theta / 2.0).tan();
            let len = (apex * 3.0).max(20.0);
            let z = 20.0;
            b.quad([0.0, 0.0, -z], [0.0, 0.0, z], [len, 0.0, z], [len, 0.0, -z], UP);
            let top = [len * theta.cos(), len * theta.sin()];
            b.quad(
                [0.0, 0.0, -z],
                [0.0, 0.0, z],
                [top[0], top[1], z],
                [top[0], top[1], -z],
                [theta.sin(), -theta.cos(), 0.0],
            );
            let mut s = scene(label(10.0), description, b.mesh()?);
            let x0 = apex + 5.0;
            s.start = [x0, x0 * (theta / 2.0).tan(), -10.0];
            s.velocity = [-0.1, 0.0, 0.02];
            s.ideal = Some([0.0, 0.0, 0.02]);
            s.frames = 300;
            s
        }
        "crease" => {
            let a = in_range(1.0, 80.0, 30.0)?.to_radians();
            let h = 20.0 * a.tan();
            b.quad([-20.0, h, -30.0], [-20.0, h, 30.0], [0.0, 0.0, 30.0], [0.0, 0.0, -30.0], [a.sin(), a.cos(), 0.0]);
            b.quad([0.0, 0.0, -30.0], [0.0, 0.0, 30.0], [20.0, h, 30.0], [20.0, h, -30.0], [-a.sin(), a.cos(), 0.0]);
            let mut s = scene(label(30.0), description, b.mesh()?);
            // 3 above the right slope along its normal.
            s.start = [2.0 - 3.0 * a.sin(), 2.0 * a.tan() + 3.0 * a.cos(), -20.0];
            s.velocity = [-0.05, -0.1, 0.1];
            // The push slid along the left slope, where the body lands after
            // the right one: back down into the crease where `tan a >= 1/2`,
            // so the slide follows the crease; below that angle it climbs
            // the left slope for good, and that is the ideal slide (the
            // drift metric found the crease's ideal wrong there).
            let left = Vector3::new(a.sin(), a.cos(), 0.0);
            let push = Vector3::from(s.velocity);
            let along_left = push - left * push.dot(&left);
            s.ideal = Some(if along_left.x >= 0.0 { [0.0, 0.0, 0.1] } else { along_left.into() });
            s.frames = 300;
            s
        }
        "fold" => {
            // The crease scene's valley, its faces' normals the parameter
            // apart, turned about a slanting axis: the normals then
            // have no zero or equal components, and their cross product
            // rounds as it does in a level's geometry (R23c).
            let half = in_range(1e-4, 20.0, 0.01)?.to_radians() / 2.0;
            let turn = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 2.0, 3.0)), 0.6);
            let t = |v: [f64; 3]| -> [f64; 3] { (turn * Vector3::from(v)).into() };
            let h = 20.0 * half.tan();
            let (left, right) = ([half.sin(), half.cos(), 0.0], [-half.sin(), half.cos(), 0.0]);
            b.quad(t([-20.0, h, -30.0]), t([-20.0, h, 30.0]), t([0.0, 0.0, 30.0]), t([0.0, 0.0, -30.0]), t(left));
            b.quad(t([0.0, 0.0, -30.0]), t([0.0, 0.0, 30.0]), t([20.0, h, 30.0]), t([20.0, h, -30.0]), t(right));
            let mut s = scene(label(0.01), description, b.mesh()?);
            // Half a radius above the fold, then pushed down into both
            // faces and along the fold.
            s.start = t([0.0, 1.5, -20.0]);
            s.velocity = t([0.0, -0.1, 0.1]);
            s.ideal = Some(t([0.0, 0.0, 0.1]));
            s.frames = 300;
            s
        }
        "dead-end" => {
            b.quad([0.0, 0.0, 0.0], [0.0, 0.0, 20.0], [20.0, 0.0, 20.0], [20.0, 0.0, 0.0], UP);
            b.quad([0.0, 0.0, 0.0], [0.0, 20.0, 0.0], [0.0, 20.0, 20.0], [0.0, 0.0, 20.0], [1.0, 0.0, 0.0]);
            b.quad([0.0, 0.0, 0.0], [20.0, 0.0, 0.0], [20.0, 20.0, 0.0], [0.0, 20.0, 0.0], [0.0, 0.0, 1.0]);
            let mut s = scene(name.to_string(), description, b.mesh()?);
            s.start = [3.0, 3.0, 3.0];
            s.velocity = [-0.1, -0.1, -0.1];
            s
        }
        "staircase" => {
            let steps = count(1.0, 1000.0, 20.0)?;
            let (rise, run, w) = (0.15, 0.6, 5.0);
            b.quad([-10.0, 0.0, -w], [-10.0, 0.0, w], [0.0, 0.0, w], [0.0, 0.0, -w], UP);
            for i in 0..steps {
                let (x, y) = (i as f64 * run, i as f64 * rise);
                b.quad([x, y, -w], [x, y + rise, -w], [x, y + rise, w], [x, y, w], [-1.0, 0.0, 0.0]);
                b.quad([x, y + rise, -w], [x, y + rise, w], [x + run, y + rise, w], [x + run, y + rise, -w], UP);
            }
            let mut s = scene(label(20.0), description, b.mesh()?);
            s.radii = [0.5; 3];
            s.start = [-2.0, 0.51, 0.0];
            s.velocity = [0.05, 0.0, 0.0];
            s.gravity = [0.0, -0.01, 0.0];
            s.frames = 300;
            s
        }
        "terrain" => {
            let n = count(2.0, 2048.0, 64.0)?;
            let cell = 0.5;
            let waves: Vec<[f64; 4]> = (0..6)
                .map(|k| {
                    [
                        rng.range(0.2, 1.0) / (k + 1) as f64,
                        rng.range(0.05, 0.4),
                        rng.range(0.0, 2.0 * PI),
                        rng.range(0.0, PI),
                    ]
                })
                .collect();
            let height = |x: f64, z: f64| {
                waves
                    .iter()
                    .map(|[amp, freq, phase, dir]| amp * ((x * dir.cos() + z * dir.sin()) * freq + phase).sin())
                    .sum::<f64>()
            };
            let half = n as f64 * cell / 2.0;
            let mut ids = Vec::with_capacity((n + 1) * (n + 1));
            for i in 0..=n {
                for k in 0..=n {
                    let (x, z) = (i as f64 * cell - half, k as f64 * cell - half);
                    ids.push(b.vertex([x, height(x, z) + rng.range(-0.01, 0.01), z]));
                }
            }
            let id = |i: usize, k: usize| ids[i * (n + 1) + k];
            for i in 0..n {
                for k in 0..n {
                    // Counter-clockwise seen from above: front faces up.
                    b.triangles.push([id(i, k), id(i, k + 1), id(i + 1, k + 1)]);
                    b.triangles.push([id(i, k), id(i + 1, k + 1), id(i + 1, k)]);
                }
            }
            let mut s = scene(label(64.0), description, b.mesh()?);
            s.radii = [0.5; 3];
            s.start = [0.0, height(0.0, 0.0) + 2.0, 0.0];
            s.velocity = [5.0 / 60.0, 0.0, 0.0];
            s.gravity = [0.0, -0.01, 0.0];
            s.motion = Motion::RandomWalk { turn_deg: 6.0 };
            s.frames = 300;
            s
        }
        "soup" => {
            let count = count(1.0, 100_000.0, 200.0)?;
            let mut added = 0;
            while added < count {
                let centre = [rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)];
                let mut corner = || [0, 1, 2].map(|i| centre[i] + rng.range(-1.5, 1.5));
                let (a, bb, c) = (corner(), corner(), corner());
                let (va, vb, vc) = (Vector3::from(a), Vector3::from(bb), Vector3::from(c));
                if (vb - va).cross(&(vc - va)).norm() > 0.1 {
                    let facing = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
                    b.tri(a, bb, c, facing);
                    added += 1;
                }
            }
            let mesh = b.mesh()?;
            let radius = 0.5;
            let start = clear_start(&mesh, radius, &mut rng)?;
            let mut s = scene(label(200.0), description, mesh);
            s.radii = [radius; 3];
            s.start = start;
            s.velocity = [0.05, 0.0, 0.0];
            s.motion = Motion::RandomWalk { turn_deg: 15.0 };
            s.frames = 300;
            s
        }
        "room" => {
            let (w, hgt) = (10.0, 4.0);
            b.quad([-w, 0.0, -w], [-w, 0.0, w], [w, 0.0, w], [w, 0.0, -w], UP);
            b.quad([-w, 0.0, -w], [-w, hgt, -w], [-w, hgt, w], [-w, 0.0, w], [1.0, 0.0, 0.0]);
            b.quad([w, 0.0, -w], [w, hgt, -w], [w, hgt, w], [w, 0.0, w], [-1.0, 0.0, 0.0]);
            b.quad([-w, 0.0, -w], [w, 0.0, -w], [w, hgt, -w], [-w, hgt, -w], [0.0, 0.0, 1.0]);
            b.quad([-w, 0.0, w], [w, 0.0, w], [w, hgt, w], [-w, hgt, w], [0.0, 0.0, -1.0]);
            for (x, z) in [(-4.0, -4.0), (4.0, -4.0), (-4.0, 4.0), (4.0, 4.0)] {
                b.open_box([x - 0.5, 0.0, z - 0.5], [x + 0.5, 3.0, z + 0.5]);
            }
            // A platform reached by a ramp, and a second, steeper ramp.
            b.open_box([5.0, 0.0, -2.0], [9.0, 1.0, 2.0]);
            b.quad([1.0, 0.0, -2.0], [1.0, 0.0, 2.0], [5.0, 1.0, 2.0], [5.0, 1.0, -2.0], UP);
            b.quad([-9.0, 0.0, 6.0], [-9.0, 0.0, 9.0], [-6.0, 2.0, 9.0], [-6.0, 2.0, 6.0], UP);
            let mut s = scene(name.to_string(), description, b.mesh()?);
            s.radii = [0.4, 0.9, 0.4];
            s.start = [0.0, 0.95, 0.0];
            s.velocity = [0.08, 0.0, 0.0];
            s.gravity = [0.0, -0.02, 0.0];
            s.motion = Motion::RandomWalk { turn_deg: 10.0 };
            s.frames = 600;
            s
        }
        "messy-floor" => {
            // Every vertex lies on `y = 0` (exactly, in every precision):
            // the flaws are in the mesh's connectivity, not its shape, so
            // the ideal slide is exact. The seams they make are *active*
            // (no neighbour shares their endpoints), where a tessellated
            // floor's are internal.
            let n = count(1.0, 1000.0, 24.0)?;
            // The near-welded tiles' gaps, and the slivers' height (enough
            // to keep them triangles in `f32` up to about `1e4` away).
            let (half, gap, crack) = (n as f64 / 2.0, 1e-4, 2e-3);
            for i in 0..n {
                for k in 0..n {
                    let (x0, z0) = (i as f64 - half, k as f64 - half);
                    let p = |dx: f64, dz: f64| [x0 + dx, 0.0, z0 + dz];
                    let tile = |b: &mut Builder| b.quad(p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0), UP);
                    match rng.next_u64() % 6 {
                        0 => tile(&mut b),
                        // A T-junction: a vertex in the middle of the edge
                        // the neighbour at `+x` gives whole.
                        1 => {
                            let m = p(1.0, 0.5);
                            b.tri(p(0.0, 0.0), p(1.0, 0.0), m, UP);
                            b.tri(p(0.0, 0.0), m, p(0.0, 1.0), UP);
                            b.tri(m, p(1.0, 1.0), p(0.0, 1.0), UP);
                        }
                        // The tile given twice, split along both diagonals.
                        2 => {
                            tile(&mut b);
                            b.quad(p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0), p(0.0, 0.0), UP);
                        }
                        // A decal: a smaller coplanar quad on the tile.
                        3 => {
                            tile(&mut b);
                            b.quad(p(0.3, 0.2), p(0.8, 0.3), p(0.7, 0.8), p(0.2, 0.7), UP);
                        }
                        // A crack-filling sliver along the diagonal: a flat
                        // cap whose apex lies `crack` off its middle.
                        4 => {
                            tile(&mut b);
                            b.tri(p(0.0, 0.0), p(1.0, 1.0), p(0.5 + crack, 0.5 - crack), UP);
                        }
                        // A near-welded tile: shrunk by `gap` on every side.
                        _ => b.quad(p(gap, gap), p(1.0 - gap, gap), p(1.0 - gap, 1.0 - gap), p(gap, 1.0 - gap), UP),
                    }
                }
            }
            let mut s = scene(label(24.0), description, b.mesh()?);
            s.radii = [0.4, 0.9, 0.4];
            s.start = [-half * 0.8, 0.95, -half * 0.3];
            s.velocity = [0.08, 0.0, 0.03];
            s.gravity = [0.0, -0.02, 0.0];
            s.ideal = Some([0.08, 0.0, 0.03]);
            s.frames = (8 * n).min(300);
            s
        }
        "slot" => {
            let g = in_range(0.0, 10.0, 0.01)?;
            // The walls' coordinates are rounded to `f32` like every
            // built-in scene's: below about `1.2e-7` a clearance rounds
            // to none, and the scene would not be what its name says.
            if g > 0.0 && q(1.0 + g / 2.0) == 1.0 {
                return Err(bad(
                    spec,
                    format!("clearance {g} rounds to 0 in the scene's f32 coordinates (the least is 1.2e-7)"),
                ));
            }
            let x = 1.0 + g / 2.0;
            b.quad([-x, -5.0, -50.0], [-x, 5.0, -50.0], [-x, 5.0, 50.0], [-x, -5.0, 50.0], [1.0, 0.0, 0.0]);
            b.quad([x, -5.0, -50.0], [x, 5.0, -50.0], [x, 5.0, 50.0], [x, -5.0, 50.0], [-1.0, 0.0, 0.0]);
            let mut s = scene(label(0.01), description, b.mesh()?);
            s.start = [0.0, 0.0, -20.0];
            s.velocity = [0.02, 0.0, 0.1];
            s.ideal = Some([0.0, 0.0, 0.1]);
            s
        }
        _ => unreachable!("names come from BUILTIN"),
    };
    Ok(Scene {
        start: q3(s.start),
        velocity: q3(s.velocity),
        gravity: q3(s.gravity),
        radii: q3(s.radii),
        ideal: s.ideal.map(q3),
        ..s
    })
}

fn bad(spec: &str, message: String) -> Error {
    Error::InvalidArgument { what: format!("scene `{spec}`"), message }
}

/// A seeded start position at least `1.2 r` (approximately, in `f64`) from
/// every triangle.
fn clear_start(mesh: &TriangleMesh, r: f64, rng: &mut Rng) -> Result<[f64; 3], Error> {
    let b = mesh.bounds();
    for _ in 0..10_000 {
        let p = Vector3::from_fn(|i, _| rng.range(b.min[i], b.max[i]));
        let clear = (0..mesh.len() as u32).all(|t| {
            let tri = mesh.triangle(t);
            let (c, _) = crate::geom::closest_point_on_triangle(&p, &tri);
            (p - c).norm() > 1.2 * r
        });
        if clear {
            return Ok(p.into());
        }
    }
    Err(Error::InvalidArgument { what: "scene".into(), message: "no free start position found".into() })
}

impl Scene {
    /// A scene made of an OBJ file, with defaults scaled to its size: a
    /// sphere of 2% of the bounding-box diagonal dropped from above the
    /// middle and steered by a random walk with gravity. The push is 0.1% of
    /// the diagonal a frame (a third of the diagonal in 300 frames), slow
    /// enough that the body lands on the model and spends most frames on it
    /// rather than walking off its edge in the first frames.
    ///
    /// # Errors
    /// As [`TriangleMesh::from_obj_file`].
    pub fn from_obj(path: &Path) -> Result<Self, Error> {
        let mesh = TriangleMesh::from_obj_file(path)?;
        let b = *mesh.bounds();
        // Scaled, so that the squares do not overflow for coordinates
        // beyond 1e154 (the box's extent itself is finite for any valid mesh
        // within half the `f64` range).
        let extent = b.max - b.min;
        let largest = extent.amax();
        let diag = if largest > 0.0 { largest * (extent / largest).norm() } else { 0.0 };
        // The lab's inputs are `f32` numbers (every precision runs the same
        // ones): the defaults scaled from the diagonal must be too.
        let in_f32 = |x: f64| {
            let f = x as f32;
            f.is_finite() && (f != 0.0 || x == 0.0)
        };
        // The radius must be a normal `f32` number, as a body's radii must
        // be in `f32` (a subnormal one was refused as a radius the user had
        // not given: a review, session 36).
        let radius_in_f32 = ((0.02 * diag) as f32).is_normal();
        if !(radius_in_f32 && [0.0004 * diag, b.max.y + 0.04 * diag].into_iter().all(in_f32)) {
            return Err(Error::InvalidArgument {
                what: path.display().to_string(),
                message: format!(
                    "the lab's default scene for this mesh (a sphere of 2% of its bounding box's diagonal, {}) \
                     needs values beyond the normal `f32` numbers that lab scenes are made of",
                    crate::error::Num(diag)
                ),
            });
        }
        let r = 0.02 * diag;
        let centre = b.centre();
        let name = path.file_stem().map_or_else(|| path.display().to_string(), |s| s.to_string_lossy().into_owned());
        Ok(Scene {
            name,
            description: format!("mesh {} ({} triangles)", path.display(), mesh.len()),
            mesh: Arc::new(mesh),
            start: [centre.x, b.max.y + 2.0 * r, centre.z],
            radii: [r; 3],
            velocity: [0.001 * diag, 0.0, 0.0004 * diag],
            gravity: [0.0, -0.004 * diag, 0.0],
            frames: 300,
            motion: Motion::RandomWalk { turn_deg: 8.0 },
            ideal: None,
            units_per_meter: 1.0,
        })
    }

    /// A scene made of a fuzz case (`fuzz/src/oracle.rs`'s `MoveCase` as
    /// JSON: a triangle soup, radii, start and frames), or of a finding file
    /// written by the `compare_responses` fuzz target (the case sits under
    /// its `"case"` key). The velocities are replayed frame by frame in
    /// `f64` exactly as recorded; the gravity must be the same in every
    /// frame (the lab's scenes have one gravity). Triangles degenerate in
    /// `f64` are skipped and listed by [`TriangleMesh::skipped`], as the
    /// fuzz oracle does.
    ///
    /// # Errors
    /// [`Error::Io`] if the file cannot be read; [`Error::InvalidArgument`]
    /// for malformed JSON (with its line and column), an unknown key (a
    /// misspelt `gravity` would otherwise run without gravity), no frame, or
    /// gravity that changes between frames, or a mesh error (no valid
    /// triangle), naming the file.
    pub fn from_case_file(path: &Path) -> Result<Self, Error> {
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Frame {
            velocity: [f64; 3],
            gravity: Option<[f64; 3]>,
        }
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Case {
            triangles: Vec<[[f64; 3]; 3]>,
            radii: [f64; 3],
            start: [f64; 3],
            frames: Vec<Frame>,
        }
        let bad = |message: String| Error::InvalidArgument { what: path.display().to_string(), message };
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::Io { path: path.to_path_buf(), message: e.to_string() })?;
        let value: serde_json::Value = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
        // A finding file's other keys say what failed (the response and
        // precision to pass on the command line, among others); any key
        // else is a mistake, not something to ignore.
        if let (Some(_), Some(keys)) = (value.get("case"), value.as_object())
            && let Some(k) = keys.keys().find(|k| !FINDING_KEYS.contains(&k.as_str()))
        {
            return Err(bad(format!("unknown key `{k}` in a finding file (known: {})", FINDING_KEYS.join(", "))));
        }
        // The case is read from the text, not from `value`, so that its
        // errors (a wrong type, a missing field) name their line and column.
        #[derive(serde::Deserialize)]
        struct Finding {
            case: Case,
        }
        let case = match value.get("case") {
            Some(_) => serde_json::from_str::<Finding>(&text).map(|f| f.case),
            None => serde_json::from_str::<Case>(&text),
        }
        .map_err(|e| bad(e.to_string()))?;
        let gravity = |f: &Frame| f.gravity.unwrap_or([0.0; 3]);
        let first = case.frames.first().ok_or_else(|| bad("the case has no frame".into()))?;
        if case.frames.iter().any(|f| gravity(f) != gravity(first)) {
            return Err(bad("the gravity changes between frames; a lab scene has one gravity".into()));
        }
        let vertices: Vec<[f64; 3]> = case.triangles.iter().flatten().copied().collect();
        let indices = (0..case.triangles.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        let mesh = TriangleMesh::new_skipping_invalid(vertices, indices).map_err(|e| bad(e.to_string()))?;
        let name = path.file_stem().map_or_else(|| path.display().to_string(), |s| s.to_string_lossy().into_owned());
        let velocities: Vec<[f64; 3]> = case.frames.iter().map(|f| f.velocity).collect();
        let motion = if velocities.iter().all(|v| *v == velocities[0]) {
            Motion::Constant
        } else {
            Motion::Scripted { velocities: velocities.clone() }
        };
        Ok(Scene {
            name: format!("case:{name}"),
            description: format!("fuzz case {} ({} triangles)", path.display(), mesh.len()),
            mesh: Arc::new(mesh),
            start: case.start,
            radii: case.radii,
            velocity: velocities[0],
            gravity: gravity(first),
            frames: velocities.len(),
            motion,
            ideal: None,
            units_per_meter: 1.0,
        })
    }

    /// The scene moved by `offset` (geometry and start), rounded again to
    /// `f32` for built-in scenes so every backend still sees the same
    /// values (the shape may change by that rounding, about `6e-8 |offset|`).
    ///
    /// # Errors
    /// [`Error::NoValidTriangle`] (with the first reason) if the rounding
    /// at that offset collapses every triangle.
    pub fn offset(&self, offset: [f64; 3], round_to_f32: bool) -> Result<Scene, Error> {
        if offset == [0.0; 3] {
            return Ok(self.clone());
        }
        let o = Vector3::from(offset);
        let round = |v: [f64; 3]| if round_to_f32 { q3(v) } else { v };
        let mesh = Arc::new(self.mesh.moved(|v| round((v + o).into()))?);
        Ok(Scene {
            name: format!("{}@{},{},{}", self.name, offset[0], offset[1], offset[2]),
            mesh,
            start: round((Vector3::from(self.start) + o).into()),
            ..self.clone()
        })
    }

    /// The scene pushed by `velocity` per frame instead. Its ideal slide is
    /// kept, scaled by `k`, where `velocity` is `k > 0` times the scene's
    /// own up to `1e-6` of its length, the motion is constant, and either
    /// there is no gravity or the surfaces take the gravity whole (the
    /// scene's ideal is its push, and the gravity is perpendicular to it:
    /// a body walking on a floor normal to the gravity, as on
    /// `messy-floor`). A frictionless slide against fixed planes is the
    /// projection of the displacement onto a convex cone `C`, which scales
    /// with a positive factor and moves by at most as much as the
    /// displacement does, so the scaled ideal is off by at most
    /// `1e-6 |velocity|` per frame. Under gravity `g` with ideal `v`, the
    /// push itself: `v` lies in `C`, `g` in its polar cone and `v . g = 0`,
    /// which by Moreau's decomposition makes `k v` the projection of
    /// `k v + g` for every `k > 0`. Otherwise the ideal is dropped (no snag
    /// ratio is reported).
    #[must_use]
    pub fn with_velocity(self, velocity: [f64; 3]) -> Scene {
        let (old, new) = (Vector3::from(self.velocity), Vector3::from(velocity));
        let k = new.dot(&old) / old.norm_squared();
        let parallel = k > 0.0 && (new - old * k).norm() <= 1e-6 * new.norm();
        let gravity_taken = self.gravity == [0.0; 3]
            || (self.ideal == Some(self.velocity) && Vector3::from(self.gravity).dot(&old) == 0.0);
        let keeps = parallel && matches!(self.motion, Motion::Constant) && gravity_taken;
        let ideal = self.ideal.filter(|_| keeps).map(|i| i.map(|v| v * k));
        Scene { velocity, ideal, ..self }
    }

    /// The scene with a body of `radii` instead. Its ideal slide is kept
    /// only where the radii are the scene's own: another body may not fit
    /// where the scene's slides (a slot, a wedge), and an ellipsoid's
    /// slide, projected in eSpace as Fauerby's scheme does, is not the
    /// velocity's projection in world space.
    #[must_use]
    pub fn with_radii(self, radii: [f64; 3]) -> Scene {
        let ideal = self.ideal.filter(|_| radii == self.radii);
        Scene { radii, ideal, ..self }
    }
}

/// The per-run state of a motion program: the steering heading and its
/// seeded generator.
#[derive(Clone, Debug)]
pub struct Steering {
    heading: f64,
    rng: Rng,
    frame: usize,
}

impl Steering {
    /// The state at frame 0 of `scene` for `seed`.
    #[must_use]
    pub fn new(scene: &Scene, seed: u64) -> Self {
        let rng = Rng::new(seed ^ 0x57ee_0000_0000_0001);
        Steering { heading: scene.velocity[2].atan2(scene.velocity[0]), rng, frame: 0 }
    }

    /// The pushing velocity of the next frame, rounded to `f32` like the
    /// scene.
    /// A scripted velocity is returned as recorded (`f64`).
    pub fn next(&mut self, scene: &Scene) -> [f64; 3] {
        let frame = self.frame;
        self.frame += 1;
        match &scene.motion {
            Motion::Constant => scene.velocity,
            Motion::RandomWalk { turn_deg } => {
                self.heading += self.rng.range(-turn_deg, *turn_deg).to_radians();
                let [vx, vy, vz] = scene.velocity;
                let speed = vx.hypot(vz);
                q3([speed * self.heading.cos(), vy, speed * self.heading.sin()])
            }
            Motion::Scripted { velocities } => velocities.get(frame).or(velocities.last()).copied().unwrap_or([0.0; 3]),
        }
    }
}

/// The `.obj` files in `dir`, sorted by name (empty when it does not exist).
#[must_use]
pub fn meshes_in(dir: &Path) -> Vec<PathBuf> {
    files_in(dir, "obj")
}

/// The fuzz cases (`.json`, see [`Scene::from_case_file`]) in `dir`, sorted
/// by name (empty when it does not exist).
#[must_use]
pub fn cases_in(dir: &Path) -> Vec<PathBuf> {
    files_in(dir, "json")
}

fn files_in(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case(extension)))
                .collect()
        })
        .unwrap_or_default();
    found.sort();
    found
}
