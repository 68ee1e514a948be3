// The 2D overlay over the 3D view: the axis triad (bottom right, turning with the
// camera), the scale bar (a round length at the target's depth) and the
// measurement (its points, the segment between them and its length).

import { COLOURS, css } from './colour.js';
import { transform } from './mat.js';

const TRIAD_PX = 42;

// The bar's length: the largest 1, 2 or 5 x 10^k mm that fits in `maxPx` pixels at
// `mmPerPx`.
export function scaleBarLength(mmPerPx, maxPx) {
  const most = mmPerPx * maxPx;
  const e = 10 ** Math.floor(Math.log10(most));
  return [5, 2, 1].map((m) => m * e).find((l) => l <= most) ?? e;
}

const mmText = (l) => `${l >= 1 ? String(Number(l.toPrecision(6))) : l.toPrecision(1)} mm`;

// The screen directions (x right, y down, pixels) of the world axes under `view`
// (a view matrix), TRIAD_PX long.
export function triadAxes(view) {
  return [0, 1, 2].map((k) => [view[k * 4] * TRIAD_PX, -view[k * 4 + 1] * TRIAD_PX, view[k * 4 + 2]]);
}

export class Overlay {
  constructor(canvas) {
    this.canvas = canvas;
    this.g = canvas.getContext('2d');
    this.triad = null;
    this.bar = null;
  }

  // Draws the overlay for `camera` over a view `w` x `h` CSS pixels; `measure` is
  // { points: [[x, y, z]...] } in the world.
  draw(camera, w, h, measure) {
    const ratio = window.devicePixelRatio || 1;
    const c = this.canvas;
    if (c.width !== Math.round(w * ratio) || c.height !== Math.round(h * ratio)) {
      c.width = Math.round(w * ratio);
      c.height = Math.round(h * ratio);
    }
    const g = this.g;
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, w, h);
    g.font = '12px system-ui, sans-serif';
    this.drawTriad(camera.view(), w - 72, h - 78);
    this.drawBar(camera.mmPerPixel(h), w - 160, h - 14);
    this.drawMeasure(camera.viewProj(), w, h, measure);
  }

  drawTriad(view, cx, cy) {
    const g = this.g;
    const axes = triadAxes(view);
    g.fillStyle = 'rgba(255, 255, 255, 0.8)';
    g.beginPath();
    g.arc(cx, cy, TRIAD_PX + 16, 0, 2 * Math.PI);
    g.fill();
    // Far axes first, so that the nearest is drawn over the others.
    const order = [0, 1, 2].sort((a, b) => axes[a][2] - axes[b][2]);
    for (const k of order) {
      const [dx, dy] = axes[k];
      g.strokeStyle = css(COLOURS.axes[k]);
      g.fillStyle = css(COLOURS.axes[k]);
      g.lineWidth = 3;
      g.beginPath();
      g.moveTo(cx, cy);
      g.lineTo(cx + dx, cy + dy);
      g.stroke();
      const l = Math.hypot(dx, dy) || 1;
      g.font = 'bold 13px system-ui, sans-serif';
      g.textAlign = 'center';
      g.textBaseline = 'middle';
      g.fillText('XYZ'[k], cx + dx + (dx / l) * 10, cy + dy + (dy / l) * 10);
    }
    this.triad = { centre: [cx, cy], axes };
  }

  drawBar(mmPerPx, right, y) {
    const g = this.g;
    const len = scaleBarLength(mmPerPx, 110);
    const px = len / mmPerPx;
    const x0 = right - px;
    g.fillStyle = 'rgba(255, 255, 255, 0.8)';
    g.fillRect(x0 - 6, y - 20, px + 12, 26);
    g.strokeStyle = '#222';
    g.lineWidth = 2;
    g.beginPath();
    g.moveTo(x0, y - 5);
    g.lineTo(x0, y);
    g.lineTo(right, y);
    g.lineTo(right, y - 5);
    g.stroke();
    g.fillStyle = '#222';
    g.font = '12px system-ui, sans-serif';
    g.textAlign = 'center';
    g.textBaseline = 'bottom';
    g.fillText(mmText(len), x0 + px / 2, y - 4);
    this.bar = { mm: len, px, text: mmText(len) };
  }

  drawMeasure(viewProj, w, h, measure) {
    const pts = measure?.points ?? [];
    if (pts.length === 0) return;
    const g = this.g;
    const screen = pts.map((p) => {
      const [x, y] = transform(viewProj, p);
      return [((x + 1) / 2) * w, ((1 - y) / 2) * h];
    });
    g.strokeStyle = css(COLOURS.measure);
    g.fillStyle = css(COLOURS.measure);
    g.lineWidth = 2;
    if (screen.length === 2) {
      g.beginPath();
      g.moveTo(...screen[0]);
      g.lineTo(...screen[1]);
      g.stroke();
      const d = Math.hypot(...pts[1].map((x, k) => x - pts[0][k]));
      const mid = [(screen[0][0] + screen[1][0]) / 2, (screen[0][1] + screen[1][1]) / 2];
      g.font = 'bold 13px system-ui, sans-serif';
      g.textAlign = 'left';
      g.textBaseline = 'bottom';
      g.fillStyle = 'rgba(255, 255, 255, 0.85)';
      const text = `${d.toFixed(3)} mm`;
      g.fillRect(mid[0] + 4, mid[1] - 18, g.measureText(text).width + 6, 17);
      g.fillStyle = css(COLOURS.measure);
      g.fillText(text, mid[0] + 7, mid[1] - 3);
    }
    for (const [x, y] of screen) {
      g.beginPath();
      g.arc(x, y, 4, 0, 2 * Math.PI);
      g.fill();
    }
  }
}
