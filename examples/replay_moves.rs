//! Replays the robust `f32` terrain moves of `docs/performance.md` in a
//! plain loop, for profilers: 256 consecutive on-ground frames of the
//! `terrain:224` scene (steering seed 7, from the first frame that touches
//! the ground), each replayed from its recorded start, `REPS` times. A
//! second argument names another built-in scene (`floor`, `corner:45`); a
//! third, `summed`, replays every frame the way `benches/peers` gives a
//! frame to Rapier's `move_shape` and to `frame_move/robust_f32_summed`:
//! velocity plus gravity as one displacement, in one pass. The frames are
//! not those of `benches/peers`, which steers with seed 1 (2.22 collision
//! checks per two-pass move there, 2.32 here).
//!
//! ```text
//! cargo build --release --example replay_moves
//! ./target/release/examples/replay_moves 2000      # ns per move, checks, checksum
//! valgrind --tool=callgrind --toggle-collect='*timed_loop*' \
//!     ./target/release/examples/replay_moves 20    # instructions: total / (20 * 256)
//! ./target/release/examples/replay_moves 2000 floor
//! ./target/release/examples/replay_moves 2000 terrain:224 summed
//! ```
//!
//! The checksum of the final positions tells whether a change kept the
//! results bit for bit. Times from this loop are as noisy as the machine;
//! the criterion benches (`benches/moves.rs`) are the measurement.

use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::scenes::{Steering, build};
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::World;

type F = f32;

fn main() {
    let reps: usize = match std::env::args().nth(1).map(|s| s.parse()) {
        None => 10,
        Some(Ok(n)) => n,
        Some(Err(e)) => {
            eprintln!("usage: replay_moves [REPS] [SCENE] [summed]: {e}");
            std::process::exit(2);
        }
    };
    let summed = match std::env::args().nth(3).as_deref() {
        None => false,
        Some("summed") => true,
        Some(other) => {
            eprintln!("usage: replay_moves [REPS] [SCENE] [summed]: unknown mode `{other}`");
            std::process::exit(2);
        }
    };
    let name = std::env::args().nth(2).unwrap_or_else(|| "terrain:224".into());
    let scene = build(&name, 1).unwrap_or_else(|e| {
        eprintln!("usage: replay_moves [REPS] [SCENE] [summed]: {e}");
        std::process::exit(2);
    });
    let world = World::<F>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<F>::new(scene.radii).expect("scene radii");
    let gravity: Vec3<F> = vec3(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let options = MoveOptions::new(Response::Robust);
    let mut steering = Steering::new(&scene, 7);
    let mut p: Vec3<F> = vec3(scene.start[0], scene.start[1], scene.start[2]);
    let mut inputs = Vec::with_capacity(256);
    while inputs.len() < 256 {
        let v = steering.next(&scene);
        let velocity: Vec3<F> = vec3(v[0], v[1], v[2]);
        let m = move_body(&world, &body, &p, &velocity, Some(&gravity), &options).expect("finite inputs");
        if !inputs.is_empty() || !m.trace.contacts.is_empty() {
            // Summed in `f64` and rounded once, as the bench sums them.
            let input = if summed {
                vec3(v[0] + scene.gravity[0], v[1] + scene.gravity[1], v[2] + scene.gravity[2])
            } else {
                velocity
            };
            inputs.push((p, input));
        }
        p = m.position;
    }
    let gravity = (!summed).then_some(gravity);
    let clock = std::time::Instant::now();
    let (checks, contacts, checksum) = timed_loop(reps, &inputs, &world, &body, gravity.as_ref(), &options);
    let n = (reps * inputs.len()) as f64;
    println!("checksum {checksum:016x}");
    println!(
        "{:.0} ns/move, {:.2} checks/move, {:.2} contacts/move",
        clock.elapsed().as_nanos() as f64 / n,
        checks as f64 / n,
        contacts as f64 / n
    );
}

/// The timed loop (a function of its own, for `--toggle-collect`).
#[inline(never)]
fn timed_loop(
    reps: usize,
    inputs: &[(Vec3<F>, Vec3<F>)],
    world: &World<F>,
    body: &Ellipsoid<F>,
    gravity: Option<&Vec3<F>>,
    options: &MoveOptions,
) -> (u64, usize, u64) {
    let (mut checks, mut contacts, mut checksum) = (0u64, 0usize, 0u64);
    for _ in 0..reps {
        for (p, v) in inputs {
            let m = move_body(world, body, p, v, gravity, options).expect("finite inputs");
            checks += u64::from(m.trace.iterations);
            contacts += m.trace.contacts.len();
            let bits = m.position.iter().map(|x| u64::from(x.to_bits())).sum::<u64>();
            checksum = checksum.wrapping_mul(31).wrapping_add(bits);
        }
    }
    (checks, contacts, checksum)
}
