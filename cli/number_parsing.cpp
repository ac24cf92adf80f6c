// Strict decimal parsing for command-line numbers and the CLI11 validators built on it
// (number_parsing.h says why CLI11's own conversion is not enough).
#include "cli/number_parsing.h"

#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "render/errors.h"

namespace pm::cli {

namespace {

// The user's text as quoted in a message: at most 40 characters, control characters shown as '?'.
std::string quoted(const std::string& text) {
  std::string shown = text.size() > 40 ? text.substr(0, 37) + "..." : text;
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return "'" + shown + "'";
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

std::string whole_range(const std::string& lo, const std::string& hi, bool unbounded) {
  return unbounded ? "a whole number >= " + lo : "a whole number from " + lo + " to " + hi;
}

// Reads digits into *value; false on no digits, a non-digit, or more than UINT64_MAX.
bool read_digits(const std::string& digits, uint64_t* value) {
  if (digits.empty()) return false;
  uint64_t v = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return false;
    const uint64_t d = uint64_t(c - '0');
    if (v > (UINT64_MAX - d) / 10) return false;
    v = v * 10 + d;
  }
  *value = v;
  return true;
}

// "" when text is acceptable (and *value set), else the reason, without the option's name.
std::string unsigned_problem(const std::string& text, uint64_t lo, uint64_t hi, uint64_t* value) {
  const std::string expected = "expected " + whole_range(std::to_string(lo), std::to_string(hi), hi == UINT64_MAX);
  if (!read_digits(text, value) || *value < lo || *value > hi) return expected + ", got " + quoted(text);
  return "";
}

std::string integer_problem(const std::string& text, int64_t lo, int64_t hi, int64_t* value) {
  const std::string expected =
      "expected " + whole_range(std::to_string(lo), std::to_string(hi), hi == INT64_MAX) + ", got " + quoted(text);
  const bool negative = !text.empty() && text[0] == '-';
  uint64_t magnitude = 0;
  if (!read_digits(negative ? text.substr(1) : text, &magnitude)) return expected;
  if (negative ? magnitude > uint64_t(INT64_MAX) + 1 : magnitude > uint64_t(INT64_MAX)) return expected;
  const int64_t v = negative ? int64_t(0 - magnitude) : int64_t(magnitude);
  if (v < lo || v > hi) return expected;
  *value = v;
  return "";
}

// Decimal syntax: [-+]digits[.digits][e[-+]digits], at least one digit before the exponent.
bool is_decimal_number(const std::string& text) {
  size_t i = 0, n = text.size();
  if (i < n && (text[i] == '-' || text[i] == '+')) ++i;
  size_t mantissa_digits = 0;
  while (i < n && text[i] >= '0' && text[i] <= '9') ++i, ++mantissa_digits;
  if (i < n && text[i] == '.') {
    ++i;
    while (i < n && text[i] >= '0' && text[i] <= '9') ++i, ++mantissa_digits;
  }
  if (mantissa_digits == 0) return false;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < n && (text[i] == '-' || text[i] == '+')) ++i;
    size_t exponent_digits = 0;
    while (i < n && text[i] >= '0' && text[i] <= '9') ++i, ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  return i == n;
}

// lo_open: lo itself is excluded (a positive number when lo is 0).
std::string finite_problem(const std::string& text, double lo, double hi, bool lo_open, double* value) {
  std::string expected;
  if (lo_open && lo == 0)
    expected = hi >= FLT_MAX ? "a positive finite number" : "a positive number up to " + number_text(hi);
  else if (lo <= -FLT_MAX && hi >= FLT_MAX)
    expected = "a finite number";
  else if (hi >= FLT_MAX)
    expected = "a finite number >= " + number_text(lo);
  else
    expected = "a number from " + number_text(lo) + " to " + number_text(hi);
  expected = "expected " + expected + ", got " + quoted(text);
  if (!is_decimal_number(text)) return expected;
  errno = 0;
  const double v = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(v) || v < lo || v > hi || (lo_open && v == lo)) return expected;
  *value = v;
  return "";
}

[[noreturn]] void refuse(const std::string& option, const std::string& problem) {
  throw InputError(option + ": " + problem);
}

}  // namespace

uint64_t parse_unsigned(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi) {
  uint64_t v = 0;
  const std::string problem = unsigned_problem(text, lo, hi, &v);
  if (!problem.empty()) refuse(option, problem);
  return v;
}

int64_t parse_integer(const std::string& option, const std::string& text, int64_t lo, int64_t hi) {
  int64_t v = 0;
  const std::string problem = integer_problem(text, lo, hi, &v);
  if (!problem.empty()) refuse(option, problem);
  return v;
}

double parse_finite(const std::string& option, const std::string& text, double lo, double hi) {
  double v = 0;
  const std::string problem = finite_problem(text, lo, hi, false, &v);
  if (!problem.empty()) refuse(option, problem);
  return v;
}

double parse_positive(const std::string& option, const std::string& text, double hi) {
  double v = 0;
  const std::string problem = finite_problem(text, 0, hi, true, &v);
  if (!problem.empty()) refuse(option, problem);
  return v;
}

// Each validator accepts the text, then hands CLI11 the canonical decimal it read, so CLI11's
// own conversion (which would read "010" as octal) sees exactly the accepted value.
CLI::Validator unsigned_in(uint64_t lo, uint64_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        uint64_t v = 0;
        std::string problem = unsigned_problem(text, lo, hi, &v);
        if (problem.empty()) text = std::to_string(v);
        return problem;
      },
      "", "unsigned_in");
}

CLI::Validator integer_in(int64_t lo, int64_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        int64_t v = 0;
        std::string problem = integer_problem(text, lo, hi, &v);
        if (problem.empty()) text = std::to_string(v);
        return problem;
      },
      "", "integer_in");
}

namespace {
CLI::Validator real_validator(double lo, double hi, bool lo_open) {
  return CLI::Validator(
      [lo, hi, lo_open](std::string& text) {
        double v = 0;
        std::string problem = finite_problem(text, lo, hi, lo_open, &v);
        if (problem.empty()) {
          char canonical[40];
          std::snprintf(canonical, sizeof(canonical), "%.17g", v);
          text = canonical;
        }
        return problem;
      },
      "", "finite_in");
}
}  // namespace

CLI::Validator finite_in(double lo, double hi) { return real_validator(lo, hi, false); }
CLI::Validator positive_in(double hi) { return real_validator(0, hi, true); }

}  // namespace pm::cli
