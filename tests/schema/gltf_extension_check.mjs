// Checks schema/gltf/LAMINA_materials_layered/material.LAMINA_materials_layered.schema.json with
// ajv (draft 2020-12, strict), together with schema/material.schema.json that its `material`
// refers to: the extension objects of tests/data/gltf/lamina_layered.gltf must be valid, the broken
// ones (below and in tests/data/gltf/bad/) must be rejected.
// Usage: node tests/schema/gltf_extension_check.mjs <repo_root>. Exit 0 all as expected, 1 otherwise.
import fs from "node:fs";
import path from "node:path";
import Ajv2020 from "ajv/dist/2020.js";

const root = path.resolve(process.argv[2] ?? ".");
const readJson = (...parts) => JSON.parse(fs.readFileSync(path.join(root, ...parts), "utf8"));
const NAME = "LAMINA_materials_layered";

const ajv = new Ajv2020({ strict: true, allErrors: true });
ajv.addSchema(readJson("schema", "material.schema.json"));
const validate = ajv.compile(readJson("schema", "gltf", NAME, `material.${NAME}.schema.json`));

const extensionsOf = (file) =>
  readJson("tests", "data", "gltf", file).materials.map((m, i) => [`${file} /materials/${i}`, m.extensions?.[NAME]]);

const good = extensionsOf("lamina_layered.gltf");
const base = good[0][1];
const bad = [
  ...extensionsOf("bad/extension_not_object.gltf").slice(0, 1),
  ...extensionsOf("bad/invalid_graph.gltf").slice(0, 1),
  ["format 2", { ...base, format: 2 }],
  ["no material", { format: 1, textures: {} }],
  ["negative texture index", { ...base, textures: { patina: { index: -1 } } }],
  ["texture entry without index", { ...base, textures: { patina: { source: 0 } } }],
  ["unknown property", { ...base, graph: {} }],
];

let failed = 0;
for (const [name, object] of good) {
  const ok = validate(object);
  if (!ok) ++failed;
  console.log(`${ok ? "PASS" : "FAIL"} ${name}: ${ok ? "valid" : `expected valid: ${ajv.errorsText(validate.errors)}`}`);
}
for (const [name, object] of bad) {
  const ok = !validate(object);
  if (!ok) ++failed;
  console.log(`${ok ? "PASS" : "FAIL"} ${name}: ${ok ? `rejected (${validate.errors[0].instancePath || "/"} ${validate.errors[0].message})` : "expected rejected, accepted"}`);
}
console.log(`${good.length + bad.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
