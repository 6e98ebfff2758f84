//! A bad scene file gets a typed error naming the item, the field and the value, with the line and column
//! of the field; nothing is built.

use rebound_scene::{Location, Scene, SceneError};

/// The error of loading `text`, which must fail.
fn error_of(text: &str) -> SceneError {
    match Scene::from_ron(text) {
        Ok(_) => panic!("the scene loaded:\n{text}"),
        Err(e) => e,
    }
}

fn at(line: usize, column: usize) -> Option<Location> {
    Some(Location { line, column })
}

#[test]
fn a_syntax_error_is_placed_at_its_line_and_column() {
    let text = "Scene(\n    bodies: [\n        (body: (position: (0.0, 1.0 0.0))),\n    ],\n)\n";
    let error = error_of(text);
    assert!(matches!(error, SceneError::Syntax { .. }), "{error:?}");
    // The missing comma: the parser stops at the third number, line 3.
    assert_eq!(error.location().map(|l| l.line), Some(3), "{error}");
    assert!(error.to_string().starts_with("line 3, column "), "{error}");
}

#[test]
fn a_misspelt_field_is_an_error_not_a_default() {
    let text = "Scene(\n  bodies: [(colliders: [(shape: Ball(radius: 0.5), densty: 2.0)])],\n)";
    let error = error_of(text);
    assert_eq!(
        error.to_string(),
        "line 2, column 52: bodies[0].colliders[0]: unknown field `densty` (at `bodies.0.colliders.0.densty`)"
    );
    // A misspelt field of a shape leaves a required one missing, which the parser names.
    let text = "Scene(\n  bodies: [(colliders: [(shape: Ball(radus: 0.5))])],\n)";
    let error = error_of(text);
    assert!(matches!(error, SceneError::Syntax { .. }), "{error:?}");
    assert!(error.to_string().starts_with("line 2, column "), "{error}");
    assert!(error.to_string().contains("`radius`"), "{error}");
    let text = "Scene(\n  bodies: [(bdy: ())],\n)";
    assert_eq!(
        error_of(text).to_string(),
        "line 2, column 13: bodies[0]: unknown field `bdy` (at `bodies.0.bdy`)"
    );
}

#[test]
fn a_negative_radius_names_the_field_the_value_and_the_place() {
    let text = "Scene(\n    bodies: [\n        (body: (body_type: Fixed)),\n        (colliders: [(density: 2.0, shape: Ball(radius: -1.5))]),\n    ],\n)\n";
    let error = error_of(text);
    assert!(matches!(error, SceneError::Invalid { .. }), "{error:?}");
    assert_eq!(error.location(), at(4, 49), "{error}");
    assert_eq!(
        error.to_string(),
        "line 4, column 49: bodies[1].colliders[0]: `radius` must be > 0, got -1.5"
    );
}

#[test]
fn nan_is_read_and_refused() {
    // `NaN` is a RON float: the text parses, the engine refuses the value.
    let text =
        "Scene(\n    bodies: [\n        (body: (linear_velocity: (0.0, NaN, 0.0))),\n    ],\n)\n";
    let error = error_of(text);
    assert_eq!(error.location(), at(3, 17), "{error}");
    assert_eq!(
        error.to_string(),
        "line 3, column 17: bodies[0].body: `linear_velocity` must be finite, got [0, NaN, 0]"
    );
}

#[test]
fn a_joint_to_a_missing_body_is_a_stale_reference() {
    let text = "Scene(\n    bodies: [(), ()],\n    joints: [\n        (body_a: 0, body_b: 1, joint: (kind: Ball(()))),\n        (body_a: 0, body_b: 7, joint: (kind: Ball(()))),\n    ],\n)\n";
    let error = error_of(text);
    assert!(
        matches!(
            error,
            SceneError::UnknownBody {
                field: "body_b",
                index: 7,
                body_count: 2,
                ..
            }
        ),
        "{error:?}"
    );
    assert_eq!(error.location(), at(5, 21), "{error}");
    assert_eq!(
        error.to_string(),
        "line 5, column 21: joints[1]: `body_b` names body 7, but the scene has 2 bodies (0 to 1)"
    );
}

#[test]
fn a_joint_option_out_of_range_is_placed_at_its_field() {
    let text = "Scene(\n    bodies: [()],\n    joints: [(body_b: 0, joint: (\n        kind: Rope((max_length: 1.0, restitution: 1.5)),\n    ))],\n)\n";
    let error = error_of(text);
    assert_eq!(error.location(), at(4, 38), "{error}");
    assert!(
        error
            .to_string()
            .ends_with("joints[0]: `restitution` must lie in [0, 1], got 1.5"),
        "{error}"
    );
}

