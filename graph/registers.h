// Reading inputs and writing outputs of texture operations on the CPU: the register file of a
// shading point is an array of floats (Program::slot_count of them), and an input is a constant or
// registers clamped to the parameter's declared range (program.h, InputRef).
#pragma once

#include <algorithm>
#include <glm/glm.hpp>

#include "graph/program.h"

namespace lamina {

inline float read_float(const InputRef& r, const float* registers) {
  return r.slot < 0 ? r.constant.x : std::clamp(registers[r.slot], r.lo, r.hi);
}

inline glm::vec2 read_vec2(const InputRef& r, const float* registers) {
  if (r.slot < 0) return glm::vec2(r.constant);
  return glm::clamp(glm::vec2(registers[r.slot], registers[r.slot + 1]), glm::vec2(r.lo), glm::vec2(r.hi));
}

inline glm::vec3 read_vec3(const InputRef& r, const float* registers) {
  if (r.slot < 0) return r.constant;
  return glm::clamp(glm::vec3(registers[r.slot], registers[r.slot + 1], registers[r.slot + 2]), glm::vec3(r.lo),
                    glm::vec3(r.hi));
}

inline void write_float(float* registers, int slot, float value) { registers[slot] = value; }

inline void write_vec3(float* registers, int slot, glm::vec3 value) {
  registers[slot] = value.x;
  registers[slot + 1] = value.y;
  registers[slot + 2] = value.z;
}

}  // namespace lamina
