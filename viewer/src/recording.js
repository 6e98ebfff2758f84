// Reads a Rebound recording (`.rrec`, format version 2) as docs/recording.md specifies it, into the model the
// viewer draws. The whole file is checked once when it is opened (every length prefix, count, flag, index and
// JSON block), so a bad file is refused up front with a RecordingError naming the byte offset and what is
// wrong; after that, frames are decoded on demand, mostly as typed-array views into the file's bytes.
//
// No DOM and no three.js here: node's test runner exercises this module directly.

const MAGIC = [0x52, 0x42, 0x52, 0x45, 0x43, 0x0d, 0x0a, 0x1a];
const VERSION = 2;
const HEADER_BYTES = 84;
const CONTACT_BYTES = 40;
const JOINT_BYTES = 40;
const EVENT_BYTES = 16;
const FORCE_BYTES = 40;
const CONTACT_FORCE_KIND = 8;
const NONE = 0xffffffff;
const BODY_KINDS = ['dynamic', 'fixed', 'kinematic'];
const JOINT_KINDS = ['spring', 'rope', 'rod', 'ball', 'hinge', 'fixed', 'prismatic', 'wheel', 'six_dof'];
const EVENT_KINDS = 8;

/** A file that is not a readable recording; the message says what is wrong and where. */
export class RecordingError extends Error {
  constructor(message) {
    super(message);
    this.name = 'RecordingError';
  }
}

const pad4 = (n) => Math.ceil(n / 4) * 4;

/**
 * Reads the recording in `input` (an ArrayBuffer or a typed array over one).
 * @returns {Recording}
 * @throws {RecordingError} when the file breaks the format
 */
export function readRecording(input) {
  const buffer = toArrayBuffer(input);
  const view = new DataView(buffer);
  const size = buffer.byteLength;
  if (size < 16) throw new RecordingError(`the file is ${size} bytes long, shorter than the 16-byte file header`);
  for (let i = 0; i < MAGIC.length; i++) {
    if (view.getUint8(i) !== MAGIC[i]) throw new RecordingError('not a Rebound recording (wrong magic bytes at offset 0)');
  }
  const version = view.getUint32(8, true);
  if (version !== VERSION) {
    throw new RecordingError(`unsupported format version ${version} at offset 8 (this viewer reads version ${VERSION})`);
  }
  const manifestBytes = view.getUint32(12, true);
  if (manifestBytes % 4 !== 0) throw new RecordingError(`manifest length ${manifestBytes} at offset 12 is not a multiple of 4`);
  if (16 + manifestBytes > size) {
    throw new RecordingError(`truncated: the manifest runs to byte ${16 + manifestBytes} but the file ends at byte ${size}`);
  }
  const manifest = parseJson(buffer, 16, manifestBytes, 'manifest');
  const world = new WorldDescription(manifest);

  const frames = [];
  let truncated = null;
  let bodyCount = world.bodies.length;
  let jointCount = world.joints.length;
  for (let at = 16 + manifestBytes; at < size;) {
    if (at + 4 > size) {
      truncated = `truncated: the file ends inside the length prefix of frame ${frames.length} at byte ${at}`;
      break;
    }
    const length = view.getUint32(at, true);
    const p = at + 4;
    if (length % 4 !== 0) throw new RecordingError(`frame ${frames.length} at byte ${at}: payload length ${length} is not a multiple of 4`);
    if (length < HEADER_BYTES) {
      throw new RecordingError(`frame ${frames.length} at byte ${at}: payload length ${length} is shorter than the ${HEADER_BYTES}-byte header`);
    }
    if (p + length > size) {
      truncated = `truncated: frame ${frames.length} at byte ${at} needs ${length} bytes but the file ends at byte ${size}`;
      break;
    }
    const frame = checkFrame(buffer, view, p, length, frames.length, world, bodyCount, jointCount);
    bodyCount = frame.nb;
    jointCount = frame.nj;
    frames.push(frame);
    at = p + length;
  }
  if (frames.length === 0) {
    throw new RecordingError(truncated ?? 'the recording holds no frames');
  }
  return new Recording(buffer, manifest, world, frames, truncated);
}

function toArrayBuffer(input) {
  if (input instanceof ArrayBuffer) return input;
  if (ArrayBuffer.isView(input)) {
    // A view into a larger buffer is copied, so every offset in the spec is an offset into `buffer`.
    return input.buffer.slice(input.byteOffset, input.byteOffset + input.byteLength);
  }
  throw new RecordingError('expected the bytes of a recording file');
}

