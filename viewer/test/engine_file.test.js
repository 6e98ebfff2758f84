// The JavaScript reader on a file the engine wrote, against the Rust reader's dump of the same frames: every
// number equal, bit for bit (the dump prints each f32 exactly, as the f64 of the same value).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { readRecording } from '../src/recording.js';
import { record, dumpFrames } from './engine.js';

test('the reader gives the Rust reader\'s numbers for every frame of an engine recording', () => {
  const file = record('scenes/newtons_cradle.ron', 'cradle-reader.rrec', 90);
  const recording = readRecording(fs.readFileSync(file));
  const all = [...Array(recording.frameCount).keys()];
  const dump = dumpFrames(file, all);
  assert.equal(recording.frameCount, dump.frame_count);
  assert.equal(recording.bodies.length, dump.bodies.length);
  dump.bodies.forEach((body, i) => {
    assert.equal(recording.bodies[i].mass, body.mass);
    assert.equal(recording.bodies[i].kind, body.kind);
    const shape = recording.bodies[i].parts[0].shape;
    assert.equal(shape.kind, 'ball');
    assert.equal(Math.fround(shape.radius), body.colliders[0].shape.Ball.radius);
  });
  let contacts = 0;
  for (const expected of dump.frames) {
    const frame = recording.frame(expected.index);
    const header = recording.header(expected.index);
    assert.equal(frame.step, expected.step);
    assert.equal(frame.time, expected.time);
    assert.equal(header.kinetic, expected.kinetic_energy);
    assert.equal(header.potential, expected.potential_energy);
    expected.bodies.forEach((b, i) => {
      assert.deepEqual([...frame.positions.subarray(3 * i, 3 * i + 3)], b.position, `frame ${expected.index} body ${i}`);
      assert.deepEqual([...frame.rotations.subarray(4 * i, 4 * i + 4)], b.rotation);
      assert.deepEqual([...frame.linearVelocities.subarray(3 * i, 3 * i + 3)], b.linear_velocity);
      assert.deepEqual([...frame.angularVelocities.subarray(3 * i, 3 * i + 3)], b.angular_velocity);
      assert.equal(frame.present[i] === 1, b.present);
      assert.equal(frame.sleeping[i] === 1, b.sleeping);
      assert.equal(frame.kinds[i], b.kind);
    });
    assert.deepEqual(frame.contacts, expected.contacts);
    contacts += expected.contacts.length;
    assert.deepEqual(
      frame.joints.map((j) => ({ anchor_a: j.anchorA, anchor_b: j.anchorB, error: j.error, present: true, broken: j.broken })),
      expected.joints.filter((j) => j.present),
    );
  }
  assert.ok(contacts > 0, 'the run has contacts to compare');
});
