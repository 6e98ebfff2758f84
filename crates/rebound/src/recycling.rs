//! **Contact recycling**: a box pair that barely moved keeps last step's contact points.
//!
//! The coherence shortcut is taken from the world's state instead of parry's: a box pair's manifold records
//! where it was computed ([`ContactBasis`]: the bodies' relative pose and the normal in A's frame), and while
//! the bodies have moved less than 1 mm and turned less than 0.5° relative to that, the pair keeps last step's
//! points as material points of each body and only measures their separations again ([`recyclable`],
//! [`Seam::recycle`]). The basis is in the world's manifolds, hence in every snapshot: recycling depends on the
//! world's state only. Box pairs only — they are what stacks are made of, and their generator is the most
//! expensive. In the pyramid scene ([docs/scenes.md](../../../docs/scenes.md)) most box tests are skipped, and
//! a column of equal boxes stands straighter than with fresh manifolds (a kept patch does not switch
//! reference face on rounding-level ties; `docs/performance.md`, "Contact recycling").

use crate::seam::Seam;
use rebound_math::{Pose, rotate, rotate_inverse};
use rebound_world::{BodyHandle, ContactManifold, ManifoldPoint, ManifoldWriter};

/// How far (m) the bodies of a box pair may move relative to each other, since the pair's manifold was
/// computed from scratch, for the manifold to be recycled: 1 mm. See [`recyclable`].
const RECYCLE_DISTANCE: f32 = 1.0e-3;

/// How far the bodies of a box pair may turn relative to each other (the sine of half the angle): half a
/// degree's worth, `sin(0.25°)`, i.e. 0.5°. See [`recyclable`].
const RECYCLE_HALF_ANGLE_SINE: f32 = 4.363_3e-3;

/// Last step's manifold of the body pair and key `order_key` in `previous` (sorted by order key), if it may be
/// recycled at the bodies' relative pose `relative` (B's body pose in A's body frame): it has a
/// [`ContactBasis`], and the bodies moved less than [`RECYCLE_DISTANCE`] and turned less than
/// [`RECYCLE_HALF_ANGLE_SINE`] relative to each other since it was computed from scratch.
///
/// **Contact recycling** (rapier's: parry's `try_update_contacts`): a box resting on a box changes its contact
/// patch only when it moves, so its points are kept — as material points of each body — and only their
/// separations are measured again, until the bodies have moved far enough from where the points were computed
/// for the patch to differ. The basis is in the world's manifold, so the choice depends on the world's state
/// only and a restored snapshot recycles exactly as the world that never stopped.
///
/// `cursor` is where the last search ended: pairs come in nearly the order of `previous`, so the search
/// gallops forward from it ([`find_from`]) instead of bisecting all of `previous` for every pair.
pub(crate) fn recyclable<'a>(
    previous: &'a [ContactManifold],
    cursor: &mut usize,
    order_key: (BodyHandle, BodyHandle, u64),
    relative: &Pose,
) -> Option<&'a ContactManifold> {
    let old = previous.get(find_from(previous, cursor, order_key)?)?;
    let basis = old.basis?;
    let moved = relative.position.distance_squared(basis.translation);
    let turn = (basis.rotation.conjugate() * relative.rotation)
        .xyz()
        .length_squared();
    (moved < RECYCLE_DISTANCE * RECYCLE_DISTANCE
        && turn < RECYCLE_HALF_ANGLE_SINE * RECYCLE_HALF_ANGLE_SINE)
        .then_some(old)
}

