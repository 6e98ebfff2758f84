//! The collide stage's walk over the thread pool gives, step by step, what the one-thread walk gives, also
//! for a backend that does everything the walk must catch: keys repeated across the pool's chunks, unusable
//! manifolds, a stale handle, a quarantined body, and the cap on contact points falling mid-list
//! (`cargo test -p rebound-world --features parallel --test collide_pool`).
#![cfg(feature = "parallel")]
#![allow(
    clippy::unwrap_used,
    reason = "the set-up fails loudly on the first unexpected error"
)]

use rebound_dynamics::BodyDesc;
use rebound_math::Vec3;
use rebound_math::par::rayon;
use rebound_world::{
    BodyHandle, BodySet, CollisionBackend, ContactManifold, ManifoldPoint, ManifoldWriter, World,
    WorldSettings,
};

const DT: f32 = 1.0 / 60.0;

/// Balls in a row, far enough apart to miss one another.
const BODIES: usize = 900;

/// A backend reporting a manifold between every two neighbours of `bodies`, whatever their distance, and
/// its faults: three manifolds of one key at the 256th (where the pool's first chunk ends), then every
/// 50th with a non-finite normal, every 97th between a body and itself, and one with a removed body.
struct Faulty {
    bodies: Vec<BodyHandle>,
    removed: BodyHandle,
}

impl CollisionBackend for Faulty {
    fn collide(
        &mut self,
        _: &BodySet,
        _: &WorldSettings,
        _: f32,
        _: &[ContactManifold],
        out: &mut ManifoldWriter<'_>,
    ) {
        // Written in reverse: the world sorts.
        for (i, pair) in self.bodies.windows(2).enumerate().rev() {
            let (a, b) = (pair[0], pair[1]);
            let normal = if i % 50 == 49 {
                Vec3::new(f32::NAN, 1.0, 0.0)
            } else {
                Vec3::Y
            };
            let b = if i % 97 == 96 { a } else { b };
            for _ in 0..if i == 254 { 3 } else { 1 } {
                let m = out.begin(a, b, 7, normal, 0.5, 0.0);
                m.push_point(ManifoldPoint {
                    local_anchor_a: Vec3::new(0.1, 0.0, 0.0),
                    local_anchor_b: Vec3::new(-0.1, 0.0, 0.0),
                    separation: -0.01,
                    feature_id: i as u32,
                    ..ManifoldPoint::default()
                });
                if i % 3 == 0 {
                    m.push_point(ManifoldPoint {
                        local_anchor_a: Vec3::new(0.0, 0.1, 0.0),
                        separation: 0.02,
                        feature_id: 1000 + i as u32,
                        ..ManifoldPoint::default()
                    });
                }
            }
        }
        out.begin(self.bodies[10], self.removed, 3, Vec3::Y, 0.5, 0.0);
    }
}

fn world(max_contact_points: u32) -> World<Faulty> {
    let mut settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    settings.limits.max_contact_points = max_contact_points;
    let mut world = World::with_backend(
        settings,
        Faulty {
            bodies: Vec::new(),
            removed: BodyHandle::invalid(),
        },
    )
    .unwrap();
    let bodies: Vec<BodyHandle> = (0..BODIES)
        .map(|i| {
            let position = Vec3::new(3.0 * i as f32, 0.0, 0.0);
            world
                .insert_body(&BodyDesc::dynamic().with_position(position))
                .unwrap()
        })
        .collect();
    let removed = world.insert_body(&BodyDesc::dynamic()).unwrap();
    world.remove_body(removed).unwrap();
    // Beyond the default position bound: quarantined at the first step, its manifolds dropped.
    world
        .body_mut(bodies[400])
        .unwrap()
        .set_position(Vec3::new(2.0e6, 0.0, 0.0))
        .unwrap();
    *world.backend_mut() = Faulty { bodies, removed };
    world
}

/// A manifold with its bodies named by slot (each world has its own handle generations).
fn by_slot(m: &ContactManifold) -> ContactManifold {
    let slot = |h: BodyHandle| BodyHandle::from_raw_parts(h.into_raw_parts().0, 0);
    ContactManifold {
        body_a: slot(m.body_a),
        body_b: slot(m.body_b),
        ..*m
    }
}

/// Per step: the contacts (bodies by slot), the rejected and capped counts; and the final digest.
type Run = (Vec<(Vec<ContactManifold>, usize, usize)>, u64);

fn run(threads: usize, max_contact_points: u32) -> Run {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("the test machine starts threads");
    pool.install(|| {
        let mut world = world(max_contact_points);
        let steps = (0..4)
            .map(|_| {
                let report = world.step(DT);
                (
                    world.contacts().iter().map(by_slot).collect(),
                    report.rejected_contact_count,
                    report.capped_manifold_count,
                )
            })
            .collect();
        (steps, world.state_digest())
    })
}

#[test]
fn the_pool_walk_keeps_matches_and_counts_as_one_thread_does() {
    // 899 pairs, 2 repeated, and 1 stale: 902 manifolds; 17 with a NaN normal (one of which, pair 399, has
    // the quarantined body and counts as quarantined), 9 against themselves, 2 with the quarantined body.
    for max_points in [1 << 19, 700] {
        let one = run(1, max_points);
        let (steps, _) = &one;
        let (contacts, rejected, capped) = &steps[3];
        assert_eq!(*rejected, 16 + 9 + 1, "cap {max_points}");
        if max_points == 700 {
            assert!(*capped > 100, "the cap falls mid-list: {capped} capped");
            assert!(contacts.len() < 600);
        } else {
            assert_eq!(*capped, 0);
            assert_eq!(contacts.len(), 902 - 26 - 2);
        }
        // The repeated key: three manifolds kept (which old one each warm-starts from is held to the one-thread
        // walk by the comparison below).
        let repeated = contacts
            .iter()
            .filter(|m| m.points()[0].feature_id == 254)
            .count();
        assert_eq!(repeated, 3);
        for threads in [2, 3] {
            let (steps, digest) = run(threads, max_points);
            for (step, (pool, alone)) in steps.iter().zip(&one.0).enumerate() {
                let first_change = pool.0.iter().zip(&alone.0).position(|(p, a)| p != a);
                assert!(
                    first_change.is_none() && pool.0.len() == alone.0.len(),
                    "{threads} threads, cap {max_points}, step {step}: manifold {first_change:?} \
                     differs, {} against {} manifolds",
                    pool.0.len(),
                    alone.0.len()
                );
                assert_eq!((pool.1, pool.2), (alone.1, alone.2), "step {step}: counts");
            }
            assert_eq!(digest, one.1, "{threads} threads, cap {max_points}: digest");
        }
    }
}
