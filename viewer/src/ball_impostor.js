// Balls drawn as ray-cast impostors: each ball is one camera-facing quad of an InstancedMesh, and the
// fragment shader intersects the view ray with the exact sphere, shades it like MeshLambertMaterial under
// the scene's two lights and writes the sphere's own depth.
//
// Why not a tessellated sphere: the browser tests run on Chromium's software rasteriser, where the 4,096-ball
// pile as 16×10-segment spheres (1.3 M triangles) draws at about 1 frame per second; as impostors it is
// 8,192 triangles and the cost is the covered pixels alone. The balls are also perfectly round at any zoom.

import * as THREE from 'three';

const vertexShader = /* glsl */ `
uniform vec3 sunDirection;

varying vec3 vCentre;
varying vec3 vPosition;
varying float vRadius;
varying vec3 vColour;
varying vec3 vUp;
varying vec3 vSun;

void main() {
  vec4 centre = modelViewMatrix * instanceMatrix * vec4(0.0, 0.0, 0.0, 1.0);
  // The instance matrix scales the unit ball uniformly by the radius.
  float radius = length((modelMatrix * instanceMatrix * vec4(1.0, 0.0, 0.0, 0.0)).xyz);
  // A quad facing the eye through the centre covers the silhouette when its half-width is r·d/√(d²−r²).
  float d = length(centre.xyz);
  float grow = d / sqrt(max(d * d - radius * radius, 1e-8));
  vec3 w = -centre.xyz / max(d, 1e-8);
  vec3 side = abs(w.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(side, w));
  vec3 v = cross(w, u);
  vec3 corner = centre.xyz + (u * position.x + v * position.y) * radius * min(grow, 8.0);
  vCentre = centre.xyz;
  vPosition = corner;
  vRadius = radius;
  vUp = (viewMatrix * vec4(0.0, 1.0, 0.0, 0.0)).xyz;
  vSun = (viewMatrix * vec4(sunDirection, 0.0)).xyz;
#ifdef USE_INSTANCING_COLOR
  vColour = instanceColor;
#else
  vColour = vec3(1.0);
#endif
  gl_Position = projectionMatrix * vec4(corner, 1.0);
}
`;

const fragmentShader = /* glsl */ `
#include <common>

uniform mat4 projectionMatrix;
uniform vec3 skyColour;
uniform vec3 groundColour;
uniform vec3 sunColour;

varying vec3 vCentre;
varying vec3 vPosition;
varying float vRadius;
varying vec3 vColour;
varying vec3 vUp;
varying vec3 vSun;

void main() {
  vec3 ray = normalize(vPosition);
  float b = dot(ray, vCentre);
  float c = dot(vCentre, vCentre) - vRadius * vRadius;
  float discriminant = b * b - c;
  if (discriminant < 0.0) discard;
  float t = b - sqrt(discriminant);
  vec3 hit = ray * t;
  vec3 n = (hit - vCentre) / vRadius;

  vec4 clip = projectionMatrix * vec4(hit, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;

  vec3 irradiance = mix(groundColour, skyColour, 0.5 * dot(n, vUp) + 0.5) + max(dot(n, vSun), 0.0) * sunColour;
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
  return new THREE.ShaderMaterial({
    vertexShader,
    fragmentShader,
    uniforms: {
      skyColour: { value: hemisphere.color.clone().multiplyScalar(hemisphere.intensity) },
      groundColour: { value: hemisphere.groundColor.clone().multiplyScalar(hemisphere.intensity) },
      sunColour: { value: sun.color.clone().multiplyScalar(sun.intensity) },
      sunDirection: { value: sun.position.clone().sub(sun.target.position).normalize() },
    },
  });
}

/** The quad every impostor instance draws (corners at ±1 in its own plane). */
export function ballImpostorGeometry() {
  return new THREE.PlaneGeometry(2, 2);
}

const centre = new THREE.Vector3();
const axis = new THREE.Vector3();
const offset = new THREE.Vector3();
const matrix = new THREE.Matrix4();

/**
 * Nearest hit of `ray` with the balls of `mesh`: `{ instance, distance }`, or null. The drawn quads are not
 * the balls' surfaces, so the spheres are intersected directly.
 * @param {THREE.Ray} ray
 * @param {THREE.InstancedMesh} mesh
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
