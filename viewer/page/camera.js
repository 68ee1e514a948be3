// The orbit camera (+z up): it looks at a target from a distance, turned by an
// azimuth about +z and raised by an elevation; left drag orbits, right drag (or
// shift + left drag) pans, the wheel zooms towards the point under the cursor.

import { add, cross, lookAt, multiply, normalize, perspective, scale, sub } from './mat.js';

const FOV = (35 * Math.PI) / 180;
const MAX_ELEVATION = Math.PI / 2 - 1e-4;

export class OrbitCamera {
  constructor() {
    this.target = [0, 0, 0];
    this.distance = 100;
    this.azimuth = -Math.PI / 2 - 0.35;
    this.elevation = 0.6;
    this.fov = FOV;
    this.aspect = 1;
    this.size = 100;
  }

  // Unit vector from the target towards the eye.
  back() {
    const c = Math.cos(this.elevation);
    return [c * Math.cos(this.azimuth), c * Math.sin(this.azimuth), Math.sin(this.elevation)];
  }

  // The screen's up direction in the world (robust looking straight down).
  up() {
    const s = Math.sin(this.elevation);
    return [-s * Math.cos(this.azimuth), -s * Math.sin(this.azimuth), Math.cos(this.elevation)];
  }

  eye() {
    return add(this.target, scale(this.back(), this.distance));
  }

  view() {
    return lookAt(this.eye(), this.target, this.up());
  }

  projection() {
    const near = Math.max(this.distance - 2 * this.size, this.distance / 1000, 1e-3);
    return perspective(this.fov, this.aspect, near, this.distance + 4 * this.size);
  }

  viewProj() {
    return multiply(this.projection(), this.view());
  }

  // Millimetres per CSS pixel at the target's depth, for a canvas `height` px high.
  mmPerPixel(height) {
    return (2 * this.distance * Math.tan(this.fov / 2)) / Math.max(height, 1);
  }

  // Frames the box [lo, hi] from the front, above and to the left, in the part of
  // a view `width` x `height` px right of its first `left` px (the panel).
  frame([lo, hi], { width, height, left }) {
    this.target = lo.map((x, k) => (x + hi[k]) / 2);
    this.size = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    this.azimuth = -Math.PI / 2 - 0.35;
    this.elevation = 0.65;
    const free = Math.max(width - left, width / 2);
    this.distance = (0.48 * this.size) / Math.tan(this.fov / 2) / Math.min(1, free / Math.max(height, 1));
    this.pan((width - free) / 2, 0, height);
  }

  // Looks straight down at `at` with `width` mm across the view.
  lookDown(at, width) {
    this.target = at;
    this.azimuth = -Math.PI / 2;
    this.elevation = MAX_ELEVATION;
    this.distance = width / 2 / Math.tan(this.fov / 2) / this.aspect;
  }

  // Turns the view to `azimuth`, `elevation` (radians) about the target.
  turnTo(azimuth, elevation) {
    this.azimuth = azimuth;
    this.elevation = Math.max(-MAX_ELEVATION, Math.min(MAX_ELEVATION, elevation));
  }

  // Moves the target by (dx, dy) CSS pixels of a canvas `height` px high.
  pan(dx, dy, height) {
    const k = this.mmPerPixel(height);
    const right = normalize(cross(this.up(), this.back()));
    this.target = add(this.target, add(scale(right, -dx * k), scale(this.up(), dy * k)));
  }

  // Zooms by `factor` (< 1: closer) keeping the world point `at` (if given) under
  // the cursor.
  zoom(factor, at) {
    const d = Math.max(this.distance * factor, this.size * 1e-4);
    if (at) this.target = add(at, scale(sub(this.target, at), d / this.distance));
    this.distance = d;
  }
}

// Mouse input on `canvas`: drags turn and pan `camera`, the wheel zooms; `changed`
// runs after each change; `pointAt(x, y)` gives the world point under a client
// position (or null) for zooming towards it. A click that did not drag calls
// `click(event)`.
export function attachControls(canvas, camera, { changed, pointAt, click }) {
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY, moved: 0, pan: e.button === 2 || e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const [dx, dy] = [e.clientX - drag.x, e.clientY - drag.y];
    drag.moved += Math.abs(dx) + Math.abs(dy);
    [drag.x, drag.y] = [e.clientX, e.clientY];
    if (drag.pan) camera.pan(dx, dy, canvas.clientHeight);
    else camera.turnTo(camera.azimuth - dx * 0.008, camera.elevation + dy * 0.008);
    changed();
  });
  canvas.addEventListener('pointerup', (e) => {
    const d = drag;
    drag = null;
    if (d && d.moved < 4 && e.button === 0) click(e);
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    camera.zoom(Math.exp(e.deltaY * 0.0015), pointAt(e.clientX, e.clientY));
    changed();
  }, { passive: false });
}
