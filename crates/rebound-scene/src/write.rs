//! Writing a scene as RON text that names only what differs from the defaults, one body or joint a line, so
//! that a 4,096-ball scene stays a few hundred kilobytes and a small one reads like a hand-written file.
//!
//! `ron`'s serializer writes every field of a struct; here each description's fields are compared with its
//! default and only the differing ones are written, each value by `ron`. Reading the text back gives the same
//! scene bit for bit (`ron` writes floats in their shortest round-trip form; the tests check every field).

use crate::{RunSettings, Scene, SceneBody, SceneCamera, SceneJoint};
use rebound::prelude::*;
use rebound::{Integrator, JointSettings, StepLimits};
use serde::Serialize;
use std::fmt::Write as _;

/// One value as RON on a single line.
fn inline<T: Serialize + ?Sized>(value: &T) -> String {
    let config = ron::ser::PrettyConfig::new()
        .compact_structs(true)
        .compact_arrays(true)
        .compact_maps(true)
        .new_line("")
        .indentor("")
        .struct_names(false);
    // Serialising these plain data types cannot fail (no maps with non-string keys, no I/O).
    ron::ser::to_string_pretty(value, config).unwrap_or_default()
}

/// Collects `name: value` pairs for the fields that differ from the default.
struct Fields(Vec<String>);

impl Fields {
    fn new() -> Self {
        Self(Vec::new())
    }

    /// Writes the field if its text differs from the default's: bits, not values, so `-0.0` is kept.
    fn differ<T: Serialize>(&mut self, name: &str, value: &T, default: &T) {
        let text = inline(value);
        if text != inline(default) {
            self.0.push(format!("{name}: {text}"));
        }
    }

    fn always<T: Serialize + ?Sized>(&mut self, name: &str, value: &T) {
        self.0.push(format!("{name}: {}", inline(value)));
    }

    fn raw(&mut self, name: &str, text: &str) {
        self.0.push(format!("{name}: {text}"));
    }

    fn finish(self) -> String {
        format!("({})", self.0.join(", "))
    }
}

fn body_desc(desc: &BodyDesc) -> String {
    let d = BodyDesc::default();
    let mut f = Fields::new();
    f.differ("body_type", &desc.body_type, &d.body_type);
    f.differ("position", &desc.position, &d.position);
    f.differ("rotation", &desc.rotation, &d.rotation);
    f.differ("linear_velocity", &desc.linear_velocity, &d.linear_velocity);
    f.differ(
        "angular_velocity",
        &desc.angular_velocity,
        &d.angular_velocity,
    );
    f.differ("mass_properties", &desc.mass_properties, &d.mass_properties);
    f.differ("gravity_scale", &desc.gravity_scale, &d.gravity_scale);
    f.differ("linear_damping", &desc.linear_damping, &d.linear_damping);
    f.differ("angular_damping", &desc.angular_damping, &d.angular_damping);
    f.differ::<Integrator>("integrator", &desc.integrator, &d.integrator);
    f.differ("gyroscopic", &desc.gyroscopic, &d.gyroscopic);
    f.differ("sleeping", &desc.sleeping, &d.sleeping);
    f.differ("can_sleep", &desc.can_sleep, &d.can_sleep);
    f.differ("locked_axes", &desc.locked_axes, &d.locked_axes);
    f.finish()
}

fn collider_desc(desc: &ColliderDesc) -> String {
    let d = ColliderDesc::default();
    let mut f = Fields::new();
    f.always("shape", &desc.shape);
    f.differ("local_pose", &desc.local_pose, &d.local_pose);
    f.differ("density", &desc.density, &d.density);
    f.differ("friction", &desc.friction, &d.friction);
    f.differ(
        "friction_combine_rule",
        &desc.friction_combine_rule,
        &d.friction_combine_rule,
    );
    f.differ("restitution", &desc.restitution, &d.restitution);
    f.differ(
        "restitution_combine_rule",
        &desc.restitution_combine_rule,
        &d.restitution_combine_rule,
    );
    f.differ(
        "rolling_friction",
        &desc.rolling_friction,
        &d.rolling_friction,
    );
    f.differ("groups", &desc.groups, &d.groups);
    f.differ("is_sensor", &desc.is_sensor, &d.is_sensor);
    f.differ("enabled", &desc.enabled, &d.enabled);
    f.differ(
        "force_event_threshold",
        &desc.force_event_threshold,
        &d.force_event_threshold,
    );
    f.finish()
}

fn joint_settings(s: &JointSettings) -> String {
    let d = JointSettings::default();
    let mut f = Fields::new();
    f.differ("frequency_hz", &s.frequency_hz, &d.frequency_hz);
    f.differ("damping_ratio", &s.damping_ratio, &d.damping_ratio);
    f.differ(
        "max_frequency_ratio",
        &s.max_frequency_ratio,
        &d.max_frequency_ratio,
    );
    f.differ("solve_iterations", &s.solve_iterations, &d.solve_iterations);
    f.differ("relax_iterations", &s.relax_iterations, &d.relax_iterations);
    f.differ("tethers", &s.tethers, &d.tethers);
    f.differ("direct_chains", &s.direct_chains, &d.direct_chains);
    f.finish()
}

