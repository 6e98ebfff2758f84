// The three.js scene of a recording: one InstancedMesh per shared shape geometry (one BallBatch for all
// balls), overlays for contacts,
// joints and bounding boxes, the orbit camera, and picking a body under the pointer.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { shapeGeometry } from './shapes.js';
import { Overlays } from './overlays.js';
import { BallBatch, ballImpostorMaterial, raycastBalls } from './ball_impostor.js';

/** Body colours by kind; sleeping bodies are blended towards SLEEP_TINT. */
export const COLOURS = {
  dynamic: new THREE.Color('#d98a45'),
  fixed: new THREE.Color('#6b717c'),
  kinematic: new THREE.Color('#5aa0ff'),
  selected: new THREE.Color('#ffffff'),
  sleepTint: new THREE.Color('#3b4f8c'),
  background: new THREE.Color('#1b1e24'),
};

const scratch = {
  body: new THREE.Matrix4(),
  world: new THREE.Matrix4(),
  position: new THREE.Vector3(),
  quaternion: new THREE.Quaternion(),
  scale: new THREE.Vector3(1, 1, 1),
  colour: new THREE.Color(),
};

export class SceneView {
  /** @param {HTMLElement} container */
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: false });
    this.renderer.setPixelRatio(1);
    this.renderer.setClearColor(COLOURS.background);
    container.appendChild(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.05, 2000);
    this.camera.position.set(6, 4, 10);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;

    this.hemisphere = new THREE.HemisphereLight(0xeef2ff, 0x40444c, 1.6);
    this.scene.add(this.hemisphere);
    this.sun = new THREE.DirectionalLight(0xffffff, 1.8);
    this.sun.position.set(4, 10, 6);
    this.scene.add(this.sun);

    this.content = new THREE.Group();
    this.scene.add(this.content);
    this.overlays = new Overlays(this.scene);
    this.grid = null;
    this.groups = [];
    this.partsByBody = [];
    this.recording = null;
    this.selected = -1;
    this.raycaster = new THREE.Raycaster();

    this.resize();
    new ResizeObserver(() => this.resize()).observe(container);
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, true);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  /** Replaces the drawn scene with the bodies of `recording` (see recording.js for the model). */
  load(recording) {
    this.clear();
    this.recording = recording;
    const byKey = new Map();
    this.partsByBody = recording.bodies.map(() => []);
    recording.bodies.forEach((body, bodyIndex) => {
      body.parts.forEach((part, partIndex) => {
        const shape = shapeGeometry(part.shape, `${bodyIndex}:${partIndex}`);
        if (shape === null) return;
        let group = byKey.get(shape.key);
        if (group === undefined) {
          group = { key: shape.key, geometry: shape.geometry(), impostor: shape.impostor === true, instances: [] };
          byKey.set(shape.key, group);
        }
        const local = new THREE.Matrix4().compose(
          new THREE.Vector3(...part.position),
          new THREE.Quaternion(...part.rotation),
          shape.scale,
        );
        const unscaledLocal = new THREE.Matrix4().compose(
          new THREE.Vector3(...part.position),
          new THREE.Quaternion(...part.rotation),
          new THREE.Vector3(1, 1, 1),
        );
        const instance = { body: bodyIndex, local, unscaledLocal, bounds: shape.localBounds };
        group.instances.push(instance);
        this.partsByBody[bodyIndex].push({ group, slot: group.instances.length - 1, instance });
      });
    });

    for (const group of byKey.values()) {
      let mesh;
      if (group.impostor) {
        mesh = new BallBatch(group.instances.length, ballImpostorMaterial(this.hemisphere, this.sun));
      } else {
        const material = new THREE.MeshLambertMaterial({ color: 0xffffff });
        mesh = new THREE.InstancedMesh(group.geometry, material, group.instances.length);
        mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
        // Bounds change every frame; the whole scene is small enough to draw without culling.
        mesh.frustumCulled = false;
      }
      group.instances.forEach((_, slot) => mesh.setColorAt(slot, COLOURS.dynamic));
      group.mesh = mesh;
      this.content.add(mesh);
      this.groups.push(group);
    }
    this.overlays.prepare(this.groups.reduce((n, g) => n + g.instances.length, 0));
    this.dirty = true;
  }

  clear() {
    for (const group of this.groups) {
      this.content.remove(group.mesh);
      group.mesh.geometry.dispose();
      group.mesh.material.dispose();
      group.mesh.dispose?.();
    }
    this.groups = [];
    this.partsByBody = [];
    this.recording = null;
    this.selected = -1;
    if (this.grid !== null) {
      this.scene.remove(this.grid);
      this.grid = null;
    }
    this.overlays.clear();
  }

  /**
   * Poses every instance at `frame` and refreshes the overlays.
   * @param {object} frame one frame of the recording model
   * @param {{contacts: boolean, joints: boolean, aabbs: boolean, sleeping: boolean}} toggles
   */
  show(frame, toggles) {
    for (const group of this.groups) {
      const mesh = group.mesh;
      group.instances.forEach((instance, slot) => {
        const b = instance.body;
        if (frame.present[b]) {
          bodyMatrix(frame, b, scratch.body);
          scratch.world.multiplyMatrices(scratch.body, instance.local);
        } else {
          // A removed body (or one not inserted yet) is drawn at zero size.
          scratch.world.makeScale(0, 0, 0);
        }
        mesh.setMatrixAt(slot, scratch.world);
        const colour = scratch.colour.copy(COLOURS[frame.kinds[b]] ?? COLOURS.dynamic);
        if (toggles.sleeping && frame.sleeping[b]) colour.lerp(COLOURS.sleepTint, 0.65);
        if (b === this.selected) colour.lerp(COLOURS.selected, 0.6);
        mesh.setColorAt(slot, colour);
      });
      if (mesh.isBallBatch) {
        mesh.markUpdated();
      } else {
        mesh.instanceMatrix.needsUpdate = true;
        if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
      }
    }
    this.overlays.update(frame, this, toggles);
    this.dirty = true;
  }

  /** World-space axis-aligned box of every drawn part at `frame`, passed to `visit(min, max)`. */
  forEachPartBounds(frame, visit) {
    const box = new THREE.Box3();
    for (const group of this.groups) {
      for (const instance of group.instances) {
        if (!frame.present[instance.body]) continue;
        bodyMatrix(frame, instance.body, scratch.body);
        scratch.world.multiplyMatrices(scratch.body, instance.unscaledLocal);
        box.copy(instance.bounds).applyMatrix4(scratch.world);
        visit(box.min, box.max);
      }
    }
  }

  /**
   * Frames the camera on where the moving bodies go over the whole recording (all bodies if none moves),
   * looking from the front and a little above, and lays a ground grid under them.
   */
  fit() {
    const moving = new THREE.Box3();
    const all = new THREE.Box3();
    const box = new THREE.Box3();
    const samples = Math.min(24, this.recording.frameCount);
    for (let k = 0; k < samples; k++) {
      const frame = this.recording.frame(Math.round((k * (this.recording.frameCount - 1)) / Math.max(1, samples - 1)));
      for (const group of this.groups) {
        for (const instance of group.instances) {
          if (!frame.present[instance.body]) continue;
          bodyMatrix(frame, instance.body, scratch.body);
          scratch.world.multiplyMatrices(scratch.body, instance.unscaledLocal);
          box.copy(instance.bounds).applyMatrix4(scratch.world);
          all.union(box);
          if (frame.kinds[instance.body] !== 'fixed') moving.union(box);
        }
      }
    }
    const bounds = moving.isEmpty() ? all : moving;
    if (bounds.isEmpty()) bounds.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    const centre = bounds.getCenter(new THREE.Vector3());
    const radius = Math.max(0.5, bounds.getSize(new THREE.Vector3()).length() / 2);
    // The narrower of the two fields of view decides the distance at which the bounding sphere fits.
    const vertical = THREE.MathUtils.degToRad(this.camera.fov);
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * this.camera.aspect);
    const distance = radius / Math.sin(Math.min(vertical, horizontal) / 2);
    const direction = new THREE.Vector3(0.3, 0.35, 1).normalize();
    this.setCamera(centre.clone().addScaledVector(direction, distance).toArray(), centre.toArray());

    const extent = Math.max(4, Math.ceil(radius * 4));
    this.grid = new THREE.GridHelper(extent * 2, extent * 2, 0x4a505c, 0x2f333b);
    // On the ground (y = 0), or under the bodies when they hang below it.
    this.grid.position.y = Math.min(0, bounds.min.y);
    this.scene.add(this.grid);
  }

  setCamera(position, target) {
    this.camera.position.set(...position);
    this.controls.target.set(...target);
    this.camera.near = Math.max(0.01, this.camera.position.distanceTo(this.controls.target) / 1000);
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.dirty = true;
  }

  /** Page pixel coordinates of the world point `p`, as drawn by the current camera. */
  project(p) {
    const v = new THREE.Vector3(...p).project(this.camera);
    const rect = this.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }

  /** Index of the body drawn under page point (x, y), or -1. */
  pick(x, y) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, 1 - ((y - rect.top) / rect.height) * 2);
    this.raycaster.setFromCamera(ndc, this.camera);
    let best = { body: -1, distance: Infinity };
    for (const group of this.groups) {
      if (group.impostor) {
        const hit = raycastBalls(this.raycaster.ray, group.mesh);
        if (hit !== null && hit.distance < best.distance) best = { body: group.instances[hit.instance].body, distance: hit.distance };
      } else {
        const hit = this.raycaster.intersectObject(group.mesh, false)[0];
        if (hit !== undefined && hit.instanceId !== undefined && hit.distance < best.distance) {
          best = { body: group.instances[hit.instanceId].body, distance: hit.distance };
        }
      }
    }
    return best.body;
  }

  /**
   * Body poses read back from the drawn instance matrices (not from the recording), so a test sees what
   * is on screen: each body's first part's matrix with the part's local pose and scale taken off.
   */
  displayedPoses() {
    const inverse = new THREE.Matrix4();
    return this.partsByBody.map((parts) => {
      if (parts.length === 0) return null;
      const { group, slot, instance } = parts[0];
      group.mesh.getMatrixAt(slot, scratch.world);
      inverse.copy(instance.local).invert();
      scratch.body.multiplyMatrices(scratch.world, inverse);
      scratch.body.decompose(scratch.position, scratch.quaternion, scratch.scale);
      return { position: scratch.position.toArray(), rotation: scratch.quaternion.toArray() };
    });
  }

  /** Draws if anything changed since the last draw; returns whether it drew. */
  render(force = false) {
    if (!this.dirty && !force) return false;
    this.renderer.render(this.scene, this.camera);
    this.dirty = false;
    return true;
  }
}

/** The world matrix of body `b` at `frame` (position in metres, rotation a unit quaternion x, y, z, w). */
export function bodyMatrix(frame, b, out) {
  const p = frame.positions;
  const q = frame.rotations;
  scratch.position.set(p[3 * b], p[3 * b + 1], p[3 * b + 2]);
  scratch.quaternion.set(q[4 * b], q[4 * b + 1], q[4 * b + 2], q[4 * b + 3]);
  return out.compose(scratch.position, scratch.quaternion, scratch.scale.set(1, 1, 1));
}
