// The side panel: the legend (a row per layer: toggle, colour, count), the
// operation, the motion slider with its G-code line, the stock's colour scale
// (neutral band, range inputs, out-of-range and unmeasured colours), the picked
// cell, the measurement and the keyboard shortcuts.

import { COLOURS, barLayout, css, gradient } from './colour.js';
import { SHORTCUTS } from './keys.js';

const $ = (id) => document.getElementById(id);
const fmt = (x) => (x == null ? '-' : `${x >= 0 ? '+' : ''}${x.toFixed(4)} mm`);
const el = (tag, props = {}, ...kids) => {
  const e = Object.assign(document.createElement(tag), props);
  e.append(...kids);
  return e;
};
export const layerId = (name) => `layer-${name.replace(/ /g, '-')}`;

const LAYER_TEXT = {
  part: 'part (design)',
  stock: 'stock, by deviation (scale below)',
  cuts: 'cuts',
  links: 'links',
  rapids: 'rapids',
  'tool axes': 'tool axes',
  cutter: 'cutter',
  origin: 'origin',
};

function swatch(name, api) {
  const s = el('span', { className: 'swatch' });
  if (name === 'stock') s.style.background = gradient(api.scale());
  else if (name === 'origin') s.style.background = `linear-gradient(to right, ${COLOURS.axes.map(css).join(', ')})`;
  else s.style.background = css(api.layerColour(name));
  if (['cuts', 'links', 'rapids', 'tool axes'].includes(name)) s.classList.add('line');
  return s;
}

function buildLegend(view, api) {
  const legend = $('legend');
  for (const name of api.layers()) {
    const box = el('input', { type: 'checkbox', id: layerId(name), checked: api.visible(name) });
    box.dataset.layer = name;
    box.addEventListener('change', () => api.setVisible(name, box.checked));
    const row = el('label', { className: name === 'stock' ? 'layer wide' : 'layer' }, box, swatch(name, api), ` ${LAYER_TEXT[name] ?? name}`);
    row.title = `${name}: ${api.layerCount(name)}`;
    row.dataset.layer = name;
    legend.append(row);
  }
  document.addEventListener('swarf-layers', () => {
    for (const box of legend.querySelectorAll('input')) box.checked = api.visible(box.dataset.layer);
  });
}

function buildOperations(view, api) {
  const ops = api.operations;
  const select = $('operation');
  if (ops.length < 2) {
    $('operations').hidden = true;
    return;
  }
  select.append(el('option', { value: '-1', textContent: `all ${ops.length} operations (final stock)` }));
  ops.forEach((o, k) => select.append(el('option', { value: String(k), textContent: `${k + 1}. ${o.name} (${o.tool}): path and stock after it` })));
  select.addEventListener('change', () => api.setOperation(Number(select.value)));
  document.addEventListener('swarf-operation', (e) => {
    select.value = String(e.detail);
  });
}

function buildMotion(view, api) {
  const slider = $('motion');
  slider.max = String(view.motions.count);
  $('motion-count').textContent = String(view.motions.count);
  slider.addEventListener('input', () => api.setMotion(Number(slider.value)));
  const upTo = $('upto');
  upTo.addEventListener('change', () => api.setUpTo(upTo.checked));
  document.addEventListener('swarf-upto', (e) => {
    upTo.checked = e.detail;
  });
  document.addEventListener('swarf-motion', (e) => {
    const pose = e.detail;
    slider.value = String(pose.index);
    $('motion-index').textContent = String(pose.index);
    const op = api.operations.length > 1 ? ` [${api.operations[pose.operation].name}]` : '';
    $('gcode-line').textContent = pose.line ? `N${pose.line}: ${view.source[pose.line - 1] ?? ''}${op}` : 'start';
  });
}

// Places tick `id` at `x` (a fraction of the bar's width).
function tick(id, x, text) {
  const t = $(id);
  t.style.left = `${100 * x}%`;
  t.textContent = text;
}

