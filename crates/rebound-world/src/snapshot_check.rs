//! The check of a snapshot before [`crate::World::restore`] trusts it: every value the step would read, as
//! the constructors and setters that made it would have checked it, and every handle it holds resolved
//! within the snapshot. A deserialised snapshot bypassed all of them. Not a step stage.
//!
//! The first failure is returned as [`WorldError::InvalidSnapshot`]: where in the snapshot (`item`, such as
//! `body 3` or `manifold 0, point 1`) and the typed error that names the field and the value.

use crate::body_set::NO_ISLAND;
use crate::error::WorldError;
use crate::handles::BodyHandle;
use crate::manifold::{ContactManifold, MAX_MANIFOLD_POINTS};
use crate::state::WorldState;
use rebound_constraints::KeptRows;
use rebound_math::Pose;
use rebound_math::validity::{check_finite, check_finite_vec3, check_non_negative, check_rotation};

/// `Err(InvalidSnapshot)` for `item` from any error of the world's kind.
fn at<T, E: Into<WorldError>>(
    item: impl FnOnce() -> String,
    result: Result<T, E>,
) -> Result<T, WorldError> {
    result.map_err(|error| WorldError::InvalidSnapshot {
        item: item(),
        source: Box::new(error.into()),
    })
}

/// A body handle of the snapshot that resolves to one of its bodies.
fn check_body(state: &WorldState, handle: BodyHandle) -> Result<BodyHandle, WorldError> {
    if state.bodies.contains(handle) {
        Ok(handle)
    } else {
        Err(WorldError::StaleBody(handle))
    }
}

/// Checks everything [`crate::World::restore`] copies in: settings, handle tables, bodies and their
/// bookkeeping, joints and their states, manifolds, islands, the accumulator and the joint
/// solver's kept rows.
///
/// # Errors
/// The first invalid item, as [`WorldError::InvalidSnapshot`].
pub(crate) fn check_state(state: &WorldState, joint_rows: &KeptRows) -> Result<(), WorldError> {
    at(|| "settings".into(), state.settings.validate())?;
    if !state.bodies.arena.is_consistent() {
        return Err(WorldError::BadSnapshot("the body table is inconsistent"));
    }
    if !state.joints.is_consistent() {
        return Err(WorldError::BadSnapshot("the joint table is inconsistent"));
    }
    for (index, entry) in state.bodies.arena.iter() {
        let item = || format!("body {}", index.index);
        at(item, entry.body.clone().validated())?;
        at(item, check_non_negative("sleep_time", entry.sleep_time))?;
        if entry.island != NO_ISLAND && !state.islands.contains_key(&entry.island) {
            return Err(WorldError::BadSnapshot(
                "a body names a sleeping island that does not exist",
            ));
        }
        if let Some(target) = entry.kinematic_target {
            at(item, Pose::try_new(target.position, target.rotation))?;
        }
    }
    for (index, entry) in state.joints.iter() {
        let item = || format!("joint {}", index.index);
        at(item, entry.joint.validated())?;
        at(item, entry.state.validated())?;
        at(item, check_body(state, entry.body_b))?;
        if let Some(a) = entry.body_a {
            at(item, check_body(state, a))?;
            if a == entry.body_b {
                return at(item, Err(WorldError::SameBody(a)));
            }
        }
    }
    for (i, manifold) in state.manifolds.iter().enumerate() {
        check_manifold(state, i, manifold)?;
    }
    // The touching pairs may name removed bodies: the next step reports their contacts as ended.
    for (island, bodies) in &state.islands {
        for &body in bodies {
            at(|| format!("island {island}"), check_body(state, body))?;
        }
    }
    at(
        || "world".into(),
        check_non_negative("accumulator", state.accumulator),
    )?;
    if !joint_rows.is_valid() {
        return Err(WorldError::BadSnapshot("invalid kept joint rows"));
    }
    Ok(())
}

/// A stored manifold: bodies that exist, a finite unit normal, finite non-negative coefficients, and each
/// point's anchors, separation, impulses and lever arms finite (warm starting feeds the impulses back).
fn check_manifold(state: &WorldState, i: usize, m: &ContactManifold) -> Result<(), WorldError> {
    let item = || format!("manifold {i}");
    at(item, check_body(state, m.body_a))?;
    at(item, check_body(state, m.body_b))?;
    if m.body_a == m.body_b {
        return at(item, Err(WorldError::SameBody(m.body_a)));
    }
    if m.point_count > MAX_MANIFOLD_POINTS {
        return at(
            item,
            Err(WorldError::SettingOutOfRange {
                field: "point_count",
                value: m.point_count as f32,
                min: 0.0,
                max: MAX_MANIFOLD_POINTS as f32,
            }),
        );
    }
    at(
        item,
        rebound_math::validity::check_unit_vec3("normal", m.normal),
    )?;
    at(item, check_non_negative("friction", m.friction))?;
    at(item, check_non_negative("restitution", m.restitution))?;
    at(
        item,
        check_non_negative("rolling_friction", m.rolling_friction),
    )?;
    if let Some(basis) = m.basis {
        at(item, check_rotation("basis.rotation", basis.rotation))?;
        at(
            item,
            check_finite_vec3("basis.translation", basis.translation),
        )?;
        at(
            item,
            check_finite_vec3("basis.local_normal", basis.local_normal),
        )?;
    }
    for (j, p) in m.points().iter().enumerate() {
        let item = || format!("manifold {i}, point {j}");
        at(item, check_finite_vec3("local_anchor_a", p.local_anchor_a))?;
        at(item, check_finite_vec3("local_anchor_b", p.local_anchor_b))?;
        at(item, check_finite("separation", p.separation))?;
        at(item, check_finite("normal_impulse", p.normal_impulse))?;
        at(
            item,
            check_finite_vec3("tangent_impulse", p.tangent_impulse),
        )?;
        for arm in p.solver_lever_arms.into_iter().flatten() {
            at(item, check_finite_vec3("solver_lever_arms", arm))?;
        }
    }
    Ok(())
}