function parseJson(buffer, offset, length, what) {
  let text;
  try {
    text = new TextDecoder('utf-8', { fatal: true }).decode(new Uint8Array(buffer, offset, length));
  } catch {
    throw new RecordingError(`the ${what} at byte ${offset} is not UTF-8`);
  }
  try {
    return JSON.parse(text);
  } catch (error) {
    throw new RecordingError(`the ${what} at byte ${offset} is not valid JSON: ${error.message}`);
  }
}

/** Checks one frame payload at `p` against the spec and the description so far; applies its changes. */
function checkFrame(buffer, view, p, length, index, world, previousBodies, previousJoints) {
  const where = `frame ${index} (payload at byte ${p})`;
  const nb = view.getUint32(p + 16, true);
  const nc = view.getUint32(p + 20, true);
  const nj = view.getUint32(p + 24, true);
  const ne = view.getUint32(p + 28, true);
  const x = view.getUint32(p + 32, true);
  const nf = view.getUint32(p + 36, true);
  if (x % 4 !== 0) throw new RecordingError(`${where}: changes length ${x} is not a multiple of 4`);
  const expected = HEADER_BYTES + x + 52 * nb + pad4(nb) + CONTACT_BYTES * nc + JOINT_BYTES * nj + EVENT_BYTES * ne + FORCE_BYTES * nf;
  if (expected !== length) {
    throw new RecordingError(
      `${where}: payload length ${length} disagrees with its counts (${nb} bodies, ${nc} contacts, ${nj} joints, ` +
        `${ne} events, ${nf} contact forces, ${x} bytes of changes need ${expected})`,
    );
  }
  if (x > 0) world.applyChanges(parseJson(buffer, p + HEADER_BYTES, x, `changes of ${where}`), where);
  if (nb < previousBodies) throw new RecordingError(`${where}: ${nb} body entries, fewer than the previous frame's ${previousBodies}`);
  if (nj < previousJoints) throw new RecordingError(`${where}: ${nj} joint entries, fewer than the previous frame's ${previousJoints}`);
  if (nb !== world.bodies.length) {
    throw new RecordingError(`${where}: ${nb} body entries but ${world.bodies.length} bodies are described`);
  }
  if (nj !== world.joints.length) {
    throw new RecordingError(`${where}: ${nj} joint entries but ${world.joints.length} joints are described`);
  }

  const bodies = p + HEADER_BYTES + x;
  const flagsAt = bodies + 52 * nb;
  const flags = new Uint8Array(buffer, flagsAt, nb);
  for (let i = 0; i < nb; i++) {
    if ((flags[i] >> 2) === 3 || flags[i] >> 4 !== 0) {
      throw new RecordingError(`${where}: body ${i} has invalid flags 0x${flags[i].toString(16)} at byte ${flagsAt + i}`);
    }
  }
  const contactsAt = flagsAt + pad4(nb);
  const contactWords = new Uint32Array(buffer, contactsAt, (CONTACT_BYTES / 4) * nc);
  for (let c = 0; c < nc; c++) {
    const a = contactWords[10 * c];
    const b = contactWords[10 * c + 1];
    if (a >= nb || b >= nb) {
      throw new RecordingError(`${where}: contact ${c} at byte ${contactsAt + CONTACT_BYTES * c} names body ${a >= nb ? a : b}, but there are ${nb}`);
    }
  }
  const jointsAt = contactsAt + CONTACT_BYTES * nc;
  const eventsAt = jointsAt + JOINT_BYTES * nj;
  let forceEvents = 0;
  for (let e = 0; e < ne; e++) {
    const kind = view.getUint32(eventsAt + EVENT_BYTES * e, true);
    if (kind < 1 || kind > EVENT_KINDS) {
      throw new RecordingError(`${where}: event ${e} at byte ${eventsAt + EVENT_BYTES * e} has unknown kind ${kind}`);
    }
    if (kind === CONTACT_FORCE_KIND) forceEvents++;
  }
  if (forceEvents !== nf) {
    throw new RecordingError(`${where}: ${nf} contact force entries but ${forceEvents} contact force events`);
  }
  const forcesAt = eventsAt + EVENT_BYTES * ne;
  return {
    offset: p,
    step: Number(view.getBigUint64(p, true)),
    time: view.getFloat64(p + 8, true),
    nb,
    nc,
    nj,
    ne,
    nf,
    bodies,
    flagsAt,
    contactsAt,
    jointsAt,
    eventsAt,
    forcesAt,
  };
}