function showScale(view, scale) {
  $('ramp').style.background = gradient(scale);
  const n = (x) => String(Number(x.toPrecision(3)));
  const [a, b] = barLayout(scale).band;
  tick('tick-lo', 0, n(scale.lo));
  tick('tick-neg', a, '');
  tick('tick-pos', b, '');
  tick('tick-hi', 1, `+${n(scale.hi)}`);
  const band = $('tick-band');
  band.style.left = `${100 * a}%`;
  band.style.width = `${100 * (b - a)}%`;
  band.textContent = `\u00b1${n(scale.tol)}`;
  $('range-lo').value = n(scale.lo);
  $('range-hi').value = n(scale.hi);
  for (const [id, count] of [['gougeBeyond', scale.beyond?.below], ['excessBeyond', scale.beyond?.above]]) {
    const label = $(`key-${id}`);
    if (label) label.textContent = ` ${label.dataset.text}${count ? ` (${count})` : ''}`;
  }
  const swatch = document.querySelector('.layer[data-layer="stock"] .swatch');
  if (swatch) swatch.style.background = gradient(scale);
}

function buildScale(view, api) {
  const d = view.deviation;
  const key = [
    ['gougeBeyond', 'below the range'],
    ['excessBeyond', 'above the range'],
    ['unmeasured', 'no stock measured'],
    ['offPart', 'off the part'],
  ];
  for (const [c, text] of key) {
    const label = el('span', { id: `key-${c}` }, ` ${text}`);
    label.dataset.text = text;
    $('scale-key').append(el('span', { className: 'key' }, el('span', { className: 'swatch', style: `background: ${css(COLOURS[c])}` }), label));
  }
  $('scale-note').textContent = `${d.mode} deviation, mm: red below the design (gouge), blue material left, ` +
    `grey within the tolerance \u00b1${d.tolerance_mm} mm (its band drawn wider than to scale); ` +
    'the range ends at the 98th percentile of each side unless set';
  const apply = () => api.setRange(Number($('range-lo').value), Number($('range-hi').value));
  $('range-lo').addEventListener('change', apply);
  $('range-hi').addEventListener('change', apply);
  $('range-auto').addEventListener('click', () => api.setRange(null, null));
  document.addEventListener('swarf-scale', (e) => showScale(view, e.detail));
  showScale(view, api.scale());
}

export function buildPanel(view, api) {
  $('title').textContent = `swarf view: ${view.program.split('/').pop()} (${view.tool})`;
  buildLegend(view, api);
  buildOperations(view, api);
  buildMotion(view, api);
  if (api.layers().includes('stock')) buildScale(view, api);
  else $('scale').hidden = true;
  const s = view.stock;
  if (s) $('mesh-note').textContent = `stock mesh: every ${s.stride} cell(s), height error \u2264 ${s.height_error.toFixed(4)} mm`;
  $('measure-button').addEventListener('click', () => api.setMeasuring(!api.measuring()));
  const keys = $('keys');
  for (const [k, what] of SHORTCUTS) keys.append(el('dt', { textContent: k }), el('dd', { textContent: what }));
}

export function showPick(p) {
  $('pick').textContent = p
    ? `cell ${p.cell[0]}, ${p.cell[1]}: ${p.state === 'measured' ? fmt(p.deviation) : p.state}\n` +
      (p.line ? `last cut by line ${p.line}: ${p.text}` : 'not cut')
    : 'no stock there';
}

export function showMeasure(m, on) {
  $('measure-button').textContent = on ? 'stop measuring (m)' : 'measure (m)';
  $('measure').textContent = m.distance != null
    ? `distance ${m.distance.toFixed(4)} mm (dx ${(m.points[1][0] - m.points[0][0]).toFixed(3)}, dy ${(m.points[1][1] - m.points[0][1]).toFixed(3)}, dz ${(m.points[1][2] - m.points[0][2]).toFixed(3)})`
    : on ? `click ${2 - m.points.length} point(s) on the stock or the part` : '';
}
