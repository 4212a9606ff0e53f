//! Rapier's kinematic character controller measured with sweepslide's exact
//! metrics, next to sweepslide's three responses, on the lab's `corner`,
//! `wedge` and `crease` scenes (seed 1, the scenes' own start, radius,
//! per-frame velocity and frame count), and on the bench's `terrain:224`
//! (a 0.5 ball dropped from 2 m above the ground, steered by the scene's
//! random walk at 5 m/s with gravity, 300 frames, closed loop: each side
//! follows its own trajectory).
//!
//! Rapier's trajectory is played in `f32` (rapier3d is an `f32` engine);
//! every position it reaches is exact in `f64`, and the metrics
//! (`penetration` at each frame through a `World<f64>` of the same mesh,
//! `jitter` over the trajectory, `snag_ratio`) are the lab's own, computed
//! at 512 bits. sweepslide's rows come from `sweepslide::lab::run`.
//!
//! Rapier gets velocity + gravity as one desired translation per frame
//! (it has no second pass). The `ns/move` column is one single-threaded
//! wall-clock pass on a shared machine: indicative only; the bench is the
//! timing reference.
//!
//! A last table replays the 256 `terrain:224` frame inputs of the
//! `frame_move` bench (open loop: every frame from our trajectory's start)
//! and compares where Rapier and our robust f32 response end, the latter
//! both in its two passes and given Rapier's one summed displacement.
//!
//! Prints markdown tables. Run:
//! `cargo run --release --manifest-path benches/peers/Cargo.toml --bin rapier_metrics`

use rapier3d::parry::shape::{Ball, TriMeshFlags};
use rapier3d::prelude::{Pose, Vector};
use std::sync::Arc;
use std::time::Instant;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::{jitter, penetration, snag_ratio};
use sweepslide::lab::scenes::{Steering, build};
use sweepslide::lab::{Precision, RunConfig, Scene, run};
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::World;
use sweepslide_peers::{FrameInput, RapierConfig, RapierScene, rv, summed, trajectory};

/// One row of the table.
struct Row {
    method: String,
    precision: &'static str,
    frames: usize,
    max_penetration: f64,
    penetrating_frames: usize,
    first_penetrating_frame: Option<usize>,
    nan_frames: usize,
    jitter: f64,
    snag: Option<f64>,
    final_position: [f64; 3],
    ns_per_move: f64,
}

fn f64v(v: Vector) -> [f64; 3] {
    [f64::from(v.x), f64::from(v.y), f64::from(v.z)]
}

