// swarf's viewer page: loads view.json and the GLB files of a view folder (written by
// `swarf view` or `swarf demo`), shows them with orbit, pan and zoom, and exposes
// window.swarfView for scripts and tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { buildPanel, showPick } from './panel.js';
import { cutterPose, motionOfLine } from './motions.js';

const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f5f7);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8890a0, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
sun.position.set(1, -2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1e5);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, canvas);
controls.addEventListener('change', render);

function render() {
  const w = canvas.clientWidth;
  const h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
  renderer.render(scene, camera);
}
window.addEventListener('resize', render);

async function loadGlb(url) {
  const gltf = await new GLTFLoader().loadAsync(url);
  return gltf.scene;
}

// Frames the camera on `box` from the front, above and to the left.
function frame(box) {
  const centre = box.getCenter(new THREE.Vector3());
  const size = box.getSize(new THREE.Vector3()).length();
  camera.near = size / 1000;
  camera.far = size * 20;
  camera.position.copy(centre).add(new THREE.Vector3(-0.35, -1.0, 0.8).normalize().multiplyScalar(size * 1.25));
  controls.target.copy(centre);
  camera.updateProjectionMatrix();
  controls.update();
}

async function main() {
  const view = await (await fetch('view.json')).json();
  const files = view.files;
  const [part, toolpath, cutter, stock] = await Promise.all(
    [files.part, files.toolpath, files.cutter, files.stock].map(loadGlb),
  );
  const layers = {};
  for (const root of [part, toolpath, stock]) {
    scene.add(root);
    root.traverse((o) => {
      if (o.name && !layers[o.name] && (o.isMesh || o.isLineSegments || o.children.length)) layers[o.name] = o;
    });
  }
  for (const name of ['part', 'stock', 'cuts', 'links', 'rapids', 'tool axes']) {
    if (!layers[name]) layers[name] = scene.getObjectByName(name);
  }
  const stockMesh = stock.getObjectByName('stock');
  if (stockMesh && stockMesh.isMesh) {
    stockMesh.material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
  }
  const tool = cutter.getObjectByName('cutter');
  scene.add(cutter);
  // The stock lies on the design, a scallop above it: the design shows when the stock is hidden.
  if (layers.part) layers.part.visible = !(stockMesh && stockMesh.isMesh);
  frame(new THREE.Box3().setFromObject(stockMesh && stockMesh.isMesh ? stockMesh : part));
  const api = makeApi(view, layers, tool, stockMesh);
  buildPanel(view, api);
  api.setMotion(0);
  window.swarfView = api;
  render();
  api.ready = true;
}

function makeApi(view, layers, tool, stockMesh) {
  const raycaster = new THREE.Raycaster();
  const api = {
    ready: false,
    view,
    layers: () => Object.keys(layers).filter((k) => layers[k]),
    visible: (name) => Boolean(layers[name] && layers[name].visible),
    setVisible(name, on) {
      if (layers[name]) layers[name].visible = on;
      render();
    },
    motion: 0,
    setMotion(k) {
      const pose = cutterPose(view.motions, k);
      api.motion = pose.index;
      tool.position.set(...pose.position);
      tool.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...pose.axis).normalize());
      render();
      document.dispatchEvent(new CustomEvent('swarf-motion', { detail: pose }));
      return pose;
    },
    motionOfLine: (line) => motionOfLine(view.motions, line),
    cutter: () => {
      tool.updateMatrixWorld();
      const axis = new THREE.Vector3(0, 0, 1).applyQuaternion(tool.quaternion);
      return { position: tool.position.toArray(), axis: axis.toArray() };
    },
    // Screen position (CSS pixels in the canvas) of a world point.
    project(x, y, z) {
      const p = new THREE.Vector3(x, y, z).project(camera);
      const r = canvas.getBoundingClientRect();
      return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
    },
    // The stock cell under a screen position: its deviation and the line that last cut it.
    pick(clientX, clientY) {
      if (!stockMesh || !stockMesh.isMesh || !stockMesh.visible) return null;
      const r = canvas.getBoundingClientRect();
      const ndc = new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
      raycaster.setFromCamera(ndc, camera);
      const hit = raycaster.intersectObject(stockMesh, false)[0];
      if (!hit) return null;
      const g = stockMesh.geometry;
      const pos = g.attributes.position;
      const p = hit.point.clone();
      stockMesh.worldToLocal(p);
      let best = hit.face.a;
      let dist = Infinity;
      for (const v of [hit.face.a, hit.face.b, hit.face.c]) {
        const d = new THREE.Vector3().fromBufferAttribute(pos, v).distanceToSquared(p);
        if (d < dist) [best, dist] = [v, d];
      }
      const cell = g.attributes._cell;
      const line = g.attributes._line.getX(best);
      const state = ['measured', 'no stock measured', 'off the part'][g.attributes._state.getX(best)];
      return {
        point: hit.point.toArray(),
        cell: [cell.getX(best), cell.getY(best)],
        deviation: state === 'measured' ? g.attributes._deviation.getX(best) : null,
        line: line >= 0 ? line : null,
        text: line >= 0 ? view.source[line - 1] ?? '' : '',
        state,
      };
    },
    // Looks straight down at (x, y) with `width` mm across the view.
    lookDown(x, y, width) {
      const box = new THREE.Box3().setFromObject(scene);
      const top = box.max.z;
      const d = width / 2 / Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) / camera.aspect;
      camera.position.set(x, y - d * 1e-4, top + d);
      controls.target.set(x, y, top);
      controls.update();
      render();
    },
    render,
  };
  canvas.addEventListener('click', (e) => showPick(api.pick(e.clientX, e.clientY)));
  return api;
}

main().catch((e) => {
  document.getElementById('title').textContent = `swarf view: ${e.message}`;
  window.swarfView = { ready: false, error: String(e) };
});
