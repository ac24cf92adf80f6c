// Strict reading of the numbers the command line takes. CLI11 on its own reads "0x100" as 256,
// "010" as 8 and "-1" into an unsigned option as 18446744073709551615, and its range messages
// print the type's limits with 300 digits. Here a number is plain decimal, in range, and finite;
// every refusal is one short sentence that names the option.
//
// Each type has a parse function (for options read by hand, e.g. --resolution) and a CLI11
// validator built on it, applied where an option is registered, with transform() (not check()).
// The command line checks the text is a number of the option's type; the library's settings
// validation (SettingError) checks the range, so each range is stated once:
//     cmd->add_option("--photons", settings.photons, "...")->transform(any_unsigned64());
// The validators rewrite the text to the canonical decimal they accepted ("010" -> "10"), so
// CLI11's own conversion afterwards, which reads a leading 0 as octal, sees exactly that value;
// check() would hand CLI11 the original text.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <limits>
#include <string>

namespace pm::cli {

// Digits only (leading zeros are decimal: "007" is 7), within [lo, hi]. No sign, no blanks,
// no hex or octal, nothing after the digits. Throws InputError "<option>: expected ...".
uint64_t parse_unsigned(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi);

// As parse_unsigned, with an optional leading '-'.
int64_t parse_integer(const std::string& option, const std::string& text, int64_t lo, int64_t hi);

// A decimal number (optional sign, digits, optional fraction and exponent: "1.5e-3"), finite and
// within [lo, hi]. "inf", "nan", hex floats and trailing text are refused.
double parse_finite(const std::string& option, const std::string& text, double lo, double hi);
// As parse_finite, but greater than 0 (lo excluded).
double parse_positive(const std::string& option, const std::string& text, double hi);

// The same checks as validators for CLI11 options (the option's name prefixes the message).
CLI::Validator unsigned_in(uint64_t lo, uint64_t hi);
CLI::Validator integer_in(int64_t lo, int64_t hi);
CLI::Validator finite_in(double lo, double hi);
// Finite, greater than 0 and at most hi.
CLI::Validator positive_in(double hi);

// Shorthands for the common cases.
inline CLI::Validator any_unsigned32() { return unsigned_in(0, std::numeric_limits<uint32_t>::max()); }
inline CLI::Validator any_unsigned64() { return unsigned_in(0, std::numeric_limits<uint64_t>::max()); }
inline CLI::Validator any_int32() {
  return integer_in(std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max());
}
inline CLI::Validator finite_float() {
  return finite_in(-double(std::numeric_limits<float>::max()), double(std::numeric_limits<float>::max()));
}
inline CLI::Validator non_negative_float() { return finite_in(0, double(std::numeric_limits<float>::max())); }
inline CLI::Validator positive_float() { return positive_in(double(std::numeric_limits<float>::max())); }

}  // namespace pm::cli