// ---- the described world: bodies with their drawable parts, and joints ----

function fail(what, value) {
  throw new RecordingError(`${what} is ${JSON.stringify(value)?.slice(0, 80) ?? String(value)}`);
}

function num(value, what) {
  if (typeof value !== 'number' || !Number.isFinite(value)) fail(what, value);
  return value;
}

function vec(value, n, what) {
  if (!Array.isArray(value) || value.length !== n) fail(what, value);
  return value.map((v, i) => num(v, `${what}[${i}]`));
}

function pose(value, what) {
  if (value === null || typeof value !== 'object') fail(what, value);
  return { position: vec(value.position, 3, `${what}.position`), rotation: vec(value.rotation, 4, `${what}.rotation`) };
}

/** The pose `outer · inner` (positions in m, unit quaternions x, y, z, w). */
function composePose(outer, inner) {
  const [x, y, z, w] = outer.rotation;
  const [px, py, pz] = inner.position;
  // Rotate the inner position by the outer quaternion: p + 2w(q×p) + 2q×(q×p).
  const tx = 2 * (y * pz - z * py);
  const ty = 2 * (z * px - x * pz);
  const tz = 2 * (x * py - y * px);
  const rotated = [px + w * tx + (y * tz - z * ty), py + w * ty + (z * tx - x * tz), pz + w * tz + (x * ty - y * tx)];
  const [bx, by, bz, bw] = inner.rotation;
  return {
    position: [outer.position[0] + rotated[0], outer.position[1] + rotated[1], outer.position[2] + rotated[2]],
    rotation: [
      w * bx + x * bw + y * bz - z * by,
      w * by - x * bz + y * bw + z * bx,
      w * bz + x * by - y * bx + z * bw,
      w * bw - x * bx - y * by - z * bz,
    ],
  };
}

/** The drawable parts of a collider shape (compounds flattened), each with its pose in the body frame. */
function shapeParts(shape, at, what) {
  if (shape === null || typeof shape !== 'object' || Object.keys(shape).length !== 1) fail(what, shape);
  const [kind, s] = Object.entries(shape)[0];
  if (s === null || typeof s !== 'object') fail(`${what}.${kind}`, s);
  const one = (model) => [{ ...at, shape: model }];
  switch (kind) {
    case 'Ball':
      return one({ kind: 'ball', radius: num(s.radius, `${what}.Ball.radius`) });
    case 'Cuboid':
      return one({ kind: 'cuboid', halfExtents: vec(s.half_extents, 3, `${what}.Cuboid.half_extents`) });
    case 'Capsule':
    case 'Cylinder':
    case 'Cone':
      return one({
        kind: kind.toLowerCase(),
        radius: num(s.radius, `${what}.${kind}.radius`),
        halfHeight: num(s.half_height, `${what}.${kind}.half_height`),
      });
    case 'ConvexHull':
      if (!Array.isArray(s.points)) fail(`${what}.ConvexHull.points`, s.points);
      return one({ kind: 'hull', vertices: s.points.flatMap((q, i) => vec(q, 3, `${what}.ConvexHull.points[${i}]`)) });
    case 'TriMesh': {
      if (!Array.isArray(s.vertices)) fail(`${what}.TriMesh.vertices`, s.vertices);
      if (!Array.isArray(s.indices)) fail(`${what}.TriMesh.indices`, s.indices);
      const vertices = s.vertices.flatMap((q, i) => vec(q, 3, `${what}.TriMesh.vertices[${i}]`));
      const indices = s.indices.flatMap((t, i) => vec(t, 3, `${what}.TriMesh.indices[${i}]`));
      if (indices.some((i) => !Number.isInteger(i) || i < 0 || 3 * i >= vertices.length)) {
        fail(`${what}.TriMesh.indices (an index out of range)`, indices.find((i) => 3 * i >= vertices.length || i < 0));
      }
      return one({ kind: 'trimesh', vertices, indices });
    }
    case 'HeightField': {
      const rows = num(s.rows, `${what}.HeightField.rows`);
      const columns = num(s.cols, `${what}.HeightField.cols`);
      if (!Array.isArray(s.heights) || s.heights.length !== rows * columns) fail(`${what}.HeightField.heights`, s.heights?.length);
      return one({
        kind: 'heightfield',
        rows,
        columns,
        heights: s.heights.map((h, i) => num(h, `${what}.HeightField.heights[${i}]`)),
        scale: vec(s.scale, 3, `${what}.HeightField.scale`),
      });
    }
    case 'Compound':
      if (!Array.isArray(s.parts)) fail(`${what}.Compound.parts`, s.parts);
      return s.parts.flatMap((part, i) => {
        if (!Array.isArray(part) || part.length !== 2) fail(`${what}.Compound.parts[${i}]`, part);
        const inner = pose(part[0], `${what}.Compound.parts[${i}][0]`);
        return shapeParts(part[1], composePose(at, inner), `${what}.Compound.parts[${i}][1]`);
      });
    default:
      return fail(`${what} (unknown shape kind)`, kind);
  }
}