/// The speed the lab's runner divides jitter by.
fn speed(scene: &Scene) -> f64 {
    let v = if scene.velocity == [0.0; 3] { scene.gravity } else { scene.velocity };
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn rapier_row(scene: &Scene, config: RapierConfig, flags: TriMeshFlags, label: &str) -> Row {
    assert!(scene.radii.iter().all(|r| *r == scene.radii[0]), "Rapier's ball needs a sphere");
    let rapier = RapierScene::new(&scene.mesh, flags);
    let queries = rapier.query_pipeline();
    let controller = config.controller();
    let ball = Ball::new(scene.radii[0] as f32);
    let mut steering = Steering::new(scene, 1);
    let mut p = rv(scene.start);
    let start = f64v(p);
    let mut positions = vec![start];
    let mut ns = 0u128;
    let mut nan_frames = 0;
    for k in 0..scene.frames {
        let v = steering.next(scene);
        let d = rv([0, 1, 2].map(|i| v[i] + scene.gravity[i]));
        let clock = Instant::now();
        let m = controller.move_shape(1.0 / 60.0, &queries, &ball, &Pose::from_translation(p), d, |_| {});
        ns += clock.elapsed().as_nanos();
        p += m.translation;
        positions.push(f64v(p));
        if !p.is_finite() {
            nan_frames = scene.frames - k;
            break;
        }
    }
    let world = World::<f64>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let radii: Vec3<f64> = vec3(scene.radii[0], scene.radii[1], scene.radii[2]);
    let trajectory: Vec<Vec3<f64>> = positions.iter().map(|q| vec3(q[0], q[1], q[2])).collect();
    let (mut max_pen, mut pen_frames, mut first) = (0.0f64, 0, None);
    for (k, q) in trajectory.iter().enumerate().skip(1) {
        if let Some(d) = penetration(&world, &radii, q).filter(|d| *d > 0.0) {
            max_pen = max_pen.max(d);
            pen_frames += 1;
            first.get_or_insert(k - 1);
        }
    }
    let end = trajectory.last().expect("start is there");
    Row {
        method: format!("{}{label}", config.name()),
        precision: "f32",
        frames: scene.frames,
        max_penetration: max_pen,
        penetrating_frames: pen_frames,
        first_penetrating_frame: first,
        nan_frames,
        jitter: jitter(&trajectory, speed(scene)),
        snag: scene.ideal.and_then(|ideal| snag_ratio(&trajectory[0], end, ideal, scene.frames)),
        final_position: *positions.last().expect("start is there"),
        ns_per_move: ns as f64 / (positions.len() - 1).max(1) as f64,
    }
}

fn our_row(scene: &Arc<Scene>, response: Response, precision: Precision) -> Row {
    let cfg = RunConfig { scene: scene.clone(), response, detection: None, precision, seed: 1 };
    let r = run(&cfg).expect("the lab runs its own scenes").result;
    Row {
        method: response.name().to_string(),
        precision: if precision == Precision::F32 { "f32" } else { "f64" },
        frames: r.frames,
        max_penetration: r.max_penetration,
        penetrating_frames: r.penetrating_frames,
        first_penetrating_frame: r.first_penetrating_frame,
        nan_frames: r.nan_frames,
        jitter: r.jitter,
        snag: r.snag,
        final_position: r.final_position,
        ns_per_move: r.ns_per_move,
    }
}

fn print_table(scene: &str, rows: &[Row]) {
    println!("\n### {scene}\n");
    println!(
        "| method | prec | frames | max penetration | penetrating frames | first | NaN frames | jitter | snag | final position | ns/move |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|");
    for r in rows {
        let first = r.first_penetrating_frame.map_or_else(|| "-".to_string(), |f| f.to_string());
        let snag = r.snag.map_or_else(|| "-".to_string(), |s| format!("{s:.4}"));
        let [x, y, z] = r.final_position;
        println!(
            "| {} | {} | {} | {:.3e} | {} | {} | {} | {:.3e} | {} | ({x:.4}, {y:.4}, {z:.4}) | {:.0} |",
            r.method,
            r.precision,
            r.frames,
            r.max_penetration,
            r.penetrating_frames,
            first,
            r.nan_frames,
            r.jitter,
            snag,
            r.ns_per_move
        );
    }
}

/// Open-loop comparison on the bench's terrain inputs.
fn terrain_agreement() {
    let scene = build("terrain:224", 1).expect("terrain scene");
    let frames = trajectory::<f32>(&scene, 1, 256);
    let world32 = World::<f32>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let world64 = World::<f64>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<f32>::new(scene.radii).expect("valid radii");
    let radii: Vec3<f64> = vec3(scene.radii[0], scene.radii[1], scene.radii[2]);
    let gravity: Vec3<f32> = vec3(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let opts = MoveOptions::new(Response::Robust);
    let rapier = RapierScene::new(&scene.mesh, TriMeshFlags::empty());
    let queries = rapier.query_pipeline();
    let ball = Ball::new(scene.radii[0] as f32);
    // Our robust f32 move over `inputs` (with `gravity` as a second pass,
    // or none): the end positions, collision checks and contacts.
    let replay = |inputs: &[FrameInput], gravity: Option<&Vec3<f32>>| {
        let (mut checks, mut contacts) = (0u64, 0usize);
        let ends: Vec<[f64; 3]> = inputs
            .iter()
            .map(|f| {
                let p: Vec3<f32> = vec3(f.position[0], f.position[1], f.position[2]);
                let v: Vec3<f32> = vec3(f.velocity[0], f.velocity[1], f.velocity[2]);
                let m = move_body(&world32, &body, &p, &v, gravity, &opts).expect("finite inputs");
                checks += u64::from(m.trace.iterations);
                contacts += m.trace.contacts.len();
                [0, 1, 2].map(|i| f64::from(m.position[i]))
            })
            .collect();
        (ends, checks, contacts)
    };
    let (ours, checks, contacts) = replay(&frames, Some(&gravity));
    // The box `move_body` gathers its candidates in: everywhere the body
    // reaches by the velocity then gravity, grown by 5%.
    let mut scratch = Vec::new();
    let candidates: usize = frames
        .iter()
        .map(|f| {
            let p: Vec3<f32> = vec3(f.position[0], f.position[1], f.position[2]);
            let v: Vec3<f32> = vec3(f.velocity[0], f.velocity[1], f.velocity[2]);
            let corners = [p, p + v, p + gravity, p + v + gravity];
            let grow = body.radii() * 1.05;
            let lo = Vec3::from_fn(|i, _| corners.iter().map(|c| c[i]).fold(f32::INFINITY, f32::min) - grow[i]);
            let hi = Vec3::from_fn(|i, _| corners.iter().map(|c| c[i]).fold(f32::NEG_INFINITY, f32::max) + grow[i]);
            world32.candidates(&lo, &hi, &mut scratch);
            scratch.len()
        })
        .sum();
    let n = frames.len() as f64;
    println!("\n### terrain:224, the 256 `frame_move` inputs, open loop\n");
    println!(
        "Per frame, robust f32: {:.1} candidate triangles gathered, {:.2} collision checks (each sweeps every \
         candidate whose box meets the swept box), {:.2} contacts.\n",
        candidates as f64 / n,
        checks as f64 / n,
        contacts as f64 / n
    );
    println!(
        "Distance from our robust f32 end position; penetration measured exactly at each end position; clearance \
         is minus the penetration (the gap to the nearest triangle), median over the frames with a triangle within \
         reach.\n"
    );
    println!(
        "| method | mean distance to robust f32 | max distance | max penetration | penetrating frames | median clearance |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    let report = |name: &str, ends: &[[f64; 3]]| {
        let dist: Vec<f64> = ends
            .iter()
            .zip(&ours)
            .map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt())
            .collect();
        let pens: Vec<f64> =
            ends.iter().filter_map(|q| penetration(&world64, &radii, &vec3(q[0], q[1], q[2]))).collect();
        let max_pen = pens.iter().copied().fold(0.0, f64::max);
        let pen_frames = pens.iter().filter(|d| **d > 0.0).count();
        let mut clearance: Vec<f64> = pens.iter().map(|d| -d).collect();
        clearance.sort_by(f64::total_cmp);
        let gap = clearance.get(clearance.len() / 2).copied().unwrap_or(f64::NAN);
        println!(
            "| {name} | {:.3e} | {:.3e} | {:.3e} | {pen_frames} | {gap:.3e} |",
            dist.iter().sum::<f64>() / dist.len() as f64,
            dist.iter().copied().fold(0.0, f64::max),
            max_pen
        );
    };
    report("robust f32", &ours);
    // Rapier's input: velocity + gravity in one pass.
    let (one_pass, summed_checks, summed_contacts) = replay(&summed(&frames, scene.gravity), None);
    report("robust f32, summed (one pass)", &one_pass);
    let mut rapier_hits = Vec::new();
    for config in RapierConfig::ALL {
        let controller = config.controller();
        let mut hits = 0usize;
        let ends: Vec<[f64; 3]> = frames
            .iter()
            .map(|f| {
                let p = rv(f.position);
                let d = rv([0, 1, 2].map(|i| f.velocity[i] + scene.gravity[i]));
                let m =
                    controller.move_shape(1.0 / 60.0, &queries, &ball, &Pose::from_translation(p), d, |_| hits += 1);
                f64v(p + m.translation)
            })
            .collect();
        report(config.name(), &ends);
        rapier_hits.push((config.name(), hits as f64 / n));
    }
    println!(
        "\nRobust f32 given velocity + gravity in one pass (Rapier's input): {:.2} collision checks, {:.2} contacts \
         per frame.",
        summed_checks as f64 / n,
        summed_contacts as f64 / n
    );
    for (name, hits) in rapier_hits {
        println!("{name}: {hits:.2} shape-cast hits (collision events) per frame.");
    }
}

fn main() {
    for name in ["corner", "wedge", "crease", "terrain:224"] {
        let scene = Arc::new(build(name, 1).expect("built-in scene"));
        let mut rows = Vec::new();
        for response in Response::ALL {
            for precision in [Precision::F32, Precision::F64] {
                rows.push(our_row(&scene, response, precision));
            }
        }
        for config in RapierConfig::ALL {
            rows.push(rapier_row(&scene, config, TriMeshFlags::empty(), ""));
        }
        rows.push(rapier_row(&scene, RapierConfig::Default, TriMeshFlags::FIX_INTERNAL_EDGES, "+fix_internal_edges"));
        print_table(&scene.name, &rows);
    }
    terrain_agreement();
}