#[test]
fn bad_settings_and_run_lengths_are_refused() {
    let error = error_of("Scene(settings: (substep_count: 0))");
    assert_eq!(error.location(), at(1, 18), "{error}");
    assert!(error.to_string().contains("substep_count"), "{error}");

    let error = error_of("Scene(\n  run: (dt: -0.01),\n)");
    assert_eq!(error.location(), at(2, 9), "{error}");
    assert_eq!(
        error.to_string(),
        "line 2, column 9: run: `dt` must be finite and > 0 (s), got -0.01"
    );
}

#[test]
fn a_bad_mass_is_refused() {
    let text = "Scene(bodies: [(body: (mass_properties: (mass: -1.0, local_center_of_mass: (0.0, 0.0, 0.0), local_inertia: (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0))))])";
    let error = error_of(text);
    // Mass properties check themselves as they are read.
    assert!(matches!(error, SceneError::Refused { .. }), "{error:?}");
    assert_eq!(error.location(), at(1, 42), "{error}");
    assert_eq!(
        error.to_string(),
        "line 1, column 42: bodies[0].body: `mass` must be > 0, got -1"
    );
}

#[test]
fn a_degenerate_hull_in_a_compound_is_refused_with_its_place() {
    let text = "Scene(bodies: [(colliders: [(shape: Compound(parts: [\n  ((position: (0.0, 0.0, 0.0), rotation: (0.0, 0.0, 0.0, 1.0)), ConvexHull(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)])),\n]))])])";
    let error = error_of(text);
    assert!(matches!(error, SceneError::Invalid { .. }), "{error:?}");
    // At the part's `points`, line 2.
    assert_eq!(error.location(), at(2, 76), "{error}");
    assert!(
        error
            .to_string()
            .contains("compound part 0: `points` must hold"),
        "{error}"
    );
}

#[test]
fn a_missing_file_is_a_read_error() {
    let error = Scene::from_file("no/such/scene.ron").unwrap_err();
    assert!(matches!(error, SceneError::Read { .. }), "{error:?}");
    assert!(error.to_string().contains("no/such/scene.ron"), "{error}");
}

#[test]
fn a_description_that_checks_itself_is_refused_at_its_field() {
    // A rope of −5 m: refused while it is read, placed at its `max_length`.
    let text = "Scene(\n    bodies: [(), ()],\n    joints: [(body_a: 0, body_b: 1, joint: (kind: Rope((max_length: -5.0, restitution: 0.0)))),\n    ],\n)\n";
    let error = error_of(text);
    assert!(matches!(error, SceneError::Refused { .. }), "{error:?}");
    assert_eq!(error.location(), at(3, 57), "{error}");
    assert_eq!(
        error.to_string(),
        "line 3, column 57: joints[0]: `max_length` must be >= 0, got -5"
    );
    // Settings above their bounds: the count that would hang the step is refused.
    for (text, field) in [
        (
            "Scene(settings: (substep_count: 4294967295))",
            "substep_count",
        ),
        (
            "Scene(settings: (max_steps_per_advance: 1000000, fixed_dt: 1e-30))",
            "fixed_dt",
        ),
        (
            "Scene(settings: (joints: (solve_iterations: 4294967295)))",
            "solve_iterations",
        ),
    ] {
        let error = error_of(text);
        assert!(matches!(error, SceneError::Refused { .. }), "{error:?}");
        assert!(error.to_string().contains("settings: "), "{error}");
        assert!(error.to_string().contains(field), "{error}");
    }
}

#[test]
fn infinite_bounds_read_as_numbers_or_strings() {
    // RON's bare `inf` and the "inf" the engine writes both mean no cap.
    for bound in ["inf", "\"inf\""] {
        let text = format!(
            "Scene(bodies: [(), ()], joints: [(body_a: 0, body_b: 1, joint: (kind: Spring((rest_length: 1.0, model: Soft(Frequency(frequency_hz: 2.0, damping_ratio: 0.5)), max_force: {bound})), break_force: {bound}))])"
        );
        let scene = Scene::from_ron(&text).unwrap();
        let joint = &scene.joints[0].joint;
        assert!(joint.break_force().is_infinite());
        let rebound::JointKind::Spring(spring) = joint.kind() else {
            panic!("{joint:?}");
        };
        assert_eq!(spring.force_range(), (f32::NEG_INFINITY, f32::INFINITY));
    }
}
