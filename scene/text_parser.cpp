#include "scene/text_parser.hpp"

#include <google/protobuf/io/tokenizer.h>

#include <algorithm>
#include <cctype>
#include <deque>
#include <set>
#include <sstream>

#include "scene/nearest_name.hpp"

namespace rockcut::scene {
namespace {

namespace pb = google::protobuf;

struct RawError {
  int line;  // 0-based, as protobuf reports
  int column;
  std::string message;
};

// With AllowUnknownField the parser skips unknown fields and reports them as warnings, so one run
// finds all of them; for a scene every warning is an error.
class Collector : public pb::io::ErrorCollector {
 public:
  void AddError(int line, int column, const std::string& message) override {
    errors.push_back({line, column, message});
  }
  void AddWarning(int line, int column, const std::string& message) override {
    errors.push_back({line, column, message});
  }
  std::vector<RawError> errors;
};

bool is_identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// The tokenizer counts a tab as advancing to the next multiple of 8 columns.
int display_column(const std::string& line, std::size_t index) {
  int column = 0;
  for (std::size_t i = 0; i < index && i < line.size(); ++i)
    column = line[i] == '\t' ? column + 8 - column % 8 : column + 1;
  return column;
}

// The index of the character at display `column` (one pass: a long line costs O(length)).
std::size_t char_index(const std::string& line, int column) {
  int at = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const int next = line[i] == '\t' ? at + 8 - at % 8 : at + 1;
    if (next > column) return i;
    at = next;
  }
  return line.size();
}

// Protobuf reports some errors at the token after the name they are about (the ':' after an unknown
// field, the line after a bad enum value): move the position back to the name itself.
void point_at_name(const std::vector<std::string>& lines, const std::string& name, RawError& error) {
  for (int l = std::min<int>(error.line, static_cast<int>(lines.size()) - 1); l >= 0; --l) {
    const std::string& line = lines[l];
    std::size_t end = l == error.line ? char_index(line, error.column) : line.size();
    while (end >= name.size()) {
      const std::size_t start = line.rfind(name, end - name.size());
      if (start == std::string::npos) break;
      const std::size_t after = start + name.size();
      if ((start == 0 || !is_identifier_char(line[start - 1])) &&
          (after >= line.size() || !is_identifier_char(line[after]))) {
        error.line = l;
        error.column = display_column(line, start);
        return;
      }
      if (start == 0) break;
      end = start + name.size() - 1;
    }
  }
}

std::vector<std::string> field_names(const pb::Descriptor* type) {
  std::vector<std::string> names;
  for (int i = 0; type != nullptr && i < type->field_count(); ++i)
    names.push_back(type->field(i)->name());
  return names;
}

// Protobuf names only the field, not its message: gather the values of every enum field of that
// name reachable from the root.
std::vector<std::string> enum_value_names(const pb::Descriptor* root, const std::string& field_name) {
  std::vector<std::string> names;
  std::set<const pb::Descriptor*> seen{root};
  std::deque<const pb::Descriptor*> queue{root};
  for (; !queue.empty(); queue.pop_front()) {
    for (int i = 0; i < queue.front()->field_count(); ++i) {
      const pb::FieldDescriptor* field = queue.front()->field(i);
      if (field->message_type() != nullptr && seen.insert(field->message_type()).second)
        queue.push_back(field->message_type());
      if (field->enum_type() != nullptr && field->name() == field_name)
        for (int v = 0; v < field->enum_type()->value_count(); ++v)
          names.push_back(field->enum_type()->value(v)->name());
    }
  }
  return names;
}

// Matches `text` against `pattern`, where each '*' stands for a quoted name ("..." without a
// quote inside) that goes into `names`. Plain string scanning: no regular expression, whose
// backtracking recursion a 50,000-character name would overflow.
bool match_quoted(const std::string& text, const std::string& pattern, bool whole,
                  std::vector<std::string>& names) {
  names.clear();
  std::size_t t = 0;
  for (std::size_t p = 0; p < pattern.size(); ++p) {
    if (pattern[p] != '*') {
      if (t >= text.size() || text[t] != pattern[p]) return false;
      ++t;
      continue;
    }
    const std::size_t end = text.find('"', t);
    if (end == std::string::npos || end == t) return false;
    names.push_back(text.substr(t, end - t));
    t = end;
  }
  return !whole || t == text.size();
}

// Adds a did-you-mean (or the valid names) to the messages about a misspelled name, and moves
// every message about a named field to that name.
std::string friendly(const pb::Descriptor* root, const std::vector<std::string>& lines, RawError& error) {
  // The hint replaces protobuf's final full stop.
  const std::string sentence = error.message.substr(0, error.message.size() - 1);
  std::vector<std::string> m;
  if (match_quoted(error.message, "Message type \"*\" has no field named \"*\".", true, m)) {
    point_at_name(lines, m[1], error);
    return sentence +
           name_hint(m[1], field_names(root->file()->pool()->FindMessageTypeByName(m[0])));
  }
  if (match_quoted(error.message, "Unknown enumeration value of \"*\" for field \"*\".", true, m)) {
    point_at_name(lines, m[0], error);
    return sentence + name_hint(m[0], enum_value_names(root, m[1]));
  }
  if (match_quoted(error.message, "Non-repeated field \"*\" is specified", false, m) ||
      match_quoted(error.message, "Field \"*\" is specified", false, m)) {
    point_at_name(lines, m[0], error);
  }
  return error.message;
}

// Protobuf's parser skips an unknown field's message by recursion, without the depth limit it keeps
// for known ones: a scene nested deeper than this is refused before it is parsed.
constexpr int kMaxNesting = 64;

// The first place where `text` opens its (kMaxNesting + 1)-th nested block, outside strings and
// comments, as a 0-based (line, column); (-1, -1) if it never does.
std::pair<int, int> too_deep(const std::string& text) {
  int depth = 0, line = 0, column = 0;
  char quote = 0;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      column = 0;
      comment = false;
      quote = 0;  // a string does not span lines in the text format
      continue;
    }
    if (comment) {
    } else if (quote) {
      if (c == '\\') {
        ++i;
        ++column;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '#') {
      comment = true;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '{' || c == '<') {
      if (++depth > kMaxNesting) return {line, column};
    } else if ((c == '}' || c == '>') && depth > 0) {
      --depth;
    }
    ++column;
  }
  return {-1, -1};
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TextParse parse_text(const std::string& text, const std::string& name, pb::Message& message,
                     pb::TextFormat::ParseInfoTree& tree) {
  if (const auto [line, column] = too_deep(text); line >= 0) {
    TextParse refused;
    refused.complete = false;
    refused.errors.push_back({name, line + 1, column + 1,
                              "blocks nested more than " + std::to_string(kMaxNesting) +
                                  " deep; a scene needs a few levels"});
    return refused;
  }
  Collector collector;
  pb::TextFormat::Parser parser;
  parser.RecordErrorsTo(&collector);
  parser.WriteLocationsTo(&tree);
  parser.AllowUnknownField(true);
  TextParse result;
  result.complete = parser.ParseFromString(text, &message);

  const std::vector<std::string> lines = split_lines(text);
  for (RawError& error : collector.errors) {
    std::string message_text = friendly(message.GetDescriptor(), lines, error);
    result.errors.push_back({name, error.line + 1, error.column + 1, std::move(message_text)});
  }
  return result;
}

}  // namespace rockcut::scene
