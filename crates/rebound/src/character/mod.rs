//! A kinematic character controller: moves a convex shape (a capsule, usually) by a desired translation and
//! returns the corrected one. Not a step stage: call it between steps, then move the character's kinematic
//! body by the result (`PhysicsWorld::set_kinematic_target`) and step.
//!
//! A move runs these phases, one per file:
//!
//! 1. [`ground`]: is the shape on walkable ground at the start (steps and snapping need it);
//! 2. [`slide`]: cast along the desired translation, stop `skin` short, turn the rest along the surface —
//!    up walkable slopes, along walls, down steep slopes — climbing steps on the way ([`autostep`]); then
//!    [`skin`]: push the shape back out to `skin` from anything it ended too close to;
//! 3. [`snap`]: pull a grounded, not rising character down onto the ground within `snap_to_ground`;
//! 4. [`ground`] again: what it stands on now (reported);
//! 5. [`platform`]: add the motion of the body it stands on.
//!
//! Pushing dynamic bodies is a separate call ([`CharacterController::push_bodies`]), since it changes the
//! world. The geometry is in `docs/physics.md`, "Character controller".
//!
//! Known limitations: the shape does not rotate (an upright capsule stays upright; a platform's spin is not
//! passed on), and a shape overlapping a collider deeply is pushed out by at most four `skin`-sized steps per
//! move.

mod autostep;
mod collision;
mod ground;
mod platform;
mod push;
mod settings;
mod skin;
mod slide;
mod snap;
mod sweep;

pub use collision::{CharacterCollision, CharacterMove};
pub use ground::Ground;
pub use push::CharacterPush;
pub use settings::{Autostep, CharacterError, CharacterSettings, MAX_SLIDE_ITERATIONS, Push};

use crate::shape::check_pose;
use crate::{
    ColliderHandle, ColliderShape, Error, MAX_SHAPE_COORDINATE, PhysicsWorld, QueryFilter,
};
use parry3d::shape::Shape;
use rebound_math::validity::{check_finite_vec3, check_positive};
use rebound_math::{MathError, Pose, Vec3};
use sweep::Probe;

/// Moves character shapes through a [`PhysicsWorld`] with validated [`CharacterSettings`]: slides along
/// walls, climbs walkable slopes at the commanded horizontal speed and slides down steeper ones, climbs steps
/// (autostep), snaps down onto the ground, keeps a `skin` off every surface, reports the ground and the
/// collisions, carries the character with a moving platform, and pushes dynamic bodies
/// ([`CharacterController::push_bodies`]). Not a step stage: call it between steps, then move the character's
/// kinematic body by the result. Holds no state between moves: the same call on the same world gives the
/// same, bit-identical, result. The geometry is in `docs/physics.md`, "Character controller".
///
/// # Examples
///
/// ```
/// use rebound::prelude::*;
///
/// let mut world = PhysicsWorld::new(WorldSettings::default())?;
/// let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))?;
/// world.insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)?;
/// let wall = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(2.0, 1.0, 0.0)))?;
/// world.insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 1.0, 5.0)), wall)?;
///
/// let controller = CharacterController::default();
/// let capsule = ColliderShape::Capsule { radius: 0.3, half_height: 0.5 };
/// let pose = Pose::from_position(Vec3::new(0.0, 0.81, 0.0));
/// // Three metres towards the wall, whose face is at x = 1.5: the capsule stops `skin` short of it.
/// let moved = controller.move_shape(&world, &capsule, pose, Vec3::new(3.0, 0.0, 0.0), 1.0 / 60.0,
///     &QueryFilter::new())?;
/// let x = pose.position.x + moved.translation.x;
/// assert!((x - (1.5 - 0.3 - 0.01)).abs() < 1e-3, "{x}");
/// assert!(moved.is_grounded());
/// # Ok::<(), rebound::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CharacterController {
    settings: CharacterSettings,
}

impl CharacterController {
    /// A controller with `settings`.
    ///
    /// # Errors
    /// Invalid settings ([`CharacterSettings::validate`]), as [`Error::Character`].
    pub fn new(settings: CharacterSettings) -> Result<Self, Error> {
        settings.validate()?;
        Ok(Self { settings })
    }

    /// The settings.
    #[must_use]
    pub const fn settings(&self) -> &CharacterSettings {
        &self.settings
    }

    /// Replaces the settings.
    ///
    /// # Errors
    /// Invalid settings; the old ones stay.
    pub fn set_settings(&mut self, settings: CharacterSettings) -> Result<(), Error> {
        settings.validate()?;
        self.settings = settings;
        Ok(())
    }

