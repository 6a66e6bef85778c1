#include "tests/render/glsl_ast.h"

#include <fmt/format.h>

#include <map>
#include <set>
#include <stdexcept>
#include <utility>

namespace zenith::render::testing {

std::string_view AstNode::head() const {
  const std::string_view t = text;
  // The type is the last top-level "( ... )"; function names ("f(vd4;i1;") hold
  // an unbalanced '(' of their own, so scan from the end.
  if (t.empty() || t.back() != ')') return t;
  int depth = 0;
  for (std::size_t i = t.size(); i-- > 0;) {
    if (t[i] == ')') ++depth;
    if (t[i] == '(' && --depth == 0) {
      std::string_view h = t.substr(0, i);
      while (!h.empty() && h.back() == ' ') h.remove_suffix(1);
      return h;
    }
  }
  return t;
}

std::string_view AstNode::type() const {
  const std::string_view h = head();
  if (h.size() == text.size()) return {};
  std::string_view t = std::string_view(text).substr(h.size());
  while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
  return t.substr(1, t.size() - 2);
}

namespace {

int parse_location_part(std::string_view s) {
  if (s == "?" || s.empty()) return -1;
  int v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return -1;
    v = v * 10 + (c - '0');
  }
  return v;
}

/// "S:L<spaces>text" → (source, line, depth, text), or false for other lines.
bool parse_line(std::string_view l, int& source, int& line, int& depth, std::string& text) {
  const std::size_t colon = l.find(':');
  const std::size_t space = l.find(' ');
  if (colon == std::string_view::npos || space == std::string_view::npos || colon > space) return false;
  const std::string_view s = l.substr(0, colon), n = l.substr(colon + 1, space - colon - 1);
  if ((s != "?" && parse_location_part(s) < 0) || (n != "?" && parse_location_part(n) < 0)) return false;
  std::size_t first = space;
  while (first < l.size() && l[first] == ' ') ++first;
  source = parse_location_part(s);
  line = parse_location_part(n);
  depth = static_cast<int>(first - space) / 2;
  text = std::string(l.substr(first));
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  return true;
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool contains(std::string_view s, std::string_view part) { return s.find(part) != std::string_view::npos; }

/// The symbol name of a node "'name' ( ... )", or empty.
std::string_view symbol(const AstNode& n) {
  const std::string_view h = n.head();
  if (h.size() >= 2 && h.front() == '\'' && h.back() == '\'') return h.substr(1, h.size() - 2);
  return {};
}

bool is_write(std::string_view head) {
  return head == "move second child to first child" || contains(head, " second child into first child") ||
         head == "Pre-Increment" || head == "Post-Increment" || head == "Pre-Decrement" || head == "Post-Decrement";
}

bool is_double_vector(std::string_view type) {
  return contains(type, "-component vector of double") && !contains(type, "array of") && !contains(type, "matrix");
}

std::string_view call_name(const AstNode& n) {
  const std::string_view h = n.head();
  constexpr std::string_view call = "Function Call: ";
  return starts_with(h, call) ? h.substr(call.size()) : std::string_view{};
}

/// Function definitions by mangled name ("f(vd4;i1;").
std::map<std::string, const AstNode*, std::less<>> functions(const AstNode& root) {
  std::map<std::string, const AstNode*, std::less<>> out;
  constexpr std::string_view definition = "Function Definition: ";
  for (const AstNode& f : root.children)
    if (starts_with(f.head(), definition)) out.emplace(std::string(f.head().substr(definition.size())), &f);
  return out;
}

const AstNode* child_with_head(const AstNode& n, std::string_view head) {
  for (const AstNode& c : n.children)
    if (c.head() == head || starts_with(c.text, head)) return &c;
  return nullptr;
}

/// The parameters of a function definition: (name, written: out or inout).
std::vector<std::pair<std::string, bool>> parameters(const AstNode& definition) {
  std::vector<std::pair<std::string, bool>> out;
  if (const AstNode* p = child_with_head(definition, "Function Parameters:"))
    for (const AstNode& c : p->children) {
      const std::string_view t = c.type();
      out.emplace_back(std::string(symbol(c)), starts_with(t, " out ") || starts_with(t, " inout "));
    }
  return out;
}

// ------------------------------------------------------------ rule 1

void check_lvalue(const AstNode& target, std::vector<Finding>& out) {
  const AstNode* n = &target;
  while (!n->children.empty()) {
    const std::string_view h = n->head();
    if (h == "indirect index" && is_double_vector(n->children[0].type())) {
      out.push_back({n->source,
                     n->line,
                     fmt::format("{} ({}) written at a non-constant index", n->children[0].head(),
                                 n->children[0].type().substr(n->children[0].type().find_first_not_of(' '))),
                     {},
                     {}});
    }
    if (h != "indirect index" && h != "direct index" && h != "vector swizzle" && !starts_with(h, "direct index for"))
      break;
    n = &n->children[0];
  }
}

void find_writes(const AstNode& n, const std::map<std::string, const AstNode*, std::less<>>& fns,
                 std::vector<Finding>& out) {
  const std::string_view h = n.head();
  if (is_write(h) && !n.children.empty()) check_lvalue(n.children[0], out);
  if (const std::string_view name = call_name(n); !name.empty()) {
    if (auto it = fns.find(name); it != fns.end()) {
      const auto params = parameters(*it->second);
      for (std::size_t i = 0; i < params.size() && i < n.children.size(); ++i)
        if (params[i].second) check_lvalue(n.children[i], out);
    }
  }
  if ((h == "modf" || h == "frexp") && n.children.size() == 2) check_lvalue(n.children[1], out);
  for (const AstNode& c : n.children) find_writes(c, fns, out);
}

// ------------------------------------------------------------ rule 2

/// Loop counters and the values that depend on them, through function calls from main().
class UnrolledLoopWalk {
 public:
  explicit UnrolledLoopWalk(const AstNode& root) : functions_(functions(root)) {}

  std::vector<Finding> run() {
    if (auto it = functions_.find("main("); it != functions_.end()) walk_function(*it->second, {});
    return std::move(findings_);
  }

 private:
  using Taint = std::set<int>;  // ids of the loops whose counters a value depends on
  struct Loop {
    int id;
    bool constant_bound;
    std::string counter;
  };
  struct Frame {
    std::map<std::string, Taint, std::less<>> values;
    std::string function;
  };

  void walk_function(const AstNode& definition, std::vector<Taint> arguments) {
    const auto params = parameters(definition);
    // The same function with the same dependences in the same loop nest adds nothing new.
    std::string key(definition.head());
    for (const Loop& l : loops_) key += l.constant_bound ? "C" : "v";
    for (const Taint& t : arguments) {
      key += '|';
      for (int id : t) key += fmt::format("{},", id);
    }
    if (!visited_.insert(key).second) return;
    frames_.emplace_back();
    frames_.back().function = std::string(definition.head().substr(definition.head().find(':') + 2));
    frames_.back().function.erase(frames_.back().function.find('('));
    for (std::size_t i = 0; i < params.size() && i < arguments.size(); ++i)
      frames_.back().values[params[i].first] = arguments[i];
    for (const AstNode& c : definition.children)
      if (c.head() != "Function Parameters:") walk(c);
    frames_.pop_back();
  }

  Taint taint_of(const AstNode& n) const {
    Taint t;
    collect_taint(n, t);
    return t;
  }
  void collect_taint(const AstNode& n, Taint& t) const {
    if (const std::string_view s = symbol(n); !s.empty()) {
      if (auto it = frames_.back().values.find(s); it != frames_.back().values.end())
        t.insert(it->second.begin(), it->second.end());
      return;
    }
    for (const AstNode& c : n.children) collect_taint(c, t);
  }

  /// The variable an l-value writes ('x', x[i], x.y → x).
  static std::string_view written_symbol(const AstNode& n) {
    const AstNode* p = &n;
    while (symbol(*p).empty() && !p->children.empty()) p = &p->children[0];
    return symbol(*p);
  }

  /// The counter of a loop node when its bound is a constant ("i < 8", step ++i), else empty.
  static std::string constant_bound_counter(const AstNode& loop) {
    const AstNode* condition = nullptr;
    const AstNode* step = nullptr;
    for (std::size_t i = 0; i + 1 < loop.children.size(); ++i) {
      if (loop.children[i].head() == "Loop Condition") condition = &loop.children[i + 1];
      if (loop.children[i].head() == "Loop Terminal Expression") step = &loop.children[i + 1];
    }
    if (!condition || !step || !starts_with(condition->head(), "Compare") || condition->children.size() != 2) return {};
    std::string counter;
    for (int k = 0; k < 2; ++k) {
      const AstNode& a = condition->children[k];
      const AstNode& b = condition->children[1 - k];
      if (!symbol(a).empty() && b.head() == "Constant:") counter = std::string(symbol(a));
    }
    if (counter.empty()) return {};
    const std::string_view s = step->head();
    const bool unit_step =
        (s == "Pre-Increment" || s == "Post-Increment" || s == "Pre-Decrement" || s == "Post-Decrement") &&
        !step->children.empty() && symbol(step->children[0]) == counter;
    const bool constant_step =
        (s == "add second child into first child" || s == "subtract second child into first child") &&
        step->children.size() == 2 && symbol(step->children[0]) == counter && step->children[1].head() == "Constant:";
    return unit_step || constant_step ? counter : std::string{};
  }

  /// "table: direct index for structure" → "table".
  static std::string_view buffer_name(const AstNode& n) {
    const std::string_view h = n.head();
    return h.substr(0, h.find(':'));
  }

  void check_buffer_index(const AstNode& access) {
    if (access.children.size() != 2) return;
    const std::string_view base = access.children[0].type();
    if (!contains(base, " buffer ") || !contains(base, "array of")) return;
    const Taint t = taint_of(access.children[1]);
    for (std::size_t i = 0; i < loops_.size(); ++i) {
      if (!loops_[i].constant_bound || !t.contains(loops_[i].id)) continue;
      for (std::size_t j = 0; j < i; ++j)
        if (loops_[j].constant_bound) {
          const std::string where = fmt::format("{}:{}", access.source, access.line);
          const std::string buffer(buffer_name(access.children[0]));
          if (reported_.insert(where).second)
            findings_.push_back({access.source, access.line,
                                 fmt::format("storage buffer '{}' indexed by the counter of a constant-bound loop "
                                             "inside another one, in {}()",
                                             buffer, frames_.back().function),
                                 frames_.back().function, buffer});
          return;
        }
    }
  }

  /// Whether `e` is a constant once the enclosing constant-bound loops are unrolled:
  /// constants, their counters and arithmetic of those.
  bool unroll_constant(const AstNode& e) const {
    if (e.head() == "Constant:") return true;
    if (const std::string_view s = symbol(e); !s.empty()) {
      for (const Loop& l : loops_)
        if (l.constant_bound && l.counter == s) return true;
      return false;
    }
    if (starts_with(e.head(), "Function Call") || e.children.empty()) return false;
    for (const AstNode& c : e.children)
      if (!unroll_constant(c)) return false;
    return true;
  }

  /// The initial value of `counter` in the statement before its loop
  /// ("Sequence" of "move second child to first child" 'counter' value), or null.
  static const AstNode* initial_value(const AstNode* before, std::string_view counter) {
    if (before == nullptr || before->head() != "Sequence") return nullptr;
    for (const AstNode& c : before->children)
      if (c.head() == "move second child to first child" && c.children.size() == 2 && symbol(c.children[0]) == counter)
        return &c.children[1];
    return nullptr;
  }

  void walk_loop(const AstNode& loop, const AstNode* before) {
    const int id = next_loop_id_++;
    std::string counter = constant_bound_counter(loop);
    // Unrolled only when it starts at a constant too (possibly an outer unrolled counter).
    if (!counter.empty()) {
      const AstNode* init = initial_value(before, counter);
      if (init == nullptr || !unroll_constant(*init)) counter.clear();
    }
    if (!counter.empty()) frames_.back().values[counter].insert(id);
    loops_.push_back({id, !counter.empty(), counter});
    for (const AstNode& c : loop.children) walk(c);
    loops_.pop_back();
  }

  void walk(const AstNode& n) {
    const std::string_view h = n.head();
    for (std::size_t i = 0; i < n.children.size(); ++i) {
      const AstNode& c = n.children[i];
      if (starts_with(c.head(), "Loop with condition"))
        walk_loop(c, i > 0 ? &n.children[i - 1] : nullptr);
      else
        walk(c);
    }
    if (is_write(h) && !n.children.empty()) {
      // A value assigned from one that depends on a counter depends on it too (flow-insensitive).
      Taint t;
      for (const AstNode& c : n.children) collect_taint(c, t);
      const std::string_view target = written_symbol(n.children[0]);
      if (!target.empty() && !t.empty()) frames_.back().values[std::string(target)].insert(t.begin(), t.end());
    }
    if (h == "indirect index") check_buffer_index(n);
    if (const std::string_view name = call_name(n); !name.empty())
      if (auto it = functions_.find(name); it != functions_.end()) {
        std::vector<Taint> arguments;
        for (const AstNode& c : n.children) arguments.push_back(taint_of(c));
        walk_function(*it->second, std::move(arguments));
      }
  }

  std::map<std::string, const AstNode*, std::less<>> functions_;
  std::vector<Frame> frames_;
  std::vector<Loop> loops_;
  int next_loop_id_ = 0;
  std::set<std::string> visited_, reported_;
  std::vector<Finding> findings_;
};

}  // namespace

AstNode parse_glslang_ast(std::string_view listing) {
  std::vector<AstNode*> stack;  // stack[d]: the last node at depth d
  AstNode root;
  bool started = false;
  while (!listing.empty()) {
    const std::size_t newline = listing.find('\n');
    const std::string_view l = listing.substr(0, newline);
    listing.remove_prefix(newline == std::string_view::npos ? listing.size() : newline + 1);
    int source = 0, line = 0, depth = 0;
    std::string text;
    if (!parse_line(l, source, line, depth, text)) continue;
    if (!started) {
      if (text != "Sequence" || depth != 0) continue;
      started = true;
      root.source = source;
      root.line = line;
      root.text = text;
      stack = {&root};
      continue;
    }
    if (depth < 1 || static_cast<std::size_t>(depth) > stack.size())
      throw std::runtime_error(fmt::format("glslang AST: unexpected depth {} at '{}'", depth, l));
    stack.resize(static_cast<std::size_t>(depth));
    AstNode& parent = *stack.back();
    parent.children.push_back(AstNode{source, line, std::move(text), {}});
    stack.push_back(&parent.children.back());
  }
  if (!started) throw std::runtime_error("glslang AST: no tree in the listing");
  return root;
}

std::vector<Finding> double_vector_index_writes(const AstNode& root) {
  std::vector<Finding> out;
  find_writes(root, functions(root), out);
  return out;
}

std::vector<Finding> nested_unrolled_buffer_indices(const AstNode& root) { return UnrolledLoopWalk(root).run(); }

}  // namespace zenith::render::testing
