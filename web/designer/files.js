// Files in and out: the preset saved (named after what it came from), opened
// from a file, dropped on the page, chosen from the shipped presets or read
// from a .glb phedra wrote; the .glb, FOLD and PNG downloads; the preset the
// page starts with.
import { baseName, canonicalPreset } from '../text.js';
import { $, clone } from './util.js';

/// The preset a .glb of phedra carries (extras.phedra.preset in its JSON chunk,
/// as text), or null. `bytes`: an ArrayBuffer.
export function presetInGlb(bytes) {
  const view = new DataView(bytes);
  if (bytes.byteLength < 20 || view.getUint32(0, true) !== 0x46546c67) return null;  // 'glTF'
  const length = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(new Uint8Array(bytes, 20, length)));
  return json.asset?.extras?.phedra?.preset ?? null;
}

function download(name, data, type) {
  const url = URL.createObjectURL(new Blob([data], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/// `designer`: the core's Designer; `apply(preset, options)`: shows a design (undoably).
export function createFiles({ renderer, scene, camera, state, designer, panel, apply }) {
  $('save').addEventListener('click', () => {
    const p = state.savedPreset($('name').value.trim(), panel.statusText);
    download(`${p.name}.json`, JSON.stringify(p, null, 2) + '\n', 'application/json');
  });
  $('name').addEventListener('change', () => {
    const name = $('name').value.trim();
    if (name && name !== state.preset.name) apply({ ...clone(state.preset), name }, { what: 'rename' });
  });

  /// Opens a preset the user picked, dropped or chose from the shipped ones;
  /// `name`: its file's name (a .glb's for the preset inside one). A new
  /// design: its own undo history (state.startHistory).
  function openPreset(text, name) {
    try {
      const loaded = JSON.parse(text);
      if (apply(loaded, { what: `load of ${name}`, record: false })) {
        state.startHistory();
        state.loadedName = loaded.name ?? name.replace(/\.(json|glb)$/i, '');
        state.fileName = baseName(name);
        panel.showTitle();
      }
    } catch (error) {
      state.failure = { field: '', message: `${name}: ${error.message}` };
      panel.showMessage();
    }
  }

  /// A preset (.json), or the preset inside a .glb phedra wrote.
  async function openFile(file) {
    if (!/\.(glb)$/i.test(file.name)) {
      openPreset(await file.text(), file.name);
      return;
    }
    let text = null;
    try {
      text = presetInGlb(await file.arrayBuffer());
    } catch { /* not a readable .glb: said below */ }
    if (text) {
      openPreset(text, file.name);
    } else {
      state.failure = { field: '', message: `${file.name} carries no preset (not written by phedra, or by an older one): view it with phedra view ${file.name}` };
      panel.showMessage();
    }
  }
  $('load').addEventListener('change', async (e) => {
    const file = e.target.files[0];
    if (file) openFile(file);
  });
  window.addEventListener('dragover', (e) => e.preventDefault());
  window.addEventListener('drop', async (e) => {
    e.preventDefault();
    const file = e.dataTransfer.files[0];
    if (file) openFile(file);
  });
  // The shipped presets, as `phedra view` serves them.
  fetch('/presets/index.json').then((r) => (r.ok ? r.json() : [])).then((list) => {
    for (const p of list) {
      const option = document.createElement('option');
      option.value = p.file;
      option.textContent = p.name;
      option.title = p.description;
      $('presets').append(option);
    }
    $('presets').disabled = list.length === 0;
  }).catch(() => { $('presets').disabled = true; });
  $('presets').addEventListener('change', async (e) => {
    const file = e.target.value;
    if (!file) return;
    openPreset(await (await fetch(`/presets/${file}`)).text(), file);
    e.target.value = '';
  });

  /// The animated .glb, written by the core as `phedra generate -o X.glb` writes it.
  function glbBytes() {
    const bytes = designer.glb(true, false);
    if (bytes.ok === false) throw new Error(bytes.message);
    return Uint8Array.from(bytes);
  }
  $('export-glb').addEventListener('click', () => download(`${state.preset.name || 'phedra'}.glb`, glbBytes(), 'model/gltf-binary'));
  $('export-fold').addEventListener('click', () => download(`${state.preset.name || 'phedra'}.fold`, designer.fold(41), 'application/json'));
  $('png').addEventListener('click', () => {
    renderer.render(scene, camera);
    const a = document.createElement('a');
    a.download = `${state.preset.name || 'phedra'}.png`;
    a.href = renderer.domElement.toDataURL('image/png');
    a.click();
  });

  /// The preset to start with: one the viewer handed over ("Edit in designer", a
  /// dropped .json), else the one `phedra view PRESET` serves, else the default.
  /// Returns {preset, file: the file's name when known}.
  async function initialPreset() {
    const handed = sessionStorage.getItem('phedra-open-preset');
    if (handed) {
      const file = sessionStorage.getItem('phedra-open-preset-file');
      sessionStorage.removeItem('phedra-open-preset');
      sessionStorage.removeItem('phedra-open-preset-file');
      try {
        return { preset: JSON.parse(handed), file };
      } catch (error) {
        state.failure = { field: '', message: `the preset handed over is not JSON: ${error.message}` };
      }
    }
    for (const url of ['/preset.json', '/presets/default.json']) {
      const response = await fetch(url);
      if (!response.ok) continue;
      const preset = await response.json();
      return { preset, file: url === '/preset.json' ? (await servedName()) ?? (await shippedFileOf(preset)) : 'default.json' };
    }
    return { preset: {}, file: null };
  }

  /// The name of the file `phedra view` serves (/served.json), or null.
  async function servedName() {
    try {
      const response = await fetch('/served.json');
      return response.ok ? (await response.json()).file ?? null : null;
    } catch {
      return null;
    }
  }

  /// The file of the shipped presets that holds `preset`, or null (a server
  /// that does not say which file it serves: a shipped one is recognised).
  async function shippedFileOf(preset) {
    try {
      const list = await (await fetch('/presets/index.json')).json();
      const wanted = canonicalPreset(preset);
      for (const p of list.filter((e) => e.name === preset.name)) {
        const text = await (await fetch(`/presets/${p.file}`)).text();
        if (canonicalPreset(JSON.parse(text)) === wanted) return p.file;
      }
    } catch { /* no list: the name alone */ }
    return null;
  }

  return { glbBytes, initialPreset, openPreset };
}
