// Checks the generated JSON Schemas (schema/material.schema.json, schema/scene.schema.json) with
// ajv, independently of the C++ checker:
//   - the schema must compile with ajv's draft 2020-12 build in strict mode;
//   - every examples/materials/*.json must be valid;
//   - every case of tests/data/bad/cases.json must be accepted or rejected as its "schema" field
//     says ("reject": the schema sees the mistake; "accept": only `lamina validate` can).
//     A file that JSON.parse refuses counts as rejected.
//   - the same for scenes: schema/scene.schema.json compiles, the scenes examples/*.json are valid,
//     tests/data/bad_scenes/cases.json says which broken scenes the schema must reject.
// Usage: node tests/schema/ajv_check.mjs <repo_root> [--schema FILE]
// (--schema checks another material schema file instead of <repo_root>/schema/material.schema.json.)
// Prints one PASS/FAIL line per file, then "N passed, M failed"; exits 1 if M > 0, else 0.
import fs from "node:fs";
import path from "node:path";
import Ajv2020 from "ajv/dist/2020.js";

function usage(message) {
  console.error(`ajv_check: ${message}`);
  console.error("usage: node tests/schema/ajv_check.mjs <repo_root> [--schema FILE]");
  process.exit(2);
}

const args = process.argv.slice(2);
let root = null;
let schemaPath = null;
for (let i = 0; i < args.length; ++i) {
  if (args[i] === "--schema") {
    if (i + 1 >= args.length) usage("--schema needs a file");
    schemaPath = path.resolve(args[++i]);
  } else if (root === null) {
    root = path.resolve(args[i]);
  } else {
    usage(`unexpected argument "${args[i]}"`);
  }
}
if (root === null) usage("missing <repo_root>");
schemaPath ??= path.join(root, "schema", "material.schema.json");

let passed = 0;
let failed = 0;
// One line per file: JSON.parse messages quote the source, newlines included.
const oneLine = (text) => String(text).replace(/\s*\n\s*/g, " ");
function pass(name, detail) {
  ++passed;
  console.log(`PASS ${name}${detail ? `: ${oneLine(detail)}` : ""}`);
}
function fail(name, detail) {
  ++failed;
  console.log(`FAIL ${name}${detail ? `: ${oneLine(detail)}` : ""}`);
}
function finish() {
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed > 0 ? 1 : 0);
}
const rel = (file) => path.relative(root, file) || file;

function errorText(e) {
  return `${e.instancePath || "/"} ${e.message}` + (e.params && Object.keys(e.params).length ? ` ${JSON.stringify(e.params)}` : "");
}

// --- the schema -----------------------------------------------------------------------------
let schema;
try {
  schema = JSON.parse(fs.readFileSync(schemaPath, "utf8"));
} catch (e) {
  fail(rel(schemaPath), `cannot read the schema: ${e.message}`);
  finish();
}
const ajv = new Ajv2020({ strict: true, allErrors: true });
let validate;
{
  // Validate the schema against the 2020-12 meta-schema first, so that its errors are listed
  // once each rather than inside one long exception message.
  const problems = [];
  if (!ajv.validateSchema(schema)) {
    const seen = new Set();
    for (const e of ajv.errors ?? []) {
      const text = `${e.instancePath || "/"} ${e.message}`;
      if (!seen.has(text)) {
        seen.add(text);
        problems.push(text);
      }
    }
  } else {
    try {
      validate = ajv.compile(schema);
    } catch (e) {
      problems.push(e.message);
    }
  }
  if (problems.length) {
    const shown = problems.slice(0, 5).join("; ") + (problems.length > 5 ? `; ... (${problems.length} problems)` : "");
    fail(rel(schemaPath), `does not compile with ajv (draft 2020-12, strict): ${shown}`);
    console.log("(the examples and the bad cases are not checked: the schema does not compile)");
    finish();
  }
  pass(rel(schemaPath), "compiles with ajv (draft 2020-12, strict)");
}

// Returns {outcome: "accept" | "reject", detail}.
function check(file) {
  let doc;
  try {
    doc = JSON.parse(fs.readFileSync(file, "utf8"));
  } catch (e) {
    return { outcome: "reject", detail: `JSON.parse: ${e.message}` };
  }
  if (validate(doc)) return { outcome: "accept", detail: "" };
  return { outcome: "reject", detail: errorText(validate.errors[0]) };
}

// --- the examples: all valid ---------------------------------------------------------------
const examplesDir = path.join(root, "examples", "materials");
const examples = fs.existsSync(examplesDir)
  ? fs.readdirSync(examplesDir).filter((f) => f.endsWith(".json")).sort()
  : [];
if (examples.length === 0) fail(rel(examplesDir), "no example material files found");
for (const f of examples) {
  const file = path.join(examplesDir, f);
  const { outcome, detail } = check(file);
  if (outcome === "accept") pass(rel(file), "valid");
  else fail(rel(file), `expected valid, rejected: ${detail}`);
}

