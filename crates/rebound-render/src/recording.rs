//! Pictures and plots of a recording (`rebound-record`): [`RecordingScenes`] turns its frames into
//! [`RenderScene`]s, tessellating each collider once, and [`time_history`] gathers the frames' diagnostics
//! for [`crate::plot_svg`].

use std::sync::Arc;

use rebound::ColliderShape;
use rebound::prelude::Pose;
use rebound_record::{BodyKind, Catalog, Frame, Manifest};

use crate::{
    ContactMark, DEFAULT_ROUND_SUBDIVISIONS, JointSegment, Mesh, RenderError, RenderScene,
    TimeHistory, body_colour,
};

/// Follows a recording frame by frame — its descriptions with each frame's changes applied — and gives the
/// scene of each frame: every present body's enabled, non-sensor colliders at the frame's poses, coloured by
/// [`body_colour`] from the frame's kind and sleeping flag; the frame's contact points and the segments of its
/// present, unbroken joints.
#[derive(Debug, Clone)]
pub struct RecordingScenes {
    catalog: Catalog,
    /// By collider index: the shape last tessellated and its mesh.
    meshes: Vec<Option<(ColliderShape, Arc<Mesh>)>>,
    subdivisions: u32,
}

impl RecordingScenes {
    /// Starts at the recording's manifest, round shapes with [`DEFAULT_ROUND_SUBDIVISIONS`].
    ///
    /// # Errors
    /// [`RenderError::Recording`] if the manifest's descriptions are inconsistent.
    pub fn new(manifest: &Manifest) -> Result<Self, RenderError> {
        Ok(Self {
            catalog: Catalog::from_manifest(manifest, 0)?,
            meshes: Vec::new(),
            subdivisions: DEFAULT_ROUND_SUBDIVISIONS,
        })
    }

    /// The same with round shapes of `subdivisions` around their axis (see [`Mesh::from_shape`]).
    #[must_use]
    pub fn with_subdivisions(mut self, subdivisions: u32) -> Self {
        self.subdivisions = subdivisions;
        self.meshes.clear();
        self
    }

    /// The descriptions as of the last frame given.
    #[must_use]
    pub fn catalog(&self) -> &Catalog {
        &self.catalog
    }

    /// Applies `frame`'s changes without building its scene: frames must be given in file order, every one
    /// of them, for the descriptions to follow the run, including the frames not drawn.
    ///
    /// # Errors
    /// [`RenderError::Recording`] if the changes do not fit the descriptions so far (nothing changes then).
    pub fn advance(&mut self, frame: &Frame) -> Result<(), RenderError> {
        if let Some(changes) = &frame.changes {
            self.catalog.apply(changes, 0)?;
        }
        Ok(())
    }

    /// Applies `frame`'s changes ([`RecordingScenes::advance`]) and gives its scene.
    ///
    /// # Errors
    /// [`RenderError::Recording`] as [`RecordingScenes::advance`]; [`RenderError::Shape`] if a shape cannot be
    /// tessellated (not for shapes the reader accepted).
    pub fn scene(&mut self, frame: &Frame) -> Result<RenderScene, RenderError> {
        self.advance(frame)?;
        let mut scene = RenderScene::new();
        for (entry, sample) in self.catalog.bodies().iter().zip(&frame.bodies) {
            if !sample.present {
                continue;
            }
            let body_pose = Pose {
                position: sample.position,
                rotation: sample.rotation,
            };
            let colour = body_colour(
                entry.index,
                sample.kind == BodyKind::Dynamic,
                sample.sleeping,
            );
            for collider in &entry.colliders {
                if collider.sensor || !collider.enabled {
                    continue;
                }
                let slot = collider.index as usize;
                if self.meshes.len() <= slot {
                    self.meshes.resize(slot + 1, None);
                }
                let mesh = match &self.meshes[slot] {
                    Some((shape, mesh)) if *shape == collider.shape => Arc::clone(mesh),
                    _ => {
                        let mesh = Arc::new(Mesh::from_shape(&collider.shape, self.subdivisions)?);
                        self.meshes[slot] = Some((collider.shape.clone(), Arc::clone(&mesh)));
                        mesh
                    }
                };
                scene.push(mesh, body_pose.mul_pose(&collider.local_pose), colour);
            }
        }
        scene.contacts = frame
            .contacts
            .iter()
            .map(|c| ContactMark {
                point: c.point,
                normal: c.normal,
            })
            .collect();
        scene.joints = frame
            .joints
            .iter()
            .filter(|j| j.present && !j.broken)
            .map(|j| JointSegment {
                anchor_a: j.anchor_a,
                anchor_b: j.anchor_b,
            })
            .collect();
        Ok(scene)
    }
}

/// The diagnostics of `frames` (energy, momentum, worst joint error, deepest penetration) against their
/// time, for [`TimeHistory::to_svg`].
#[must_use]
pub fn time_history(frames: &[Frame]) -> TimeHistory {
    let column = |value: fn(&Frame) -> f32| frames.iter().map(|f| f64::from(value(f))).collect();
    let vector = |value: fn(&Frame) -> rebound::prelude::Vec3| {
        frames
            .iter()
            .map(|f| value(f).to_array().map(f64::from))
            .collect()
    };
    TimeHistory {
        time: frames.iter().map(|f| f.time).collect(),
        kinetic_energy: column(|f| f.diagnostics.kinetic_energy),
        potential_energy: column(|f| f.diagnostics.potential_energy),
        spring_energy: column(|f| f.diagnostics.spring_energy),
        linear_momentum: vector(|f| f.diagnostics.linear_momentum),
        angular_momentum: vector(|f| f.diagnostics.angular_momentum),
        worst_joint_error: column(|f| f.diagnostics.worst_joint_error),
        deepest_penetration: column(|f| f.diagnostics.deepest_penetration),
    }
}
