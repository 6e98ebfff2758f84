// Recordings written by the engine itself, through the `rebound` command, and the command's own JSON dump of
// a frame (read by the Rust reader), so the browser tests compare the page with numbers that did not pass
// through the viewer's JavaScript reader.

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO_DIR } from './support.js';

/** Where generated recordings go (inside the ignored target directory). */
export const OUT_DIR = path.join(REPO_DIR, 'target', 'viewer-test');

let built = null;

/** The `rebound` binary: `REBOUND_BIN` if set, else the release build, built once per test run. */
export function reboundBinary() {
  if (process.env.REBOUND_BIN) return process.env.REBOUND_BIN;
  if (built === null) {
    const cargo = spawnSync('cargo', ['build', '--release', '--quiet', '-p', 'rebound-cli'], {
      cwd: REPO_DIR,
      stdio: ['ignore', 'inherit', 'inherit'],
    });
    if (cargo.status !== 0) throw new Error(`cargo build --release -p rebound-cli failed (${cargo.status})`);
    built = path.join(REPO_DIR, 'target', 'release', 'rebound');
  }
  return built;
}

function rebound(args) {
  const run = spawnSync(reboundBinary(), args, { cwd: REPO_DIR, encoding: 'utf8', maxBuffer: 256 * 1024 * 1024 });
  if (run.status !== 0) throw new Error(`rebound ${args.join(' ')} failed (${run.status}):\n${run.stderr}`);
  return run.stdout;
}

/** Runs `scene` (a path under the repository) and records it to OUT_DIR/`name`; returns the file's path. */
export function record(scene, name, extra = []) {
  fs.mkdirSync(OUT_DIR, { recursive: true });
  const out = path.join(OUT_DIR, name);
  rebound(['run', scene, '--record', out, ...extra]);
  return out;
}

/** The Rust reader's JSON dump of frames `frames` of `file` (see `rebound frame --help`). */
export function dumpFrames(file, frames) {
  return JSON.parse(rebound(['frame', file, ...frames.map(String)]));
}
