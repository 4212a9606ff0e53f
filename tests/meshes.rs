//! The real meshes in `../shared/meshes/` (cow, fandisk, Stanford bunny,
//! teapot): they load through [`TriangleMesh::from_obj_file`] with every
//! input face accounted for (kept or skipped with a reason, printed), and
//! spheres swept down onto them with the robust detection in `f32` and
//! `f64` give sane hits: `t` in `[0, 1]`, finite, a unit normal, and for a
//! sample, a sphere that exactly touches its triangle at `t` (distance
//! computed in MPFR at 512 bits from the backend's values) without
//! overlapping any triangle at `t` or at eight earlier times.
//!
//! The meshes are not part of this repository. When the folder is absent
//! every test prints why and passes, so the crate still tests on its own.
#![cfg(feature = "mpfr")]

use rug::Float;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use sweepslide::Real;
use sweepslide::detect::{DetectOptions, Detection, sweep_world};
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::triangle_distance_sq;
use sweepslide::lab::scenes::Scene;
use sweepslide::lab::{Precision, RunConfig, run};
use sweepslide::respond::Response;
use sweepslide::world::{TriangleMesh, World};

/// Bound on `|D / r - 1|` (eSpace distance error) in units of
/// `u * s * max(1, aspect)`, with `s = max(1, |p - base|_inf / r,
/// |vel|_inf / r)` over the triangle's vertices (about the length of the
/// motion in radii, here 35 to 55) and `aspect = longest edge^2 / (2 area)`
/// (the error of a unit normal grows with it; real meshes have slivers):
/// the bound of `detect_props.rs`.
const BOUND_ULPS: f64 = 16.0;

/// `longest edge^2 / (2 area)` of a triangle (its longest edge over the
/// height on it; 1.15 for an equilateral one).
fn aspect<T: Real>(t: &sweepslide::geom::Triangle<T>) -> f64 {
    let p = [&t.a, &t.b, &t.c].map(|v| nalgebra::Vector3::new(v[0].to_f64(), v[1].to_f64(), v[2].to_f64()));
    let longest = (0..3).map(|i| (p[(i + 1) % 3] - p[i]).norm_squared()).fold(0.0, f64::max);
    longest / (p[1] - p[0]).cross(&(p[2] - p[0])).norm()
}

fn mesh_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/meshes")
}

/// Loads `name`, or explains why the test is skipped.
fn load(name: &str) -> Option<TriangleMesh> {
    let dir = mesh_dir();
    if !dir.is_dir() {
        eprintln!("SKIPPED: {} is absent (the shared test meshes are not part of this crate)", dir.display());
        return None;
    }
    let path = dir.join(format!("{name}.obj"));
    let mesh = TriangleMesh::from_obj_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
    Some(mesh)
}

/// Prints the mesh's size and its skipped faces grouped by reason, and
/// checks that every face of the file is accounted for.
fn report_loading(name: &str, mesh: &TriangleMesh, faces_in_file: usize) {
    let mut reasons: std::collections::BTreeMap<String, usize> = std::collections::BTreeMap::new();
    for e in mesh.skipped() {
        // "path:line: message": group by the message.
        let text = e.to_string();
        let message = text.rsplit(": ").next().unwrap_or(&text).to_string();
        *reasons.entry(message).or_default() += 1;
    }
    let b = mesh.bounds();
    eprintln!(
        "{name}: {} triangles kept, {} skipped; bounds {:?} .. {:?}",
        mesh.len(),
        mesh.skipped().len(),
        b.min.as_slice(),
        b.max.as_slice()
    );
    for (why, n) in &reasons {
        eprintln!("  skipped {n}: {why}");
    }
    assert_eq!(mesh.len() + mesh.skipped().len(), faces_in_file, "{name}: every face kept or skipped");
    assert!(mesh.skipped().len() * 100 < faces_in_file, "{name}: more than 1% skipped");
}

// ------------------------------------------------------ exact distance --

const PREC: u32 = 512;
type X = [Float; 3];

fn xv<T: Real>(v: &Vec3<T>) -> X {
    [0, 1, 2].map(|i| Float::with_val(PREC, v[i].to_rug()))
}

