// Balls drawn as ray-cast impostors: every ball of the scene is one camera-facing quad in a single mesh, and
// the fragment shader intersects the view ray with the exact sphere, shades it like MeshLambertMaterial under
// the scene's two lights and writes the sphere's own depth.
//
// Why not tessellated spheres in an InstancedMesh, as every other shape is drawn: the browser tests run on
// Chromium's software rasteriser (SwiftShader), where the 4,096-ball pile as 16×10-segment spheres
// (1.3 M triangles) draws at about one frame a second, and where an instanced draw costs a fixed ~25 µs per
// instance however small it is (4,096 instanced quads: ~100 ms a frame on the loaded test machine; the same
// quads in one ordinary buffer: ~10 ms). So the balls' quads share one vertex buffer rewritten each frame,
// one draw call for all of them, and the cost is the covered pixels. The balls are also round at any zoom.
//
// BallBatch keeps InstancedMesh's per-slot calls (setMatrixAt, getMatrixAt, setColorAt, count), so the
// scene poses, tints, reads back and picks balls exactly as it does the instanced shapes.

import * as THREE from 'three';

const vertexShader = /* glsl */ `
attribute vec3 centre;
attribute float radius;
attribute vec3 colour;

// Constant over a ball's quad, so not interpolated (the software rasteriser pays per interpolated float).
flat varying vec3 vCentre;
flat varying vec4 vSphere; // 1/r, |c|² − r², and two unused lanes
flat varying vec3 vColour;
varying vec3 vPosition;

void main() {
  vec4 viewCentre = modelViewMatrix * vec4(centre, 1.0);
  // A quad facing the eye through the centre covers the silhouette when its half-width is r·d/√(d²−r²);
  // position.xy is the quad corner, (±1, ±1).
  float d = length(viewCentre.xyz);
  float grow = d / sqrt(max(d * d - radius * radius, 1e-8));
  vec3 w = -viewCentre.xyz / max(d, 1e-8);
  vec3 side = abs(w.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(side, w));
  vec3 v = cross(w, u);
  vec3 corner = viewCentre.xyz + (u * position.x + v * position.y) * radius * min(grow, 8.0);
  vCentre = viewCentre.xyz;
  vSphere = vec4(1.0 / radius, d * d - radius * radius, 0.0, 0.0);
  vColour = colour;
  vPosition = corner;
  gl_Position = projectionMatrix * vec4(corner, 1.0);
}
`;

const fragmentShader = /* glsl */ `
#include <common>

uniform mat4 projectionMatrix;
uniform vec3 skyColour;
uniform vec3 groundColour;
uniform vec3 sunColour;
// The world's up and the direction to the sun, in view space (set before each draw).
uniform vec3 viewUp;
uniform vec3 viewSun;

flat varying vec3 vCentre;
flat varying vec4 vSphere;
flat varying vec3 vColour;
varying vec3 vPosition;

void main() {
  // The ray from the eye through this pixel meets the sphere |p − c| = r at t = b − √(b² − (|c|² − r²)).
  vec3 ray = normalize(vPosition);
  float b = dot(ray, vCentre);
  float discriminant = b * b - vSphere.y;
  if (discriminant < 0.0) discard;
  vec3 hit = ray * (b - sqrt(discriminant));
  vec3 n = (hit - vCentre) * vSphere.x;

  // Depth of the hit as the projection would give it: z_ndc = (P₂₂·z + P₃₂) / −z.
  gl_FragDepth = 0.5 * ((projectionMatrix[2][2] * hit.z + projectionMatrix[3][2]) / -hit.z) + 0.5;

  vec3 irradiance = mix(groundColour, skyColour, 0.5 * dot(n, viewUp) + 0.5) + max(dot(n, viewSun), 0.0) * sunColour;
  gl_FragColor = vec4(vColour * irradiance * RECIPROCAL_PI, 1.0);
  #include <colorspace_fragment>
}
`;

/**
 * The impostor material, lit like the scene's hemisphere and directional lights.
 * @param {THREE.HemisphereLight} hemisphere
 * @param {THREE.DirectionalLight} sun
 */
