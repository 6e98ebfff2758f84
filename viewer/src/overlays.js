// Debug overlays drawn over the bodies: contact points with their normals, joint anchors with the lines
// that tie them to their bodies, and every part's axis-aligned bounding box. Each is one line-segment
// buffer (plus one point buffer for contacts and anchors) grown on demand and rewritten per frame.

import * as THREE from 'three';

export const OVERLAY_COLOURS = {
  contact: new THREE.Color('#ff00ff'),
  joint: new THREE.Color('#ffd400'),
  aabb: new THREE.Color('#39d353'),
};

/** Length in metres of a contact normal drawn with no impulse; impulses lengthen it (see NORMAL_PER_NS). */
const NORMAL_BASE = 0.15;
/** Extra normal length per newton-second of normal impulse, capped at NORMAL_MAX. */
const NORMAL_PER_NS = 0.05;
const NORMAL_MAX = 0.6;

class LineBuffer {
  constructor(scene, colour, points) {
    this.positions = new Float32Array(0);
    this.geometry = new THREE.BufferGeometry();
    // Rewritten every frame and never culled: a fixed bound spares three.js recomputing one per frame.
    this.geometry.boundingSphere = new THREE.Sphere(new THREE.Vector3(), Infinity);
    const material = points
      ? new THREE.PointsMaterial({ color: colour, size: 7, sizeAttenuation: false, depthTest: false })
      : new THREE.LineBasicMaterial({ color: colour, depthTest: false });
    this.object = points ? new THREE.Points(this.geometry, material) : new THREE.LineSegments(this.geometry, material);
    this.object.frustumCulled = false;
    this.object.renderOrder = 10;
    this.object.visible = false;
    this.count = 0;
    scene.add(this.object);
  }

  begin() {
    this.count = 0;
  }

  push(x, y, z) {
    if (3 * (this.count + 1) > this.positions.length) {
      const grown = new Float32Array(Math.max(64, this.positions.length * 2));
      grown.set(this.positions);
      this.positions = grown;
      this.geometry.setAttribute('position', new THREE.BufferAttribute(this.positions, 3));
      this.geometry.attributes.position.setUsage(THREE.DynamicDrawUsage);
    }
    this.positions[3 * this.count] = x;
    this.positions[3 * this.count + 1] = y;
    this.positions[3 * this.count + 2] = z;
    this.count++;
  }

  end(visible) {
    this.object.visible = visible && this.count > 0;
    if (this.geometry.attributes.position) this.geometry.attributes.position.needsUpdate = true;
    this.geometry.setDrawRange(0, this.count);
  }

  dispose(scene) {
    scene.remove(this.object);
    this.geometry.dispose();
    this.object.material.dispose();
  }
}

export class Overlays {
  constructor(scene) {
    this.scene = scene;
    this.contactLines = new LineBuffer(scene, OVERLAY_COLOURS.contact, false);
    this.contactPoints = new LineBuffer(scene, OVERLAY_COLOURS.contact, true);
    this.jointLines = new LineBuffer(scene, OVERLAY_COLOURS.joint, false);
    this.jointPoints = new LineBuffer(scene, OVERLAY_COLOURS.joint, true);
    this.aabbLines = new LineBuffer(scene, OVERLAY_COLOURS.aabb, false);
  }

  prepare() {}

  clear() {
    for (const b of [this.contactLines, this.contactPoints, this.jointLines, this.jointPoints, this.aabbLines]) {
      b.begin();
      b.end(false);
    }
  }

  update(frame, view, toggles) {
    this.contactLines.begin();
    this.contactPoints.begin();
    if (toggles.contacts) {
      for (const c of frame.contacts) {
        const [x, y, z] = c.point;
        const [nx, ny, nz] = c.normal;
        const length = Math.min(NORMAL_MAX, NORMAL_BASE + NORMAL_PER_NS * Math.abs(c.impulse ?? 0));
        this.contactPoints.push(x, y, z);
        this.contactLines.push(x, y, z);
        this.contactLines.push(x + nx * length, y + ny * length, z + nz * length);
      }
    }
    this.contactLines.end(toggles.contacts);
    this.contactPoints.end(toggles.contacts);

    this.jointLines.begin();
    this.jointPoints.begin();
    if (toggles.joints) {
      const p = frame.positions;
      for (const j of frame.joints) {
        this.jointPoints.push(...j.anchorA);
        this.jointPoints.push(...j.anchorB);
        // Body centre → its anchor, then anchor to anchor (the joint's error, when the two differ).
        if (j.a >= 0) {
          this.jointLines.push(p[3 * j.a], p[3 * j.a + 1], p[3 * j.a + 2]);
          this.jointLines.push(...j.anchorA);
        }
        if (j.b >= 0) {
          this.jointLines.push(p[3 * j.b], p[3 * j.b + 1], p[3 * j.b + 2]);
          this.jointLines.push(...j.anchorB);
        }
        this.jointLines.push(...j.anchorA);
        this.jointLines.push(...j.anchorB);
      }
    }
    this.jointLines.end(toggles.joints);
    this.jointPoints.end(toggles.joints);

    this.aabbLines.begin();
    if (toggles.aabbs) {
      view.forEachPartBounds(frame, (min, max) => pushBox(this.aabbLines, min, max));
    }
    this.aabbLines.end(toggles.aabbs);
  }
}

/** The 12 edges of the box [min, max]. */
function pushBox(lines, min, max) {
  const xs = [min.x, max.x];
  const ys = [min.y, max.y];
  const zs = [min.z, max.z];
  for (const y of ys) for (const z of zs) { lines.push(xs[0], y, z); lines.push(xs[1], y, z); }
  for (const x of xs) for (const z of zs) { lines.push(x, ys[0], z); lines.push(x, ys[1], z); }
  for (const x of xs) for (const y of ys) { lines.push(x, y, zs[0]); lines.push(x, y, zs[1]); }
}
