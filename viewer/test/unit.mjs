// Unit tests of the page's modules that need no browser (node's test runner):
// the GLB reader on a view's files, the colour scale, the scale bar's length and
// the pose matrix. Usage: node --test test/unit.mjs (VIEW_DIR in $SWARF_VIEW: a
// view folder written by `swarf view`, for the GLB checks).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseGlb } from '../page/glb.js';
import { COLOURS, barLayout, deviationColour, robustRange } from '../page/colour.js';
import { scaleBarLength } from '../page/overlay.js';
import { poseMatrix, transform } from '../page/mat.js';

const dir = process.env.SWARF_VIEW;

test('the GLB reader reads what swarf view wrote', { skip: !dir && 'no SWARF_VIEW' }, () => {
  const view = JSON.parse(readFileSync(join(dir, 'view.json'), 'utf8'));
  const read = (f) => {
    const b = readFileSync(join(dir, f));
    return parseGlb(b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength));
  };
  const stock = read('stock.glb').nodes.find((n) => n.name === 'stock');
  assert.equal(stock.mesh.attributes.POSITION.data.length / 3, view.stock.vertices);
  assert.equal(stock.mesh.indices.length / 3, view.stock.triangles);
  for (const a of ['_DEVIATION', '_STATE', '_LINE']) assert.equal(stock.mesh.attributes[a].data.length, view.stock.vertices, a);
  const path = read('toolpath.glb');
  const names = path.nodes.map((n) => n.name);
  assert.deepEqual(names.slice(0, 3), ['cuts', 'links', 'rapids']);
  for (const n of path.nodes.filter((x) => x.mesh)) {
    const m = n.mesh.attributes._MOTION.data;
    assert.equal(m.length, n.mesh.attributes.POSITION.data.length / 3, n.name);
    assert.ok(m.every((k) => k >= 0 && k < view.motions.count && Number.isInteger(k)), n.name);
    const letter = n.name === 'tool axes' ? 'c' : n.name[0];
    assert.ok(m.every((k) => view.motions.kind[k] === letter), `${n.name}: every motion of its class`);
  }
});

test('the neutral band holds |d| <= tol and the sides run pale to deep', () => {
  const s = { lo: -0.1, hi: 0.2, tol: 0.01 };
  for (const d of [0, 0.01, -0.01, 0.005]) assert.deepEqual(deviationColour(d, s), COLOURS.neutral, String(d));
  assert.deepEqual(deviationColour(0.0100001, s), COLOURS.excessPale);
  assert.deepEqual(deviationColour(0.2, s), COLOURS.excessDeep);
  assert.deepEqual(deviationColour(0.21, s), COLOURS.excessBeyond);
  assert.deepEqual(deviationColour(-0.1, s), COLOURS.gougeDeep);
  assert.deepEqual(deviationColour(-0.11, s), COLOURS.gougeBeyond);
  const [a, b] = barLayout(s).band;
  assert.ok(a >= 0.14 && b - a > 0.15 && b <= 0.86, `band ${a} to ${b}`);
});

test('one deep spot does not stretch the range', () => {
  const n = 1000;
  const dev = Float32Array.from({ length: n }, (_, k) => (k < 990 ? 0.05 * (k / 990) : 0.73));
  const state = new Float32Array(n);
  const r = robustRange(dev, state, 0.01);
  assert.ok(r.hi < 0.1 && r.hi >= 0.045, `hi ${r.hi}`);
  assert.equal(r.lo, -0.02);
  assert.ok(r.beyond.above >= 10 && r.beyond.above < 30, `${r.beyond.above} above the range`);
});

test('the scale bar is the largest round length that fits', () => {
  assert.equal(scaleBarLength(0.1, 110), 10);
  assert.equal(scaleBarLength(0.3, 110), 20);
  assert.equal(scaleBarLength(0.5, 110), 50);
  assert.equal(scaleBarLength(0.004, 110), 0.2);
});

test('a pose puts the tool frame on its CL point along its axis', () => {
  const a = [0.6, 0, 0.8];
  const m = poseMatrix([1, 2, 3], a);
  const tip = transform(m, [0, 0, 0]);
  const up = transform(m, [0, 0, 10]);
  assert.deepEqual(tip.slice(0, 3).map((x) => +x.toFixed(5)), [1, 2, 3]);
  assert.deepEqual(up.slice(0, 3).map((x) => +x.toFixed(5)), [7, 2, 11]);
  const down = transform(poseMatrix([0, 0, 0], [0, 0, -1]), [0, 0, 1]);
  assert.deepEqual(down.slice(0, 3).map((x) => +x.toFixed(5)), [0, 0, -1]);
});
