//! Reading a recording back gives the numbers the recorder wrote, bit for bit, and the descriptions of every
//! body, collider and joint — including those inserted, edited and removed during the run.

mod support;

use rebound::prelude::*;
use rebound_record::{BodyKind, FrameReader, JointKindName, RecordedEvent, Recorder, Recording};
use support::{DT, ball_on_ground, bits, menagerie, record};

#[test]
fn every_number_reads_back_bit_for_bit() {
    let mut world = menagerie();
    let (bytes, written) = record(&mut world, 120);
    let recording = Recording::read(bytes.as_slice()).unwrap();
    assert_eq!(recording.frames().len(), written.len());
    for (i, (read, wrote)) in recording.frames().iter().zip(&written).enumerate() {
        assert_eq!(bits(read), bits(wrote), "frame {i}");
        assert_eq!(read.events, wrote.events, "frame {i}");
    }
    // The frames hold the world's own numbers: the last frame against the world itself.
    let last = recording.frames().last().unwrap();
    for (i, (handle, body)) in world.bodies().iter().enumerate() {
        let sample = &last.bodies[i];
        assert_eq!(
            sample.position.to_array().map(f32::to_bits),
            body.position().to_array().map(f32::to_bits),
            "{handle:?}"
        );
        assert_eq!(
            sample.rotation.to_array().map(f32::to_bits),
            body.rotation().to_array().map(f32::to_bits)
        );
        assert_eq!(
            sample.linear_velocity.to_array().map(f32::to_bits),
            body.linear_velocity().to_array().map(f32::to_bits)
        );
    }
    assert_eq!(last.step, 120);
    assert!((last.time - 120.0 * f64::from(DT)).abs() < 1e-9);
    assert!(!last.contacts.is_empty(), "the shapes land on the ground");
    // The contacts are the world's manifold points, in order: the point is `world_point` (to rounding: the
    // recorder rotates the anchors by matrices), every other number the manifold's own.
    let index = |h: BodyHandle| world.bodies().iter().position(|(b, _)| b == h).unwrap() as u32;
    let pose = |h: BodyHandle| world.body(h).unwrap().pose();
    let expected: Vec<_> = world
        .contacts()
        .iter()
        .flat_map(|m| m.points[..m.point_count].iter().map(move |p| (m, p)))
        .collect();
    assert_eq!(last.contacts.len(), expected.len());
    let mut deepest = 0.0f32;
    for (c, (m, p)) in last.contacts.iter().zip(&expected) {
        assert_eq!((c.body_a, c.body_b), (index(m.body_a), index(m.body_b)));
        let point = p.world_point(pose(m.body_a), pose(m.body_b));
        assert!(
            c.point.distance(point) <= 1e-6 * (1.0 + point.length()),
            "{} vs {point}",
            c.point
        );
        assert_eq!(
            c.normal.to_array().map(f32::to_bits),
            m.normal.to_array().map(f32::to_bits)
        );
        assert_eq!(c.normal_impulse.to_bits(), p.normal_impulse.to_bits());
        assert_eq!(c.separation.to_bits(), p.separation.to_bits());
        deepest = deepest.max(-p.separation);
    }
    assert_eq!(
        last.diagnostics.deepest_penetration.to_bits(),
        deepest.to_bits()
    );
}

