#include "scene/text_parser.hpp"

#include <google/protobuf/io/tokenizer.h>

#include <algorithm>
#include <cctype>
#include <deque>
#include <regex>
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

std::size_t char_index(const std::string& line, int column) {
  std::size_t i = 0;
  while (i < line.size() && display_column(line, i + 1) <= column) ++i;
  return i;
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

// Adds a did-you-mean (or the valid names) to the messages about a misspelled name, and moves
// every message about a named field to that name.
std::string friendly(const pb::Descriptor* root, const std::vector<std::string>& lines, RawError& error) {
  static const std::regex unknown_field(R"re(^Message type "([^"]+)" has no field named "([^"]+)"\.$)re");
  static const std::regex unknown_enum(R"re(^Unknown enumeration value of "([^"]+)" for field "([^"]+)"\.$)re");
  static const std::regex named_field(R"re(^(?:Non-repeated field|Field) "([^"]+)" is specified)re");
  // The hint replaces protobuf's final full stop.
  const std::string sentence = error.message.substr(0, error.message.size() - 1);
  std::smatch m;
  if (std::regex_match(error.message, m, unknown_field)) {
    point_at_name(lines, m[2], error);
    return sentence + name_hint(m[2].str(),
                                field_names(root->file()->pool()->FindMessageTypeByName(m[1])));
  }
  if (std::regex_match(error.message, m, unknown_enum)) {
    point_at_name(lines, m[1], error);
    return sentence + name_hint(m[1].str(), enum_value_names(root, m[2]));
  }
  if (std::regex_search(error.message, m, named_field)) point_at_name(lines, m[1], error);
  return error.message;
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
