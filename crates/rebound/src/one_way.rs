//! [`OneWayPlatform`]: a contact hook (stage *collide*, see [`ContactHooks`]) that lets bodies pass through a
//! collider from one side and stand on it from the other — the jump-through platform of platformers.

use crate::hooks::{ContactEdit, ContactHooks, ContactPair};
use crate::{ColliderHandle, Error};
use rebound_math::Vec3;
use rebound_math::validity::{check_finite, check_non_negative};

/// A one-way platform: contacts with `collider` hold only what lies on its `up` side.
///
/// A contact point with the platform is kept when the normal out of the platform is within `max_angle` of
/// `up` and the point overlaps the platform by at most `max_penetration`; every other point is disabled.
/// A body coming from below meets the platform's underside (normal pointing down): it passes. Once through
/// the middle the normal turns up but the overlap is deep: it still passes, until it has (almost) left the
/// platform, and falls back onto the top, where speculative contacts catch it before it overlaps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OneWayPlatform {
    collider: ColliderHandle,
    up: Vec3,
    cos_max_angle: f32,
    max_penetration: f32,
}

impl OneWayPlatform {
    /// The platform `collider`, solid from the `up` side (a world direction, normalised here), accepting
    /// normals within 45° of `up` and overlaps up to 5 cm.
    ///
    /// # Errors
    /// An `up` that is not finite or has zero length.
    pub fn new(collider: ColliderHandle, up: Vec3) -> Result<Self, Error> {
        if !up.is_finite() {
            return Err(Error::Math(rebound_math::MathError::NonFiniteVector {
                field: "up",
                value: up,
            }));
        }
        let up = up
            .try_normalize()
            .ok_or(Error::Math(rebound_math::MathError::ZeroLength {
                field: "up",
                value: up,
            }))?;
        Ok(Self {
            collider,
            up,
            cos_max_angle: core::f32::consts::FRAC_1_SQRT_2,
            max_penetration: 0.05,
        })
    }

    /// The largest angle (rad, in `[0, π/2]`) between `up` and a contact normal that holds. Default: π/4.
    ///
    /// # Errors
    /// An angle outside `[0, π/2]` or not finite.
    pub fn with_max_angle(mut self, max_angle: f32) -> Result<Self, Error> {
        check_finite("max_angle", max_angle)?;
        if !(0.0..=core::f32::consts::FRAC_PI_2).contains(&max_angle) {
            return Err(Error::OutOfRange {
                field: "max_angle",
                value: max_angle,
                min: 0.0,
                max: core::f32::consts::FRAC_PI_2,
            });
        }
        self.cos_max_angle = rebound_math::real::cos(max_angle);
        Ok(self)
    }

    /// The deepest overlap (m, ≥ 0) at which a point still holds. Default: 0.05 m.
    ///
    /// # Errors
    /// A negative or non-finite depth.
    pub fn with_max_penetration(mut self, max_penetration: f32) -> Result<Self, Error> {
        check_finite("max_penetration", max_penetration)?;
        check_non_negative("max_penetration", max_penetration)?;
        self.max_penetration = max_penetration;
        Ok(self)
    }

    /// The platform's collider.
    #[must_use]
    pub fn collider(&self) -> ColliderHandle {
        self.collider
    }

    /// Disables the points of `contacts` (a manifold of `pair`) that do not hold (see the type's docs); a
    /// pair without the platform is left alone. For use inside a hook of one's own.
    pub fn apply(&self, pair: &ContactPair<'_>, contacts: &mut ContactEdit) {
        // The normal out of the platform, towards the other collider.
        let out = if pair.collider_a == self.collider {
            contacts.normal()
        } else if pair.collider_b == self.collider {
            -contacts.normal()
        } else {
            return;
        };
        let facing = out.dot(self.up) >= self.cos_max_angle;
        for p in contacts.points_mut() {
            p.enabled &= facing && p.separation >= -self.max_penetration;
        }
    }
}

impl ContactHooks for OneWayPlatform {
    fn modify_contacts(&self, pair: &ContactPair<'_>, contacts: &mut ContactEdit) {
        self.apply(pair, contacts);
    }
}

impl ContactHooks for [OneWayPlatform] {
    fn modify_contacts(&self, pair: &ContactPair<'_>, contacts: &mut ContactEdit) {
        for platform in self {
            platform.apply(pair, contacts);
        }
    }
}
