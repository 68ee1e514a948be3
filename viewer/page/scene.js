// The view's scene: the GLB files that view.json names, read into renderer items
// grouped by layer (part, stock, cuts, links, rapids, tool axes, cutter, origin),
// with the stock of each operation and the cutter of each operation.

import { COLOURS } from './colour.js';
import { bounds, loadGlb } from './glb.js';
import { vertexNormals } from './pick.js';

// The operations of `view`: those it lists, else one for the whole program.
export function operationsOf(view) {
  if (Array.isArray(view.operations) && view.operations.length) return view.operations;
  return [{ name: 'program', tool: view.tool, first_motion: 0, motions: view.motions.count, stock: view.files.stock, cutter: view.files.cutter }];
}

// The mesh node `name` of a parsed GLB, or null.
const node = (glb, name) => glb.nodes.find((n) => n.name === name && n.mesh) ?? null;

// The stock of a stock GLB: its arrays for picking and the colour range, and its
// renderer item (null for a stock with no triangles).
function stockOf(glb, renderer) {
  const n = node(glb, 'stock');
  if (!n) return null;
  const a = n.mesh.attributes;
  const data = {
    pos: a.POSITION.data,
    indices: n.mesh.indices,
    dev: a._DEVIATION.data,
    state: a._STATE.data,
    cell: a._CELL.data,
    line: a._LINE.data,
    extras: n.extras,
  };
  const item = renderer.surfaceItem({ pos: data.pos, normal: a.NORMAL?.data, dev: data.dev, state: data.state, indices: data.indices });
  return { ...data, item, bounds: bounds(data.pos) };
}

function cutterOf(glb, renderer) {
  const n = node(glb, 'cutter');
  if (!n) return null;
  const pos = n.mesh.attributes.POSITION.data;
  const normal = n.mesh.attributes.NORMAL?.data ?? vertexNormals(pos, n.mesh.indices);
  return renderer.surfaceItem({ pos, normal, indices: n.mesh.indices, colour: COLOURS.cutter });
}

// Axes at the world origin, `len` mm long: one line item per axis.
function originItems(renderer, len) {
  return [0, 1, 2].map((k) => {
    const pos = new Float32Array(6);
    pos[3 + k] = len;
    return renderer.lineItem({ pos, motion: null, colour: COLOURS.axes[k] });
  });
}

// Reads every file of `view` into `renderer`: { layers, stocks, cutters, bounds }.
// layers[name] = { items, colour, count } (count: triangles or segments).
export async function loadScene(view, renderer) {
  const ops = operationsOf(view);
  const names = [...new Set([view.files.part, view.files.toolpath, ...ops.map((o) => o.stock), ...ops.map((o) => o.cutter)])];
  const files = Object.fromEntries(await Promise.all(names.map(async (f) => [f, await loadGlb(f)])));
  const layers = {};
  const part = node(files[view.files.part], 'part');
  if (part) {
    const m = part.mesh;
    const normal = m.attributes.NORMAL?.data ?? vertexNormals(m.attributes.POSITION.data, m.indices);
    const item = renderer.surfaceItem({ pos: m.attributes.POSITION.data, normal, indices: m.indices, colour: COLOURS.part });
    layers.part = { items: [item], colour: COLOURS.part, count: m.indices.length / 3, pos: m.attributes.POSITION.data, indices: m.indices };
  }
  const stocks = ops.map((o) => stockOf(files[o.stock], renderer));
  if (stocks.some(Boolean)) layers.stock = { items: stocks.filter(Boolean).map((s) => s.item), colour: null, count: stocks.at(-1)?.indices.length / 3 };
  const path = files[view.files.toolpath];
  for (const name of ['cuts', 'links', 'rapids', 'tool axes']) {
    const n = path.nodes.find((x) => x.name === name);
    if (!n) continue;
    const colour = COLOURS[name];
    const items = [];
    if (n.mesh) {
      const a = n.mesh.attributes;
      items.push(renderer.lineItem({ pos: a.POSITION.data, motion: a._MOTION?.data ?? null, colour }));
    }
    layers[name] = { items, colour, count: n.mesh ? n.mesh.attributes.POSITION.data.length / 6 : 0 };
  }
  const cutters = ops.map((o) => cutterOf(files[o.cutter], renderer));
  layers.cutter = { items: cutters.filter(Boolean), colour: COLOURS.cutter, count: 1 };
  const box = sceneBounds(layers, stocks);
  const size = Math.hypot(...box[1].map((x, k) => x - box[0][k])) || 1;
  layers.origin = { items: originItems(renderer, size * 0.08), colour: null, count: 3 };
  return { layers, stocks, cutters, bounds: box, ops };
}

// The box of the stock (else the part, else the tool path).
function sceneBounds(layers, stocks) {
  const boxes = stocks.filter(Boolean).map((s) => s.bounds);
  if (!boxes.length && layers.part) boxes.push(bounds(layers.part.pos));
  if (!boxes.length) {
    for (const name of ['cuts', 'links', 'rapids']) {
      const it = layers[name]?.items[0];
      if (it?.pos) boxes.push(bounds(it.pos));
    }
  }
  if (!boxes.length) return [[-1, -1, -1], [1, 1, 1]];
  return [0, 1].map((s) => [0, 1, 2].map((k) => (s ? Math.max : Math.min)(...boxes.map((b) => b[s][k]))));
}