/// The index of the manifold of `order_key` in `previous` (sorted by order key), searched from `*cursor`:
/// forward in steps of 1, 2, 4, … until passed, then by bisection within the last step; from the start if
/// the key lies before the cursor. `*cursor` is left where the key is or would be. The same answer as one
/// bisection of the whole slice, found in O(log d) reads for a key `d` places past the cursor — a pile's pairs
/// come in nearly manifold order, so `d` is small and the reads stay in cache.
fn find_from(
    previous: &[ContactManifold],
    cursor: &mut usize,
    order_key: (BodyHandle, BodyHandle, u64),
) -> Option<usize> {
    let start = (*cursor).min(previous.len());
    let ahead = previous
        .get(start)
        .is_some_and(|m| m.order_key() < order_key);
    let found = if ahead {
        // previous[start] < key: gallop until an element ≥ key (or the end), then bisect the bracket.
        let mut low = start + 1;
        let mut step = 1;
        while previous
            .get(low + step - 1)
            .is_some_and(|m| m.order_key() < order_key)
        {
            low += step;
            step *= 2;
        }
        let high = (low + step).min(previous.len());
        previous[low..high]
            .binary_search_by_key(&order_key, ContactManifold::order_key)
            .map(|i| low + i)
            .map_err(|i| low + i)
    } else if previous
        .get(start)
        .is_some_and(|m| m.order_key() == order_key)
    {
        Ok(start)
    } else if start == 0 || previous[start - 1].order_key() < order_key {
        // Between the cursor's neighbours: absent.
        Err(start)
    } else {
        previous[..start].binary_search_by_key(&order_key, ContactManifold::order_key)
    };
    match found {
        Ok(index) => {
            *cursor = index + 1;
            Some(index)
        }
        Err(index) => {
            *cursor = index;
            None
        }
    }
}

impl Seam<'_> {
    /// Pushes `old` (last step's manifold of this pair, see [`recyclable`]) recycled onto `out`: its points as
    /// material points of each body, each with its separation along the kept normal measured at the bodies'
    /// relative pose `relative` — `s = n·(T·p_B − p_A)` in A's body frame — those within `prediction`
    /// (m) kept; the normal turned with A; the basis kept; materials combined afresh (they may have changed).
    /// Nothing if no point is within `prediction`.
    pub(crate) fn recycle(
        &self,
        old: &ContactManifold,
        relative: &Pose,
        prediction: f32,
        out: &mut ManifoldWriter<'_>,
    ) {
        let Some(basis) = old.basis else {
            return;
        };
        let n = basis.local_normal;
        // Written in place in `out`: its header and its points, not the unused point slots.
        let manifold = out.begin(
            old.body_a,
            old.body_b,
            old.key,
            rotate(self.b1.rotation(), n),
            0.0,
            0.0,
        );
        (
            manifold.friction,
            manifold.restitution,
            manifold.rolling_friction,
        ) = self.materials();
        manifold.basis = Some(basis);
        // s = n·(R·p_B + t − p_A) = (R*·n)·p_B + n·t − n·p_A: one rotation per manifold, two dot products
        // per point.
        let normal_in_b = rotate_inverse(relative.rotation, n);
        let offset = n.dot(relative.position);
        for p in old.points() {
            let separation = normal_in_b.dot(p.local_anchor_b) + offset - n.dot(p.local_anchor_a);
            if separation <= prediction {
                manifold.push_point(ManifoldPoint {
                    local_anchor_a: p.local_anchor_a,
                    local_anchor_b: p.local_anchor_b,
                    separation,
                    feature_id: p.feature_id,
                    ..ManifoldPoint::default()
                });
            }
        }
        if manifold.point_count == 0 {
            out.pop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rebound_math::Vec3;

    proptest::proptest! {
        /// The galloping search finds what one bisection of the whole slice finds, from any cursor, and leaves
        /// the cursor just past a found key or at an absent key's insertion point.
        #[test]
        fn galloping_search_matches_bisection(
            keys in proptest::collection::btree_set((0u32..40, 0u32..40, 0u64..3), 0..60),
            probes in proptest::collection::vec(((0u32..42, 0u32..42, 0u64..4), 0usize..70), 1..20),
        ) {
            let previous: Vec<ContactManifold> = keys
                .iter()
                .map(|&(a, b, key)| {
                    ContactManifold::new(
                        BodyHandle::from_raw_parts(a, 0),
                        BodyHandle::from_raw_parts(b, 0),
                        key,
                        Vec3::Y,
                        0.5,
                        0.0,
                    )
                })
                .collect();
            for ((a, b, key), mut cursor) in probes {
                let order_key = (BodyHandle::from_raw_parts(a, 0), BodyHandle::from_raw_parts(b, 0), key);
                let bisected = previous.binary_search_by_key(&order_key, ContactManifold::order_key);
                let found = find_from(&previous, &mut cursor, order_key);
                proptest::prop_assert_eq!(found, bisected.ok());
                proptest::prop_assert_eq!(cursor, bisected.map_or_else(|i| i, |i| i + 1));
            }
        }
    }
}
