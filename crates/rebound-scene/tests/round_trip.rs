//! A scene written with `Scene::to_ron` reads back as the same scene, bit for bit, for every shape kind,
//! every joint kind with its options, and every field of every description set away from its default; and
//! a world read back with `Scene::from_world` builds the same world.

use rebound::prelude::*;
use rebound::{Integrator, JointSpring};
use rebound_scene::{RunSettings, Scene, SceneBody, SceneCamera, SceneJoint};

fn every_shape() -> Vec<ColliderShape> {
    let tetrahedron = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    vec![
        ColliderShape::Ball { radius: 0.25 },
        ColliderShape::Cuboid {
            half_extents: Vec3::new(0.5, 0.1, 0.3),
        },
        ColliderShape::Capsule {
            radius: 0.2,
            half_height: 0.4,
        },
        ColliderShape::Cylinder {
            radius: 0.3,
            half_height: 0.2,
        },
        ColliderShape::Cone {
            radius: 0.3,
            half_height: 0.5,
        },
        ColliderShape::ConvexHull {
            points: tetrahedron.clone(),
        },
        ColliderShape::TriMesh {
            vertices: tetrahedron,
            indices: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
        },
        ColliderShape::HeightField {
            rows: 2,
            cols: 3,
            heights: vec![0.0, 0.1, -0.2, 0.3, 0.0, 1.0 / 3.0],
            scale: Vec3::new(4.0, 1.0, 2.0),
        },
        ColliderShape::Compound {
            parts: vec![
                (
                    Pose::new(Vec3::new(0.0, 0.5, 0.0), Quat::from_rotation_z(0.3)),
                    ColliderShape::Ball { radius: 0.1 },
                ),
                (
                    Pose::IDENTITY,
                    ColliderShape::Cuboid {
                        half_extents: Vec3::splat(0.2),
                    },
                ),
            ],
        },
    ]
}

fn every_joint() -> Result<Vec<Joint>, Error> {
    let soft = SoftSpring::frequency(3.0, 0.4)?;
    let limits = Limits::new(-0.5, 0.75)?;
    let motor = Motor::new(2.0, 40.0)?;
    let spring = JointSpring::new(0.1, soft)?;
    let kinds: Vec<JointKind> = vec![
        Spring::new(1.5, SpringModel::Soft(soft))?
            .with_force_range(-100.0, 200.0)?
            .into(),
        Spring::new(
            0.7,
            SpringModel::Force {
                stiffness: 50.0,
                damping: 1.5,
            },
        )?
        .into(),
        Rope::new(2.0)?.with_restitution(0.25)?.into(),
        Rod::new(0.8)?.into(),
        BallJoint::new().into(),
        HingeJoint::new()
            .with_limits(-1.0, 1.25)?
            .with_motor(motor)
            .with_spring(spring)
            .into(),
        FixedJoint::new().into(),
        PrismaticJoint::new()
            .with_limits(limits)
            .with_motor(motor)
            .with_spring(spring)
            .into(),
        WheelJoint::new(soft)?
            .with_suspension_limits(limits)
            .with_motor(motor)
            .into(),
    ];
    kinds
        .into_iter()
        .enumerate()
        .map(|(i, kind)| {
            let mut joint = Joint::new(kind)
                .with_local_anchors(Vec3::new(0.1, -0.2, 0.3), Vec3::new(-0.5, 0.0, 0.0))?
                .with_local_axes(Vec3::Z, Vec3::new(0.0, 1.0, 1.0))?;
            if i % 2 == 0 {
                joint = joint.with_break_force(1e4)?.with_break_torque(5e3)?;
            }
            Ok(joint)
        })
        .collect()
}

