// Keyboard shortcuts: one table drives both the handler and the list in the page.

// [keys as shown, what they do, action(api, event)].
export const SHORTCUTS = [
  ['0', 'frame the whole view', (api) => api.viewFrom('iso')],
  ['1 / 2 / 3', 'view from the top / front / right', null],
  ['m', 'measure: click two points (again: stop)', (api) => api.setMeasuring(!api.measuring())],
  ['Esc', 'clear the measurement', (api) => api.setMeasuring(false)],
  ['\u2190 / \u2192', 'previous / next motion (shift: 100)', null],
  ['Home / End', 'start / end of the program', null],
  ['u', 'path up to the cutter / whole', (api) => api.setUpTo(!api.upTo())],
  ['[ / ]', 'previous / next operation', null],
  ['s p c l r a k o', 'toggle stock, part, cuts, links, rapids, tool axes, cutter, origin', null],
];

const LAYER_KEYS = { s: 'stock', p: 'part', c: 'cuts', l: 'links', r: 'rapids', a: 'tool axes', k: 'cutter', o: 'origin' };
const VIEW_KEYS = { 1: 'top', 2: 'front', 3: 'right' };

// What key `e` does to `api`; false when it does nothing.
function act(api, e) {
  const k = e.key;
  const plain = SHORTCUTS.find(([keys, , f]) => f && keys === (k === 'Escape' ? 'Esc' : k));
  if (plain) return plain[2](api, e) ?? true;
  if (VIEW_KEYS[k]) return api.viewFrom(VIEW_KEYS[k]) ?? true;
  if (LAYER_KEYS[k] && api.layers().includes(LAYER_KEYS[k])) {
    api.setVisible(LAYER_KEYS[k], !api.visible(LAYER_KEYS[k]));
    return true;
  }
  const count = api.view.motions.count;
  const step = e.shiftKey ? 100 : 1;
  const moves = { ArrowLeft: api.motion - step, ArrowRight: api.motion + step, Home: 0, End: count };
  if (k in moves) return api.setMotion(moves[k]) && true;
  const n = api.operations.length;
  if ((k === '[' || k === ']') && n > 1) {
    const next = api.operation() + (k === ']' ? 1 : -1);
    api.setOperation(next < -1 ? n - 1 : next >= n ? -1 : next);
    return true;
  }
  return false;
}

// Listens for the shortcuts on the page (not while typing in an input).
export function attachKeys(api) {
  document.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement || e.ctrlKey || e.metaKey || e.altKey) return;
    if (act(api, e)) e.preventDefault();
  });
}