#[test]
fn the_manifest_describes_every_shape_and_joint() {
    let mut world = menagerie();
    let (bytes, _) = record(&mut world, 2);
    let recording = Recording::read(bytes.as_slice()).unwrap();
    let manifest = recording.manifest();
    assert_eq!(manifest.format, "rebound-recording");
    assert_eq!(manifest.substeps, world.settings().substep_count);
    assert_eq!(manifest.gravity, world.settings().gravity);
    assert_eq!(manifest.bodies.len(), world.bodies().len());
    let shapes: Vec<&str> = manifest
        .bodies
        .iter()
        .flat_map(|b| b.colliders.iter().map(|c| c.shape.kind_name()))
        .collect();
    for kind in [
        "ball",
        "cuboid",
        "capsule",
        "cylinder",
        "cone",
        "convex hull",
        "triangle mesh",
        "height field",
        "compound",
    ] {
        assert!(shapes.contains(&kind), "{kind} missing from {shapes:?}");
    }
    // Shapes round-trip exactly through JSON: each equals the world's description.
    for (body, (handle, _)) in manifest.bodies.iter().zip(world.bodies().iter()) {
        let descs: Vec<_> = world
            .colliders()
            .of_body(handle)
            .iter()
            .map(|&c| world.collider(c).unwrap().desc().clone())
            .collect();
        assert_eq!(body.colliders.len(), descs.len());
        for (entry, desc) in body.colliders.iter().zip(&descs) {
            assert_eq!(entry.shape, desc.shape);
            assert_eq!(entry.local_pose, desc.local_pose);
            assert_eq!(entry.sensor, desc.is_sensor);
        }
    }
    assert_eq!(manifest.bodies[0].kind, BodyKind::Fixed);
    let kinds: Vec<JointKindName> = manifest.joints.iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKindName::Hinge,
            JointKindName::Rope,
            JointKindName::Rod,
            JointKindName::Spring,
            JointKindName::Ball,
            JointKindName::Fixed,
            JointKindName::Prismatic,
            JointKindName::Wheel,
        ]
    );
    let hinge = &manifest.joints[0];
    assert_eq!(hinge.body_a, None);
    assert_eq!(hinge.limits.map(|l| (l.lower, l.upper)), Some((-1.0, 1.0)));
    assert!((hinge.local_axis_a - Vec3::Z).length() < 1e-6);
    assert!(hinge.break_force.is_infinite());
    assert_eq!(manifest.joints[1].length, Some(1.2));
    assert!((manifest.joints[5].break_force - 1.0e6).abs() < 1.0);
}

#[test]
fn inserted_edited_and_removed_objects_are_described_when_they_change() {
    let mut world = menagerie();
    let mut recorder = Recorder::new(&world, Vec::new()).unwrap();
    recorder.record(&world).unwrap();
    recorder.step(&mut world, DT).unwrap();
    let bodies_before = world.bodies().len();
    // Insert a body with two colliders, and a joint to it.
    let extra = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 5.0, -5.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.25), extra)
        .unwrap();
    let second = world
        .insert_collider(ColliderDesc::ball(0.25).with_position(Vec3::X), extra)
        .unwrap();
    world
        .insert_world_joint(
            Joint::new(Rope::new(2.0).unwrap())
                .with_local_anchors(Vec3::new(0.0, 7.0, -5.0), Vec3::ZERO)
                .unwrap(),
            extra,
        )
        .unwrap();
    recorder.step(&mut world, DT).unwrap();
    // Edit a collider, remove it, remove a body.
    world.set_collider_friction(second, 0.1).unwrap();
    recorder.step(&mut world, DT).unwrap();
    world.remove_collider(second).unwrap();
    let (victim, _) = world.bodies().iter().nth(4).unwrap();
    world.remove_body(victim).unwrap();
    recorder.step(&mut world, DT).unwrap();
    recorder.step(&mut world, DT).unwrap();
    let bytes = recorder.finish().unwrap();

    let recording = Recording::read(bytes.as_slice()).unwrap();
    let frames = recording.frames();
    assert!(frames[0].changes.is_none() && frames[1].changes.is_none());
    let added = frames[2].changes.as_ref().unwrap();
    assert_eq!(added.bodies.len(), 1);
    let new_index = bodies_before as u32;
    assert_eq!(added.bodies[0].index, new_index);
    assert_eq!(added.bodies[0].colliders.len(), 2);
    assert_eq!(added.joints.len(), 1);
    assert_eq!(frames[2].bodies.len(), bodies_before + 1);
    assert!(frames[2].bodies[new_index as usize].present);
    let edited = frames[3].changes.as_ref().unwrap();
    assert_eq!(edited.colliders.len(), 1);
    assert!((edited.colliders[0].friction - 0.1).abs() < 1e-7);
    let removed = frames[4].changes.as_ref().unwrap();
    // The removed collider, and the collider of the removed body (body 4 holds collider 4).
    assert_eq!(
        removed.removed_colliders,
        vec![4, edited.colliders[0].index]
    );
    // The removed body keeps its slot, marked absent, in every later frame.
    for frame in &frames[4..] {
        assert_eq!(frame.bodies.len(), bodies_before + 1);
        assert!(!frame.bodies[4].present);
    }
    assert!(frames[3].bodies[4].present);
    let catalog = recording.catalog();
    assert_eq!(catalog.bodies()[new_index as usize].colliders.len(), 1);
    assert!(catalog.collider(edited.colliders[0].index).is_none());
    let at_3 = recording.catalog_at(3).unwrap();
    assert_eq!(at_3.bodies()[new_index as usize].colliders.len(), 2);
}

