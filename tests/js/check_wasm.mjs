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
  if (fold.file_frames.length !== 4) fail(`${name}: FOLD has ${fold.file_frames.length + 1} frames`);
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
  run(["generate", file, "-o", cliFile, "-q", ...(morph ? ["--morph"] : []), ...(cycle ? ["--cycle"] : [])]);
  const json = (b) => {
    const length = new DataView(b.buffer, b.byteOffset).getUint32(12, true);
    return JSON.parse(new TextDecoder().decode(b.subarray(20, 20 + length)));
  };
  const page = json(bytes), cli = json(new Uint8Array(readFileSync(cliFile)));
  const keys = (g) => g.asset.extras.phedra.keyframe_t.length;
  if (page.nodes.length !== cli.nodes.length || page.meshes.length !== cli.meshes.length) fail(`${name}: .glb structure differs`);
  if (Math.abs(keys(page) - keys(cli)) > 2) fail(`${name}: ${keys(page)} keyframes in the page, ${keys(cli)} from the command`);
  console.log(`ok ${name} .glb${morph ? " (morph)" : ""}${cycle ? " (cycle)" : ""}: ${bytes.length} bytes, ${keys(page)} keyframes (command: ${keys(cli)}), valid`);
}
rmSync(scratch, { recursive: true, force: true });

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
