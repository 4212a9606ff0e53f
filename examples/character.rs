//! A character controller loop, as a game would write it: an ellipsoid
//! character walks through a small level (floor, walls, a ramp and two pillars)
//! steered by scripted input, with gravity, using the robust response in
//! `f32` and no MPFR.
//!
//! Run with `cargo run --example character`.

use std::sync::Arc;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// A level: a 20 x 20 floor, four walls, a ramp up to a ledge, two pillars.
fn level() -> Result<TriangleMesh, sweepslide::Error> {
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let mut triangles = Vec::new();
    // A quad a b c d, counter-clockwise seen from the side it faces.
    let mut quad = |q: [[f64; 3]; 4]| {
        let base = vertices.len() as u32;
        vertices.extend(q);
        triangles.push([base, base + 1, base + 2]);
        triangles.push([base, base + 2, base + 3]);
    };
    let (w, h) = (10.0, 3.0);
    quad([[-w, 0.0, -w], [-w, 0.0, w], [w, 0.0, w], [w, 0.0, -w]]); // floor, up
    quad([[-w, 0.0, -w], [w, 0.0, -w], [w, h, -w], [-w, h, -w]]); // walls, inward
    quad([[w, 0.0, w], [-w, 0.0, w], [-w, h, w], [w, h, w]]);
    quad([[-w, 0.0, w], [-w, 0.0, -w], [-w, h, -w], [-w, h, w]]);
    quad([[w, 0.0, -w], [w, 0.0, w], [w, h, w], [w, h, -w]]);
    quad([[2.0, 0.0, -2.0], [2.0, 0.0, 2.0], [6.0, 1.0, 2.0], [6.0, 1.0, -2.0]]); // ramp, up
    quad([[6.0, 1.0, -2.0], [6.0, 1.0, 2.0], [w, 1.0, 2.0], [w, 1.0, -2.0]]); // ledge, up
    for (x0, z0, x1, z1) in [(-3.0, -3.0, -2.0, -2.0), (3.0, 5.0, 4.0, 6.0)] {
        quad([[x0, 0.0, z0], [x1, 0.0, z0], [x1, h, z0], [x0, h, z0]]); // pillar, outward
        quad([[x1, 0.0, z1], [x0, 0.0, z1], [x0, h, z1], [x1, h, z1]]);
        quad([[x0, 0.0, z1], [x0, 0.0, z0], [x0, h, z0], [x0, h, z1]]);
        quad([[x1, 0.0, z0], [x1, 0.0, z1], [x1, h, z1], [x1, h, z0]]);
    }
    TriangleMesh::new(vertices, triangles)
}

fn main() -> Result<(), sweepslide::Error> {
    let world = World::<f32>::new(Arc::new(level()?))?;
    let body = Ellipsoid::<f32>::new([0.4, 0.9, 0.4])?;
    let options = MoveOptions::new(Response::Robust);
    let dt: f32 = 1.0 / 60.0;
    let speed: f32 = 4.0; // metres per second
    let gravity: Vec3<f32> = vec3(0.0, -9.81 * f64::from(dt) * f64::from(dt) * 30.0, 0.0); // a firm push down each frame
    let mut position: Vec3<f32> = vec3(-6.0, 0.95, 0.5);
    // Scripted input: walk east up the ramp, then north into the wall, then
    // west around the pillar.
    let inputs = [(240, [1.0f32, 0.0, 0.0]), (120, [0.0, 0.0, 1.0]), (240, [-1.0, 0.0, -0.7])];
    let mut frame = 0;
    for (frames, dir) in inputs {
        for _ in 0..frames {
            let velocity: Vec3<f32> = Vec3::from(dir).normalize() * (speed * dt);
            let step = move_body(&world, &body, &position, &velocity, Some(&gravity), &options)?;
            position = step.position;
            if frame % 60 == 0 {
                println!(
                    "t={:4.1}s  position ({:7.3}, {:6.3}, {:7.3})  checks {}  {:?}",
                    frame as f32 * dt,
                    position.x,
                    position.y,
                    position.z,
                    step.trace.iterations,
                    step.trace.stop
                );
            }
            frame += 1;
        }
    }
    println!("final position ({:.3}, {:.3}, {:.3})", position.x, position.y, position.z);
    Ok(())
}
