// Validates glTF files (.glb, or .gltf with its external buffers) with the Khronos
// glTF-Validator (npm gltf-validator, pinned in package.json) and prints each report's issues as
// one JSON object per line on stdout:
//   {"file", "uri", "errors", "warnings", "infos", "hints", "messages": [...], "extensionsUsed"}
// Exit status 0 when the validator ran on every file (whatever it found), 2 when it could not
// (unreadable file, unknown format). One process for many files: the validator (Dart compiled
// to JavaScript) takes longer to load than to check a small file.
// Used by tests/export/gltf_validator_test.cc.
//
//   node tests/consumers/validate_gltf.mjs FILE...
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate_gltf.mjs FILE.glb|FILE.gltf ...');
  process.exit(2);
}

for (const file of files) {
  try {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 0,  // every issue, not the first hundred
      externalResourceFunction: async (uri) =>
        new Uint8Array(await readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))),
    });
    const issues = report.issues;
    console.log(JSON.stringify({
      file,
      uri: report.uri,
      errors: issues.numErrors,
      warnings: issues.numWarnings,
      infos: issues.numInfos,
      hints: issues.numHints,
      messages: issues.messages,
      extensionsUsed: report.info ? report.info.extensionsUsed : [],
    }));
  } catch (error) {
    console.error(`validate_gltf: ${file}: ${error}`);
    process.exit(2);
  }
}