#[test]
fn events_name_recording_indices() {
    let mut world = ball_on_ground(1.2);
    let (bytes, _) = record(&mut world, 60);
    let recording = Recording::read(bytes.as_slice()).unwrap();
    let began: Vec<_> = recording
        .frames()
        .iter()
        .flat_map(|f| f.events.iter())
        .filter_map(|e| match e {
            RecordedEvent::ContactBegan { body_a, body_b, .. } => Some((*body_a, *body_b)),
            _ => None,
        })
        .collect();
    assert_eq!(began, vec![(Some(0), Some(1))]);
}

#[test]
fn the_streaming_reader_gives_the_same_frames_as_the_whole_file_reader() {
    let mut world = menagerie();
    let (bytes, _) = record(&mut world, 30);
    let whole = Recording::read(bytes.as_slice()).unwrap();
    let streamed: Vec<_> = FrameReader::new(bytes.as_slice())
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(streamed.len(), whole.frames().len());
    for (a, b) in streamed.iter().zip(whole.frames()) {
        assert_eq!(bits(a), bits(b));
    }
}

#[test]
fn the_layout_matches_the_documented_offsets() {
    let mut world = menagerie();
    let (bytes, written) = record(&mut world, 3);
    assert_eq!(&bytes[..8], b"RBREC\r\n\x1a");
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 2);
    let m = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    assert_eq!(m % 4, 0);
    let frame = 16 + m;
    let len = u32::from_le_bytes(bytes[frame..frame + 4].try_into().unwrap()) as usize;
    let p = frame + 4;
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let f32_at = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let nb = word(p + 16) as usize;
    let nc = word(p + 20) as usize;
    let nj = word(p + 24) as usize;
    let ne = word(p + 28) as usize;
    let x = word(p + 32) as usize;
    let nf = word(p + 36) as usize;
    assert_eq!(
        len,
        84 + x + 52 * nb + nb.div_ceil(4) * 4 + 40 * nc + 40 * nj + 16 * ne + 40 * nf
    );
    let first = &written[0];
    assert_eq!(nb, first.bodies.len());
    let bodies = p + 84 + x;
    // Body 3's position y, rotation w and flags, where the doc puts them.
    assert_eq!(
        f32_at(bodies + 3 * 12 + 4).to_bits(),
        first.bodies[3].position.y.to_bits()
    );
    assert_eq!(
        f32_at(bodies + 12 * nb + 3 * 16 + 12).to_bits(),
        first.bodies[3].rotation.w.to_bits()
    );
    assert_eq!(bytes[bodies + 52 * nb], 0b101, "body 0: present, fixed");
    assert_eq!(
        f32_at(p + 40).to_bits(),
        first.diagnostics.kinetic_energy.to_bits()
    );
}

#[test]
fn a_restored_snapshot_is_noticed_as_edits() {
    let mut world = menagerie();
    let (collider, desc) = world
        .colliders()
        .iter()
        .map(|(handle, collider)| (handle, collider.desc().clone()))
        .next()
        .unwrap();
    let snapshot = world.snapshot();
    let mut recorder = Recorder::new(&world, Vec::new()).unwrap();
    recorder.record(&world).unwrap();
    world
        .set_collider_friction(collider, desc.friction + 0.25)
        .unwrap();
    recorder.step(&mut world, DT).unwrap();
    world.restore(&snapshot).unwrap();
    recorder.step(&mut world, DT).unwrap();
    recorder.step(&mut world, DT).unwrap();
    let bytes = recorder.finish().unwrap();

    let recording = Recording::read(bytes.as_slice()).unwrap();
    let frames = recording.frames();
    let edited = frames[1].changes.as_ref().unwrap();
    assert_eq!(edited.colliders.len(), 1);
    assert!((edited.colliders[0].friction - (desc.friction + 0.25)).abs() < 1e-6);
    // The restore puts the old friction back: written as an edit of the same collider.
    let restored = frames[2].changes.as_ref().unwrap();
    assert_eq!(restored.colliders.len(), 1);
    assert_eq!(restored.colliders[0].index, edited.colliders[0].index);
    assert!((restored.colliders[0].friction - desc.friction).abs() < 1e-7);
    assert!(frames[3].changes.is_none());
}

