// swarf's viewer page: loads view.json and the GLB files of a view folder (written
// by `swarf view` or `swarf demo`), draws them with WebGL2 (orbit, pan, zoom),
// and exposes window.swarfView for scripts and tests. Dependency-free ES modules:
// these files are the page, embedded in the swarf binary as they are.

import { OrbitCamera, attachControls } from './camera.js';
import { cellColour, countBeyond, robustRange } from './colour.js';
import { Renderer } from './gl.js';
import { poseMatrix, transform } from './mat.js';
import { cutterPose, motionOfLine } from './motions.js';
import { Overlay } from './overlay.js';
import { buildPanel, showMeasure, showPick } from './panel.js';
import { intersect, nearestVertex, rayAt } from './pick.js';
import { loadScene } from './scene.js';
import { attachKeys } from './keys.js';

const canvas = document.getElementById('view');
const STATES = ['measured', 'no stock measured', 'off the part'];
const LIGHT = (() => {
  const l = [0.35, -0.45, 1];
  const n = Math.hypot(...l);
  return l.map((x) => x / n);
})();

async function main() {
  const res = await fetch('view.json');
  if (!res.ok) throw new Error(`view.json: ${res.status} ${res.statusText}`);
  const view = await res.json();
  const renderer = new Renderer(canvas);
  const scene = await loadScene(view, renderer);
  const camera = new OrbitCamera();
  const overlay = new Overlay(document.getElementById('overlay'));
  const api = makeApi(view, scene, renderer, camera, overlay);
  resize(camera);
  camera.frame(scene.bounds, freeView());
  buildPanel(view, api);
  attachControls(canvas, camera, {
    changed: api.render,
    pointAt: (x, y) => api.surfaceAt(x, y)?.point ?? null,
    click: (e) => api.clicked(e.clientX, e.clientY),
  });
  attachKeys(api);
  window.addEventListener('resize', () => api.render());
  api.setMotion(0);
  window.swarfView = api;
  api.render();
  api.ready = true;
}

// The view's size and the width the panel covers on its left (CSS pixels).
function freeView() {
  const panel = document.getElementById('panel').getBoundingClientRect();
  return { width: canvas.clientWidth, height: canvas.clientHeight, left: panel.right + 8 };
}

// Sizes the canvas to its box (device pixels); the camera's aspect.
function resize(camera) {
  const ratio = window.devicePixelRatio || 1;
  const [w, h] = [canvas.clientWidth, canvas.clientHeight];
  if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
    canvas.width = Math.round(w * ratio);
    canvas.height = Math.round(h * ratio);
  }
  camera.aspect = w / Math.max(h, 1);
}

