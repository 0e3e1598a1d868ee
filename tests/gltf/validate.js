// The Khronos glTF-Validator (npm gltf-validator) on each file given: prints one JSON line per
// file with its issue counts and messages; exits non-zero when a file cannot be validated.
// Usage: NODE_PATH=<dir with node_modules> node validate.js FILE...
const fs = require("fs");
const path = require("path");
const validator = require("gltf-validator");

async function one(file) {
  const data = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(data, {
    uri: path.basename(file),
    maxIssues: 100,
    // external resources: none are written (buffers are embedded)
    externalResourceFunction: (uri) => Promise.reject(new Error(`no external resource ${uri}`)),
  });
  const i = report.issues;
  return {
    file,
    errors: i.numErrors,
    warnings: i.numWarnings,
    infos: i.numInfos,
    hints: i.numHints,
    messages: i.messages.map((m) => `${["error", "warning", "info", "hint"][m.severity]} ${m.code}: ${m.message} (${m.pointer || ""})`),
    info: report.info,
  };
}

(async () => {
  for (const f of process.argv.slice(2)) console.log(JSON.stringify(await one(f)));
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
