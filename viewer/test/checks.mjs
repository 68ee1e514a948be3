// The browser test's checks of what the page explains: the legend, the axis triad
// and scale bar, the neutral band and colour range of the deviation scale, the
// measurement, the keyboard shortcuts, and the operations of a sequence.

// Pixels of the WebGL canvas that are not the background, and a checksum of them.
export const pixels = (page) => page.evaluate(() => {
  const c = document.getElementById('view');
  const copy = document.createElement('canvas');
  [copy.width, copy.height] = [c.width, c.height];
  const g = copy.getContext('2d');
  g.drawImage(c, 0, 0);
  const d = g.getImageData(0, 0, copy.width, copy.height).data;
  let drawn = 0;
  let sum = 0;
  for (let k = 0; k < d.length; k += 4) {
    if (Math.abs(d[k] - 244) + Math.abs(d[k + 1] - 245) + Math.abs(d[k + 2] - 247) > 12) drawn += 1;
    sum = (sum * 31 + d[k] + 7 * d[k + 1] + 13 * d[k + 2]) % 1000000007;
  }
  return { drawn, sum, total: d.length / 4 };
});

// The mean colour of the WebGL canvas in a 5 x 5 pixel box round a client position.
const pixelAt = (page, at) => page.evaluate(({ x, y }) => {
  const c = document.getElementById('view');
  const r = c.getBoundingClientRect();
  const [px, py] = [Math.round(((x - r.left) / r.width) * c.width), Math.round(((y - r.top) / r.height) * c.height)];
  const copy = document.createElement('canvas');
  [copy.width, copy.height] = [c.width, c.height];
  const g = copy.getContext('2d');
  g.drawImage(c, 0, 0);
  const d = g.getImageData(px - 2, py - 2, 5, 5).data;
  const m = [0, 0, 0];
  for (let k = 0; k < d.length; k += 4) for (let i = 0; i < 3; i += 1) m[i] += d[k + i] / 25;
  return m.map(Math.round);
}, at);

const distance = (a, b) => Math.hypot(...a.map((x, k) => x - b[k]));
const spread = (c) => Math.max(...c) - Math.min(...c);

export async function legendChecks(page, ok) {
  const rows = await page.$$eval('#legend .layer', (ls) => ls.map((l) => ({
    layer: l.dataset.layer,
    text: l.textContent.trim(),
    swatch: getComputedStyle(l.querySelector('.swatch')).backgroundColor,
    image: getComputedStyle(l.querySelector('.swatch')).backgroundImage,
  })));
  const names = rows.map((r) => r.layer);
  for (const want of ['part', 'stock', 'cuts', 'links', 'rapids', 'cutter', 'origin']) {
    ok(names.includes(want), `the legend has a row for ${want}`);
  }
  const colours = await page.evaluate(() => ['part', 'cuts', 'links', 'rapids', 'cutter'].map((n) => window.swarfView.layerColour(n)));
  const scale = await page.evaluate(() => window.swarfView.scale());
  const blue = await page.evaluate((s) => window.swarfView.colourOf(s.hi * 0.9), scale);
  const red = await page.evaluate((s) => window.swarfView.colourOf(s.lo * 0.9), scale);
  let closest = Infinity;
  for (let i = 0; i < colours.length; i += 1) {
    for (let j = i + 1; j < colours.length; j += 1) closest = Math.min(closest, distance(colours[i], colours[j]));
  }
  ok(closest > 60, `the layers' colours are apart (closest pair ${closest.toFixed(0)} apart in sRGB)`);
  const cuts = colours[1];
  ok(distance(cuts, blue) > 100 && distance(cuts, red) > 100, `cuts rgb(${cuts}) do not look like material left rgb(${blue}) nor a gouge rgb(${red})`);
  const swatches = Object.fromEntries(rows.map((r) => [r.layer, r]));
  ok(swatches.cuts.swatch === `rgb(${cuts.join(', ')})`, `the cuts' swatch is their colour (${swatches.cuts.swatch})`);
  ok(swatches.stock.image.includes('gradient'), 'the stock\'s swatch is the deviation scale');
}

