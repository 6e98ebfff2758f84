//! Every file under `scenes/` builds the same world as the code it was written from: the example scenes
//! (`rebound_suite::demos`) and the five benchmark scenes (`rebound_suite::scenes`). Same world means the
//! same [`PhysicsWorld::state_digest`] — bit-identical poses and velocities — after 60 steps.
//!
//! `REBOUND_WRITE_SCENES=1 cargo test --test scene_files` writes the files from the code first (after a
//! deliberate change to a scene).

use rebound::prelude::*;
use rebound_scene::Scene;
use rebound_suite::demos::{self, About};
use rebound_suite::scenes::{self, SceneOptions};
use std::path::PathBuf;

/// Steps before the digests are compared: enough for contacts, joints and sleep to act in every scene.
const STEPS: usize = 60;

fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

/// Loads `path` (writing it from `scene` first if asked) and checks it reads back as `scene`.
fn load(path: &PathBuf, scene: &Scene) -> PhysicsWorld {
    if std::env::var_os("REBOUND_WRITE_SCENES").is_some() {
        std::fs::write(path, scene.to_ron()).expect("the scene file is written");
    }
    let (from_file, built) =
        rebound_scene::load_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        from_file.to_ron(),
        scene.to_ron(),
        "{} differs from the code; rewrite it with REBOUND_WRITE_SCENES=1",
        path.display()
    );
    built.world
}

fn digest_after_steps(world: &mut PhysicsWorld) -> u64 {
    for _ in 0..STEPS {
        world.step(demos::DT);
    }
    world.state_digest()
}

#[test]
fn every_example_scene_file_builds_the_code_built_world() {
    for name in demos::DEMOS {
        let (mut code, about) = demos::build(name).unwrap().unwrap();
        let scene = demos::scene_of(&code, &about);
        let mut file = load(&scenes_dir().join(format!("{name}.ron")), &scene);
        assert_eq!(file.bodies().len(), code.bodies().len(), "{name}");
        assert_eq!(file.colliders().len(), code.colliders().len(), "{name}");
        assert_eq!(
            file.world().joints().count(),
            code.world().joints().count(),
            "{name}"
        );
        let (a, b) = (digest_after_steps(&mut code), digest_after_steps(&mut file));
        assert_eq!(a, b, "{name}: the file's world moves differently");
    }
}

#[test]
fn every_benchmark_scene_file_builds_the_code_built_world() {
    for About { name, .. } in demos::BENCHMARKS {
        let about = demos::BENCHMARKS
            .iter()
            .find(|a| a.name == name)
            .copied()
            .unwrap();
        let mut code = scenes::build(name, SceneOptions::default())
            .unwrap()
            .unwrap();
        let scene = demos::scene_of(code.world(), &about);
        let path = scenes_dir().join("benchmarks").join(format!("{name}.ron"));
        let mut file = load(&path, &scene);
        assert_eq!(file.bodies().len(), code.world().bodies().len(), "{name}");
        for _ in 0..STEPS {
            code.step();
        }
        assert_eq!(
            code.world().state_digest(),
            digest_after_steps(&mut file),
            "{name}: the file's world moves differently"
        );
    }
}
