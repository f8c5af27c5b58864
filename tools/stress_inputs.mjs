// Writes the big-but-valid inputs that lamina's timings are measured on (README, "Limits and
// safety"): a material file of N distinct materials, and a chain of L layers over a Lambert base.
//
//   node tools/stress_inputs.mjs materials N OUT.json   # N materials, parameters from a fixed seed
//   node tools/stress_inputs.mjs chain L OUT.json       # L dielectric coats over a Lambert base
import { writeFileSync } from "node:fs";

const [kind, countText, out] = process.argv.slice(2);
const count = Number(countText);
if (!out || !Number.isInteger(count) || count < 1 || (kind !== "materials" && kind !== "chain")) {
  console.error("usage: node tools/stress_inputs.mjs materials|chain COUNT OUT.json");
  process.exit(2);
}

// A small deterministic generator (mulberry32), so that the same command writes the same file.
let state = 20261124;
function random() {
  state = (state + 0x6d2b79f5) | 0;
  let t = Math.imul(state ^ (state >>> 15), 1 | state);
  t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
  return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
}
const between = (lo, hi) => Math.round((lo + (hi - lo) * random()) * 1000) / 1000;
const colour = (lo, hi) => [between(lo, hi), between(lo, hi), between(lo, hi)];
const metals = ["gold", "silver", "aluminium", "copper", "chromium"];

// The course's structures: a coat over a diffuse base, a tinted coat over a metal, two coats.
function material(i) {
  const varnish = { id: "varnish", type: "interface/dielectric", ior: between(1.3, 1.7), roughness_deg: between(0.5, 20) };
  switch (i % 3) {
    case 0:
      return {
        name: `m${i}`, surface: "@coat",
        nodes: [
          { id: "coat", type: "layer", interface: "@varnish", base: "@paint" }, varnish,
          { id: "paint", type: "substrate/lambert", albedo: colour(0.05, 0.9) },
        ],
      };
    case 1:
      return {
        name: `m${i}`, surface: "@coat",
        nodes: [
          { id: "coat", type: "layer", interface: "@varnish", medium: "@tint", base: "@metal" }, varnish,
          { id: "tint", type: "medium/absorbing", thickness: between(0.5, 3), absorption: colour(0, 1) },
          { id: "metal", type: "substrate/conductor", metal: metals[i % metals.length], roughness_deg: between(1, 30) },
        ],
      };
    default:
      return {
        name: `m${i}`, surface: "@top",
        nodes: [
          { id: "top", type: "layer", interface: "@varnish", base: "@under" }, varnish,
          { id: "under", type: "layer", interface: "@inner", base: "@paint" },
          { id: "inner", type: "interface/dielectric", ior: between(1.3, 1.7), roughness_deg: between(1, 25) },
          { id: "paint", type: "substrate/oren_nayar", albedo: colour(0.05, 0.9), sigma: between(0, 0.5) },
        ],
      };
  }
}

function chain(layers) {
  const nodes = [];
  for (let i = 0; i < layers; ++i) {
    nodes.push({ id: `l${i}`, type: "layer", interface: `@i${i}`, base: i + 1 < layers ? `@l${i + 1}` : "@base" });
    nodes.push({ id: `i${i}`, type: "interface/dielectric", ior: 1.5, roughness_deg: 2 });
  }
  nodes.push({ id: "base", type: "substrate/lambert", albedo: [0.5, 0.5, 0.5] });
  return { name: "chain", surface: "@l0", nodes };
}

const materials = kind === "materials" ? Array.from({ length: count }, (_, i) => material(i)) : [chain(count)];
writeFileSync(out, JSON.stringify({ format: 1, materials }) + "\n");