/// A 10 kg box resting on the ground with a force event threshold: every frame after it settles holds
/// one contact force event carrying its weight, m·g = 98.1 N (±1 %), with the step's own numbers bit for
/// bit — in the frame the recorder keeps, in the bytes where docs/recording.md puts them, and read back.
#[test]
fn contact_force_events_are_recorded_field_by_field() {
    let settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)
        .unwrap();
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5))
                .with_density(10.0)
                .with_force_event_threshold(0.0),
            body,
        )
        .unwrap();
    let mut recorder = Recorder::new(&world, Vec::new()).unwrap();
    recorder.record(&world).unwrap();
    let mut expected = Vec::new();
    for step in 1..=120 {
        recorder.step(&mut world, DT).unwrap();
        let forces: Vec<ContactForce> = world
            .events()
            .iter()
            .filter_map(|e| match *e {
                Event::ContactForce { force, .. } => Some(force),
                _ => None,
            })
            .collect();
        let frame = recorder.last_frame().unwrap();
        let recorded: Vec<RecordedEvent> = frame
            .events
            .iter()
            .copied()
            .filter(|e| matches!(e, RecordedEvent::ContactForce { .. }))
            .collect();
        assert_eq!(recorded.len(), forces.len(), "step {step}");
        for (event, force) in recorded.iter().zip(&forces) {
            let RecordedEvent::ContactForce {
                body_a,
                body_b,
                collider_a,
                collider_b,
                normal,
                total_impulse,
                total_force,
                max_impulse_point,
                max_impulse,
            } = *event
            else {
                unreachable!("filtered above");
            };
            // Ground: body 0 with collider 0; the box: body 1 with collider 1.
            assert_eq!((body_a, body_b), (Some(0), Some(1)));
            assert_eq!((collider_a, collider_b), (Some(0), Some(1)));
            let bits3 = |v: Vec3| v.to_array().map(f32::to_bits);
            assert_eq!(bits3(normal), bits3(force.normal));
            assert_eq!(bits3(max_impulse_point), bits3(force.max_impulse_point));
            assert_eq!(
                [total_impulse, total_force, max_impulse].map(f32::to_bits),
                [force.total_impulse, force.total_force, force.max_impulse].map(f32::to_bits)
            );
            if step > 60 {
                assert!(
                    (total_force - 98.1).abs() < 0.981,
                    "step {step}: {total_force} N"
                );
            }
        }
        if step > 60 {
            assert_eq!(recorded.len(), 1, "step {step}");
        }
        expected.push(frame.events.clone());
    }
    let bytes = recorder.finish().unwrap();
    let recording = Recording::read(bytes.as_slice()).unwrap();
    for (i, (read, wrote)) in recording.frames()[1..].iter().zip(&expected).enumerate() {
        assert_eq!(&read.events, wrote, "frame {}", i + 1);
    }
    // The last frame's bytes: NF = 1, the event of kind 8, then its FORCE entry.
    let last = recording.frames().last().unwrap();
    let RecordedEvent::ContactForce {
        total_force,
        total_impulse,
        max_impulse,
        ..
    } = last.events[0]
    else {
        panic!("{:?}", last.events);
    };
    let payload_len = 84 + 52 * 2 + 4 + 40 * last.contacts.len() + 16 * last.events.len() + 40;
    let p = bytes.len() - payload_len;
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    assert_eq!(word(p - 4) as usize, payload_len);
    assert_eq!(word(p + 36), 1, "NF");
    let events = p + payload_len - 40 - 16 * last.events.len();
    assert_eq!(word(events), 8);
    assert_eq!((word(events + 4), word(events + 8)), (0, 1));
    assert_eq!(word(events + 12), total_force.to_bits());
    let force = p + payload_len - 40;
    assert_eq!((word(force), word(force + 4)), (0, 1));
    assert_eq!(word(force + 20), total_impulse.to_bits());
    assert_eq!(word(force + 36), max_impulse.to_bits());
}
