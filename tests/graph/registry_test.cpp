// Every registered node type brings its behaviour for every back end: the test walks the registry,
// not the examples, so a new type without one of its parts fails here.
#include <doctest/doctest.h>

#include <set>
#include <string>

#include "graph/node_decl.h"
#include "graph/registry.h"

using namespace lamina;

TEST_CASE(
    "every registered node type lowers into the program, and a texture or math node also runs on the CPU and emits "
    "GLSL") {
  const auto& all = NodeRegistry::builtin().all();
  REQUIRE_FALSE(all.empty());
  std::set<NodeKind> kinds;
  for (const NodeDecl& decl : all) {
    CAPTURE(decl.type);
    kinds.insert(decl.kind);
    CHECK_MESSAGE(bool(decl.lower), decl.type << " has no lowering into the program");
    const bool op = decl.kind == NodeKind::Texture || decl.kind == NodeKind::Math;
    // A texture or math node is an op: the CPU runs it and the GLSL back end writes it. A stack
    // node is a part of a stack entry, which the kernels' composition evaluates in both back ends.
    CHECK_MESSAGE(bool(decl.run) == op, decl.type << ": a CPU run exactly for texture and math nodes");
    CHECK_MESSAGE(bool(decl.emit_glsl) == op, decl.type << ": a GLSL emission exactly for texture and math nodes");
    // glTF: every node travels losslessly in the extension; what the fallback does is stated.
    CHECK_MESSAGE(!decl.gltf.empty(), decl.type << " says nothing about glTF");
    // Classification facts belong to the kinds they describe.
    if (decl.metal) CHECK(bool(decl.kind == NodeKind::Substrate));
    if (decl.tint) CHECK(bool(decl.kind == NodeKind::Medium));
  }
  // Every medium answers whether it tints; the classification has no default for a new one.
  for (const NodeDecl& decl : all)
    if (decl.kind == NodeKind::Medium) CHECK_MESSAGE(bool(decl.tint), decl.type << " does not say whether it tints");
  CHECK(kinds.count(NodeKind::Substrate));
  CHECK(kinds.count(NodeKind::Layer));
}