export async function triadChecks(page, ok) {
  const triad = await page.evaluate(() => window.swarfView.triad());
  ok(triad && triad.axes.length === 3, 'the overlay draws the axis triad');
  const drawn = await page.evaluate(({ centre }) => {
    const g = document.getElementById('overlay').getContext('2d');
    const ratio = window.devicePixelRatio || 1;
    const d = g.getImageData((centre[0] - 40) * ratio, (centre[1] - 40) * ratio, 80 * ratio, 80 * ratio).data;
    let coloured = 0;
    for (let k = 0; k < d.length; k += 4) if (d[k + 3] > 200 && Math.max(d[k], d[k + 1], d[k + 2]) - Math.min(d[k], d[k + 1], d[k + 2]) > 80) coloured += 1;
    return coloured;
  }, triad);
  ok(drawn > 50, `the triad's axes are on screen (${drawn} coloured pixels)`);
  await page.evaluate(() => window.swarfView.viewFrom('top'));
  const top = await page.evaluate(() => window.swarfView.triad().axes);
  ok(top[0][0] > 30 && Math.abs(top[0][1]) < 5, `seen from the top, X points right (${top[0].slice(0, 2).map((x) => x.toFixed(1))})`);
  ok(top[1][1] < -30 && Math.abs(top[1][0]) < 5, `and Y points up (${top[1].slice(0, 2).map((x) => x.toFixed(1))})`);
  ok(Math.hypot(top[2][0], top[2][1]) < 5, 'and Z points at the viewer');
  const bar = await page.evaluate(() => window.swarfView.scaleBar());
  const mant = bar.mm / 10 ** Math.floor(Math.log10(bar.mm) + 1e-9);
  ok([1, 2, 5].some((m) => Math.abs(mant - m) < 1e-6) && bar.px > 20 && bar.px <= 110, `the scale bar is a round length: ${bar.text} over ${bar.px.toFixed(0)} px`);
  await page.evaluate(() => window.swarfView.viewFrom('iso'));
}

// A measured stock vertex well inside a patch of cells within (or beyond) the
// tolerance: { x, y, z, d } or null. `want` is 'neutral', 'excess' or 'gouge'.
const findCell = (page, want) => page.evaluate((want) => {
  const api = window.swarfView;
  const s = api.stockArrays();
  const { tol, lo, hi } = api.scale();
  const at = new Map();
  for (let v = 0; v < s.dev.length; v += 1) at.set(`${s.cell[2 * v]},${s.cell[2 * v + 1]}`, v);
  const test = { neutral: (d) => Math.abs(d) <= tol * 0.8, excess: (d) => d > tol * 1.5 && d < hi * 0.9, gouge: (d) => d < -tol * 1.5 && d > lo * 0.9 }[want];
  for (let v = 0; v < s.dev.length; v += 7) {
    const [i, j] = [s.cell[2 * v], s.cell[2 * v + 1]];
    let all = true;
    for (let dj = -1; dj <= 1 && all; dj += 1) {
      for (let di = -1; di <= 1 && all; di += 1) {
        const w = at.get(`${i + di},${j + dj}`);
        all = w !== undefined && s.state[w] === 0 && test(s.dev[w]);
      }
    }
    if (all) return { x: s.pos[3 * v], y: s.pos[3 * v + 1], z: s.pos[3 * v + 2], d: s.dev[v] };
  }
  return null;
}, want);

export async function scaleChecks(page, ok, view) {
  const tol = view.deviation.tolerance_mm;
  const neutral = await page.evaluate((t) => [window.swarfView.colourOf(t * 0.5), window.swarfView.colourOf(-t * 0.5), window.swarfView.colourOf(0)], tol);
  ok(neutral.every((c) => distance(c, neutral[0]) === 0) && spread(neutral[0]) < 12, `|d| <= tol is one neutral grey rgb(${neutral[0]})`);
  const ramp = await page.$eval('#ramp', (e) => getComputedStyle(e).backgroundImage);
  ok(ramp.includes(`rgb(${neutral[0].join(', ')})`), 'the legend\'s bar shows the neutral band');
  const band = await page.textContent('#tick-band');
  ok(band.includes(String(tol)), `the band's tick names the tolerance (${band})`);
  const scale = await page.evaluate(() => window.swarfView.scale());
  ok(scale.hi <= Math.max(view.deviation.max_mm, 2 * tol) + 1e-9 && scale.lo < -tol && scale.hi > tol, `the range is by percentiles: ${scale.lo} to ${scale.hi} mm (deviations ${view.deviation.min_mm.toFixed(4)} to ${view.deviation.max_mm.toFixed(4)})`);
  for (const layer of ['cuts', 'links', 'rapids', 'cutter', 'origin']) await page.evaluate((n) => window.swarfView.setVisible(n, false), layer);
  for (const [want, looks] of [['neutral', (c) => spread(c) < 16], ['excess', (c) => c[2] > c[0] + 25]]) {
    const cell = await findCell(page, want);
    ok(cell, `the stock has a patch of ${want} cells`);
    await page.evaluate(({ x, y }) => window.swarfView.lookDown(x, y, 1.2), cell);
    const at = await page.evaluate(({ x, y, z }) => window.swarfView.project(x, y, z), cell);
    const c = await pixelAt(page, at);
    ok(looks(c), `a ${want} cell (${cell.d.toFixed(4)} mm) is drawn ${want === 'neutral' ? 'grey' : 'blue'} on the range: rgb(${c})`);
  }
  await page.fill('#range-hi', String(scale.hi * 4));
  await page.dispatchEvent('#range-hi', 'change');
  const wider = await page.evaluate(() => window.swarfView.scale());
  ok(Math.abs(wider.hi - scale.hi * 4) < 1e-9, `the range's input sets its top (${wider.hi} mm)`);
  await page.click('#range-auto');
  ok((await page.evaluate(() => window.swarfView.scale().hi)) === scale.hi, 'auto restores the percentile range');
  for (const layer of ['cuts', 'links', 'rapids', 'cutter', 'origin']) await page.evaluate((n) => window.swarfView.setVisible(n, true), layer);
}

