// A reader of the GLB files swarf writes (crates/swarf-report/src/gltf): one
// buffer in the binary chunk, tightly packed views, FLOAT attributes and
// UNSIGNED_INT indices, one primitive per mesh, meshes on root nodes with an
// optional translation and rotation, colours as material base colour factors
// (linear light). Khronos glTF 2.0, section 4.4 "GLB file format".

const FLOAT = 5126;
const UNSIGNED_INT = 5125;
const SIZE = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

// The typed array of accessor `k` of `doc` over `bin` (a view of the file's bytes).
function accessor(doc, bin, k) {
  const a = doc.accessors[k];
  const view = doc.bufferViews[a.bufferView];
  const n = a.count * SIZE[a.type];
  const offset = bin.byteOffset + (view.byteOffset ?? 0) + (a.byteOffset ?? 0);
  if (view.byteStride && view.byteStride !== 4 * SIZE[a.type]) throw new Error(`accessor ${k}: interleaved views are not read`);
  if (a.componentType === FLOAT) return new Float32Array(bin.buffer, offset, n);
  if (a.componentType === UNSIGNED_INT) return new Uint32Array(bin.buffer, offset, n);
  throw new Error(`accessor ${k}: component type ${a.componentType} is not read`);
}

// The scene of a GLB file: { nodes: [{ name, extras, translation, rotation, mesh }],
// extras }, where mesh is { mode, attributes: { NAME: { data, size } }, indices,
// colour: [r, g, b, a] } or null for an empty node.
export function parseGlb(buffer) {
  const head = new DataView(buffer);
  if (head.getUint32(0, true) !== 0x46546c67) throw new Error('not a GLB file');
  const jsonLength = head.getUint32(12, true);
  const doc = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 20, jsonLength)));
  const binStart = 20 + jsonLength;
  const bin = binStart + 8 <= buffer.byteLength
    ? new Uint8Array(buffer, binStart + 8, head.getUint32(binStart, true))
    : new Uint8Array(0);
  const nodes = (doc.nodes ?? []).map((node) => {
    let mesh = null;
    if (node.mesh !== undefined) {
      const p = doc.meshes[node.mesh].primitives[0];
      const attributes = {};
      for (const [name, k] of Object.entries(p.attributes)) {
        attributes[name] = { data: accessor(doc, bin, k), size: SIZE[doc.accessors[k].type] };
      }
      const material = doc.materials?.[p.material];
      mesh = {
        mode: p.mode ?? 4,
        attributes,
        indices: p.indices === undefined ? null : accessor(doc, bin, p.indices),
        colour: material?.pbrMetallicRoughness?.baseColorFactor ?? [1, 1, 1, 1],
      };
    }
    return {
      name: node.name ?? '',
      extras: node.extras ?? {},
      translation: node.translation ?? [0, 0, 0],
      rotation: node.rotation ?? [0, 0, 0, 1],
      mesh,
    };
  });
  return { nodes, extras: doc.scenes?.[doc.scene ?? 0]?.extras ?? {} };
}

// The GLB at `url`, read.
export async function loadGlb(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: ${res.status} ${res.statusText}`);
  return parseGlb(await res.arrayBuffer());
}

// The bounds [[min x, y, z], [max x, y, z]] of a POSITION array.
export function bounds(pos) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let k = 0; k < pos.length; k += 3) {
    for (let c = 0; c < 3; c += 1) {
      const x = pos[k + c];
      if (x < lo[c]) lo[c] = x;
      if (x > hi[c]) hi[c] = x;
    }
  }
  return [lo, hi];
}
