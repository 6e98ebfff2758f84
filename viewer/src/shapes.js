// Collider shapes as three.js geometry.
//
// Each shape becomes a geometry plus a per-instance scale, chosen so that shapes differing only in size
// share one geometry: every ball is the unit sphere scaled by its radius, every cuboid the unit cube scaled
// by its extents. The `key` names the shared geometry; bodies whose parts have the same key are drawn by one
// InstancedMesh. Axis conventions follow the engine (parry3d): capsules, cylinders and cones stand along +Y,
// a cone's apex at +half_height.

import * as THREE from 'three';
import { ConvexGeometry } from 'three/addons/geometries/ConvexGeometry.js';

const ROUND_SEGMENTS = 20;

/**
 * `impostor` marks the balls, drawn by ball_impostor.js's BallBatch rather than as triangles (no geometry).
 * @typedef {{geometry: () => THREE.BufferGeometry, key: string, scale: THREE.Vector3,
 *            localBounds: THREE.Box3, impostor?: boolean}} ShapeGeometry
 */

/**
 * Geometry for one (non-compound) shape of the recording model, or null for a kind the viewer cannot draw.
 * `uid` makes keys unique for shapes that cannot share geometry (hulls, meshes, heightfields).
 * @returns {ShapeGeometry | null}
 */
export function shapeGeometry(shape, uid) {
  switch (shape.kind) {
    case 'ball': {
      const r = shape.radius;
      return {
        key: 'ball',
        impostor: true,
        geometry: () => null,
        scale: new THREE.Vector3(r, r, r),
        localBounds: new THREE.Box3(new THREE.Vector3(-r, -r, -r), new THREE.Vector3(r, r, r)),
      };
    }
    case 'cuboid': {
      const [x, y, z] = shape.halfExtents;
      return {
        key: 'cuboid',
        geometry: () => new THREE.BoxGeometry(2, 2, 2),
        scale: new THREE.Vector3(x, y, z),
        localBounds: new THREE.Box3(new THREE.Vector3(-x, -y, -z), new THREE.Vector3(x, y, z)),
      };
    }
    case 'cylinder': {
      const { radius: r, halfHeight: h } = shape;
      return {
        key: 'cylinder',
        geometry: () => new THREE.CylinderGeometry(1, 1, 2, ROUND_SEGMENTS),
        scale: new THREE.Vector3(r, h, r),
        localBounds: new THREE.Box3(new THREE.Vector3(-r, -h, -r), new THREE.Vector3(r, h, r)),
      };
    }
    case 'cone': {
      const { radius: r, halfHeight: h } = shape;
      return {
        key: 'cone',
        geometry: () => new THREE.ConeGeometry(1, 2, ROUND_SEGMENTS),
        scale: new THREE.Vector3(r, h, r),
        localBounds: new THREE.Box3(new THREE.Vector3(-r, -h, -r), new THREE.Vector3(r, h, r)),
      };
    }
    case 'capsule': {
      // A capsule does not scale into another capsule, so its key carries both dimensions.
      const { radius: r, halfHeight: h } = shape;
      return {
        key: `capsule:${r}:${h}`,
        geometry: () => new THREE.CapsuleGeometry(r, 2 * h, 6, ROUND_SEGMENTS),
        scale: new THREE.Vector3(1, 1, 1),
        localBounds: new THREE.Box3(new THREE.Vector3(-r, -h - r, -r), new THREE.Vector3(r, h + r, r)),
      };
    }
    case 'hull': {
      const points = toVectors(shape.vertices);
      if (points.length < 4) return null;
      return {
        key: `hull:${uid}`,
        geometry: () => new ConvexGeometry(points),
        scale: new THREE.Vector3(1, 1, 1),
        localBounds: new THREE.Box3().setFromPoints(points),
      };
    }
    case 'trimesh': {
      const points = toVectors(shape.vertices);
      if (points.length < 3) return null;
      return {
        key: `trimesh:${uid}`,
        geometry: () => {
          const g = new THREE.BufferGeometry();
          g.setAttribute('position', new THREE.Float32BufferAttribute(Array.from(shape.vertices), 3));
          g.setIndex(Array.from(shape.indices));
          g.computeVertexNormals();
          return g;
        },
        scale: new THREE.Vector3(1, 1, 1),
        localBounds: new THREE.Box3().setFromPoints(points),
      };
    }
    case 'heightfield':
      return heightfieldGeometry(shape, uid);
    default:
      return null;
  }
}

/**
 * A heightfield: `rows × columns` heights on a grid spanning `scale` (x and z full widths, y a height
 * multiplier), centred on the body's origin as parry3d lays it out.
 */
function heightfieldGeometry(shape, uid) {
  const { rows, columns, heights } = shape;
  const [sx, sy, sz] = shape.scale;
  if (rows < 2 || columns < 2 || heights.length !== rows * columns) return null;
  const positions = new Float32Array(rows * columns * 3);
  for (let i = 0; i < rows; i++) {
    for (let j = 0; j < columns; j++) {
      const k = i * columns + j;
      positions[3 * k] = (j / (columns - 1) - 0.5) * sx;
      positions[3 * k + 1] = heights[k] * sy;
      positions[3 * k + 2] = (i / (rows - 1) - 0.5) * sz;
    }
  }
  const indices = [];
  for (let i = 0; i + 1 < rows; i++) {
    for (let j = 0; j + 1 < columns; j++) {
      const a = i * columns + j;
      indices.push(a, a + columns, a + 1, a + 1, a + columns, a + columns + 1);
    }
  }
  const bounds = new THREE.Box3();
  bounds.setFromArray(positions);
  return {
    key: `heightfield:${uid}`,
    geometry: () => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
      g.setIndex(indices);
      g.computeVertexNormals();
      return g;
    },
    scale: new THREE.Vector3(1, 1, 1),
    localBounds: bounds,
  };
}

function toVectors(flat) {
  const points = [];
  for (let i = 0; i + 2 < flat.length; i += 3) points.push(new THREE.Vector3(flat[i], flat[i + 1], flat[i + 2]));
  return points;
}
