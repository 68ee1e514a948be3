// The side panel: layer toggles, the motion slider with its G-code line, the
// deviation scale and the picked cell.
const $ = (id) => document.getElementById(id);
const fmt = (x) => (x == null ? '-' : `${x >= 0 ? '+' : ''}${x.toFixed(4)} mm`);

export function buildPanel(view, api) {
  $('title').textContent = `swarf view: ${view.program.split('/').pop()} (${view.tool})`;
  const layers = $('layers');
  for (const name of api.layers()) {
    const label = document.createElement('label');
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = api.visible(name);
    box.id = `layer-${name}`;
    box.addEventListener('change', () => api.setVisible(name, box.checked));
    label.append(box, ` ${name.replace('_', ' ')}`);
    layers.append(label);
  }
  const slider = $('motion');
  slider.max = String(view.motions.count);
  $('motion-count').textContent = String(view.motions.count);
  slider.addEventListener('input', () => api.setMotion(Number(slider.value)));
  document.addEventListener('swarf-motion', (e) => {
    const pose = e.detail;
    slider.value = String(pose.index);
    $('motion-index').textContent = String(pose.index);
    $('gcode-line').textContent = pose.line ? `N${pose.line}: ${view.source[pose.line - 1] ?? ''}` : 'start';
  });
  const stock = view.stock;
  const stops = [...view.deviation.ramp].reverse().map(([t, [r, g, b]]) => `rgb(${r},${g},${b}) ${((1 - t) / 2) * 100}%`);
  $('ramp').style.background = `linear-gradient(to right, ${stops.join(', ')})`;
  $('tick-below').textContent = fmt(stock.scale_above);
  $('tick-above').textContent = fmt(stock.scale_below);
  $('scale-note').textContent = `${view.deviation.mode} deviation: blue material left, red below the design; ` +
    `tol ${view.deviation.tolerance_mm} mm; stock mesh every ${stock.stride} cell(s), height error <= ${stock.height_error.toFixed(4)} mm`;
}

export function showPick(p) {
  $('pick').textContent = p
    ? `cell ${p.cell[0]}, ${p.cell[1]}: ${p.state === 'measured' ? fmt(p.deviation) : p.state}\n` +
      (p.line ? `last cut by line ${p.line}: ${p.text}` : 'not cut')
    : 'no stock there';
}
