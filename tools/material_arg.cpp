#include "tools/material_arg.h"

#include <charconv>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "graph/compile.h"
#include "graph/cpu/reference.h"
#include "graph/load.h"
#include "graph/model.h"
#include "tools/commands.h"

namespace lamina::cli {

void add_material_options(CLI::App& cmd, MaterialArg& arg) {
  cmd.add_option("file", arg.file, "a material file")->required();
  cmd.add_option("-m,--material", arg.material, "the material's name (may be omitted when the file has only one)");
  add_model_option(cmd, arg);
  add_input_options(cmd, arg.input_options);
}

void add_model_option(CLI::App& cmd, MaterialArg& arg) {
  cmd.add_option("--model", arg.model,
                 "compose the stack in this model instead of the material's own \"model\": " + model_summary())
      ->check(CLI::IsMember(model_names()));
}

int load_programs(const MaterialArg& arg, bool all_when_unnamed, std::vector<Program>& out,
                  std::vector<size_t>* indices) {
  CheckedFile checked;
  try {
    checked = check_file(arg.file, arg.input_options.policy_for(arg.file));
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  }
  if (!print_diagnostics(checked.diagnostics)) return kExitInvalid;
  const auto& materials = checked.document.materials;
  std::vector<std::string> names;
  std::string listed;  // "a, b, c"
  for (const auto& m : materials) {
    listed += (names.empty() ? "" : ", ") + m.name;
    names.push_back(m.name);
  }
  std::vector<size_t> chosen;
  if (arg.material.empty()) {
    if (materials.size() == 1 || all_when_unnamed) {
      for (size_t i = 0; i < materials.size(); ++i) chosen.push_back(i);
    } else {
      std::cerr << format(
                       {Severity::Error, arg.file, "/materials",
                        "the file has " + std::to_string(materials.size()) + " materials; choose one with --material",
                        "materials: " + listed})
                << "\n";
      return kExitInvalid;
    }
  } else {
    for (size_t i = 0; i < materials.size(); ++i)
      if (materials[i].name == arg.material) chosen.push_back(i);
    if (chosen.empty()) {
      std::string suggestion = closest_match(arg.material, names);
      std::string hint = (suggestion.empty() ? "" : "did you mean '" + suggestion + "'? ") + "materials: " + listed;
      std::cerr << format({Severity::Error, arg.file, "/materials", "no material named '" + arg.material + "'", hint})
                << "\n";
      return kExitInvalid;
    }
  }
  if (indices) *indices = chosen;
  out.clear();
  for (size_t index : chosen) {
    const std::optional<Graph>& graph = checked.graphs[index];
    if (!graph) throw std::logic_error("load_programs: a valid file without a graph for " + names[index]);
    try {
      out.push_back(compile(*graph, arg.file, checked.document.policy));
      if (!arg.model.empty()) out.back().model = model_number(arg.model);
    } catch (const IoError& e) {
      print_problem(e.what());
      return kExitIo;
    }
  }
  return kExitOk;
}

int load_material(const MaterialArg& arg, std::optional<cpu::Evaluator>& out) {
  std::vector<Program> programs;
  if (int code = load_programs(arg, false, programs); code != kExitOk) return code;
  try {
    out.emplace(std::move(programs.front()));
  } catch (const std::length_error& e) {
    std::cerr << format({Severity::Error, arg.file, "/materials", e.what(), "split the material into smaller stacks"})
              << "\n";
    return kExitInvalid;
  }
  return kExitOk;
}

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<std::vector<float>> parse_numbers(std::string_view option, std::string_view text, size_t count,
                                                std::string_view form) {
  static const char* const kShapes[] = {"", "X", "U,V", "X,Y,Z"};
  std::string written(form);
  if (written.empty())
    written = (count < 4 ? std::string(kShapes[count]) : std::to_string(count) + " numbers") + ", e.g. " +
              (count == 2 ? "0.5,0.5" : "0.3,0,1");
  auto fail = [&](const std::string& why) {
    print_problem(std::string(option) + ": " + why + " (write " + written + ")");
    return std::nullopt;
  };
  std::vector<float> values;
  std::string_view rest = text;
  while (true) {
    size_t comma = rest.find(',');
    std::string_view item = trim(rest.substr(0, comma));
    double value = 0.0;
    const char* first = item.data();
    const char* last = item.data() + item.size();
    if (!item.empty() && *first == '+') ++first;
    auto [end, ec] = std::from_chars(first, last, value);
    // A value below the smallest double (1e-400) is read as 0, like a denormal; above the largest
    // float it cannot be used.
    if (ec == std::errc::result_out_of_range && end == last && item.find_first_of("eE") != std::string_view::npos) {
      const auto exponent = item.substr(item.find_first_of("eE") + 1);
      if (!exponent.empty() && exponent.front() == '-') {
        value = 0.0;
        ec = std::errc();
      }
    }
    if (item.empty() || ec == std::errc::invalid_argument || end != last)
      return fail("'" + std::string(item) + "' in '" + std::string(text) + "' is not a number");
    if (std::isnan(value))
      return fail("'" + std::string(item) + "' in '" + std::string(text) + "' is not a number (NaN)");
    if (ec != std::errc() || !(std::abs(value) <= double(std::numeric_limits<float>::max())))
      return fail("'" + std::string(item) + "' in '" + std::string(text) +
                  "' is beyond the single-precision range (about 3.4e38) the evaluator computes in");
    values.push_back(static_cast<float>(value));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (values.size() != count)
    return fail("expected " + std::to_string(count) + " numbers, got " + std::to_string(values.size()) + " in '" +
                std::string(text) + "'");
  return values;
}

std::optional<glm::vec3> parse_direction(std::string_view option, std::string_view text) {
  auto numbers = parse_numbers(option, text, 3);
  if (!numbers) return std::nullopt;
  glm::vec3 v((*numbers)[0], (*numbers)[1], (*numbers)[2]);
  float largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (largest == 0.0f) {
    print_problem(std::string(option) + ": the zero vector '" + std::string(text) +
                  "' has no direction (give X,Y,Z with z along the normal, e.g. 0,0,1)");
    return std::nullopt;
  }
  float length_squared = glm::dot(v, v);
  // Rescale first when squaring would overflow or underflow; otherwise exactly glm::normalize.
  if (!std::isfinite(length_squared) || length_squared < 1.0e-30f) v /= largest;
  return glm::normalize(v);
}

void add_context_options(CLI::App& cmd, ContextArg& arg) {
  cmd.add_option("--uv", arg.uv, "texture coordinates U,V of the shading point")->capture_default_str();
  cmd.add_option("--position", arg.position,
                 "world-space position X,Y,Z of the shading point (procedural textures with \"space\": "
                 "\"position\")")
      ->capture_default_str();
  cmd.add_option("--footprint", arg.footprint,
                 "the pixel's footprint in uv units, which procedural textures filter over (0: a point sample)")
      ->capture_default_str();
}

std::optional<ShadingContext> parse_context(const ContextArg& arg) {
  auto uv = parse_numbers("--uv", arg.uv, 2);
  if (!uv) return std::nullopt;
  auto position = parse_numbers("--position", arg.position, 3);
  if (!position) return std::nullopt;
  if (!(arg.footprint >= 0.0 && arg.footprint <= 1.0e6)) {
    std::ostringstream text;
    text << "--footprint: " << arg.footprint << " is outside [0, 1e6] (the pixel's size in uv units; 0 is a point)";
    print_problem(text.str());
    return std::nullopt;
  }
  ShadingContext ctx;
  ctx.uv = glm::vec2((*uv)[0], (*uv)[1]);
  ctx.position = glm::vec3((*position)[0], (*position)[1], (*position)[2]);
  ctx.footprint = static_cast<float>(arg.footprint);
  return ctx;
}

std::optional<glm::vec3> parse_view_angle(double theta_deg) {
  if (!(theta_deg >= 0.0 && theta_deg < 90.0)) {
    std::ostringstream text;
    text << "--theta: " << theta_deg
         << " is outside [0, 90) (the view angle from the normal in degrees; 90 is grazing and has no albedo)";
    print_problem(text.str());
    return std::nullopt;
  }
  return direction_in_plane(theta_deg);
}

int refuse_tilted(const MaterialArg& arg, const cpu::Evaluator& evaluator, const cpu::ShadingPoint& point) {
  const int i = cpu::tilted_entry(point);
  if (i < 0) return kExitOk;
  const StackEntry& e = evaluator.program().stack[size_t(i)];
  const std::string& node = e.interface_node.empty() ? e.node : e.interface_node;
  std::cerr << "lamina: " << arg.file << ": material \"" << evaluator.program().name << "\": node \"" << node
            << "\" is tilted by its normal input at this shading point; the reference solver walks flat, parallel "
               "boundaries only (README, Per-layer normals)\n";
  return kExitInvalid;
}

}  // namespace lamina::cli
