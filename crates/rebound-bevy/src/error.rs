//! [`PhysicsError`]: why the plugin refused a component value. Each one is logged (`log::error!`, which
//! Bevy's `LogPlugin` shows) and sent as a message; the physics world is left as it was. Produced by the
//! prepare systems; never a panic.

use bevy_ecs::entity::Entity;
use bevy_ecs::message::Message;

/// A component value the physics world refused. The world is unchanged by the refused value; the
/// component is tried again when it next changes.
#[derive(Message, Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PhysicsError {
    /// The engine refused a component's value (its error names the field and the value).
    #[error("entity {entity}: `{component}` refused: {source}")]
    Refused {
        /// The entity holding the component.
        entity: Entity,
        /// The component (`"Body"`, `"Transform"`, `"Velocity"`, `"Collider"`, `"PhysicsJoint"`, …).
        component: &'static str,
        /// What the engine said.
        source: rebound::Error,
    },
    /// A [`crate::Body`]'s description sets a field that another component of the entity gives (the pose
    /// is the `Transform`, the velocities the `Velocity`, ...); the body is not inserted or edited.
    #[error(
        "entity {entity}: `Body.desc.{field}` is {value}; a body's {field} comes from its `{component}` (leave the description's at its default)"
    )]
    BodyField {
        /// The body entity.
        entity: Entity,
        /// The description's field (`"position"`, `"rotation"`, `"linear_velocity"`,
        /// `"angular_velocity"`, `"sleeping"`, `"mass_properties"`).
        field: &'static str,
        /// Its value.
        value: String,
        /// The component that gives it (`"Transform"`, `"Velocity"`, `"Sleeping"`, `"MassOverride"`).
        component: &'static str,
    },
    /// A joint names an entity that has no [`crate::Body`] (or does not exist).
    #[error("entity {entity}: `PhysicsJoint.{field}` names entity {target}, which has no `Body`")]
    NotABody {
        /// The entity holding the joint.
        entity: Entity,
        /// `"body_a"` or `"body_b"`.
        field: &'static str,
        /// The entity named.
        target: Entity,
    },
    /// The settings resource holds invalid world settings; the previous ones stay in force.
    #[error("`PhysicsSettings.world` refused: {0}")]
    Settings(rebound::Error),
}

impl PhysicsError {
    /// A refused component value.
    pub(crate) fn refused(
        entity: Entity,
        component: &'static str,
        source: impl Into<rebound::Error>,
    ) -> Self {
        Self::Refused {
            entity,
            component,
            source: source.into(),
        }
    }
}
