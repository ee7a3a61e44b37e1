#!/usr/bin/env node
// Validates glTF / GLB files with the Khronos glTF Validator and prints one JSON object per file:
//   {"file":..., "validator":..., "errors":N, "warnings":N, "infos":N, "hints":N, "messages":[...]}
// messages lists every error and warning (code, message, pointer). Exit status: 0 when every file has
// zero errors and zero warnings, 1 when any has some, 2 when a file cannot be read or parsed at all.
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('validate.js: the gltf-validator package is not installed; run `npm ci` in ' + __dirname);
  process.exit(2);
}

async function validateFile(file) {
  const full = path.resolve(file);
  const bytes = new Uint8Array(fs.readFileSync(full));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(full),
    maxIssues: 0,
    writeTimestamp: false,
    // .gltf files reference their .bin beside them; load it so buffer contents get validated too.
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      fs.readFile(path.resolve(path.dirname(full), decodeURIComponent(uri)), (err, data) => {
        if (err) reject(err.toString()); else resolve(new Uint8Array(data));
      });
    }),
  });
  const issues = report.issues;
  // severity: 0 error, 1 warning, 2 info, 3 hint.
  const messages = issues.messages.filter((m) => m.severity <= 1)
      .map((m) => ({severity: m.severity === 0 ? 'error' : 'warning', code: m.code, message: m.message,
                    pointer: m.pointer}));
  return {file: full, validator: report.validatorVersion, errors: issues.numErrors,
          warnings: issues.numWarnings, infos: issues.numInfos, hints: issues.numHints, messages,
          infoCodes: [...new Set(issues.messages.filter((m) => m.severity === 2).map((m) => m.code))]};
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: node validate.js FILE.glb|FILE.gltf...');
    process.exit(2);
  }
  let status = 0;
  for (const f of files) {
    try {
      const r = await validateFile(f);
      console.log(JSON.stringify(r));
      if (r.errors > 0 || r.warnings > 0) status = Math.max(status, 1);
    } catch (e) {
      console.log(JSON.stringify({file: f, fatal: String(e)}));
      status = 2;
    }
  }
  process.exit(status);
})();
