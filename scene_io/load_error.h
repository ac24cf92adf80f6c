// Owns the one way scene_io reports bad input: a pm::InputError whose message is a single line
// "<where>: <what>", where <where> is a file plus a line number or a field path. Every loader in
// scene_io throws through here so the command line can print the message as-is.
#pragma once

#include <string>

#include "render/errors.h"

namespace pm {

// Messages quote user text (JSON keys, OBJ material names, frame lists) that may contain line
// breaks or other control characters; the CLI prints one line per error, so those are escaped
// (\n, \r, \t, \xNN) rather than passed through to the terminal.
inline std::string single_line(const std::string& text) {
  static const char hex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

[[noreturn]] inline void throw_input_error(const std::string& where, const std::string& what) {
  throw InputError(single_line(where.empty() ? what : where + ": " + what));
}

// "<file>: line <n>" — the <where> for errors tied to a line of a text file.
inline std::string file_line(const std::string& file, size_t line) {
  return file + ": line " + std::to_string(line);
}

}  // namespace pm
