#pragma once
// Line-level reading of GLSL text, shared by the #define injection
// (shader_program.cpp) and the annotated compiler logs (shader_build.cpp).
// Internal to render/gl.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace zenith::render::gl::glsl_text {

/// The lines of `text`, without their '\n'.
std::vector<std::string_view> split_lines(std::string_view text);
/// `s` without leading and trailing white space.
std::string_view trim(std::string_view s);
/// The words of a preprocessor directive line ("#line 3 1" → {"line", "3", "1"}), or empty.
std::vector<std::string_view> directive_words(std::string_view line);
/// A non-negative decimal of at most 9 digits, or nothing.
std::optional<int> parse_int(std::string_view s);

/// A driver's info log with, under each message that names a (source string,
/// line) — "0:7(12): ..." (Mesa), "0(7) : ..." (NVIDIA), "ERROR: 0:7: ..."
/// (others) — that line of `compiled` (following its #line directives),
/// prefixed by the file that source-string number stands for in `files`.
std::string annotate_log(std::string_view log, std::string_view compiled, const std::vector<std::string>& files);

}  // namespace zenith::render::gl::glsl_text