/// A scene with every field of every description away from its default.
fn full_scene() -> Result<Scene, Error> {
    let mut settings = WorldSettings {
        gravity: Vec3::new(0.1, -3.7, 0.0),
        substep_count: 6,
        contact_frequency_hz: 25.0,
        contact_damping_ratio: 4.0,
        max_push_out_speed: 2.0,
        restitution_threshold: 0.5,
        warm_starting: false,
        speculative_margin: 0.03,
        sleep_enabled: false,
        linear_sleep_threshold: 0.04,
        angular_sleep_threshold: 0.06,
        time_to_sleep: 0.7,
        fixed_dt: 1.0 / 120.0,
        max_steps_per_advance: 4,
        ..WorldSettings::default()
    };
    settings.joints.frequency_hz = 50.0;
    settings.joints.damping_ratio = 1.5;
    settings.joints.max_frequency_ratio = 0.4;
    settings.joints.solve_iterations = 2;
    settings.joints.relax_iterations = 3;
    settings.joints.tethers = false;
    settings.joints.direct_chains = false;
    settings.limits.max_speed = 500.0;
    settings.limits.max_angular_speed = 300.0;
    settings.limits.max_position = 2.0e4;
    settings.limits.max_candidate_pairs = 1_000;
    settings.limits.max_contact_points = 3_000;
    let body = BodyDesc {
        body_type: BodyType::Kinematic,
        position: Vec3::new(1.0, 2.0, -3.0),
        rotation: Quat::from_rotation_y(0.7),
        linear_velocity: Vec3::new(0.5, -0.25, 1.0 / 7.0),
        angular_velocity: Vec3::new(0.0, 3.0, -0.0),
        mass_properties: MassProperties::new(
            2.5,
            Vec3::new(0.0, 0.1, 0.0),
            Vec3::new(0.2, 0.3, 0.4),
        )?,
        gravity_scale: 0.5,
        linear_damping: 0.1,
        angular_damping: 0.2,
        integrator: Integrator::ExplicitEuler,
        gyroscopic: false,
        sleeping: true,
        can_sleep: false,
        locked_axes: LockedAxes::PLANE_XY,
    };
    let colliders = every_shape()
        .into_iter()
        .map(|shape| ColliderDesc {
            shape,
            local_pose: Pose::new(Vec3::new(0.0, 0.25, 0.0), Quat::from_rotation_x(0.1)),
            density: 0.0,
            friction: 0.9,
            friction_combine_rule: CombineRule::Max,
            restitution: 0.3,
            restitution_combine_rule: CombineRule::Min,
            rolling_friction: 0.01,
            groups: CollisionGroups::new(0b01, 0b10),
            is_sensor: true,
            enabled: false,
            force_event_threshold: Some(12.5),
        })
        .collect();
    let mut bodies = vec![
        SceneBody {
            name: "ground \"one\"".to_owned(),
            body: BodyDesc::fixed(),
            colliders: vec![ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0))],
        },
        SceneBody {
            name: String::new(),
            body,
            colliders,
        },
    ];
    bodies.extend((0..9).map(|i| SceneBody {
        name: format!("link {i}"),
        body: BodyDesc::dynamic().with_position(Vec3::new(i as f32, 3.0, 0.0)),
        colliders: vec![ColliderDesc::ball(0.2)],
    }));
    let joints = every_joint()?
        .into_iter()
        .enumerate()
        .map(|(k, joint)| SceneJoint {
            body_a: (k % 3 != 0).then_some(k + 1),
            body_b: k + 2,
            joint,
            contacts_enabled: k % 2 == 0,
        })
        .collect();
    Ok(Scene {
        name: "every field".to_owned(),
        description: "Every description, every field away from its default.".to_owned(),
        settings,
        run: RunSettings {
            dt: 1.0 / 90.0,
            steps: 42,
        },
        camera: Some(SceneCamera {
            position: Vec3::new(1.0, 2.0, 3.0),
            target: Vec3::new(0.0, 0.5, 0.0),
            fov_degrees: 50.0,
        }),
        bodies,
        joints,
    })
}

#[test]
fn every_field_reads_back_bit_for_bit() -> Result<(), Box<dyn std::error::Error>> {
    let scene = full_scene()?;
    let text = scene.to_ron();
    let back = Scene::from_ron(&text)?;
    // `PartialEq` on floats would call -0.0 and 0.0 equal: compare the written text too.
    assert_eq!(back, scene, "{text}");
    assert_eq!(back.to_ron(), text);
    assert!(text.contains("-0.0"), "the signed zero is kept:\n{text}");
    Ok(())
}

#[test]
fn defaults_are_left_out() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene {
        bodies: vec![SceneBody {
            body: BodyDesc::dynamic().with_position(Vec3::new(0.0, 2.0, 0.0)),
            colliders: vec![ColliderDesc::ball(0.5)],
            ..SceneBody::default()
        }],
        ..Scene::default()
    };
    assert_eq!(
        scene.to_ron(),
        "Scene(\n    settings: (),\n    bodies: [\n        (body: (position: (0.0, 2.0, 0.0)), colliders: [(shape: Ball(radius: 0.5))]),\n    ],\n)\n"
    );
    Ok(())
}

#[test]
fn a_world_read_back_builds_the_same_world() -> Result<(), Box<dyn std::error::Error>> {
    let scene = full_scene()?;
    let mut built = scene.build()?.world;
    let mut again = Scene::from_world(&built).build()?.world;
    for _ in 0..30 {
        built.step(1.0 / 60.0);
        again.step(1.0 / 60.0);
    }
    assert_eq!(built.state_digest(), again.state_digest());
    Ok(())
}
