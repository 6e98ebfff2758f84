//! Records the resolved rapier3d version (from Cargo.lock) so the output can name the exact release that ran.

use std::fs;

fn main() {
    println!("cargo:rerun-if-changed=Cargo.lock");
    let version = fs::read_to_string("Cargo.lock")
        .ok()
        .and_then(|lock| rapier_version(&lock))
        .unwrap_or_else(|| "0.36".to_owned());
    println!("cargo:rustc-env=PEERS_RAPIER3D_VERSION={version}");
}

/// The `version` line that follows `name = "rapier3d"` in a Cargo.lock.
fn rapier_version(lock: &str) -> Option<String> {
    let mut lines = lock.lines();
    lines.find(|line| line.trim() == r#"name = "rapier3d""#)?;
    let line = lines.next()?.trim();
    let version = line.strip_prefix("version = \"")?.strip_suffix('"')?;
    Some(version.to_owned())
}
