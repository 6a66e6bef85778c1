#pragma once
// The abstract syntax tree that glslangValidator prints with `-i` (one node a
// line: "S:L" — source-string number and line — then two spaces per level and
// the node's text), parsed back into a tree, and the two checks of
// tests/render/glsl_nvidia_rules_test.cpp that walk it: the GLSL constructs
// NVIDIA's compiler refuses while Mesa accepts them (docs/gpu-precompute.md,
// "What NVIDIA's compiler refuses").
#include <string>
#include <string_view>
#include <vector>

namespace zenith::render::testing {

struct AstNode {
  int source = -1;   ///< source-string number (#line's second argument), -1 for '?'
  int line = -1;     ///< -1 for '?'
  std::string text;  ///< "indirect index ( temp double)", "'s' ( temp 4-component vector of double)"
  std::vector<AstNode> children;

  /// The text before the type in parentheses: "indirect index", "'s'", "Function Call: f(vd4;i1;".
  std::string_view head() const;
  /// The type in parentheses that ends the text, without them: " temp double"; empty if none.
  std::string_view type() const;
};

/// The tree of a glslangValidator -i listing (the root is its first "Sequence").
/// Throws std::runtime_error when the listing has none.
AstNode parse_glslang_ast(std::string_view listing);

/// One construct a check found.
struct Finding {
  int source = -1, line = -1;  ///< where: source-string number, line
  std::string what;
  std::string function;  ///< the function it is in ("spline_value"); rule 2 only
  std::string buffer;    ///< the storage buffer's array ("table_data"); rule 2 only
};

/// Rule 1 (NVIDIA: "C9999: can't find __setVectorIndex function in stdlib", a
/// link failure): a write — assignment (=, op=), ++/--, or an argument given to
/// an out or inout parameter of a function, modf or frexp — whose l-value
/// selects one component of a double vector (dvec2..4; the shaders' real2..4
/// in fp64) by an index that is not a constant expression.
std::vector<Finding> double_vector_index_writes(const AstNode& root);

/// Rule 2 (NVIDIA: "C5025: lvalue in array access too complex", a link
/// failure that #pragma optionNV(unroll none) avoids): a storage-buffer array
/// element, read or written, whose index depends on the counter of a loop with
/// a constant bound that runs inside another loop with a constant bound — both
/// loops NVIDIA's compiler unrolls — following values through function calls
/// from main(). A loop has a constant bound when its counter starts at a
/// constant (or at the counter of an enclosing such loop: a constant once that
/// one is unrolled), its condition compares the counter with a constant and its
/// step is ++, -- or += / -= a constant.
std::vector<Finding> nested_unrolled_buffer_indices(const AstNode& root);

}  // namespace zenith::render::testing
