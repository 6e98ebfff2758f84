// The text shown for a clicked body: its mass, velocities and the contacts it has at the shown frame.

const fmt = (v) => (Math.abs(v) >= 1e4 || (v !== 0 && Math.abs(v) < 1e-3) ? v.toExponential(3) : v.toFixed(4));
const vec = (a, i = 0) => `(${fmt(a[i])}, ${fmt(a[i + 1])}, ${fmt(a[i + 2])})`;
const norm = (a, i = 0) => Math.hypot(a[i], a[i + 1], a[i + 2]);

/** A plain-text description of body `b` at `frame` (units in brackets). */
export function describeBody(recording, frame, b) {
  const body = recording.bodies[b];
  const lines = [
    `body ${b} (${frame.kinds[b]}${frame.present[b] ? '' : ', removed'})`,
    `mass        ${fmt(body.mass)} kg${frame.kinds[b] === 'dynamic' ? '' : ' (moves as if infinite)'}`,
    `position    ${vec(frame.positions, 3 * b)} m`,
    `velocity    ${vec(frame.linearVelocities, 3 * b)} m/s  |v| = ${fmt(norm(frame.linearVelocities, 3 * b))}`,
    `angular vel ${vec(frame.angularVelocities, 3 * b)} rad/s`,
    `sleeping    ${frame.sleeping[b] ? 'yes' : 'no'}`,
  ];
  const contacts = frame.contacts.filter((c) => c.a === b || c.b === b);
  lines.push(`contacts    ${contacts.length}`);
  for (const c of contacts) {
    const other = c.a === b ? c.b : c.a;
    lines.push(`  with ${other}: at ${vec(c.point)} n ${vec(c.normal)} impulse ${fmt(c.impulse ?? 0)} N·s`);
  }
  return lines.join('\n');
}
