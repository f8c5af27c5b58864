// Runs the Khronos glTF-Validator (npm gltf-validator, pinned in package-lock.json) on each
// .gltf/.glb file given on the command line. Exit 0 when no file has errors or warnings, 1 when
// some file has, 2 on a usage problem. Infos and hints are printed but tolerated: the validator
// reports an extension it does not know (our LAMINA_materials_layered) as the info
// UNSUPPORTED_EXTENSION, which is expected.
import { readFile } from "node:fs/promises";
import path from "node:path";
import validator from "gltf-validator";

const SEVERITY = ["error", "warning", "info", "hint"];

async function validate(file) {
  const bytes = new Uint8Array(await readFile(file));
  const directory = path.dirname(path.resolve(file));
  // Buffers and images referenced by relative URI are read next to the .gltf.
  const externalResourceFunction = async (uri) =>
    new Uint8Array(await readFile(path.join(directory, decodeURIComponent(uri))));
  return validator.validateBytes(bytes, {
    uri: path.basename(file),
    externalResourceFunction,
    maxIssues: 0,
    writeTimestamp: false,
  });
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node validate_gltf.mjs FILE.gltf|FILE.glb...");
  process.exit(2);
}

let failed = 0;
for (const file of files) {
  let report;
  try {
    report = await validate(file);
  } catch (e) {
    console.log(`${file}: cannot validate: ${e.message ?? e}`);
    ++failed;
    continue;
  }
  const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
  const ok = numErrors === 0 && numWarnings === 0;
  console.log(
    `${file}: ${ok ? "ok" : "FAILED"} (${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints)`
  );
  for (const m of messages)
    console.log(`  ${SEVERITY[m.severity] ?? m.severity} ${m.code} ${m.pointer ?? ""}: ${m.message}`);
  if (!ok) ++failed;
}
console.log(`${files.length - failed} of ${files.length} glTF files pass the Khronos validator (validator ${validator.version()})`);
process.exit(failed === 0 ? 0 : 1);
