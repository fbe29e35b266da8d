// Runs the Khronos glTF-Validator on each file given; prints its counts and
// exits 1 unless every file has 0 errors and 0 warnings.
// usage: node tests/js/validate_gltf.mjs FILE.glb|FILE.gltf ...
import { createRequire } from 'node:module';
import { readFile } from 'node:fs/promises';
import path from 'node:path';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const validator = require('gltf-validator');

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    externalResourceFunction: () => Promise.reject(new Error('external resources are not used')),
  });
  const { numErrors, numWarnings, numInfos, numHints } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`);
  if (numErrors || numWarnings) {
    failed = true;
    for (const m of report.issues.messages.filter((m) => m.severity <= 1).slice(0, 5)) {
      console.log(`  ${m.code}: ${m.message} (${m.pointer ?? ''})`);
    }
  }
}
process.exit(failed ? 1 : 0);