// --- the bad cases: outcome as in cases.json -------------------------------------------------
const badDir = path.join(root, "tests", "data", "bad");
const manifest = path.join(badDir, "cases.json");
let cases = [];
try {
  cases = JSON.parse(fs.readFileSync(manifest, "utf8"));
  if (!Array.isArray(cases)) throw new Error("not a JSON array");
} catch (e) {
  fail(rel(manifest), `cannot read the case list: ${e.message}`);
  cases = [];
}
const listed = new Set();
for (const [i, c] of cases.entries()) {
  const name = c && typeof c.file === "string" ? c.file : `case ${i}`;
  if (!c || typeof c.file !== "string" || !["accept", "reject"].includes(c.schema)) {
    fail(`${rel(manifest)} [${i}]`, `needs "file" and "schema": "accept" or "reject", found ${JSON.stringify(c)}`);
    continue;
  }
  listed.add(c.file);
  const file = path.join(badDir, c.file);
  if (!fs.existsSync(file)) {
    fail(rel(file), "listed in cases.json but missing");
    continue;
  }
  const { outcome, detail } = check(file);
  const said = outcome === "accept" ? "accepted" : `rejected: ${detail}`;
  if (outcome === c.schema) pass(rel(file), said);
  else fail(rel(file), `expected the schema to ${c.schema}, ${said}`);
}
if (fs.existsSync(badDir)) {
  for (const f of fs.readdirSync(badDir).sort()) {
    if (f.endsWith(".json") && f !== "cases.json" && !listed.has(f))
      fail(rel(path.join(badDir, f)), "not listed in cases.json");
  }
}

// --- scenes: the same checks against the scene schema -----------------------------------------
function compileSchema(file) {
  let parsed;
  try {
    parsed = JSON.parse(fs.readFileSync(file, "utf8"));
  } catch (e) {
    fail(rel(file), `cannot read the schema: ${e.message}`);
    return null;
  }
  const sceneAjv = new Ajv2020({ strict: true, allErrors: true });
  try {
    const compiled = sceneAjv.compile(parsed);
    pass(rel(file), "compiles with ajv (draft 2020-12, strict)");
    return compiled;
  } catch (e) {
    fail(rel(file), `does not compile with ajv (draft 2020-12, strict): ${e.message}`);
    return null;
  }
}

function checkWith(compiled, file) {
  let doc;
  try {
    doc = JSON.parse(fs.readFileSync(file, "utf8"));
  } catch (e) {
    return { outcome: "reject", detail: `JSON.parse: ${e.message}` };
  }
  if (compiled(doc)) return { outcome: "accept", detail: "" };
  return { outcome: "reject", detail: errorText(compiled.errors[0]) };
}

const sceneSchema = compileSchema(path.join(root, "schema", "scene.schema.json"));
if (sceneSchema) {
  // Scenes sit at the top of examples/, so that the material files they name lie inside their folder.
  const scenesDir = path.join(root, "examples");
  const scenes = fs.readdirSync(scenesDir).filter((f) => f.endsWith(".json")).sort();
  if (scenes.length === 0) fail(rel(scenesDir), "no example scene files found");
  for (const f of scenes) {
    const file = path.join(scenesDir, f);
    const { outcome, detail } = checkWith(sceneSchema, file);
    if (outcome === "accept") pass(rel(file), "valid");
    else fail(rel(file), `expected valid, rejected: ${detail}`);
  }
  const badScenes = path.join(root, "tests", "data", "bad_scenes");
  const sceneManifest = path.join(badScenes, "cases.json");
  let sceneCases = [];
  try {
    sceneCases = JSON.parse(fs.readFileSync(sceneManifest, "utf8"));
    if (!Array.isArray(sceneCases)) throw new Error("not a JSON array");
  } catch (e) {
    fail(rel(sceneManifest), `cannot read the case list: ${e.message}`);
    sceneCases = [];
  }
  const listedScenes = new Set();
  for (const [i, c] of sceneCases.entries()) {
    if (!c || typeof c.file !== "string" || !["accept", "reject"].includes(c.schema)) {
      fail(`${rel(sceneManifest)} [${i}]`, `needs "file" and "schema": "accept" or "reject", found ${JSON.stringify(c)}`);
      continue;
    }
    listedScenes.add(c.file);
    const file = path.join(badScenes, c.file);
    if (!fs.existsSync(file)) {
      fail(rel(file), "listed in cases.json but missing");
      continue;
    }
    const { outcome, detail } = checkWith(sceneSchema, file);
    const said = outcome === "accept" ? "accepted" : `rejected: ${detail}`;
    if (outcome === c.schema) pass(rel(file), said);
    else fail(rel(file), `expected the schema to ${c.schema}, ${said}`);
  }
  for (const f of fs.readdirSync(badScenes).sort()) {
    if (f.endsWith(".json") && f !== "cases.json" && !listedScenes.has(f))
      fail(rel(path.join(badScenes, f)), "not listed in cases.json");
  }
}
finish();