export function ballImpostorMaterial(hemisphere, sun) {
  const sunDirection = sun.position.clone().sub(sun.target.position).normalize();
  const material = new THREE.ShaderMaterial({
    vertexShader,
    fragmentShader,
    uniforms: {
      skyColour: { value: hemisphere.color.clone().multiplyScalar(hemisphere.intensity) },
      groundColour: { value: hemisphere.groundColor.clone().multiplyScalar(hemisphere.intensity) },
      sunColour: { value: sun.color.clone().multiplyScalar(sun.intensity) },
      viewUp: { value: new THREE.Vector3() },
      viewSun: { value: new THREE.Vector3() },
    },
  });
  material.onBeforeRender = (renderer, scene, camera) => {
    material.uniforms.viewUp.value.set(0, 1, 0).transformDirection(camera.matrixWorldInverse);
    material.uniforms.viewSun.value.copy(sunDirection).transformDirection(camera.matrixWorldInverse);
  };
  return material;
}

/**
 * `count` balls in one mesh: four vertices a ball (the quad corners) carrying its centre, radius and colour.
 * Slots are posed with a matrix, as an InstancedMesh's instances are: its translation is the centre and the
 * length of its first column the radius (the unit ball scaled).
 */
export class BallBatch extends THREE.Mesh {
  constructor(count, material) {
    const geometry = new THREE.BufferGeometry();
    const corners = new Float32Array(12 * count);
    const index = new Uint32Array(6 * count);
    const quad = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0];
    for (let i = 0; i < count; i++) {
      corners.set(quad, 12 * i);
      index.set([4 * i, 4 * i + 1, 4 * i + 2, 4 * i, 4 * i + 2, 4 * i + 3], 6 * i);
    }
    geometry.setAttribute('position', new THREE.BufferAttribute(corners, 3));
    for (const [name, size] of [['centre', 3], ['radius', 1], ['colour', 3]]) {
      const attribute = new THREE.BufferAttribute(new Float32Array(4 * size * count), size);
      attribute.setUsage(THREE.DynamicDrawUsage);
      geometry.setAttribute(name, attribute);
    }
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    // The quads move every frame and are never culled: a fixed bound spares recomputing one.
    geometry.boundingSphere = new THREE.Sphere(new THREE.Vector3(), Infinity);
    super(geometry, material);
    this.isBallBatch = true;
    this.count = count;
    this.frustumCulled = false;
    this.matrices = new Float32Array(16 * count);
  }

  setMatrixAt(slot, matrix) {
    matrix.toArray(this.matrices, 16 * slot);
    const e = matrix.elements;
    const radius = Math.hypot(e[0], e[1], e[2]);
    const centres = this.geometry.attributes.centre.array;
    const radii = this.geometry.attributes.radius.array;
    for (let k = 0; k < 4; k++) {
      const v = 4 * slot + k;
      centres[3 * v] = e[12];
      centres[3 * v + 1] = e[13];
      centres[3 * v + 2] = e[14];
      radii[v] = radius;
    }
  }

  getMatrixAt(slot, matrix) {
    matrix.fromArray(this.matrices, 16 * slot);
  }

  setColorAt(slot, colour) {
    const colours = this.geometry.attributes.colour.array;
    for (let k = 0; k < 4; k++) {
      const v = 4 * slot + k;
      colours[3 * v] = colour.r;
      colours[3 * v + 1] = colour.g;
      colours[3 * v + 2] = colour.b;
    }
  }

  /** Uploads the slots written since the last draw. */
  markUpdated() {
    for (const name of ['centre', 'radius', 'colour']) this.geometry.attributes[name].needsUpdate = true;
  }
}

const centre = new THREE.Vector3();
const axis = new THREE.Vector3();
const offset = new THREE.Vector3();
const matrix = new THREE.Matrix4();

/**
 * Nearest hit of `ray` with the balls of `mesh`: `{ instance, distance }`, or null. The drawn quads are not
 * the balls' surfaces, so the spheres are intersected directly.
 * @param {THREE.Ray} ray
 * @param {BallBatch} mesh
 */
export function raycastBalls(ray, mesh) {
  let best = null;
  for (let i = 0; i < mesh.count; i++) {
    mesh.getMatrixAt(i, matrix);
    centre.setFromMatrixPosition(matrix);
    const radius = axis.setFromMatrixColumn(matrix, 0).length();
    offset.subVectors(centre, ray.origin);
    const along = offset.dot(ray.direction);
    const squared = offset.lengthSq() - along * along;
    if (squared > radius * radius) continue;
    const distance = along - Math.sqrt(radius * radius - squared);
    if (distance < 0) continue;
    if (best === null || distance < best.distance) best = { instance: i, distance };
  }
  return best;
}