fn world_settings(s: &WorldSettings) -> String {
    let d = WorldSettings::default();
    let mut f = Fields::new();
    f.differ("gravity", &s.gravity, &d.gravity);
    f.differ("substep_count", &s.substep_count, &d.substep_count);
    f.differ(
        "contact_frequency_hz",
        &s.contact_frequency_hz,
        &d.contact_frequency_hz,
    );
    f.differ(
        "contact_damping_ratio",
        &s.contact_damping_ratio,
        &d.contact_damping_ratio,
    );
    f.differ(
        "max_push_out_speed",
        &s.max_push_out_speed,
        &d.max_push_out_speed,
    );
    f.differ(
        "restitution_threshold",
        &s.restitution_threshold,
        &d.restitution_threshold,
    );
    f.differ("warm_starting", &s.warm_starting, &d.warm_starting);
    f.differ(
        "speculative_margin",
        &s.speculative_margin,
        &d.speculative_margin,
    );
    f.differ("sleep_enabled", &s.sleep_enabled, &d.sleep_enabled);
    f.differ(
        "linear_sleep_threshold",
        &s.linear_sleep_threshold,
        &d.linear_sleep_threshold,
    );
    f.differ(
        "angular_sleep_threshold",
        &s.angular_sleep_threshold,
        &d.angular_sleep_threshold,
    );
    f.differ("time_to_sleep", &s.time_to_sleep, &d.time_to_sleep);
    f.differ("fixed_dt", &s.fixed_dt, &d.fixed_dt);
    f.differ(
        "max_steps_per_advance",
        &s.max_steps_per_advance,
        &d.max_steps_per_advance,
    );
    let joints = joint_settings(&s.joints);
    if joints != "()" {
        f.raw("joints", &joints);
    }
    let limits = step_limits(&s.limits);
    if limits != "()" {
        f.raw("limits", &limits);
    }
    f.finish()
}

fn step_limits(s: &StepLimits) -> String {
    let d = StepLimits::default();
    let mut f = Fields::new();
    f.differ("max_speed", &s.max_speed, &d.max_speed);
    f.differ(
        "max_angular_speed",
        &s.max_angular_speed,
        &d.max_angular_speed,
    );
    f.differ("max_position", &s.max_position, &d.max_position);
    f.differ(
        "max_candidate_pairs",
        &s.max_candidate_pairs,
        &d.max_candidate_pairs,
    );
    f.differ(
        "max_contact_points",
        &s.max_contact_points,
        &d.max_contact_points,
    );
    f.finish()
}

fn run_settings(r: &RunSettings) -> String {
    let d = RunSettings::default();
    let mut f = Fields::new();
    f.differ("dt", &r.dt, &d.dt);
    f.differ("steps", &r.steps, &d.steps);
    f.finish()
}

fn camera(c: &SceneCamera) -> String {
    let mut f = Fields::new();
    f.always("position", &c.position);
    f.always("target", &c.target);
    f.always("fov_degrees", &c.fov_degrees);
    f.finish()
}

fn body(b: &SceneBody) -> String {
    let mut f = Fields::new();
    if !b.name.is_empty() {
        f.always("name", &b.name);
    }
    f.raw("body", &body_desc(&b.body));
    if !b.colliders.is_empty() {
        let colliders: Vec<String> = b.colliders.iter().map(collider_desc).collect();
        f.raw("colliders", &format!("[{}]", colliders.join(", ")));
    }
    f.finish()
}

fn joint(j: &SceneJoint) -> String {
    let mut f = Fields::new();
    if let Some(a) = j.body_a {
        f.always("body_a", &a);
    }
    f.always("body_b", &j.body_b);
    let joint = &j.joint;
    let mut g = Fields::new();
    g.always("kind", joint.kind());
    g.differ("local_anchor_a", &joint.local_anchor_a(), &Vec3::ZERO);
    g.differ("local_anchor_b", &joint.local_anchor_b(), &Vec3::ZERO);
    g.differ("local_basis_a", &joint.local_basis_a(), &Quat::IDENTITY);
    g.differ("local_basis_b", &joint.local_basis_b(), &Quat::IDENTITY);
    if joint.break_force().is_finite() {
        g.always("break_force", &Some(joint.break_force()));
    }
    if joint.break_torque().is_finite() {
        g.always("break_torque", &Some(joint.break_torque()));
    }
    f.raw("joint", &g.finish());
    if !j.contacts_enabled {
        f.always("contacts_enabled", &false);
    }
    f.finish()
}

impl Scene {
    /// The scene as RON text: fields equal to their defaults left out, one body or joint a line. Reading it
    /// back ([`Scene::from_ron`]) gives this scene bit for bit.
    #[must_use]
    pub fn to_ron(&self) -> String {
        let mut out = String::from("Scene(\n");
        let mut line = |text: String| {
            let _ = writeln!(out, "    {text},");
        };
        if !self.name.is_empty() {
            line(format!("name: {}", inline(&self.name)));
        }
        if !self.description.is_empty() {
            line(format!("description: {}", inline(&self.description)));
        }
        line(format!("settings: {}", world_settings(&self.settings)));
        let run = run_settings(&self.run);
        if run != "()" {
            line(format!("run: {run}"));
        }
        if let Some(c) = &self.camera {
            line(format!("camera: Some({})", camera(c)));
        }
        let mut list = |name: &str, items: Vec<String>| {
            if items.is_empty() {
                return;
            }
            let _ = writeln!(out, "    {name}: [");
            for item in items {
                let _ = writeln!(out, "        {item},");
            }
            let _ = writeln!(out, "    ],");
        };
        list("bodies", self.bodies.iter().map(body).collect());
        list("joints", self.joints.iter().map(joint).collect());
        out.push_str(")\n");
        out
    }
}
