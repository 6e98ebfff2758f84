// Writes small recordings byte by byte as docs/recording.md lays them out, so the reader's checks can be
// tried on files the engine would never write (the engine-written recordings come from the `rebound` command).

const MAGIC = [0x52, 0x42, 0x52, 0x45, 0x43, 0x0d, 0x0a, 0x1a];

const pad4 = (n) => Math.ceil(n / 4) * 4;

function paddedJson(value) {
  const bytes = new TextEncoder().encode(JSON.stringify(value));
  const out = new Uint8Array(pad4(bytes.length)).fill(0x20);
  out.set(bytes);
  return out;
}

/** A manifest of `balls` unit-radius dynamic balls and no joints. */
export function ballsManifest(balls) {
  const bodies = [];
  for (let i = 0; i < balls; i++) {
    bodies.push({
      index: i,
      handle: [i, 0],
      kind: 'dynamic',
      mass: 1,
      local_center_of_mass: [0, 0, 0],
      inertia: [[0.4, 0, 0], [0, 0.4, 0], [0, 0, 0.4]],
      gravity_scale: 1,
      colliders: [{
        index: i,
        body: i,
        shape: { Ball: { radius: 0.5 } },
        local_pose: { position: [0, 0, 0], rotation: [0, 0, 0, 1] },
        density: 1,
        friction: 0.5,
        restitution: 0,
        rolling_friction: 0,
        sensor: false,
        enabled: true,
      }],
    });
  }
  return { format: 'rebound-recording', engine: 'rebound', engine_version: '0.1.0', dt: 1 / 60, substeps: 4,
    gravity: [0, -9.81, 0], bodies, joints: [] };
}

/**
 * One frame payload. `bodies` entries: {position, rotation, linearVelocity, angularVelocity, flags};
 * `contacts`: {a, b, point, normal, impulse, separation}; `events`: {kind, a, b, value}, and for a contact force
 * event (kind 8) `force`: {colliderA, colliderB, normal, totalImpulse, maxImpulsePoint, maxImpulse}, written to the
 * FORCE block.
 */
export function framePayload({ step = 0, time = 0, energy = [0, 0, 0], bodies = [], contacts = [], events = [],
  changes = null }) {
  const x = changes === null ? new Uint8Array(0) : paddedJson(changes);
  const nb = bodies.length;
  const forces = events.filter((e) => e.kind === 8).map((e) => e.force);
  const length = 84 + x.length + 52 * nb + pad4(nb) + 40 * contacts.length + 16 * events.length + 40 * forces.length;
  const bytes = new Uint8Array(length);
  const view = new DataView(bytes.buffer);
  view.setBigUint64(0, BigInt(step), true);
  view.setFloat64(8, time, true);
  view.setUint32(16, nb, true);
  view.setUint32(20, contacts.length, true);
  view.setUint32(24, 0, true);
  view.setUint32(28, events.length, true);
  view.setUint32(32, x.length, true);
  view.setUint32(36, forces.length, true);
  energy.forEach((e, i) => view.setFloat32(40 + 4 * i, e, true));
  bytes.set(x, 84);
  let at = 84 + x.length;
  const put = (values, stride) => {
    bodies.forEach((b, i) => values(b).forEach((v, k) => view.setFloat32(at + stride * i + 4 * k, v, true)));
    at += stride * nb;
  };
  put((b) => b.position, 12);
  put((b) => b.rotation ?? [0, 0, 0, 1], 16);
  put((b) => b.linearVelocity ?? [0, 0, 0], 12);
  put((b) => b.angularVelocity ?? [0, 0, 0], 12);
  bodies.forEach((b, i) => view.setUint8(at + i, b.flags ?? 1));
  at += pad4(nb);
  for (const c of contacts) {
    view.setUint32(at, c.a, true);
    view.setUint32(at + 4, c.b, true);
    [...c.point, ...c.normal, c.impulse, c.separation].forEach((v, k) => view.setFloat32(at + 8 + 4 * k, v, true));
    at += 40;
  }
  for (const e of events) {
    view.setUint32(at, e.kind, true);
    view.setUint32(at + 4, e.a, true);
    view.setUint32(at + 8, e.b, true);
    view.setFloat32(at + 12, e.value, true);
    at += 16;
  }
  for (const f of forces) {
    view.setUint32(at, f.colliderA, true);
    view.setUint32(at + 4, f.colliderB, true);
    [...f.normal, f.totalImpulse, ...f.maxImpulsePoint, f.maxImpulse].forEach((v, k) =>
      view.setFloat32(at + 8 + 4 * k, v, true),
    );
    at += 40;
  }
  return bytes;
}

/** A whole file: header, manifest and the given frame payloads with their length prefixes. */
export function recordingFile(manifest, payloads, { version = 2 } = {}) {
  const m = paddedJson(manifest);
  const total = 16 + m.length + payloads.reduce((n, p) => n + 4 + p.length, 0);
  const bytes = new Uint8Array(total);
  const view = new DataView(bytes.buffer);
  bytes.set(MAGIC, 0);
  view.setUint32(8, version, true);
  view.setUint32(12, m.length, true);
  bytes.set(m, 16);
  let at = 16 + m.length;
  for (const p of payloads) {
    view.setUint32(at, p.length, true);
    bytes.set(p, at + 4);
    at += 4 + p.length;
  }
  return bytes;
}
