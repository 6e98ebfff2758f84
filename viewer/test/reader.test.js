// The JavaScript reader against hand-laid files: the numbers come back bit for bit, and each way a file can
// break the format is refused with a message naming what and where.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readRecording, RecordingError } from '../src/recording.js';
import { Player } from '../src/player.js';
import { ballsManifest, framePayload, recordingFile } from './encode.js';

const f32 = (v) => Math.fround(v);

function twoBallFile() {
  const frames = [0, 1, 2].map((k) => framePayload({
    step: k,
    time: k / 60,
    energy: [1.5 * k, 10 - k, 0],
    bodies: [
      { position: [0.1 * k, 1, 0], linearVelocity: [6, 0, 0], flags: 1 },
      { position: [1, 0.5, -0.25 * k], flags: k === 2 ? 0b11 : 1 },
    ],
    contacts: k === 1 ? [{ a: 0, b: 1, point: [0.5, 0.75, 0], normal: [1, 0, 0], impulse: 2.5, separation: -0.01 }] : [],
    events: k === 1 ? [{ kind: 1, a: 0, b: 1, value: 6 }] : [],
  }));
  return recordingFile(ballsManifest(2), frames);
}

test('a well-formed file reads back its numbers bit for bit', () => {
  const r = readRecording(twoBallFile());
  assert.equal(r.frameCount, 3);
  assert.equal(r.bodies.length, 2);
  assert.deepEqual(r.bodies[0].parts[0].shape, { kind: 'ball', radius: 0.5 });
  const frame = r.frame(2);
  assert.equal(frame.step, 2);
  assert.equal(frame.time, 2 / 60);
  assert.deepEqual([...frame.positions], [f32(0.2), 1, 0, 1, 0.5, -0.5]);
  assert.deepEqual([...frame.linearVelocities.slice(0, 3)], [6, 0, 0]);
  assert.deepEqual([...frame.sleeping], [0, 1]);
  assert.deepEqual(r.frame(1).contacts, [{ a: 0, b: 1, point: [0.5, 0.75, 0], normal: [1, 0, 0], impulse: 2.5,
    separation: f32(-0.01) }]);
  assert.deepEqual(r.events(1), [{ kind: 1, a: 0, b: 1, value: 6 }]);
  assert.equal(r.header(1).kinetic, 1.5);
  const series = r.energySeries();
  assert.deepEqual(series.map((s) => s.name), ['total', 'kinetic', 'potential']);
  assert.deepEqual([...series[0].values], [0, 0.5, 1]);
  assert.deepEqual([...series[1].values], [0, 1.5, 3]);
  assert.ok(Math.abs(r.frameDt - 1 / 60) < 1e-12, `frame spacing ${r.frameDt}`);
  assert.equal(r.truncated, null);
});

test('a contact force event reads back with its FORCE entry, and a count that disagrees is refused', () => {
  const force = { colliderA: 0, colliderB: 0xffffffff, normal: [0, 1, 0], totalImpulse: 1.635, maxImpulsePoint: [0.25, 0, -0.5],
    maxImpulse: 0.5 };
  const frame = (events) => framePayload({ bodies: [{ position: [0, 0, 0] }, { position: [0, 1, 0] }], events });
  const events = [
    { kind: 1, a: 0, b: 1, value: 2 },
    { kind: 8, a: 0, b: 1, value: 98.1, force },
  ];
  const r = readRecording(recordingFile(ballsManifest(2), [frame(events)]));
  assert.deepEqual(r.events(0), [
    { kind: 1, a: 0, b: 1, value: 2 },
    { kind: 8, a: 0, b: 1, value: f32(98.1), force: { colliderA: 0, colliderB: -1, normal: [0, 1, 0],
      totalImpulse: f32(1.635), maxImpulsePoint: [0.25, 0, -0.5], maxImpulse: 0.5 } },
  ]);
  // NF one too many, with the payload length grown to match: the count must equal the kind-8 events.
  const payload = frame(events);
  const grown = new Uint8Array(payload.length + 40);
  grown.set(payload);
  new DataView(grown.buffer).setUint32(36, 2, true);
  refuses(recordingFile(ballsManifest(2), [grown]), /2 contact force entries but 1 contact force events/);
});

test('bodies inserted later are absent from the earlier frames', () => {
  const manifest = ballsManifest(1);
  const later = ballsManifest(2).bodies[1];
  const file = recordingFile(manifest, [
    framePayload({ bodies: [{ position: [0, 1, 0] }] }),
    framePayload({ step: 1, time: 1 / 60, bodies: [{ position: [0, 1, 0] }, { position: [3, 1, 0] }],
      changes: { bodies: [later] } }),
  ]);
  const r = readRecording(file);
  assert.equal(r.bodies.length, 2);
  assert.deepEqual([...r.frame(0).present], [1, 0]);
  assert.deepEqual([...r.frame(0).rotations.slice(4)], [0, 0, 0, 1]);
  assert.deepEqual([...r.frame(1).positions.slice(3)], [3, 1, 0]);
});

