//! Everything one rapier simulation needs, in one place, and the single call that is timed.

use rapier3d::prelude::*;

/// Gravity of every scene except `springs`.
pub const GRAVITY: Vector = Vector::new(0.0, -9.81, 0.0);

/// A rapier3d world: the sets, the pipeline's persistent state and the parameters it steps with.
///
/// The parameters are `IntegrationParameters::default()` (dt = 1/60) and are never changed, so every scene
/// runs on rapier's defaults.
pub struct World {
    /// Gravity applied to every dynamic body.
    pub gravity: Vector,
    /// Solver and collision settings: rapier's defaults.
    pub params: IntegrationParameters,
    /// The stepping pipeline (holds the solver's scratch buffers between steps).
    pub pipeline: PhysicsPipeline,
    /// Active/sleeping islands.
    pub islands: IslandManager,
    /// Broad phase (BVH).
    pub broad_phase: BroadPhaseBvh,
    /// Narrow phase: the contact pairs.
    pub narrow_phase: NarrowPhase,
    /// All rigid bodies, fixed ones included.
    pub bodies: RigidBodySet,
    /// All colliders.
    pub colliders: ColliderSet,
    /// The joints solved by the impulse solver (all joints of these scenes).
    pub impulse_joints: ImpulseJointSet,
    /// Reduced-coordinate joints: unused, but `step` needs the set.
    pub multibody_joints: MultibodyJointSet,
    /// Soft bodies: unused, but `step` needs the set.
    pub soft_bodies: SoftBodySet,
    /// Continuous collision detection state.
    pub ccd_solver: CCDSolver,
}

impl World {
    /// An empty world with the given gravity and rapier's default integration parameters.
    pub fn new(gravity: Vector) -> Self {
        Self {
            gravity,
            params: IntegrationParameters::default(),
            pipeline: PhysicsPipeline::new(),
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd_solver: CCDSolver::new(),
        }
    }

    /// Inserts `body` with `collider` attached (if any) and returns the body's handle.
    pub fn add_body(
        &mut self,
        body: impl Into<RigidBody>,
        collider: Option<Collider>,
    ) -> RigidBodyHandle {
        let handle = self.bodies.insert(body);
        if let Some(collider) = collider {
            self.colliders
                .insert_with_parent(collider, handle, &mut self.bodies);
        }
        handle
    }

    /// Inserts an impulse joint between `body1` and `body2`.
    pub fn add_joint(
        &mut self,
        body1: RigidBodyHandle,
        body2: RigidBodyHandle,
        joint: impl Into<GenericJoint>,
    ) {
        self.impulse_joints.insert(body1, body2, joint, true);
    }

    /// One `PhysicsPipeline::step` of `params.dt`, without hooks or events: the call the benchmark times.
    pub fn step(&mut self) {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd_solver,
            &(),
            &(),
        );
    }

    /// Number of dynamic bodies (the "bodies" column of docs/scenes.md: fixed ground and anchors are not counted).
    pub fn dynamic_body_count(&self) -> usize {
        self.bodies.iter().filter(|(_, b)| b.is_dynamic()).count()
    }

    /// Number of joints.
    pub fn joint_count(&self) -> usize {
        self.impulse_joints.len()
    }

    /// Centre (translation) of a body.
    pub fn pos(&self, handle: RigidBodyHandle) -> Vector {
        self.bodies[handle].translation()
    }
}
