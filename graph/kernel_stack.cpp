#include "graph/kernel_stack.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "graph/limits.h"
#include "graph/registers.h"

namespace lamina {

namespace {

bool folds_slope(const StackEntry& e, bool fold_slopes) { return fold_slopes && e.degrees && !e.scalar_y.linked(); }

}  // namespace

kernels::LaminaEntry kernel_entry(const StackEntry& s, bool fold_slopes) {
  kernels::LaminaEntry e;
  e.kind = s.kind;
  e.model = s.model;
  e.medium = s.medium;
  e.distribution = s.distribution;
  e.fresnel = s.fresnel;
  e.degrees = s.degrees && !folds_slope(s, fold_slopes) ? 1 : 0;
  e.parent = s.parent;
  e.side = s.side;
  e.first = s.first;
  e.second = s.second;
  return e;
}

kernels::LaminaInputs kernel_constants(const StackEntry& s, bool fold_slopes) {
  kernels::LaminaInputs x;
  x.colour0 = s.colour0.constant;
  x.colour1 = s.colour1.constant;
  x.colour2 = s.colour2.constant;
  x.scalars = glm::vec4(s.scalar_x.constant.x, s.scalar_y.constant.x, s.scalar_z.constant.x, s.scalar_w.constant.x);
  x.normal = s.normal.constant;
  if (folds_slope(s, fold_slopes)) x.scalars.y = kernels::lamina_slope(x.scalars.y, true);
  return x;
}

kernels::LaminaInputs kernel_inputs(const StackEntry& s, const kernels::LaminaInputs& constants,
                                    const float* registers) {
  kernels::LaminaInputs x = constants;
  if (s.colour0.linked()) x.colour0 = read_vec3(s.colour0, registers);
  if (s.colour1.linked()) x.colour1 = read_vec3(s.colour1, registers);
  if (s.colour2.linked()) x.colour2 = read_vec3(s.colour2, registers);
  if (s.scalar_x.linked()) x.scalars.x = read_float(s.scalar_x, registers);
  if (s.scalar_y.linked()) x.scalars.y = read_float(s.scalar_y, registers);
  if (s.scalar_z.linked()) x.scalars.z = read_float(s.scalar_z, registers);
  if (s.scalar_w.linked()) x.scalars.w = read_float(s.scalar_w, registers);
  if (s.normal.linked()) x.normal = read_vec3(s.normal, registers);
  return x;
}

int StackBlend::longest_part() const {
  int longest = 0;
  for (const Part& part : parts) longest = std::max(longest, part.count);
  return longest;
}

std::vector<kernels::LaminaEntry> StackBlend::part_entries(const Program& program, size_t k, bool fold_slopes) const {
  const Part& part = parts.at(k);
  auto local = [&](int i) { return i < 0 ? -1 : i - part.first; };
  std::vector<kernels::LaminaEntry> out;
  for (int i = part.first; i < part.first + part.count; ++i) {
    kernels::LaminaEntry e = kernel_entry(program.stack[size_t(i)], fold_slopes);
    e.parent = i == part.first ? -1 : local(e.parent);
    e.first = local(e.first);
    e.second = local(e.second);
    out.push_back(e);
  }
  return out;
}

StackBlend split_blend(const Program& program, bool fold_slopes) {
  const std::vector<StackEntry>& stack = program.stack;
  const int n = int(stack.size());
  // An entry is in the blend when every entry above it is a mix: a mix there is one of the blend's,
  // anything else begins a part, which runs to the end of its subtree (depth first, parents before
  // children: the entries after it whose parents are in it).
  std::vector<int> in_blend(size_t(n), -1);
  StackBlend blend;
  for (int i = 0; i < n; ++i) {
    const int parent = stack[size_t(i)].parent;
    const bool top = parent < 0 || (in_blend[size_t(parent)] >= 0 && stack[size_t(parent)].kind == kernels::LAMINA_MIX);
    if (!top) continue;
    in_blend[size_t(i)] = int(blend.entries.size());
    kernels::LaminaEntry e = kernel_entry(stack[size_t(i)], fold_slopes);
    e.parent = parent < 0 ? -1 : in_blend[size_t(parent)];
    e.first = -1;
    e.second = -1;
    blend.entries.push_back(e);
    blend.whole.push_back(i);
    if (e.kind == kernels::LAMINA_MIX) continue;
    StackBlend::Part part;
    part.first = i;
    part.blend = in_blend[size_t(i)];
    std::vector<bool> inside(size_t(n), false);
    inside[size_t(i)] = true;
    int end = i + 1;
    while (end < n && stack[size_t(end)].parent >= i && inside[size_t(stack[size_t(end)].parent)])
      inside[size_t(end++)] = true;
    part.count = end - i;
    blend.parts.push_back(part);
  }
  // A mix's children in the blend (they come after it).
  for (size_t b = 0; b < blend.entries.size(); ++b) {
    const int parent = blend.entries[b].parent;
    if (parent < 0) continue;
    if (stack[size_t(blend.whole[b])].side == 0)
      blend.entries[size_t(parent)].first = int(b);
    else
      blend.entries[size_t(parent)].second = int(b);
  }
  return blend;
}

int shown_stack(int count, const kernels::LaminaEntry* entries, const kernels::LaminaParams* params,
                kernels::LaminaEntry* out_entries, kernels::LaminaParams* out_params, int* whole) {
  const auto shown = [&](int i) { return params[i].share > 0.0f; };
  bool hides = false;
  for (int i = 0; i < count; ++i) hides = hides || !shown(i);
  if (!hides) return 0;
  if (count > kMaxStackEntries) throw std::length_error("shown_stack: a stack beyond the evaluator's limits");
  // Top down (a parent comes before its children): an entry is kept when it is shown or its parent
  // is (a shown mix's hidden stack; a layer passes its share on unchanged, so below a shown layer
  // every entry is shown).
  std::array<int, kMaxStackEntries> place;
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const int parent = entries[i].parent;
    place[size_t(i)] = -1;
    if (!shown(i) && (parent < 0 || !shown(parent))) continue;
    place[size_t(i)] = n;
    kernels::LaminaEntry e = entries[i];
    e.parent = parent < 0 ? -1 : place[size_t(parent)];
    if (!shown(i)) {
      e.kind = kernels::LAMINA_SUBSTRATE;
      e.model = kernels::LAMINA_SUBSTRATE_LAMBERT;
      e.first = -1;
      e.second = -1;
    }
    out_entries[n] = e;
    out_params[n] = params[i];
    whole[n] = i;
    ++n;
  }
  // Children come after their parents: re-index them once every entry has its place.
  for (int j = 0; j < n; ++j) {
    kernels::LaminaEntry& e = out_entries[j];
    if (e.first >= 0) e.first = place[size_t(e.first)];
    if (e.second >= 0) e.second = place[size_t(e.second)];
  }
  return n;
}

}  // namespace lamina
