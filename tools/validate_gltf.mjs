#!/usr/bin/env node
// Validates glTF/GLB files with the Khronos glTF Validator (npm package `gltf-validator`).
//
// Usage: node tools/validate_gltf.mjs FILE.glb [FILE...]
//
// The validator is looked up in, in order: $SKELFIT_GLTF_VALIDATOR (a directory holding
// node_modules/gltf-validator, i.e. an `npm install --prefix` target), $HOME/.cache/skelfit-tools,
// /work/tools, then Node's normal module resolution. Install it with
//   npm install --prefix "$HOME/.cache/skelfit-tools" gltf-validator@2.0.0-dev.3.10
//
// Prints one summary line per file (numErrors, numWarnings, numInfos, numHints) followed by
// every error and warning with its JSON pointer.
// Exit codes: 0 = no errors, 1 = at least one file has errors, 2 = usage error, validator not
// installed or a file could not be read.

import { createRequire } from "node:module";
import { existsSync, readFileSync } from "node:fs";
import { join, basename } from "node:path";

function loadValidator() {
  const prefixes = [
    process.env.SKELFIT_GLTF_VALIDATOR,
    process.env.HOME && join(process.env.HOME, ".cache", "skelfit-tools"),
    "/work/tools",
  ].filter(Boolean);
  for (const prefix of prefixes) {
    const pkg = join(prefix, "node_modules", "gltf-validator", "package.json");
    if (existsSync(pkg)) {
      return createRequire(pkg)("gltf-validator");
    }
  }
  try {
    return createRequire(import.meta.url)("gltf-validator");
  } catch {
    return null;
  }
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node tools/validate_gltf.mjs FILE.glb [FILE...]");
  process.exit(2);
}
const validator = loadValidator();
if (!validator) {
  console.error(
    "validate_gltf: gltf-validator is not installed; run: npm install --prefix \"$HOME/.cache/skelfit-tools\" gltf-validator"
  );
  process.exit(2);
}

let failed = false;
for (const file of files) {
  let bytes;
  try {
    bytes = new Uint8Array(readFileSync(file));
  } catch (error) {
    console.error(`validate_gltf: cannot read ${file}: ${error.message}`);
    process.exit(2);
  }
  const report = await validator.validateBytes(bytes, { uri: basename(file), maxIssues: 1000 });
  const issues = report.issues;
  console.log(
    `${file}: numErrors=${issues.numErrors} numWarnings=${issues.numWarnings} numInfos=${issues.numInfos} numHints=${issues.numHints} validator=${report.validatorVersion}`
  );
  for (const message of issues.messages) {
    if (message.severity <= 1) {
      const kind = message.severity === 0 ? "error" : "warning";
      console.log(`  ${kind} ${message.code} at ${message.pointer ?? "-"}: ${message.message}`);
    }
  }
  if (issues.numErrors > 0) {
    failed = true;
  }
}
process.exit(failed ? 1 : 0);
