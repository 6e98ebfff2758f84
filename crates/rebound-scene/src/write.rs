//! Writing a scene as RON text that names only what differs from the defaults, one body or joint a line, so
//! that a 4,096-ball scene stays a few hundred kilobytes and a small one reads like a hand-written file.
//!
//! `ron`'s serializer writes every field of a struct; here each description's fields are compared with its
//! default and only the differing ones are written, each value by `ron`. Reading the text back gives the same
//! scene bit for bit (`ron` writes floats in their shortest round-trip form; the tests check every field).

use crate::{RunSettings, Scene, SceneBody, SceneCamera, SceneJoint};
use rebound::prelude::*;
use rebound::{JointSettings, StepLimits};
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

/// Adds to `$fields` each listed field of `$value` whose text differs from the same field of `$default`
/// (the one comparison every description kind makes, field by field, in the listed order).
macro_rules! differing {
    ($fields:expr, $value:expr, $default:expr, [$($field:ident),* $(,)?]) => {{
        let (value, default) = ($value, &$default);
        $( $fields.differ(stringify!($field), &value.$field, &default.$field); )*
    }};
}

fn body_desc(desc: &BodyDesc) -> String {
    let mut f = Fields::new();
    differing!(
        f,
        desc,
        BodyDesc::default(),
        [
            body_type,
            position,
            rotation,
            linear_velocity,
            angular_velocity,
            mass_properties,
            gravity_scale,
            linear_damping,
            angular_damping,
            integrator,
            gyroscopic,
            sleeping,
            can_sleep,
            locked_axes,
        ]
    );
    f.finish()
}

fn collider_desc(desc: &ColliderDesc) -> String {
    let mut f = Fields::new();
    f.always("shape", &desc.shape);
    differing!(
        f,
        desc,
        ColliderDesc::default(),
        [
            local_pose,
            density,
            friction,
            friction_combine_rule,
            restitution,
            restitution_combine_rule,
            rolling_friction,
            groups,
            is_sensor,
            enabled,
            force_event_threshold,
        ]
    );
    f.finish()
}

fn joint_settings(s: &JointSettings) -> String {
    let mut f = Fields::new();
    differing!(
        f,
        s,
        JointSettings::default(),
        [
            frequency_hz,
            damping_ratio,
            max_frequency_ratio,
            solve_iterations,
            relax_iterations,
            tethers,
            direct_chains,
        ]
    );
    f.finish()
}

fn world_settings(s: &WorldSettings) -> String {
    let mut f = Fields::new();
    differing!(
        f,
        s,
        WorldSettings::default(),
        [
            gravity,
            substep_count,
            contact_frequency_hz,
            contact_damping_ratio,
            max_push_out_speed,
            restitution_threshold,
            warm_starting,
            speculative_margin,
            sleep_enabled,
            linear_sleep_threshold,
            angular_sleep_threshold,
            time_to_sleep,
            fixed_dt,
            max_steps_per_advance,
        ]
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
    let mut f = Fields::new();
    differing!(
        f,
        s,
        StepLimits::default(),
        [
            max_speed,
            max_angular_speed,
            max_position,
            max_candidate_pairs,
            max_contact_points,
        ]
    );
    f.finish()
}

fn run_settings(r: &RunSettings) -> String {
    let mut f = Fields::new();
    differing!(f, r, RunSettings::default(), [dt, steps]);
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