function makeApi(view, scene, renderer, camera, overlay) {
  const { layers, stocks, cutters, ops } = scene;
  const last = stocks.at(-1);
  const tol = view.deviation.tolerance_mm;
  const shown = Object.fromEntries(Object.keys(layers).map((k) => [k, true]));
  // The stock lies on the design, a scallop above it: the design shows when the stock is hidden.
  if (last) shown.part = false;
  const state = {
    operation: -1,
    motion: 0,
    scale: last ? robustRange(last.dev, last.state, tol) : { lo: -2 * tol, hi: 2 * tol, tol },
    measuring: false,
    points: [],
    upTo: false,
  };
  const opIndex = () => (state.operation >= 0 ? state.operation : ops.length - 1);
  const opOfMotion = (k) => {
    const i = ops.findIndex((o) => k > o.first_motion && k <= o.first_motion + o.motions);
    return i >= 0 ? i : k === 0 ? 0 : ops.length - 1;
  };
  const stock = () => stocks[opIndex()] ?? null;
  // The motions whose path is drawn: the operation's (all without one), up to the
  // cutter's when asked.
  const motionRange = () => {
    const o = ops[state.operation];
    const [a, b] = o ? [o.first_motion, o.first_motion + o.motions - 1] : [-Infinity, Infinity];
    return [a, state.upTo ? Math.min(b, state.motion - 1) : b];
  };
  const items = () => {
    const out = [];
    for (const [name, layer] of Object.entries(layers)) {
      for (const it of layer.items) {
        it.visible = shown[name];
        if (it.kind === 'line' && it.hasMotion) it.range = motionRange();
        out.push(it);
      }
    }
    const s = stock();
    for (const x of stocks) if (x) x.item.visible = shown.stock && x === s;
    const c = cutters[opOfMotion(state.motion)];
    for (const x of cutters) if (x) x.visible = shown.cutter && x === c;
    return out;
  };
  const rect = () => canvas.getBoundingClientRect();
  const ndc = (clientX, clientY) => {
    const r = rect();
    return [((clientX - r.left) / r.width) * 2 - 1, -(((clientY - r.top) / r.height) * 2 - 1)];
  };

  const api = {
    ready: false,
    view,
    operations: ops,
    layers: () => Object.keys(layers),
    layerColour: (name) => layers[name]?.colour ?? null,
    layerCount: (name) => layers[name]?.count ?? 0,
    visible: (name) => Boolean(shown[name]),
    setVisible(name, on) {
      if (name in shown) shown[name] = on;
      document.dispatchEvent(new CustomEvent('swarf-layers'));
      api.render();
    },
    render() {
      resize(camera);
      renderer.draw(items(), camera.viewProj(), state.scale, LIGHT);
      overlay.draw(camera, canvas.clientWidth, canvas.clientHeight, { points: state.points });
    },
    motion: 0,
    setMotion(k) {
      const pose = cutterPose(view.motions, k);
      state.motion = pose.index;
      api.motion = pose.index;
      api.cutterPose = pose;
      for (const c of cutters) if (c) c.model = poseMatrix(pose.position, pose.axis);
      api.render();
      document.dispatchEvent(new CustomEvent('swarf-motion', { detail: { ...pose, operation: opOfMotion(pose.index) } }));
      return pose;
    },
    motionOfLine: (line) => motionOfLine(view.motions, line),
    cutter: () => ({ position: api.cutterPose.position, axis: api.cutterPose.axis }),
    operation: () => state.operation,
    upTo: () => state.upTo,
    // Draws the path only up to the cutter (true) or whole.
    setUpTo(on) {
      state.upTo = on;
      document.dispatchEvent(new CustomEvent('swarf-upto', { detail: on }));
      api.render();
    },
    // Shows operation k's path and the stock after it (-1: the whole program).
    setOperation(k) {
      state.operation = Math.max(-1, Math.min(ops.length - 1, k));
      const s = stock();
      if (s) state.scale = robustRange(s.dev, s.state, tol);
      if (state.operation >= 0) api.setMotion(ops[state.operation].first_motion + 1);
      document.dispatchEvent(new CustomEvent('swarf-operation', { detail: state.operation }));
      document.dispatchEvent(new CustomEvent('swarf-scale', { detail: state.scale }));
      api.render();
    },
    scale: () => ({ ...state.scale }),
    // The colour range [lo, hi] mm (lo below -tol, hi above tol); null for the robust one.
    setRange(lo, hi) {
      const s = stock();
      if (lo == null || hi == null) state.scale = s ? robustRange(s.dev, s.state, tol) : state.scale;
      else {
        const [l, h] = [Math.min(lo, -tol * 1.001), Math.max(hi, tol * 1.001)];
        state.scale = { lo: l, hi: h, tol, beyond: s ? countBeyond(s.dev, s.state, l, h) : null };
      }
      document.dispatchEvent(new CustomEvent('swarf-scale', { detail: state.scale }));
      api.render();
    },
    colourOf: (d, st = 0) => cellColour(d, st, state.scale),
    // Screen position (CSS pixels) of a world point.
    project(x, y, z) {
      const p = transform(camera.viewProj(), [x, y, z]);
      const r = rect();
      return { x: r.left + ((p[0] + 1) / 2) * r.width, y: r.top + ((1 - p[1]) / 2) * r.height };
    },
    // The stock cell under a screen position: its deviation and the line that last cut it.
    pick(clientX, clientY) {
      const s = stock();
      if (!s || !shown.stock) return null;
      const hit = intersect(rayAt(camera.viewProj(), ...ndc(clientX, clientY)), s.pos, s.indices);
      if (!hit) return null;
      const v = nearestVertex(hit);
      const line = s.line[v];
      const st = STATES[s.state[v]];
      return {
        point: hit.point,
        cell: [s.cell[2 * v], s.cell[2 * v + 1]],
        deviation: st === 'measured' ? s.dev[v] : null,
        line: line >= 0 ? line : null,
        text: line >= 0 ? view.source[line - 1] ?? '' : '',
        state: st,
        operation: state.operation,
      };
    },
    // The nearest visible surface point (stock, else part) under a screen position.
    surfaceAt(clientX, clientY) {
      const ray = rayAt(camera.viewProj(), ...ndc(clientX, clientY));
      const hits = [];
      const s = stock();
      if (s && shown.stock) hits.push(intersect(ray, s.pos, s.indices));
      if (layers.part && shown.part) hits.push(intersect(ray, layers.part.pos, layers.part.indices));
      return hits.filter(Boolean).sort((a, b) => a.t - b.t)[0] ?? null;
    },
    measuring: () => state.measuring,
    setMeasuring(on) {
      state.measuring = on;
      state.points = [];
      showMeasure(api.measurement(), on);
      api.render();
    },
    // Adds the surface point under a screen position to the measurement.
    measureAt(clientX, clientY) {
      const hit = api.surfaceAt(clientX, clientY);
      if (!hit) return null;
      if (state.points.length >= 2) state.points = [];
      state.points.push(hit.point);
      showMeasure(api.measurement(), state.measuring);
      api.render();
      return hit.point;
    },
    measurement() {
      const [a, b] = state.points;
      return { points: state.points.map((p) => [...p]), distance: b ? Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) : null };
    },
    clicked(clientX, clientY) {
      if (state.measuring) api.measureAt(clientX, clientY);
      else showPick(api.pick(clientX, clientY));
    },
    // Looks straight down at (x, y) with `width` mm across the view.
    lookDown(x, y, width) {
      camera.lookDown([x, y, scene.bounds[1][2]], width);
      api.render();
    },
    // Named views: 'top', 'front', 'right', 'iso' (the framing one).
    viewFrom(name) {
      const turns = { top: [-Math.PI / 2, Math.PI / 2], front: [-Math.PI / 2, 0], right: [0, 0] };
      if (name === 'iso') camera.frame(scene.bounds, freeView());
      else if (turns[name]) camera.turnTo(...turns[name]);
      api.render();
    },
    // The arrays of the stock shown (for scripts: positions, deviations, states, cells).
    stockArrays() {
      const s = stock();
      return s && { pos: s.pos, dev: s.dev, state: s.state, cell: s.cell };
    },
    // Turns the view to an azimuth and elevation (degrees; azimuth -90: from the front).
    turn(azimuthDeg, elevationDeg) {
      camera.turnTo((azimuthDeg * Math.PI) / 180, (elevationDeg * Math.PI) / 180);
      api.render();
    },
    // Zooms by `factor` (< 1: closer) about the target.
    zoom(factor) {
      camera.zoom(factor, null);
      api.render();
    },
    triad: () => overlay.triad,
    scaleBar: () => overlay.bar,
  };
  return api;
}

main().catch((e) => {
  document.getElementById('title').textContent = `swarf view: ${e.message}`;
  window.swarfView = { ready: false, error: String(e) };
});
