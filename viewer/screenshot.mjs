// A screenshot of a view folder's page, for the docs.
// Usage: node screenshot.mjs VIEW_DIR OUT.png [--hide LAYER,...] [--show LAYER,...] [--motion K] [--size WxH]
import { openView } from './test/page.mjs';

const [dir, out, ...rest] = process.argv.slice(2);
if (!dir || !out) {
  console.error('usage: node screenshot.mjs VIEW_DIR OUT.png [--hide LAYER,...] [--show LAYER,...] [--motion K] [--size WxH]');
  process.exit(2);
}
const flag = (name) => {
  const k = rest.indexOf(name);
  return k >= 0 ? rest[k + 1] : undefined;
};
const [width, height] = (flag('--size') ?? '1100x700').split('x').map(Number);
const { page, close } = await openView(dir, { width, height });
try {
  for (const [name, on] of [['--hide', false], ['--show', true]]) {
    for (const layer of (flag(name) ?? '').split(',').filter(Boolean)) {
      await page.evaluate(([n, v]) => window.swarfView.setVisible(n, v), [layer, on]);
    }
  }
  for (const box of await page.$$('#layers input')) {
    await box.evaluate((b) => { b.checked = window.swarfView.visible(b.id.slice(6)); });
  }
  const motion = flag('--motion');
  if (motion) await page.evaluate((k) => window.swarfView.setMotion(k), Number(motion));
  await page.screenshot({ path: out });
  console.log(`screenshot: ${out}`);
} finally {
  await close();
}