    /// Moves `shape`, placed at `pose`, by `desired_translation` (m) through `world`'s colliders that
    /// `filter` lets through, over `dt` (s, used for carrying and pushing). The shape keeps its rotation.
    /// Sensors are never obstacles, whatever the filter says.
    ///
    /// # Errors
    /// A shape that is not convex or not valid, an invalid pose, a non-finite translation or one longer than
    /// [`MAX_SHAPE_COORDINATE`], a `dt` that is not finite and > 0.
    pub fn move_shape(
        &self,
        world: &PhysicsWorld,
        shape: &ColliderShape,
        pose: Pose,
        desired_translation: Vec3,
        dt: f32,
        filter: &QueryFilter,
    ) -> Result<CharacterMove, Error> {
        if !shape.is_convex() {
            return Err(CharacterError::NonConvexShape {
                kind: shape.kind_name(),
            }
            .into());
        }
        let shape = shape.to_parry()?;
        self.run(world, shape.as_ref(), pose, desired_translation, dt, filter)
    }

    /// Moves the collider `collider` (its shape at its body's pose) by `desired_translation` (m) over `dt`
    /// (s); the colliders of its own body are ignored (`filter.exclude_body` is replaced). Move the body by
    /// the result's `translation`.
    ///
    /// # Errors
    /// A stale collider, one whose shape is not convex, and the errors of
    /// [`CharacterController::move_shape`].
    pub fn move_collider(
        &self,
        world: &PhysicsWorld,
        collider: ColliderHandle,
        desired_translation: Vec3,
        dt: f32,
        filter: &QueryFilter,
    ) -> Result<CharacterMove, Error> {
        let found = world
            .collider(collider)
            .ok_or(Error::StaleCollider(collider))?;
        if !found.desc().shape.is_convex() {
            return Err(CharacterError::NonConvexShape {
                kind: found.desc().shape.kind_name(),
            }
            .into());
        }
        let body = world
            .body(found.body())
            .ok_or(Error::StaleCollider(collider))?;
        let pose = found.world_pose(body.pose());
        let filter = filter.excluding_body(found.body());
        self.run(
            world,
            found.shape().as_ref(),
            pose,
            desired_translation,
            dt,
            &filter,
        )
    }

    /// Gives the dynamic bodies `moved` ran into the impulses that push them along at the character's desired
    /// velocity ([`Push`]; nothing when [`CharacterSettings::push`] is `None`), and returns them.
    ///
    /// # Errors
    /// An impulse the world refuses (one that would make a velocity non-finite); the pushes before it stay.
    pub fn push_bodies(
        &self,
        world: &mut PhysicsWorld,
        moved: &CharacterMove,
    ) -> Result<Vec<CharacterPush>, Error> {
        match &self.settings.push {
            Some(push) if moved.dt > 0.0 => push::push_bodies(world, push, moved),
            _ => Ok(Vec::new()),
        }
    }

    fn run(
        &self,
        world: &PhysicsWorld,
        shape: &dyn Shape,
        pose: Pose,
        desired: Vec3,
        dt: f32,
        filter: &QueryFilter,
    ) -> Result<CharacterMove, Error> {
        let pose = check_pose("pose", pose)?;
        check_finite_vec3("desired_translation", desired)?;
        if desired.length() > MAX_SHAPE_COORDINATE {
            return Err(CharacterError::TooLong {
                value: desired,
                max: MAX_SHAPE_COORDINATE,
            }
            .into());
        }
        if !dt.is_finite() {
            return Err(MathError::NonFinite {
                field: "dt",
                value: dt,
            }
            .into());
        }
        check_positive("dt", dt)?;
        let settings = &self.settings;
        let probe = Probe {
            scene: world.scene(),
            shape,
            rotation: pose.rotation,
            filter: filter.excluding_sensors(),
            settings,
        };
        let start = pose.position;
        let ground_at_start = ground::detect(&probe, start);
        let grounded_at_start = ground_at_start.is_some();
        let mut collisions = Vec::new();
        let slid = slide::slide(
            &probe,
            start,
            desired,
            ground_at_start.map(|g| g.point),
            &mut collisions,
        );
        let mut position = skin::restore(&probe, slid.position);
        let mut ground = ground::detect(&probe, position);
        let mut snapped = false;
        let was_grounded = grounded_at_start || slid.touched_ground;
        let snap = settings
            .snap_to_ground
            .filter(|_| was_grounded && desired.dot(settings.up) <= 0.0)
            .and_then(|distance| snap::snap(&probe, position, distance));
        if let Some((snapped_to, under)) = snap {
            snapped = snapped_to != position;
            position = snapped_to;
            ground = Some(under);
        }
        let carried = match &ground {
            Some(under) if settings.carry_with_ground => {
                platform::carry(&probe, position, under, dt)
            }
            _ => Vec3::ZERO,
        };
        position += carried;
        Ok(CharacterMove {
            translation: position - start,
            desired_translation: desired,
            dt,
            ground,
            stepped: slid.stepped,
            snapped,
            carried,
            collisions,
        })
    }
}