test('a file cut inside a frame keeps its complete frames and says where it ends', () => {
  const whole = twoBallFile();
  const r = readRecording(whole.slice(0, whole.length - 10));
  assert.equal(r.frameCount, 2);
  assert.match(r.truncated, /frame 2 at byte \d+ needs \d+ bytes but the file ends at byte \d+/);
});

function refuses(bytes, pattern) {
  assert.throws(() => readRecording(bytes), (error) => {
    assert.ok(error instanceof RecordingError, `a RecordingError, got ${error}`);
    assert.match(error.message, pattern);
    return true;
  });
}

test('broken files are refused with what and where', () => {
  const good = twoBallFile();
  const manifestLength = new DataView(good.buffer).getUint32(12, true);
  const firstFrame = 16 + manifestLength;

  refuses(new Uint8Array(8), /16-byte file header/);
  refuses(new TextEncoder().encode('this is just some text, not a recording'), /wrong magic bytes at offset 0/);
  refuses(recordingFile(ballsManifest(1), [], { version: 1 }), /unsupported format version 1 at offset 8/);
  refuses(recordingFile(ballsManifest(1), []), /no frames/);
  refuses(good.slice(0, 40), /truncated: the manifest runs to byte/);

  const badJson = good.slice();
  badJson[16] = 0x7b + 1; // '|' in place of '{'
  refuses(badJson, /manifest at byte 16 is not valid JSON/);

  const notRecording = recordingFile({ format: 'something-else' }, []);
  refuses(notRecording, /manifest field "format" is "something-else"/);

  const badShape = ballsManifest(1);
  badShape.bodies[0].colliders[0].shape = { Ball: { radius: 'big' } };
  refuses(recordingFile(badShape, []), /bodies\[0\]\.colliders\[0\]\.shape\.Ball\.radius is "big"/);

  const oddLength = good.slice();
  new DataView(oddLength.buffer).setUint32(firstFrame, 86, true);
  refuses(oddLength, /frame 0 at byte \d+: payload length 86 is not a multiple of 4/);

  const wrongCount = good.slice();
  new DataView(wrongCount.buffer).setUint32(firstFrame + 4 + 16, 3, true);
  refuses(wrongCount, /frame 0 .*payload length \d+ disagrees with its counts \(3 bodies/);

  const badKind = twoBallFile();
  const flagsAt = firstFrame + 4 + 84 + 52 * 2;
  badKind[flagsAt] = 0b1101;
  refuses(badKind, /body 0 has invalid flags 0xd at byte/);

  const badContact = recordingFile(ballsManifest(2), [framePayload({
    bodies: [{ position: [0, 0, 0] }, { position: [1, 0, 0] }],
    contacts: [{ a: 0, b: 7, point: [0, 0, 0], normal: [1, 0, 0], impulse: 0, separation: 0 }],
  })]);
  refuses(badContact, /contact 0 at byte \d+ names body 7, but there are 2/);

  const badEvent = recordingFile(ballsManifest(1), [framePayload({
    bodies: [{ position: [0, 0, 0] }], events: [{ kind: 9, a: 0, b: 0, value: 0 }],
  })]);
  refuses(badEvent, /event 0 at byte \d+ has unknown kind 9/);
});

test('random bytes after a good header never escape as anything but a RecordingError', () => {
  const good = twoBallFile();
  let seed = 12345;
  const next = () => {
    seed = (seed * 1103515245 + 12345) % 2147483648;
    return seed;
  };
  for (let trial = 0; trial < 300; trial++) {
    const bytes = good.slice();
    for (let k = 0; k < 4; k++) bytes[16 + (next() % (bytes.length - 16))] = next() % 256;
    try {
      readRecording(bytes);
    } catch (error) {
      assert.ok(error instanceof RecordingError, `trial ${trial}: ${error}`);
    }
  }
});

test('the player steps, seeks, clamps and plays at the chosen speed', () => {
  const p = new Player(10, 0.1);
  assert.equal(p.frame, 0);
  assert.equal(p.step(3), true);
  assert.equal(p.frame, 3);
  p.seek(99);
  assert.equal(p.frame, 9);
  p.seek(-4);
  assert.equal(p.frame, 0);
  p.setSpeed(2);
  p.play();
  p.tick(0.15); // 0.3 s of recording at twice real time: three frames
  assert.equal(p.frame, 3);
  p.tick(0.25);
  p.tick(0.25); // 1.0 s more: ten frames on, wrapping round a 10-frame recording
  assert.equal(p.frame, 3);
  p.tick(5); // a stalled page resumes at most 0.25 s of real time later (5 frames here)
  assert.equal(p.frame, 8);
  p.pause();
  assert.equal(p.tick(1), false);
  p.setSpeed(-1);
  assert.equal(p.speed, 2, 'a negative speed is ignored');
});
