// Recordings written by the engine itself (rebound-record's Recorder, through the `viewer_fixtures` example),
// and the Rust reader's JSON dump of frames, so the browser tests compare the page with numbers that did not
// pass through the viewer's JavaScript reader.

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO_DIR } from './support.js';

/** Where generated recordings go (inside the ignored target directory). */
export const OUT_DIR = path.join(REPO_DIR, 'target', 'viewer-test');

let built = null;

/**
 * The fixture program: `REBOUND_FIXTURES` if set, else rebound-record's `viewer_fixtures` example in release,
 * built once per test run.
 */
export function fixturesBinary() {
  if (process.env.REBOUND_FIXTURES) return process.env.REBOUND_FIXTURES;
  if (built === null) {
    const cargo = spawnSync('cargo', ['build', '--release', '--quiet', '-p', 'rebound-record', '--example', 'viewer_fixtures'], {
      cwd: REPO_DIR,
      stdio: ['ignore', 'inherit', 'inherit'],
    });
    if (cargo.status !== 0) throw new Error(`building the viewer_fixtures example failed (${cargo.status})`);
    built = path.join(REPO_DIR, 'target', 'release', 'examples', 'viewer_fixtures');
  }
  return built;
}

function fixtures(args) {
  const run = spawnSync(fixturesBinary(), args, { cwd: REPO_DIR, encoding: 'utf8', maxBuffer: 256 * 1024 * 1024 });
  if (run.status !== 0) throw new Error(`viewer_fixtures ${args.join(' ')} failed (${run.status}):\n${run.stderr}`);
  return run.stdout;
}

/** Records the scene file `scene` (a path under the repository) for `steps` steps to OUT_DIR/`name`. */
export function record(scene, name, steps) {
  fs.mkdirSync(OUT_DIR, { recursive: true });
  const out = path.join(OUT_DIR, name);
  fixtures(['record', scene, out, String(steps)]);
  return out;
}

/**
 * The Rust reader's JSON dump of frames `frames` of `file`: `{frame_count, bodies (the manifest's entries),
 * frames: [{index, step, time, bodies, contacts, joints, …}]}`.
 */
export function dumpFrames(file, frames) {
  return JSON.parse(fixtures(['frames', file, ...frames.map(String)]));
}
