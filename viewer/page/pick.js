// Picking on the CPU: the ray through a screen position, and its nearest hit on a
// triangle mesh (Moller-Trumbore, every triangle: a click tests a few hundred
// thousand in milliseconds, with no index to build or keep).

import { invert, transform } from './mat.js';

// The ray { origin, dir } of NDC position (x, y) under the inverse of a
// projection-view matrix.
export function rayAt(viewProj, x, y) {
  const inv = invert(viewProj);
  const a = transform(inv, [x, y, -1]);
  const b = transform(inv, [x, y, 1]);
  const dir = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
  const l = Math.hypot(...dir);
  return { origin: a.slice(0, 3), dir: dir.map((c) => c / l) };
}

// The nearest hit of `ray` on the triangles `indices` (null: consecutive triples)
// over `pos`: { t, point, triangle: [a, b, c] vertex indices, uvw barycentrics } or
// null.
export function intersect(ray, pos, indices) {
  const [ox, oy, oz] = ray.origin;
  const [dx, dy, dz] = ray.dir;
  const n = indices ? indices.length : pos.length / 3;
  let best = null;
  let bestT = Infinity;
  for (let k = 0; k < n; k += 3) {
    const ia = indices ? indices[k] : k;
    const ib = indices ? indices[k + 1] : k + 1;
    const ic = indices ? indices[k + 2] : k + 2;
    const ax = pos[3 * ia];
    const ay = pos[3 * ia + 1];
    const az = pos[3 * ia + 2];
    const e1x = pos[3 * ib] - ax;
    const e1y = pos[3 * ib + 1] - ay;
    const e1z = pos[3 * ib + 2] - az;
    const e2x = pos[3 * ic] - ax;
    const e2y = pos[3 * ic + 1] - ay;
    const e2z = pos[3 * ic + 2] - az;
    const px = dy * e2z - dz * e2y;
    const py = dz * e2x - dx * e2z;
    const pz = dx * e2y - dy * e2x;
    const det = e1x * px + e1y * py + e1z * pz;
    if (Math.abs(det) < 1e-14) continue;
    const f = 1 / det;
    const sx = ox - ax;
    const sy = oy - ay;
    const sz = oz - az;
    const u = f * (sx * px + sy * py + sz * pz);
    if (u < 0 || u > 1) continue;
    const qx = sy * e1z - sz * e1y;
    const qy = sz * e1x - sx * e1z;
    const qz = sx * e1y - sy * e1x;
    const v = f * (dx * qx + dy * qy + dz * qz);
    if (v < 0 || u + v > 1) continue;
    const t = f * (e2x * qx + e2y * qy + e2z * qz);
    if (t > 0 && t < bestT) {
      bestT = t;
      best = { t, triangle: [ia, ib, ic], uvw: [1 - u - v, u, v] };
    }
  }
  if (!best) return null;
  best.point = [ox + dx * bestT, oy + dy * bestT, oz + dz * bestT];
  return best;
}

// The vertex of the hit's triangle nearest to its point.
export function nearestVertex(hit) {
  const [w0, w1, w2] = hit.uvw;
  const k = w0 >= w1 && w0 >= w2 ? 0 : w1 >= w2 ? 1 : 2;
  return hit.triangle[k];
}

// Area-weighted unit vertex normals of an indexed triangle mesh.
export function vertexNormals(pos, indices) {
  const acc = new Float32Array(pos.length);
  for (let k = 0; k < indices.length; k += 3) {
    const [a, b, c] = [indices[k], indices[k + 1], indices[k + 2]];
    const e1 = [0, 1, 2].map((i) => pos[3 * b + i] - pos[3 * a + i]);
    const e2 = [0, 1, 2].map((i) => pos[3 * c + i] - pos[3 * a + i]);
    const nrm = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    for (const v of [a, b, c]) for (let i = 0; i < 3; i += 1) acc[3 * v + i] += nrm[i];
  }
  for (let v = 0; v < acc.length; v += 3) {
    const l = Math.hypot(acc[v], acc[v + 1], acc[v + 2]) || 1;
    for (let i = 0; i < 3; i += 1) acc[v + i] /= l;
  }
  return acc;
}