/// The exact distance from `p` to the triangle `t`: the lab's metric
/// (`lab::metrics::triangle_distance_sq`, itself checked against brute force
/// in `tests/lab.rs`), computed at the same 512 bits as this file.
fn dist_triangle(p: &X, t: &[X; 3]) -> Float {
    triangle_distance_sq(p, &t[0], &t[1], &t[2]).sqrt()
}

/// The exact centre `base + t vel`.
fn centre<T: Real>(base: &Vec3<T>, vel: &Vec3<T>, t: &Float) -> X {
    let (b, v) = (xv(base), xv(vel));
    [0, 1, 2].map(|i| Float::with_val(PREC, &b[i] + Float::with_val(PREC, &v[i] * t)))
}

// ------------------------------------------------------------ sweeping --

/// A small deterministic generator (xorshift64*), uniform in `[0, 1)`.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[derive(Default)]
struct Stats {
    sweeps: usize,
    hits: usize,
    checked: usize,
    worst_touch: f64,
    worst_overlap: f64,
}

/// Sweeps `sweeps` spheres of radius 2% of the bounding-box diagonal
/// straight down (along -y, with a little sideways drift) from above the
/// mesh, through its whole height, in backend `T`; checks every hit and,
/// for the first `exact_sample` hits, the exact distances.
fn sweep_mesh<T: Real>(name: &str, mesh: &Arc<TriangleMesh>, sweeps: usize, exact_sample: usize) -> Stats {
    let world = World::<T>::new(mesh.clone()).expect("the mesh fits the backend");
    let b = *mesh.bounds();
    let diag = (b.max - b.min).norm();
    let r = 0.02 * diag;
    let body = Ellipsoid::<T>::sphere(r).expect("valid radius");
    let opts = DetectOptions::default();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ mesh.len() as u64);
    let mut stats = Stats::default();
    let drop = (b.max.y - b.min.y) + 3.0 * r;
    let name = format!("{name} [{}]", T::name());
    for _ in 0..sweeps {
        let x = b.min.x - r + rng.next() * (b.max.x - b.min.x + 2.0 * r);
        let z = b.min.z - r + rng.next() * (b.max.z - b.min.z + 2.0 * r);
        let start = [x, b.max.y + 1.5 * r, z];
        let motion = [(rng.next() - 0.5) * 0.2 * r, -drop, (rng.next() - 0.5) * 0.2 * r];
        let (pos, vel) = (vec3::<T>(start[0], start[1], start[2]), vec3::<T>(motion[0], motion[1], motion[2]));
        stats.sweeps += 1;
        let hit = sweep_world(&world, &body, &pos, &vel, Detection::Robust, &opts).expect("finite input");
        let Some(h) = hit else { continue };
        stats.hits += 1;
        let t = h.t.to_f64();
        assert!((0.0..=1.0).contains(&t), "{name}: t = {t}");
        let finite = (0..3).all(|i| h.point[i].is_finite() && h.normal[i].is_finite());
        assert!(finite, "{name}: non-finite hit {h:?}");
        let n = (0..3).map(|i| h.normal[i].to_f64().powi(2)).sum::<f64>().sqrt();
        assert!((n - 1.0).abs() < 1e-5, "{name}: |normal| = {n}");
        assert!((h.triangle as usize) < mesh.len(), "{name}: triangle {}", h.triangle);
        assert!(!h.started_overlapping, "{name}: the start is above the mesh, yet overlapping: {h:?}");
        if stats.checked >= exact_sample {
            continue;
        }
        stats.checked += 1;
        // The exact distance to the hit triangle at t, in eSpace units.
        let tri = world.triangle(h.triangle);
        let verts = [&tri.a, &tri.b, &tri.c];
        // The motion's length dominates s (the triangles touched lie along
        // it), so one s serves every triangle checked below.
        let s = verts
            .iter()
            .flat_map(|p| (0..3).map(|i| (p[i].to_f64() - pos[i].to_f64()).abs() / r))
            .chain((0..3).map(|i| vel[i].to_f64().abs() / r))
            .fold(1.0, f64::max);
        let unit = T::unit_roundoff() * s * aspect(&tri).max(1.0);
        let exact_tri = verts.map(|p| xv(p));
        let radius = Float::with_val(PREC, body.radii()[0].to_rug());
        let t_exact = Float::with_val(PREC, h.t.to_rug());
        let d = dist_triangle(&centre(&pos, &vel, &t_exact), &exact_tri) / &radius;
        let touch = (d - 1u32).to_f64().abs() / unit;
        stats.worst_touch = stats.worst_touch.max(touch);
        assert!(
            touch <= BOUND_ULPS,
            "{name}: |D/r - 1| = {touch} u*s (u*s = {unit:e}) at t = {t}, start {start:?}, motion {motion:?}, r = {r}: {h:?}"
        );
        // No triangle overlapped at t or at eight earlier times.
        let mut near = Vec::new();
        for k in 0..=8 {
            let tk = t * k as f64 / 8.0;
            let c: Vec3<T> =
                vec3(start[0] + tk * vel[0].to_f64(), start[1] + tk * vel[1].to_f64(), start[2] + tk * vel[2].to_f64());
            let grow = T::from_f64(1.01 * r);
            let (lo, hi) = (c.map(|x| x - grow.clone()), c.map(|x| x + grow.clone()));
            world.candidates(&lo, &hi, &mut near);
            let at = centre(&pos, &vel, &Float::with_val(PREC, tk));
            for &j in &near {
                let w = world.triangle(j);
                let d = dist_triangle(&at, &[xv(&w.a), xv(&w.b), xv(&w.c)]) / &radius;
                let unit = T::unit_roundoff() * s * aspect(&w).max(1.0);
                let overlap = (1u32 - d).to_f64() / unit;
                stats.worst_overlap = stats.worst_overlap.max(overlap);
                assert!(
                    overlap <= BOUND_ULPS,
                    "{name}: at t = {tk} (hit at {t}) the sphere overlaps triangle {j} by {overlap} u*s"
                );
            }
        }
    }
    eprintln!(
        "{name}: {} sweeps, {} hits; exact checks on {}: worst |D/r - 1| = {:.2}, worst overlap = {:.2} (units of u*s*aspect)",
        stats.sweeps, stats.hits, stats.checked, stats.worst_touch, stats.worst_overlap
    );
    stats
}

