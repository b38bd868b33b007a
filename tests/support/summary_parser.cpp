#include "support/summary_parser.hpp"

#include <charconv>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rockcut::coupler {

namespace {

class Parser {
 public:
  Parser(std::string_view text, const std::string& source) : s_(text), source_(source) {}

  std::vector<std::pair<std::string, SummaryValue>> object() {
    std::vector<std::pair<std::string, SummaryValue>> entries;
    skip_ws();
    expect('{', "expected '{' to open the object");
    skip_ws();
    if (peek() == '}') {
      ++pos_;
    } else {
      while (true) {
        skip_ws();
        if (peek() != '"') error("expected a string key");
        std::string key = string();
        skip_ws();
        expect(':', "expected ':' after the key");
        skip_ws();
        entries.emplace_back(std::move(key), value());
        skip_ws();
        if (peek() == ',') {
          ++pos_;
        } else if (peek() == '}') {
          ++pos_;
          break;
        } else {
          error("expected ',' or '}'");
        }
      }
    }
    skip_ws();
    if (pos_ != s_.size()) error("unexpected content after the object");
    return entries;
  }

 private:
  [[noreturn]] void error(const std::string& problem) const { error_at(pos_, problem); }

  [[noreturn]] void error_at(std::size_t at, const std::string& problem) const {
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < at && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw std::runtime_error(source_ + ": line " + std::to_string(line) + ", column " +
                             std::to_string(column) + " (offset " + std::to_string(at) +
                             "): " + problem);
  }

  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
  bool at_end() const { return pos_ >= s_.size(); }

  void skip_ws() {
    while (!at_end() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' ||
                         s_[pos_] == '\r')) {
      ++pos_;
    }
  }

  void expect(char c, const char* problem) {
    if (at_end() || s_[pos_] != c) error(problem);
    ++pos_;
  }

  unsigned hex4() {
    if (s_.size() - pos_ < 4) error("truncated \\u escape");
    unsigned code = 0;
    const auto result = std::from_chars(s_.data() + pos_, s_.data() + pos_ + 4, code, 16);
    if (result.ec != std::errc() || result.ptr != s_.data() + pos_ + 4) {
      error("invalid \\u escape");
    }
    pos_ += 4;
    return code;
  }

  static void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xc0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xe0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    }
  }

  std::string string() {
    const std::size_t start = pos_;
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (at_end()) error_at(start, "unterminated string");
      const char c = s_[pos_];
      if (c == '"') {
        ++pos_;
        return out;
      }
      if (static_cast<unsigned char>(c) < 0x20) error("control character in string");
      if (c != '\\') {
        out += c;
        ++pos_;
        continue;
      }
      ++pos_;
      if (at_end()) error_at(start, "unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xdc00 && cp <= 0xdfff) error("unpaired low surrogate in \\u escape");
          if (cp >= 0xd800 && cp <= 0xdbff) {
            if (s_.substr(pos_, 2) != "\\u") error("unpaired high surrogate in \\u escape");
            pos_ += 2;
            const std::uint32_t low = hex4();
            if (low < 0xdc00 || low > 0xdfff) error("invalid low surrogate in \\u escape");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
          }
          append_utf8(out, cp);
          break;
        }
        default:
          --pos_;
          error(std::string("invalid escape '\\") + e + "'");
      }
    }
  }

  void literal(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) error("expected a value");
    pos_ += word.size();
  }

  bool digits() {
    const std::size_t start = pos_;
    while (!at_end() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
    return pos_ > start;
  }

  SummaryValue number() {
    const std::size_t start = pos_;
    if (peek() == '-') ++pos_;
    if (peek() == '0') {
      ++pos_;  // JSON forbids leading zeros such as 012
    } else if (!digits()) {
      error("invalid number");
    }
    bool is_double = false;
    if (peek() == '.') {
      ++pos_;
      if (!digits()) error("expected digits after '.'");
      is_double = true;
    }
    if (peek() == 'e' || peek() == 'E') {
      ++pos_;
      if (peek() == '+' || peek() == '-') ++pos_;
      if (!digits()) error("expected digits in the exponent");
      is_double = true;
    }
    const char* first = s_.data() + start;
    const char* last = s_.data() + pos_;
    if (is_double) {
      double value = 0.0;
      const auto result = std::from_chars(first, last, value);
      if (result.ec != std::errc() || result.ptr != last) error_at(start, "number out of range");
      return value;
    }
    std::int64_t value = 0;
    const auto result = std::from_chars(first, last, value);
    if (result.ec != std::errc() || result.ptr != last) error_at(start, "integer out of range");
    return value;
  }

  SummaryValue value() {
    switch (peek()) {
      case '"': return string();
      case 't': literal("true"); return SummaryValue(std::in_place_type<bool>, true);
      case 'f': literal("false"); return SummaryValue(std::in_place_type<bool>, false);
      case 'n': literal("null"); return std::numeric_limits<double>::quiet_NaN();
      case '{':
      case '[': error("nested objects and arrays are not supported");
      default:
        if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return number();
        error(at_end() ? "unexpected end of input" : "expected a value");
    }
  }

  std::string_view s_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

}  // namespace

std::vector<std::pair<std::string, SummaryValue>> parse_flat_json_object(
    std::string_view text, const std::string& source) {
  return Parser(text, source).object();
}

Summary read_summary(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw std::runtime_error(file.string() + ": read error");
  Summary summary;
  for (auto& [key, value] : parse_flat_json_object(buffer.str(), file.string())) {
    summary.set(key, std::move(value));
  }
  return summary;
}

}  // namespace rockcut::coupler