export async function measureChecks(page, ok) {
  await page.evaluate(() => window.swarfView.viewFrom('iso'));
  await page.keyboard.press('m');
  ok(await page.evaluate(() => window.swarfView.measuring()), 'the m key starts measuring');
  const box = await page.$eval('#view', (c) => {
    const r = c.getBoundingClientRect();
    return { x: r.left, y: r.top, w: r.width, h: r.height };
  });
  const clicks = [[0.55, 0.45], [0.7, 0.6]].map(([u, v]) => [box.x + u * box.w, box.y + v * box.h]);
  const points = [];
  for (const [x, y] of clicks) {
    points.push(await page.evaluate(([x, y]) => window.swarfView.surfaceAt(x, y)?.point, [x, y]));
    await page.mouse.click(x, y);
  }
  ok(points.every(Boolean), 'both clicks land on the stock');
  const m = await page.evaluate(() => window.swarfView.measurement());
  const want = distance(points[0], points[1]);
  ok(m.distance !== null && Math.abs(m.distance - want) < 1e-6, `two clicks measure ${m.distance?.toFixed(4)} mm (the points are ${want.toFixed(4)} mm apart)`);
  const text = await page.textContent('#measure');
  ok(text.includes(m.distance.toFixed(4)), `the panel shows it: ${text}`);
  await page.keyboard.press('m');
  ok(!(await page.evaluate(() => window.swarfView.measuring())), 'm again stops measuring');
}

export async function keyChecks(page, ok) {
  const keys = await page.$$eval('#keys dt', (d) => d.map((x) => x.textContent));
  ok(keys.length >= 6 && keys.includes('m'), `the page lists its shortcuts (${keys.join(', ')})`);
  const was = await page.evaluate(() => window.swarfView.visible('cuts'));
  await page.keyboard.press('c');
  const now = await page.evaluate(() => window.swarfView.visible('cuts'));
  const box = await page.isChecked('#layer-cuts');
  ok(now === !was && box === now, 'the c key toggles the cuts and their box');
  await page.keyboard.press('c');
  const whole = await pixels(page);
  await page.evaluate(() => window.swarfView.setMotion(Math.floor(window.swarfView.view.motions.count / 3)));
  const before = await pixels(page);
  await page.keyboard.press('u');
  const part = await pixels(page);
  ok(await page.isChecked('#upto') && part.sum !== before.sum && part.drawn < before.drawn, `the u key draws the path up to the cutter only (${before.drawn} -> ${part.drawn} pixels drawn)`);
  await page.keyboard.press('u');
  ok((await pixels(page)).sum === before.sum && whole.drawn > 0, 'u again draws it whole');
}

// A view of several operations: each shows its own path, stock and cutter.
export async function operationChecks(page, ok) {
  const ops = await page.evaluate(() => window.swarfView.operations);
  ok(ops.length > 1, `the view has ${ops.length} operations: ${ops.map((o) => o.name).join(', ')}`);
  const options = await page.$$eval('#operation option', (o) => o.length);
  ok(options === ops.length + 1, 'the panel offers each operation and the whole program');
  const all = await pixels(page);
  const seen = new Set([all.sum]);
  for (let k = 0; k < ops.length; k += 1) {
    await page.selectOption('#operation', String(k));
    const p = await pixels(page);
    ok(!seen.has(p.sum), `operation ${k + 1} (${ops[k].name}, ${ops[k].tool}) draws its own picture (stock ${ops[k].stock})`);
    seen.add(p.sum);
    const m = await page.evaluate(() => window.swarfView.motion);
    ok(m === ops[k].first_motion + 1, `and puts the cutter at its first motion (${m})`);
  }
  await page.selectOption('#operation', '-1');
}