/** Bodies and joints as described by the manifest and by every frame's changes, by recording index. */
class WorldDescription {
  constructor(manifest) {
    if (manifest === null || typeof manifest !== 'object') fail('the manifest', manifest);
    if (manifest.format !== 'rebound-recording') fail('manifest field "format"', manifest.format);
    this.dt = num(manifest.dt, 'manifest field "dt"');
    this.gravity = vec(manifest.gravity, 3, 'manifest field "gravity"');
    if (!Array.isArray(manifest.bodies)) fail('manifest field "bodies"', manifest.bodies);
    if (!Array.isArray(manifest.joints)) fail('manifest field "joints"', manifest.joints);
    this.bodies = [];
    this.joints = [];
    this.colliderCount = 0;
    manifest.bodies.forEach((b, i) => this.setBody(b, `manifest bodies[${i}]`));
    manifest.joints.forEach((j, i) => this.setJoint(j, `manifest joints[${i}]`));
  }

  applyChanges(changes, where) {
    if (changes === null || typeof changes !== 'object') fail(`changes of ${where}`, changes);
    for (const [key, list] of Object.entries(changes)) {
      if (!['bodies', 'colliders', 'joints', 'removed_colliders'].includes(key) || !Array.isArray(list)) {
        fail(`changes of ${where}: field "${key}"`, list);
      }
    }
    (changes.bodies ?? []).forEach((b, i) => this.setBody(b, `changes of ${where}: bodies[${i}]`));
    (changes.colliders ?? []).forEach((c, i) => this.setCollider(c, `changes of ${where}: colliders[${i}]`));
    (changes.joints ?? []).forEach((j, i) => this.setJoint(j, `changes of ${where}: joints[${i}]`));
    (changes.removed_colliders ?? []).forEach((c, i) => {
      if (!Number.isInteger(c) || c < 0 || c >= this.colliderCount) fail(`changes of ${where}: removed_colliders[${i}]`, c);
      for (const body of this.bodies) body.parts = body.parts.filter((part) => part.collider !== c);
    });
  }

  /** A new body (index = count so far) or a new description of an existing one. */
  setBody(b, what) {
    if (b === null || typeof b !== 'object') fail(what, b);
    const index = b.index;
    if (!Number.isInteger(index) || index < 0 || index > this.bodies.length) fail(`${what}.index`, index);
    if (!BODY_KINDS.includes(b.kind)) fail(`${what}.kind`, b.kind);
    if (!Array.isArray(b.colliders)) fail(`${what}.colliders`, b.colliders);
    const body = {
      index,
      kind: b.kind,
      // The manifest writes each f32 in its shortest form; fround gives back the recorded value itself.
      mass: Math.fround(num(b.mass, `${what}.mass`)),
      localCenterOfMass: vec(b.local_center_of_mass, 3, `${what}.local_center_of_mass`),
      parts: index < this.bodies.length ? this.bodies[index].parts : [],
    };
    this.bodies[index] = body;
    b.colliders.forEach((c, i) => this.setCollider(c, `${what}.colliders[${i}]`));
  }

  /** A new collider (index = count so far) or a new description of one: its parts replace the old ones. */
  setCollider(c, what) {
    if (c === null || typeof c !== 'object') fail(what, c);
    if (!Number.isInteger(c.index) || c.index < 0 || c.index > this.colliderCount) fail(`${what}.index`, c.index);
    if (!Number.isInteger(c.body) || c.body < 0 || c.body >= this.bodies.length) fail(`${what}.body`, c.body);
    const parts = shapeParts(c.shape, pose(c.local_pose, `${what}.local_pose`), `${what}.shape`).map((part) => ({
      ...part,
      collider: c.index,
      sensor: c.sensor === true,
    }));
    for (const body of this.bodies) body.parts = body.parts.filter((part) => part.collider !== c.index);
    this.bodies[c.body].parts.push(...parts);
    if (c.index === this.colliderCount) this.colliderCount++;
  }

