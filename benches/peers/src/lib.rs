//! Shared set-up for the peer comparisons: the same geometry and the same
//! moves handed to sweepslide and to Rapier's kinematic character
//! controller.
//!
//! This package is not part of the sweepslide build (its `Cargo.toml` has
//! its own `[workspace]`); it exists only to run `benches/peers.rs` and the
//! `rapier_metrics` binary.

use rapier3d::control::{CharacterLength, KinematicCharacterController};
use rapier3d::parry::shape::TriMeshFlags;
use rapier3d::prelude::{
    BroadPhaseBvh, ColliderBuilder, ColliderSet, IntegrationParameters, NarrowPhase, QueryFilter, QueryPipeline,
    RigidBodySet, Vector,
};
use std::sync::Arc;
use sweepslide::Real;
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::lab::Scene;
use sweepslide::lab::scenes::Steering;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// One frame's input: where the body starts and the pushing displacement
/// (world space, per frame). Gravity is the scene's, the same every frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameInput {
    /// Centre of the body at the start of the frame.
    pub position: [f64; 3],
    /// Pushing displacement of the frame.
    pub velocity: [f64; 3],
}

/// `frames` with the gravity added to each pushing displacement (in
/// `f64`): the one displacement per frame that Rapier's `move_shape` takes,
/// handed to sweepslide's `move_body` without a gravity pass too, so that
/// both sides get the very same input.
#[must_use]
pub fn summed(frames: &[FrameInput], gravity: [f64; 3]) -> Vec<FrameInput> {
    frames
        .iter()
        .map(|f| FrameInput { position: f.position, velocity: [0, 1, 2].map(|i| f.velocity[i] + gravity[i]) })
        .collect()
}

/// `count` consecutive frame inputs of `scene` (its start, its motion
/// program for `seed`, its gravity) taken from a trajectory played by
/// sweepslide's robust response in `T`, starting with the first frame
/// whose move touched the geometry (so a falling start is skipped and every
/// input is a realistic grounded move). The velocities do not depend on
/// `T`; the positions are `T`'s own (an `f64` trajectory rounded to `f32`
/// would start most `f32` frames embedded by the rounding).
///
/// # Panics
/// If the scene cannot be played, or the body never touches anything within
/// `count + 10_000` frames.
#[must_use]
pub fn trajectory<T: Real>(scene: &Scene, seed: u64, count: usize) -> Vec<FrameInput> {
    let world = World::<T>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<T>::new(scene.radii).expect("scene radii are valid");
    let opts = MoveOptions::new(Response::Robust);
    let v = |a: [f64; 3]| vec3::<T>(a[0], a[1], a[2]);
    let gravity = v(scene.gravity);
    let mut steering = Steering::new(scene, seed);
    let mut p = v(scene.start);
    let mut out = Vec::with_capacity(count);
    for _ in 0..count + 10_000 {
        let velocity = steering.next(scene);
        let m = move_body(&world, &body, &p, &v(velocity), Some(&gravity), &opts).expect("finite inputs");
        if !out.is_empty() || !m.trace.contacts.is_empty() {
            out.push(FrameInput { position: [0, 1, 2].map(|i| p[i].to_f64()), velocity });
            if out.len() == count {
                return out;
            }
        }
        p = m.position;
    }
    panic!("the body never touched the geometry of {}", scene.name);
}

/// `a` as a Rapier (`f32`) vector.
#[must_use]
pub fn rv(a: [f64; 3]) -> Vector {
    Vector::new(a[0] as f32, a[1] as f32, a[2] as f32)
}

/// A Rapier scene holding one fixed triangle-mesh collider: the
/// sweepslide mesh's vertices rounded to `f32` (exact for the built-in
/// scenes, whose coordinates are `f32` values) and the same triangles.
pub struct RapierScene {
    bodies: RigidBodySet,
    colliders: ColliderSet,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
}

impl RapierScene {
    /// Builds the scene from `mesh` with the given trimesh pre-processing
    /// flags.
    ///
    /// # Panics
    /// If parry rejects the mesh.
    #[must_use]
    pub fn new(mesh: &Arc<TriangleMesh>, flags: TriMeshFlags) -> Self {
        let vertices = mesh.vertices().iter().map(|v| Vector::new(v.x as f32, v.y as f32, v.z as f32)).collect();
        let indices = mesh.triangles().to_vec();
        let collider = ColliderBuilder::trimesh_with_flags(vertices, indices, flags).expect("valid trimesh").build();
        let mut colliders = ColliderSet::new();
        let handle = colliders.insert(collider);
        let bodies = RigidBodySet::new();
        let mut broad_phase = BroadPhaseBvh::new();
        let params = IntegrationParameters::default();
        broad_phase.update(&params, &colliders, &bodies, &[handle], &[], &mut Vec::new());
        RapierScene { bodies, colliders, broad_phase, narrow_phase: NarrowPhase::new() }
    }

    /// The query pipeline the character controller runs its casts on.
    #[must_use]
    pub fn query_pipeline(&self) -> QueryPipeline<'_> {
        self.broad_phase.as_query_pipeline(
            self.narrow_phase.query_dispatcher(),
            &self.bodies,
            &self.colliders,
            QueryFilter::default(),
        )
    }
}

/// How Rapier's controller is configured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RapierConfig {
    /// `KinematicCharacterController::default()`: 1% offset, slide, 45 degree
    /// climb and slide angles, snap to ground within 20% of the height.
    Default,
    /// The closest to a plain collide-and-slide: no snap to ground, no
    /// slope rules (no slope is a wall, none is non-slip: every hit slides
    /// freely along its plane), no autostep; the default offset and nudge.
    Plain,
}

impl RapierConfig {
    /// Both, in report order.
    pub const ALL: [RapierConfig; 2] = [RapierConfig::Default, RapierConfig::Plain];

    /// The controller.
    #[must_use]
    pub fn controller(self) -> KinematicCharacterController {
        let default = KinematicCharacterController::default();
        match self {
            RapierConfig::Default => default,
            RapierConfig::Plain => KinematicCharacterController {
                snap_to_ground: None,
                autostep: None,
                // `is_wall` is `angle >= max_slope_climb_angle`, and
                // `is_nonslip_slope` is `angle <= min_slope_slide_angle`,
                // with `angle` in [0, pi]: both are then always false.
                max_slope_climb_angle: f32::INFINITY,
                min_slope_slide_angle: -1.0,
                offset: CharacterLength::Relative(0.01),
                ..default
            },
        }
    }

    /// Short name for tables and bench ids.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            RapierConfig::Default => "rapier_default",
            RapierConfig::Plain => "rapier_plain",
        }
    }
}
