//! A tall ellipsoid sliding down a steep wall onto a floor it could not
//! reach in a straight line.
//!
//! Slides project eSpace displacements, so the centre's path is bounded in
//! eSpace, not in world space: an ellipsoid with radii (1, 1, 10) pushed
//! one unit along x into a wall whose eSpace normal is (1, 0, 1) / sqrt(2)
//! slides 3.6 world units down. The frame once gathered its candidates from
//! a world box grown by the world length of the moves (11.5 units below the
//! centre) and never saw the floor 12 units below: the body ended inside
//! it. The reach is now an eSpace ball (`detect::Reach`).

use std::sync::Arc;
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

#[test]
fn tall_ellipsoid_slides_down_a_steep_wall_onto_the_floor() {
    // The wall: x + z / 10 = 1.2 sqrt(2) (eSpace distance 1.2 from the
    // start); the floor: z = -12 (eSpace distance 1.2 below the start).
    let w = 1.2 * 2f64.sqrt();
    let wall_x = |z: f64| w - z / 10.0;
    let vertices = vec![
        [wall_x(-30.0), -20.0, -30.0],
        [wall_x(-30.0), 20.0, -30.0],
        [wall_x(30.0), 20.0, 30.0],
        [wall_x(30.0), -20.0, 30.0],
        [-20.0, -20.0, -12.0],
        [20.0, -20.0, -12.0],
        [20.0, 20.0, -12.0],
        [-20.0, 20.0, -12.0],
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    let world = World::<f64>::new(Arc::new(TriangleMesh::new(vertices, triangles).unwrap()))
        .expect("the mesh fits the backend");
    let body = Ellipsoid::<f64>::new([1.0, 1.0, 10.0]).unwrap();
    let start = vec3::<f64>(0.0, 0.0, 0.0);
    let m = move_body(&world, &body, &start, &vec3(1.0, 0.0, 0.0), None, &MoveOptions::new(Response::Robust)).unwrap();
    // It slid down the wall (it met the wall and then the floor)...
    assert!(m.trace.contacts.len() >= 2, "{:?}", m.trace);
    assert!(m.position.z < -1.0, "{:?}", m.position);
    // ... and stopped on the floor, not inside it.
    let depth = penetration(&world, body.radii(), &m.position).expect("near the geometry");
    assert!(depth <= 0.0, "ended {depth} radii inside, at {:?}", m.position);
    assert!(m.position.z >= -2.0 - 1e-9, "below the floor's contact height: {:?}", m.position);
}
