// A screenshot of a view folder's page, for the docs.
// Usage: node screenshot.mjs VIEW_DIR OUT.png [--hide LAYER,...] [--show LAYER,...]
//   [--motion K] [--operation K] [--range LO,HI] [--view top|front|right|iso]
//   [--turn AZIMUTH_DEG,ELEVATION_DEG] [--zoom F] [--measure U1,V1,U2,V2] [--size WxH]
// (--measure: two points as fractions of the canvas's width and height).
import { openView } from './test/page.mjs';

const [dir, out, ...rest] = process.argv.slice(2);
if (!dir || !out) {
  console.error('usage: node screenshot.mjs VIEW_DIR OUT.png [--hide LAYER,...] [--show LAYER,...] [--motion K] [--operation K] [--range LO,HI] [--view NAME] [--turn AZ,EL] [--zoom F] [--measure U1,V1,U2,V2] [--size WxH]');
  process.exit(2);
}
const flag = (name) => {
  const k = rest.indexOf(name);
  return k >= 0 ? rest[k + 1] : undefined;
};
const numbers = (name) => flag(name)?.split(',').map(Number);
const [width, height] = (flag('--size') ?? '1100x700').split('x').map(Number);
const { page, close } = await openView(dir, { width, height });
const api = (f, arg) => page.evaluate(f, arg);
try {
  for (const [name, on] of [['--hide', false], ['--show', true]]) {
    for (const layer of (flag(name) ?? '').split(',').filter(Boolean)) {
      await api(([n, v]) => window.swarfView.setVisible(n, v), [layer, on]);
    }
  }
  if (flag('--operation')) await api((k) => window.swarfView.setOperation(k), Number(flag('--operation')));
  if (flag('--motion')) await api((k) => window.swarfView.setMotion(k), Number(flag('--motion')));
  if (flag('--range')) await api(([lo, hi]) => window.swarfView.setRange(lo, hi), numbers('--range'));
  if (flag('--view')) await api((v) => window.swarfView.viewFrom(v), flag('--view'));
  if (flag('--turn')) await api(([a, e]) => window.swarfView.turn(a, e), numbers('--turn'));
  if (flag('--zoom')) await api((f) => window.swarfView.zoom(f), Number(flag('--zoom')));
  const m = numbers('--measure');
  if (m) {
    const box = await page.$eval('#view', (c) => c.getBoundingClientRect().toJSON());
    await api(() => window.swarfView.setMeasuring(true));
    for (const [u, v] of [[m[0], m[1]], [m[2], m[3]]]) {
      const p = await api(([x, y]) => window.swarfView.measureAt(x, y), [box.left + u * box.width, box.top + v * box.height]);
      if (!p) console.error(`--measure: nothing under ${u}, ${v}`);
    }
  }
  await page.screenshot({ path: out });
  console.log(`screenshot: ${out}`);
} finally {
  await close();
}
