// Browser test of the viewer page in headless Chromium (Debian's /usr/bin/chromium,
// driven by playwright-core; no browser is downloaded).
// Usage: node test/browser.mjs VIEW_DIR [--sequence SEQUENCE_VIEW_DIR] [--shot SCREENSHOT.png]
// VIEW_DIR is a view of the iso-scallop program of wave, written by
//   swarf view --job jobs/wave-iso-scallop.toml --cell 0.2 --scallop 0 --max-vertices 600000 -o VIEW_DIR
// (every cell a vertex, every scallop crest above the tolerance flagged as excess);
// SEQUENCE_VIEW_DIR a view of a sequence job (jobs/fillet-pocket-sequence.toml).
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import assert from 'node:assert/strict';
import { openView } from './page.mjs';
import { keyChecks, legendChecks, measureChecks, operationChecks, pixels as canvasPixels, scaleChecks, triadChecks } from './checks.mjs';

const [dir, ...rest] = process.argv.slice(2);
const flag = (name) => {
  const k = rest.indexOf(name);
  return k >= 0 ? rest[k + 1] : undefined;
};
const shot = flag('--shot');
const sequence = flag('--sequence');
if (!dir) {
  console.error('usage: node test/browser.mjs VIEW_DIR [--sequence SEQUENCE_VIEW_DIR] [--shot SCREENSHOT.png]');
  process.exit(2);
}

// Modal X Y Z of every line of a G-code program, read here on its own (G0/G1 words
// only): the expected cutter position after each line.
function gcodePositions(text) {
  const at = { X: NaN, Y: NaN, Z: NaN };
  const out = new Map();
  text.split('\n').forEach((raw, k) => {
    const line = raw.replace(/\(.*?\)/g, '').replace(/;.*/, '').toUpperCase();
    let moved = false;
    for (const m of line.matchAll(/([XYZ])\s*([-+]?\d*\.?\d+)/g)) {
      at[m[1]] = Number(m[2]);
      moved = true;
    }
    if (moved) out.set(k + 1, { ...at, text: raw });
  });
  return out;
}

let checks = 0;
const ok = (cond, what) => {
  assert.ok(cond, what);
  checks += 1;
  console.log(`ok ${checks} - ${what}`);
};

const { page, close } = await openView(dir);
try {
  const error = await page.evaluate(() => window.swarfView.error);
  ok(!error, `the page loads the view (${error ?? 'no error'})`);

  const pixels = () => canvasPixels(page);
  const first = await pixels();
  ok(first.drawn > first.total * 0.05, `the canvas is not blank (${first.drawn} of ${first.total} pixels drawn)`);
  if (shot) await page.screenshot({ path: shot });

  for (const layer of ['stock', 'part', 'cuts', 'rapids']) {
    const visible = () => page.evaluate((n) => window.swarfView.visible(n), layer);
    const [was, before] = [await visible(), await pixels()];
    await page.click(`#layer-${layer}`);
    const after = await pixels();
    const now = await visible();
    ok(now !== was && after.sum !== before.sum, `toggling ${layer} ${was ? 'off' : 'on'} changes the picture (${before.drawn} -> ${after.drawn} pixels drawn)`);
    await page.click(`#layer-${layer}`);
    const back = await pixels();
    ok(back.sum === before.sum && (await visible()) === was, `toggling ${layer} back restores it`);
  }

  // The slider moves the cutter to the pose of a chosen line.
  const view = JSON.parse(readFileSync(join(dir, 'view.json'), 'utf8'));
  const ngc = readdirSync(dir).find((f) => f.endsWith('.ngc'));
  const positions = gcodePositions(readFileSync(join(dir, ngc), 'utf8'));
  const feedLines = [...positions.keys()].filter((l) => /^\s*(N\d+\s*)?G0?1\b/i.test(positions.get(l).text) || /^\s*[XYZ]/i.test(positions.get(l).text));
  for (const line of [feedLines[Math.floor(feedLines.length / 3)], feedLines[Math.floor((2 * feedLines.length) / 3)]]) {
    const k = await page.evaluate((l) => window.swarfView.motionOfLine(l), line);
    ok(k > 0, `line ${line} commands motion ${k}`);
    await page.evaluate((v) => {
      const s = document.getElementById('motion');
      s.value = String(v);
      s.dispatchEvent(new Event('input'));
    }, k);
    const pose = await page.evaluate(() => window.swarfView.cutter());
    const want = positions.get(line);
    const err = Math.hypot(pose.position[0] - want.X, pose.position[1] - want.Y, pose.position[2] - want.Z);
    ok(err < 1e-3, `the cutter is at line ${line}'s X${want.X} Y${want.Y} Z${want.Z} (off by ${err.toExponential(2)} mm)`);
    const shown = await page.textContent('#gcode-line');
    ok(shown.includes(want.text.trim()), `the panel shows line ${line}: ${shown}`);
  }

  // Clicking the stock reads the deviation the report gives for that cell.
  const report = JSON.parse(readFileSync(join(dir, 'report.json'), 'utf8'));
  const g = report.grid;
  const cellOf = ([x, y]) => [Math.floor((x - g.origin_mm[0]) / g.cell_mm), Math.floor((y - g.origin_mm[1]) / g.cell_mm)];
  const inside = (r) => {
    const [i, j] = cellOf(r.at);
    return i > 2 && j > 2 && i < g.nx - 3 && j < g.ny - 3;
  };
  const region = [...report.deviation.excesses, ...report.deviation.gouges].find(inside);
  ok(region, 'the report lists a flagged region inside the grid');
  const [x, y, z] = region.at;
  const cell = cellOf(region.at);
  await page.evaluate(([x, y]) => window.swarfView.lookDown(x, y, 12), [x, y]);
  const at = await page.evaluate(([x, y, z]) => window.swarfView.project(x, y, z), [x, y, z]);
  await page.mouse.click(at.x, at.y);
  const pick = await page.evaluate(([px, py]) => window.swarfView.pick(px, py), [at.x, at.y]);
  ok(pick && pick.cell[0] === cell[0] && pick.cell[1] === cell[1], `the click finds cell ${cell} (${pick && pick.cell})`);
  ok(Math.abs(pick.deviation - region.worst) < 1e-5, `its deviation ${pick.deviation} is the report's ${region.worst}`);
  ok(pick.line === region.line, `the line that last cut it, ${pick.line}, is the report's ${region.line}`);
  const panel = await page.textContent('#pick');
  ok(panel.includes(`line ${region.line}`), `the panel shows it: ${panel.split('\n')[0]}`);
  ok(view.motions.count > 0, `${view.motions.count} motions in view.json`);
  ok((await page.evaluate(() => window.swarfView.operations.length)) === 1, 'one program is one operation');

  await legendChecks(page, ok);
  await triadChecks(page, ok);
  await scaleChecks(page, ok, view);
  await measureChecks(page, ok);
  await keyChecks(page, ok);
} finally {
  await close();
}

if (sequence) {
  const seq = await openView(sequence);
  try {
    const error = await seq.page.evaluate(() => window.swarfView.error);
    ok(!error, `the page loads the sequence's view (${error ?? 'no error'})`);
    await operationChecks(seq.page, ok);
    const pick = await seq.page.evaluate(() => {
      const r = document.getElementById('view').getBoundingClientRect();
      return window.swarfView.pick(r.left + r.width * 0.6, r.top + r.height * 0.5);
    });
    ok(pick && pick.state, `picking the final stock reads a cell (${pick && pick.state}, line ${pick && pick.line})`);
  } finally {
    await seq.close();
  }
}
console.log(`${checks} checks passed`);