fn check_mesh(name: &str, faces_in_file: usize) {
    let Some(mesh) = load(name) else { return };
    report_loading(name, &mesh, faces_in_file);
    let mesh = Arc::new(mesh);
    for stats in [sweep_mesh::<f32>(name, &mesh, 150, 12), sweep_mesh::<f64>(name, &mesh, 150, 12)] {
        assert!(stats.hits * 4 >= stats.sweeps, "{name}: only {} of {} sweeps hit", stats.hits, stats.sweeps);
    }
    check_obj_scene(name);
}

/// The lab's default scene on the mesh (the one the report and the mesh
/// benches run) measures the model, not a fall past it: the body lands and
/// spends at least a sixth of its frames within `PENETRATION_REACH` (0.05
/// radii) of it, never inside. (With a push of 0.4% of the diagonal a
/// frame, the walk left the bunny and the fandisk before touching them.
/// Until the eighteenth session "near" was looser, a triangle's box
/// meeting the body's, and the bar a fifth; the fandisk's walk is within
/// 0.05 radii in 58 of 300 frames, the cow's 83, the bunny's 105, the
/// teapot's 285.)
fn check_obj_scene(name: &str) {
    let scene = Arc::new(Scene::from_obj(&mesh_dir().join(format!("{name}.obj"))).expect("loads"));
    let config = RunConfig { scene, response: Response::Robust, detection: None, precision: Precision::F64, seed: 1 };
    let out = run(&config).expect("runs");
    let near = out.frames.iter().filter(|f| f.penetration.is_some()).count();
    eprintln!("{name}: lab scene near the model in {near} of {} frames", out.frames.len());
    assert!(near * 6 >= out.frames.len(), "{name}: near the model in only {near} of {} frames", out.frames.len());
    assert_eq!(out.result.penetrating_frames, 0, "{name}: {:?}", out.result);
}

#[test]
fn cow() {
    check_mesh("cow", 5804);
}

#[test]
fn fandisk() {
    check_mesh("fandisk", 12946);
}

#[test]
fn stanford_bunny() {
    check_mesh("stanford-bunny", 69451);
}

#[test]
fn teapot() {
    check_mesh("teapot", 6320);
}
