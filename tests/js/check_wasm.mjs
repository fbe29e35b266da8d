// The core compiled to WebAssembly (web/wasm/phedra.mjs) against the native
// command: for every shipped preset, the same t*, flexion interval and counts as
// `phedra info --json`, the same vertex positions as `phedra sample` at five
// configurations, the same FOLD frames; bad presets give the CLI's field and
// message. usage: node tests/js/check_wasm.mjs PHEDRA_BINARY
import { execFileSync } from "node:child_process";
import { readFileSync, readdirSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const top = path.resolve(path.dirname(fileURLToPath(import.meta.url)), "../..");
const phedra = process.argv[2];
// Emscripten 3.1.6's ES module still reads `require` and `__dirname` when it runs in node.
globalThis.require = createRequire(import.meta.url);
globalThis.__dirname = path.join(top, "web/wasm");
const { default: createPhedra } = await import(path.join(top, "web/wasm/phedra.mjs"));
// Node's fetch does not read files: hand the module its binary.
const module = await createPhedra({ wasmBinary: readFileSync(path.join(top, "web/wasm/phedra.wasm")) });

let failures = 0;
const fail = (what) => {
  console.error("FAIL: " + what);
  failures += 1;
};
const run = (args) =>
  execFileSync(phedra, args, { encoding: "utf8", maxBuffer: 1 << 28, stdio: ["ignore", "pipe", "pipe"] });

const designer = new module.Designer();
const presets = readdirSync(path.join(top, "presets")).filter((f) => f.endsWith(".json") && !f.includes("schema"));
for (const name of presets) {
  try {
    checkPreset(name);
  } catch (e) {
    fail(`${name}: ${String(e.message || e).slice(0, 400)}`);
  }
}

function checkPreset(name) {
  const file = path.join(top, "presets", name);
  const loaded = designer.load(readFileSync(file, "utf8"));
  if (!loaded.ok) {
    fail(`${name}: ${loaded.field}: ${loaded.message}`);
    return;
  }
  const info = designer.info();
  const native = JSON.parse(run(["info", file, "--json"]));
  if (info.t_star !== native.t_star) fail(`${name}: t* ${info.t_star} != ${native.t_star}`);
  // The limits are bisected to adjacent doubles; the browser's libm (acos, cos) may
  // differ from glibc's in the last bit, so the ends agree to 1e-12 of the width.
  const [lo, hi] = native.flexion_interval;
  if (Math.abs(info.t_lambda - lo) > 1e-12 * (hi - lo) || Math.abs(info.t_mu - hi) > 1e-12 * (hi - lo)) {
    fail(`${name}: interval [${info.t_lambda}, ${info.t_mu}] != [${native.flexion_interval}]`);
  }
  if (info.vertices !== native.vertices || info.faces !== native.faces) fail(`${name}: counts differ`);
  // Inside both intervals; next to a limit positions move like the square root of
  // the distance to it, so there they agree to 1e-6 of the size, elsewhere to 1e-12.
  const fractions = [0, 0.25, 0.5, 0.75, 1];
  const ts = fractions.map((f) => Math.max(lo, info.t_lambda) + f * (Math.min(hi, info.t_mu) - Math.max(lo, info.t_lambda)));
  ts[4] = Math.min(hi, info.t_mu);
  const sample = JSON.parse(run(["sample", file, ...ts.flatMap((t) => ["--t", String(t)])]));
  let worst = 0, worstAtLimits = 0;
  ts.forEach((t, k) => {
    const positions = Float64Array.from(designer.evaluate(t));
    const expected = sample.samples[k].vertices;
    if (positions.length !== 3 * expected.length) {
      fail(`${name}: ${positions.length / 3} vertices, CLI ${expected.length}`);
      return;
    }
    let here = 0;
    expected.forEach((v, i) => {
      for (let c = 0; c < 3; ++c) here = Math.max(here, Math.abs(positions[3 * i + c] - v[c]));
    });
    if (k === 0 || k === 4) worstAtLimits = Math.max(worstAtLimits, here);
    else worst = Math.max(worst, here);
  });
  if (!(worst <= 1e-12 * info.model_size)) fail(`${name}: positions differ from phedra sample by ${worst}`);
  if (!(worstAtLimits <= 1e-6 * info.model_size)) fail(`${name}: at the limits, positions differ by ${worstAtLimits}`);
  const faces = Uint32Array.from(designer.faces());
  if (faces.length !== 4 * info.faces) fail(`${name}: ${faces.length / 4} faces`);
  const outside = designer.evaluate(info.t_mu + 0.1 * (info.t_mu - info.t_lambda));
  if (outside.ok !== false || outside.field !== "t") fail(`${name}: evaluate outside the interval did not refuse`);
  const check = designer.check(21);
  if (!check.passed || !(check.planarity < 1e-9) || !(check.isometry < 1e-9)) fail(`${name}: check ${JSON.stringify(check)}`);
  const fold = JSON.parse(designer.fold(5));
  // The key frame at t*, then one frame a requested t.
  if (fold.file_frames.length !== 5) fail(`${name}: FOLD has ${fold.file_frames.length} frames after the key frame`);
  if (fold["frame_phedra:t"] !== info.t_star) fail(`${name}: the FOLD key frame is at t = ${fold["frame_phedra:t"]}, not t*`);
  // Buildability: the same verdict, counts, panels and buildable interval as
  // `phedra info` (numbers in the text may differ in the last digit: libm).
  const built = designer.buildability(true, 0, 0);
  const cli = JSON.parse(run(["info", file, "--json"])).buildability;
  const words = (text) => text.replace(/-?[0-9][0-9.e+-]*/g, "#");
  const sameInterval = (a, b) => (a === null && b === null) ||
    (a !== null && b !== null && a.every((x, k) => Math.abs(x - b[k]) <= 1e-9 * (hi - lo)));
  for (const [what, other] of [["core", built], ["FOLD", fold["phedra:buildability"]]]) {
    const panels = what === "core" ? other.invalid.map((p) => p.panel) : other.invalid_panels;
    const interval = what === "core" ? other.interval : other.buildable_interval;
    if (other.buildable !== cli.buildable || words(other.summary) !== words(cli.summary) || other.bow_tie !== cli.bow_tie ||
        other.panels !== cli.panels || JSON.stringify(panels) !== JSON.stringify(cli.invalid_panels) ||
        !sameInterval(interval, cli.buildable_interval)) {
      fail(`${name}: ${what} buildability ${JSON.stringify(other).slice(0, 300)} != ${JSON.stringify(cli).slice(0, 300)}`);
    }
  }
  console.log(`ok ${name}: ${info.kind}, ${info.vertices} vertices, largest difference ${worst} (${worstAtLimits} at the limits)`);
}

// Animated .glb written in the browser core: valid for the Khronos validator, and
// the same nodes, meshes and keyframe count as `phedra generate` (both
// representations, and the configuration curve).
const validator = createRequire(path.join(top, "web/package.json"))("gltf-validator");
const { mkdtempSync, rmSync } = await import("node:fs");
const scratch = mkdtempSync(path.join((await import("node:os")).tmpdir(), "phedra-wasm-"));
for (const [name, morph, cycle] of [["default.json", false, false], ["grid-3x3.json", true, false], ["helix-tube.json", false, true]]) {
  const file = path.join(top, "presets", name);
  designer.load(readFileSync(file, "utf8"));
  const bytes = Uint8Array.from(designer.glb(morph, cycle));
  const report = await validator.validateBytes(bytes, { uri: "page.glb", externalResourceFunction: () => Promise.reject(new Error("none")) });
  if (report.issues.numErrors || report.issues.numWarnings) fail(`${name}: the page's .glb has ${report.issues.numErrors} errors`);
  const cliFile = path.join(scratch, "cli.glb");
  run(["generate", file, "-o", cliFile, "-q", ...(morph ? [] : ["--nodes"]), ...(cycle ? ["--cycle"] : [])]);
  const json = (b) => {
    const length = new DataView(b.buffer, b.byteOffset).getUint32(12, true);
    return JSON.parse(new TextDecoder().decode(b.subarray(20, 20 + length)));
  };
  const page = json(bytes), cli = json(new Uint8Array(readFileSync(cliFile)));
  const keys = (g) => g.asset.extras.phedra.keyframe_t.length;
  if (page.nodes.length !== cli.nodes.length || page.meshes.length !== cli.meshes.length) fail(`${name}: .glb structure differs`);
  // Splitting stops where an interval's error crosses the tolerance: rounding
  // that differs between WebAssembly and native code can split a few more or less.
  if (Math.abs(keys(page) - keys(cli)) > Math.max(2, 0.05 * keys(cli))) fail(`${name}: ${keys(page)} keyframes in the page, ${keys(cli)} from the command`);
  console.log(`ok ${name} .glb${morph ? " (morph)" : ""}${cycle ? " (cycle)" : ""}: ${bytes.length} bytes, ${keys(page)} keyframes (command: ${keys(cli)}), valid`);
}
rmSync(scratch, { recursive: true, force: true });

// Designer.set (the drag path) against a load of the edited preset's text: the
// same interval and positions, for every kind of handle of several presets; an
// edit the core refuses gives the CLI's message and keeps the previous design.
const editDesigner = new module.Designer();
const setAt = (p, key, index, value) => {
  const parts = key.split(".");
  if (index < 0) { const last = parts.pop(); parts.reduce((o, k) => o[k], p)[last] = value; }
  else parts.reduce((o, k) => o[k], p)[index] = value;
};
let edits = 0;
const sameDesign = (a, b, what) => {
  const ia = a.info(), ib = b.info();
  if (ia.t_lambda !== ib.t_lambda || ia.t_mu !== ib.t_mu || ia.vertices !== ib.vertices) fail(`${what}: interval or counts differ after set`);
  const t = 0.5 * (ia.t_lambda + ia.t_mu);
  const pa = Float64Array.from(a.evaluate(t)), pb = Float64Array.from(b.evaluate(t));
  if (pa.some((x, i) => x !== pb[i])) fail(`${what}: positions differ after set`);
};
// d turned a little about the axis a (stays orthogonal to it): d + 0.05 a x d.
const turned = (d, a) => [d[0] + 0.05 * (a[1] * d[2] - a[2] * d[1]), d[1] + 0.05 * (a[2] * d[0] - a[0] * d[2]), d[2] + 0.05 * (a[0] * d[1] - a[1] * d[0])];
const editsOf = (p) => {
  const list = [["trajectory", 1, p.trajectory[1].map((x, c) => x + [0.03, -0.02, 0.01][c])],
                ["directions", 0, turned(p.directions[0], p.axis || [0, 0, 1])]];
  if (p.apex_heights) list.push(["apex_heights", 2, p.apex_heights[2] + 0.05]);
  if (p.tube) list.push(["tube.apex_heights", 1, p.tube.apex_heights[1] + 0.05]);
  if (p.grid) list.push(["grid.u_heights", 2, p.grid.u_heights[2] + 0.05], ["grid.w_heights", 3, p.grid.w_heights[3] - 0.05]);
  if (p.row) list.push(["row.free_heights", 1, p.row.free_heights[1] + 0.05]);
  (p.couplings || []).forEach((c, k) => {
    if (c.free_heights) list.push([`couplings.${k}.free_heights`, 0, c.free_heights[0] + 0.05]);
    if (typeof c.free_height === "number") list.push([`couplings.${k}.free_height`, -1, c.free_height + 0.05]);
  });
  return list;
};
for (const name of ["default.json", "parallelogram-tube.json", "grid-3x3.json", "row-of-cells.json", "edge-sharing-pair.json", "tilted-axis.json"]) {
  const preset = JSON.parse(readFileSync(path.join(top, "presets", name), "utf8"));
  if (!Array.isArray(preset.trajectory) || !Array.isArray(preset.directions)) continue;
  designer.load(JSON.stringify(preset));
  for (const [key, index, value] of editsOf(preset)) {
    const v = Array.isArray(value) ? value : [value, 0, 0];
    const result = designer.set(key, index, ...v);
    const candidate = JSON.parse(JSON.stringify(preset));
    setAt(candidate, key, index, value);
    const loaded = editDesigner.load(JSON.stringify(candidate));
    if (result.ok !== loaded.ok || result.message !== loaded.message) {
      fail(`${name}: set(${key}, ${index}) says ${JSON.stringify(result)}, load says ${JSON.stringify(loaded)}`);
    } else if (result.ok) {
      setAt(preset, key, index, value);
      sameDesign(designer, editDesigner, `${name} ${key}[${index}]`);
      edits += 1;
    }
  }
  // Refused: a direction along the axis; the design before it stays.
  const before = Float64Array.from(designer.evaluate(designer.info().t_star));
  const axis = preset.axis || [0, 0, 1];
  const refused = designer.set("directions", 1, ...axis);
  const refusedPreset = JSON.parse(JSON.stringify(preset));
  refusedPreset.directions[1] = axis;
  const fresh = new module.Designer();
  const loadRefused = fresh.load(JSON.stringify(refusedPreset));
  fresh.delete();
  if (refused.ok || loadRefused.ok || refused.field !== loadRefused.field || refused.message !== loadRefused.message) {
    fail(`${name}: refused set ${JSON.stringify(refused)} vs load ${JSON.stringify(loadRefused)}`);
  }
  const after = Float64Array.from(designer.evaluate(designer.info().t_star));
  if (after.some((x, i) => x !== before[i])) fail(`${name}: a refused set changed the design`);
}
for (const [key, index] of [["trajectory", 10000], ["grid.x", 0], ["nothing.0", 0], ["trajectory", -1], ["couplings.99999999999.free_height", -1]]) {
  const r = designer.set(key, index, 0, 0, 0);
  if (r.ok !== false || r.field !== key || !r.message.startsWith("no such entry")) fail(`set(${key}, ${index}): ${JSON.stringify(r)}`);
}
console.log(`${edits} edits through Designer.set agree with loads of the edited presets`);

// Every bad preset of the robustness suite: the CLI's field and message.
const expected = readFileSync(path.join(top, "tests/data/bad/expected.tsv"), "utf8").trim().split("\n");
let bad = 0;
for (const line of expected) {
  const [file] = line.split("\t");
  if (!file || file.startsWith("#")) continue;
  const text = readFileSync(path.join(top, "tests/data/bad", file), "utf8");
  let cli = "";
  try {
    run(["info", path.join(top, "tests/data/bad", file)]);
  } catch (e) {
    cli = String(e.stderr);
  }
  const result = designer.load(text);
  if (result.ok) {
    fail(`${file}: loaded in the browser core, refused by the CLI: ${cli.trim()}`);
    continue;
  }
  const message = result.field ? `${result.field}: ${result.message}` : result.message;
  if (!cli.includes(message)) fail(`${file}: browser "${message}" vs CLI "${cli.trim()}"`);
  bad += 1;
}
console.log(`${bad} bad presets give the CLI's messages`);
if (failures) {
  console.error(`${failures} failures`);
  process.exit(1);
}
