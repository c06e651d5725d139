// Validates glTF files with the Khronos glTF validator (npm gltf-validator), resolving their
// external .bin and image files next to them. Prints each report's counts and every message
// of severity error or warning; exits 1 if any file has an error, 2 on a usage problem.
// Usage: node validate-gltf.mjs FILE.gltf|FILE.glb...
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate-gltf.mjs FILE.gltf|FILE.glb...');
  process.exit(2);
}
let failed = false;
for (const file of files) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ` +
      `${i.numHints} hints; extensions: ${(report.info.extensionsUsed || []).join(', ')}`);
  for (const m of i.messages)
    if (m.severity <= 1) console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} at ${m.pointer || '-'}: ${m.message}`);
  if (i.numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
