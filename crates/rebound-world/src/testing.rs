//! A small collision backend of spheres and half-spaces, for tests, examples and benchmarks of the world
//! without parry. Brute force over all pairs (O(n²)): fine for tens of bodies, not for games — the `rebound`
//! facade has the real one.

use crate::{
    BodyHandle, BodySet, CollisionBackend, ContactManifold, ManifoldPoint, ManifoldWriter,
    WorldSettings,
};
use rebound_dynamics::{BodyType, CombineRule, RigidBody};
use rebound_math::Vec3;

/// A shape of the test backend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TestShape {
    /// A ball of `radius` (m) centred at the body's centre of mass.
    Sphere {
        /// Radius (m).
        radius: f32,
    },
    /// The half-space `{p : n·p ≤ 0}` in the body's frame, with `normal` the unit outward normal in the body
    /// frame (for a ground body at y = 0: `Vec3::Y`).
    HalfSpace {
        /// Outward unit normal, body frame.
        normal: Vec3,
    },
}

/// A shape on a body with its surface material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TestCollider {
    /// The body it is attached to.
    pub body: BodyHandle,
    /// The shape.
    pub shape: TestShape,
    /// Friction coefficient (combined by geometric mean).
    pub friction: f32,
    /// Coefficient of restitution (combined by max).
    pub restitution: f32,
}

/// Spheres and half-spaces, all pairs.
#[derive(Debug, Clone, Default)]
pub struct SimpleBackend {
    colliders: Vec<TestCollider>,
    /// Rolling resistance lever arm given to every manifold (m). Default: 0.
    pub rolling_friction: f32,
    /// Scratch: whether each collider's body is awake and moving.
    active: Vec<bool>,
}

impl SimpleBackend {
    /// An empty backend.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a collider; returns its index (the manifold key is built from these indices).
    pub fn add(&mut self, collider: TestCollider) -> usize {
        self.colliders.push(collider);
        self.colliders.len() - 1
    }

    /// Adds a sphere of `radius` on `body` with the given material.
    pub fn add_sphere(
        &mut self,
        body: BodyHandle,
        radius: f32,
        friction: f32,
        restitution: f32,
    ) -> usize {
        self.add(TestCollider {
            body,
            shape: TestShape::Sphere { radius },
            friction,
            restitution,
        })
    }

    /// Adds the half-space below the plane through `body`'s origin with outward `normal` (body frame).
    pub fn add_half_space(
        &mut self,
        body: BodyHandle,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) -> usize {
        self.add(TestCollider {
            body,
            shape: TestShape::HalfSpace {
                normal: normal.normalize_or(Vec3::Y),
            },
            friction,
            restitution,
        })
    }

    /// Removes every collider of `body`.
    pub fn remove_body(&mut self, body: BodyHandle) {
        self.colliders.retain(|c| c.body != body);
    }

    /// The colliders.
    #[must_use]
    pub fn colliders(&self) -> &[TestCollider] {
        &self.colliders
    }
}

fn active(body: &RigidBody) -> bool {
    !body.is_sleeping() && body.body_type() != BodyType::Fixed
}

impl CollisionBackend for SimpleBackend {
    fn collide(
        &mut self,
        bodies: &BodySet,
        settings: &WorldSettings,
        dt: f32,
        _previous: &[ContactManifold],
        out: &mut ManifoldWriter<'_>,
    ) {
        // Pairs with at least one awake moving body: O(awake · n), so a sleeping scene costs O(n).
        self.active.clear();
        self.active.extend(
            self.colliders
                .iter()
                .map(|c| bodies.get(c.body).is_some_and(active)),
        );
        for (i, ci) in self.colliders.iter().enumerate() {
            for (j, cj) in self.colliders.iter().enumerate().skip(i + 1) {
                if !(self.active[i] || self.active[j]) || ci.body == cj.body {
                    continue;
                }
                let (Some(bi), Some(bj)) = (bodies.get(ci.body), bodies.get(cj.body)) else {
                    continue;
                };
                let margin = settings.speculative_margin
                    + (bi.linear_velocity() - bj.linear_velocity()).length() * dt;
                let key = ((i as u64) << 32) | j as u64;
                let friction = CombineRule::combine(
                    ci.friction,
                    CombineRule::GeometricMean,
                    cj.friction,
                    CombineRule::GeometricMean,
                );
                let restitution = CombineRule::combine(
                    ci.restitution,
                    CombineRule::Max,
                    cj.restitution,
                    CombineRule::Max,
                );
                let manifold = match (ci.shape, cj.shape) {
                    (TestShape::Sphere { radius: ra }, TestShape::Sphere { radius: rb }) => {
                        sphere_sphere(ci.body, bi, ra, cj.body, bj, rb, margin)
                    }
                    (TestShape::HalfSpace { normal }, TestShape::Sphere { radius }) => {
                        plane_sphere(ci.body, bi, normal, cj.body, bj, radius, margin)
                    }
                    (TestShape::Sphere { radius }, TestShape::HalfSpace { normal }) => {
                        plane_sphere(cj.body, bj, normal, ci.body, bi, radius, margin)
                    }
                    (TestShape::HalfSpace { .. }, TestShape::HalfSpace { .. }) => None,
                };
                if let Some(mut m) = manifold {
                    m.key = key;
                    m.friction = friction;
                    m.restitution = restitution;
                    m.rolling_friction = self.rolling_friction;
                    out.push(m);
                }
            }
        }
    }
}

fn sphere_sphere(
    ha: BodyHandle,
    a: &RigidBody,
    ra: f32,
    hb: BodyHandle,
    b: &RigidBody,
    rb: f32,
    margin: f32,
) -> Option<ContactManifold> {
    let (ca, cb) = (a.center_of_mass(), b.center_of_mass());
    let d = cb - ca;
    let distance = d.length();
    let separation = distance - ra - rb;
    if separation > margin {
        return None;
    }
    // Concentric spheres have no defined normal: push apart along +y, deterministically.
    let normal = d.try_normalize().unwrap_or(Vec3::Y);
    let mut m = ContactManifold::new(ha, hb, 0, normal, 0.0, 0.0);
    m.push_point(ManifoldPoint {
        local_anchor_a: a.pose().inverse_transform_point(ca + normal * ra),
        local_anchor_b: b.pose().inverse_transform_point(cb - normal * rb),
        separation,
        feature_id: 0,
        ..ManifoldPoint::default()
    });
    Some(m)
}

fn plane_sphere(
    hp: BodyHandle,
    plane: &RigidBody,
    local_normal: Vec3,
    hs: BodyHandle,
    sphere: &RigidBody,
    radius: f32,
    margin: f32,
) -> Option<ContactManifold> {
    let normal = plane.rotation() * local_normal;
    let center = sphere.center_of_mass();
    let height = normal.dot(center - plane.position());
    let separation = height - radius;
    if separation > margin {
        return None;
    }
    let mut m = ContactManifold::new(hp, hs, 0, normal, 0.0, 0.0);
    m.push_point(ManifoldPoint {
        local_anchor_a: plane
            .pose()
            .inverse_transform_point(center - normal * height),
        local_anchor_b: sphere
            .pose()
            .inverse_transform_point(center - normal * radius),
        separation,
        feature_id: 0,
        ..ManifoldPoint::default()
    });
    Some(m)
}
