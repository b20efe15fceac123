// node validate.js NPM_DIR FILE...: validates glTF files (.gltf, .glb) with
// the Khronos glTF validator installed in NPM_DIR/node_modules (by
// packaging/setup.sh from this folder's package-lock.json). Prints each
// file's counts and its errors and warnings; exits 1 if any file has an
// error (severity 0), 2 if the validator cannot run.
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [npmDir, ...files] = process.argv.slice(2);
  if (!npmDir || files.length === 0) throw new Error('usage: node validate.js NPM_DIR FILE...');
  const validator = require(path.resolve(npmDir, 'node_modules', 'gltf-validator'));
  let failed = 0;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      maxIssues: 100,
      // Everything a PaintLab file needs is inside it.
      externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
    });
    const issues = report.issues;
    console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos, ` +
                `${issues.numHints} hints (validator ${report.validatorVersion})`);
    for (const m of issues.messages)
      if (m.severity <= 1)
        console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ${m.message}`);
    if (issues.numErrors > 0) failed += 1;
  }
  process.exit(failed > 0 ? 1 : 0);
}

main().catch((e) => {
  console.error(`validate.js: ${e.message}`);
  process.exit(2);
});
