// Validates every .glb under the folders given (recursively) with the Khronos glTF
// validator; prints one line per file and exits non-zero when any file has errors.
// Usage: node validate.mjs DIR...
import validator from 'gltf-validator';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';

function* glbs(dir) {
  for (const name of readdirSync(dir).sort()) {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) yield* glbs(path);
    else if (name.endsWith('.glb')) yield path;
  }
}

const dirs = process.argv.slice(2);
if (dirs.length === 0) {
  console.error('usage: node validate.mjs DIR...');
  process.exit(2);
}
let files = 0;
let failed = 0;
for (const dir of dirs) {
  for (const path of glbs(dir)) {
    files += 1;
    const report = await validator.validateBytes(new Uint8Array(readFileSync(path)), { uri: path, maxIssues: 50 });
    const { numErrors, numWarnings, numInfos } = report.issues;
    console.log(`${path}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos`);
    for (const m of report.issues.messages.filter((m) => m.severity <= 1).slice(0, 10)) {
      console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
    }
    if (numErrors > 0) failed += 1;
  }
}
console.log(`${files} GLB files, ${failed} with errors`);
if (files === 0 || failed > 0) process.exit(1);