  setJoint(j, what) {
    if (j === null || typeof j !== 'object') fail(what, j);
    if (!Number.isInteger(j.index) || j.index < 0 || j.index > this.joints.length) fail(`${what}.index`, j.index);
    if (!JOINT_KINDS.includes(j.kind)) fail(`${what}.kind`, j.kind);
    const bodyIndex = (value, field) => {
      if (value === null && field === 'body_a') return -1;
      if (!Number.isInteger(value) || value < 0 || value >= this.bodies.length) fail(`${what}.${field}`, value);
      return value;
    };
    this.joints[j.index] = { index: j.index, kind: j.kind, a: bodyIndex(j.body_a, 'body_a'), b: bodyIndex(j.body_b, 'body_b') };
  }
}

// ---- the model the viewer draws ----

/**
 * A checked recording. Bodies are every body ever described (a body inserted later is absent from the frames
 * before it); each frame gives arrays over all of them.
 */
export class Recording {
  constructor(buffer, manifest, world, frames, truncated) {
    this.buffer = buffer;
    this.manifest = manifest;
    this.bodies = world.bodies;
    this.joints = world.joints;
    this.frames = frames;
    this.frameCount = frames.length;
    /** Why the file ended early (the complete frames before are shown), or null. */
    this.truncated = truncated;
    const span = frames[frames.length - 1].time - frames[0].time;
    /** Simulated seconds between frames, for playback (the mean spacing; the manifest's dt for one frame). */
    this.frameDt = frames.length > 1 && span > 0 ? span / (frames.length - 1) : world.dt;
    this.cache = { index: -1, frame: null };
  }

  /** Header numbers of frame `i`: energies (J), momenta, worst joint error and deepest penetration (m). */
  header(i) {
    const view = new DataView(this.buffer, this.frames[i].offset, HEADER_BYTES);
    const f32 = (o) => view.getFloat32(o, true);
    return {
      step: this.frames[i].step,
      time: this.frames[i].time,
      kinetic: f32(40),
      potential: f32(44),
      spring: f32(48),
      linearMomentum: [f32(52), f32(56), f32(60)],
      angularMomentum: [f32(64), f32(68), f32(72)],
      worstJointError: f32(76),
      deepestPenetration: f32(80),
    };
  }

  /**
   * Total, kinetic, potential and (if any) spring energy, one value a frame, each as its change since the
   * first frame (J): potential energy is measured from an arbitrary height, and differences are what show
   * a drift or an exchange between the kinds.
   */
  energySeries() {
    const n = this.frameCount;
    const names = ['total', 'kinetic', 'potential', 'spring'];
    const series = names.map((name) => ({ name, values: new Float64Array(n) }));
    const first = this.header(0);
    const firstTotal = first.kinetic + first.potential + first.spring;
    for (let i = 0; i < n; i++) {
      const h = this.header(i);
      series[0].values[i] = h.kinetic + h.potential + h.spring - firstTotal;
      series[1].values[i] = h.kinetic - first.kinetic;
      series[2].values[i] = h.potential - first.potential;
      series[3].values[i] = h.spring - first.spring;
    }
    return series.filter((s) => s.name !== 'spring' || s.values.some((v) => v !== 0));
  }

  /** Frame `i` in the drawing model (see decodeFrame); the last one decoded is kept. */
  frame(i) {
    if (this.cache.index !== i) this.cache = { index: i, frame: this.decodeFrame(i) };
    return this.cache.frame;
  }

  decodeFrame(i) {
    const f = this.frames[i];
    const n = this.bodies.length;
    const { buffer } = this;
    const nb = f.nb;
    const views = {
      positions: new Float32Array(buffer, f.bodies, 3 * nb),
      rotations: new Float32Array(buffer, f.bodies + 12 * nb, 4 * nb),
      linearVelocities: new Float32Array(buffer, f.bodies + 28 * nb, 3 * nb),
      angularVelocities: new Float32Array(buffer, f.bodies + 40 * nb, 3 * nb),
    };
    // Bodies inserted after this frame are absent here: the arrays are widened to every body, at rest.
    const widen = (array, width, fill) => {
      if (nb === n) return array;
      const wide = new Float32Array(width * n);
      wide.set(array);
      if (fill) for (let b = nb; b < n; b++) wide[width * b + 3] = 1;
      return wide;
    };
    const flags = new Uint8Array(buffer, f.flagsAt, nb);
    const present = new Uint8Array(n);
    const sleeping = new Uint8Array(n);
    const kinds = new Array(n).fill('dynamic');
    for (let b = 0; b < nb; b++) {
      present[b] = flags[b] & 1;
      sleeping[b] = (flags[b] >> 1) & 1;
      kinds[b] = BODY_KINDS[(flags[b] >> 2) & 3];
    }
    const recording = this;
    let contacts = null;
    let joints = null;
    return {
      index: i,
      step: f.step,
      time: f.time,
      positions: widen(views.positions, 3, false),
      rotations: widen(views.rotations, 4, true),
      linearVelocities: widen(views.linearVelocities, 3, false),
      angularVelocities: widen(views.angularVelocities, 3, false),
      present,
      sleeping,
      kinds,
      /** Contact points, decoded on first use (a pile has thousands a frame). */
      get contacts() {
        contacts ??= recording.decodeContacts(f);
        return contacts;
      },
      /** World anchors of the present joints. */
      get joints() {
        joints ??= recording.decodeJoints(f);
        return joints;
      },
    };
  }

  decodeContacts(f) {
    const words = new Uint32Array(this.buffer, f.contactsAt, 10 * f.nc);
    const floats = new Float32Array(this.buffer, f.contactsAt, 10 * f.nc);
    const contacts = new Array(f.nc);
    for (let c = 0; c < f.nc; c++) {
      const o = 10 * c;
      contacts[c] = {
        a: words[o],
        b: words[o + 1],
        point: [floats[o + 2], floats[o + 3], floats[o + 4]],
        normal: [floats[o + 5], floats[o + 6], floats[o + 7]],
        impulse: floats[o + 8],
        separation: floats[o + 9],
      };
    }
    return contacts;
  }

  decodeJoints(f) {
    const floats = new Float32Array(this.buffer, f.jointsAt, 10 * f.nj);
    const words = new Uint32Array(this.buffer, f.jointsAt, 10 * f.nj);
    const joints = [];
    for (let j = 0; j < f.nj; j++) {
      const o = 10 * j;
      if ((words[o + 9] & 1) === 0) continue;
      const description = this.joints[j];
      joints.push({
        index: j,
        kind: description.kind,
        a: description.a,
        b: description.b,
        anchorA: [floats[o], floats[o + 1], floats[o + 2]],
        anchorB: [floats[o + 3], floats[o + 4], floats[o + 5]],
        error: floats[o + 6],
        broken: (words[o + 9] & 2) !== 0,
      });
    }
    return joints;
  }

  /**
   * The events of frame `i`: `{kind, a, b, value}` with `NONE` as -1; a contact force event (kind 8) also has
   * `force: {colliderA, colliderB, normal, totalImpulse, maxImpulsePoint, maxImpulse}` from its FORCE entry.
   */
  events(i) {
    const f = this.frames[i];
    const words = new Uint32Array(this.buffer, f.eventsAt, 4 * f.ne);
    const floats = new Float32Array(this.buffer, f.eventsAt, 4 * f.ne);
    const forceCount = f.nf * (FORCE_BYTES / 4);
    const forceWords = new Uint32Array(this.buffer, f.forcesAt, forceCount);
    const forceFloats = new Float32Array(this.buffer, f.forcesAt, forceCount);
    const id = (w) => (w === NONE ? -1 : w);
    const out = [];
    let k = 0;
    for (let e = 0; e < f.ne; e++) {
      const event = { kind: words[4 * e], a: id(words[4 * e + 1]), b: id(words[4 * e + 2]), value: floats[4 * e + 3] };
      if (event.kind === CONTACT_FORCE_KIND) {
        const o = (FORCE_BYTES / 4) * k++;
        event.force = {
          colliderA: id(forceWords[o]),
          colliderB: id(forceWords[o + 1]),
          normal: [forceFloats[o + 2], forceFloats[o + 3], forceFloats[o + 4]],
          totalImpulse: forceFloats[o + 5],
          maxImpulsePoint: [forceFloats[o + 6], forceFloats[o + 7], forceFloats[o + 8]],
          maxImpulse: forceFloats[o + 9],
        };
      }
      out.push(event);
    }
    return out;
  }
}
