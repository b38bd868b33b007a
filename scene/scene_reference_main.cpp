// scene_reference [DESCRIPTOR_SET] [-o FILE] [--field-docs FILE]
// Prints the field reference of the scene schema (docs/scene_reference.md) as Markdown, from the
// descriptor set protoc writes with the proto comments. --field-docs also writes the field comments
// as C++ (scene/field_docs.cpp) for the loader's messages.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rockcut/options.pb.h"
#include "scene/format.hpp"

namespace {

namespace pb = google::protobuf;
using rockcut::scene::join;

constexpr const char* kRegenerate =
    "build/bin/scene_reference -o docs/scene_reference.md --field-docs scene/field_docs.cpp";

// Builds each file after its dependencies, whatever order the set lists them in.
const pb::FileDescriptor* build(const std::string& name,
                                const std::map<std::string, const pb::FileDescriptorProto*>& files,
                                pb::DescriptorPool& pool) {
  if (const pb::FileDescriptor* built = pool.FindFileByName(name)) return built;
  const auto file = files.find(name);
  if (file == files.end()) return nullptr;
  for (const std::string& dependency : file->second->dependency())
    if (build(dependency, files, pool) == nullptr) return nullptr;
  return pool.BuildFile(*file->second);
}

// The pool holds its own copy of options.proto, so its options may keep our extensions as unknown
// fields: a round trip through the generated FieldOptions makes GetExtension(rockcut::unit) work.
pb::FieldOptions options_of(const pb::FieldDescriptor& field) {
  pb::FieldOptions options;
  options.ParseFromString(field.options().SerializeAsString());
  return options;
}

// A leading comment on one line.
template <class Descriptor>
std::string comment_of(const Descriptor& descriptor) {
  pb::SourceLocation location;
  if (!descriptor.GetSourceLocation(&location)) return "";
  std::istringstream lines(location.leading_comments);
  std::vector<std::string> words;
  for (std::string word; lines >> word;) words.push_back(word);
  return join(words, " ");
}

std::string cell(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2))
    text.replace(at, 1, "\\|");
  return text;
}

std::string code(const std::string& text) { return "`" + text + "`"; }

// The section title of a message: its name within the package ("Time", "Outer.Inner").
std::string title_of(const pb::Descriptor& type) {
  const std::string& package = type.file()->package();
  return package.empty() ? type.full_name() : type.full_name().substr(package.size() + 1);
}

// GitHub's heading anchor: lower case, punctuation dropped.
std::string anchor_of(const pb::Descriptor& type) {
  std::string anchor;
  for (char c : title_of(type))
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')
      anchor += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return anchor;
}

// Messages of the root's package reachable from it, breadth first, root first.
std::vector<const pb::Descriptor*> reachable(const pb::Descriptor& root) {
  std::vector<const pb::Descriptor*> order{&root};
  std::set<const pb::Descriptor*> seen{&root};
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int f = 0; f < order[i]->field_count(); ++f) {
      const pb::Descriptor* type = order[i]->field(f)->message_type();
      if (type != nullptr && type->file()->package() == root.file()->package() && seen.insert(type).second)
        order.push_back(type);
    }
  return order;
}

// The schema files the reference comes from: those of the reachable messages, root's first.
std::vector<std::string> sources_of(const pb::Descriptor& root) {
  std::vector<std::string> files;
  for (const pb::Descriptor* type : reachable(root)) {
    std::string file = "proto/" + type->file()->name();
    if (std::find(files.begin(), files.end(), file) == files.end()) files.push_back(std::move(file));
  }
  return files;
}

std::string type_of(const pb::FieldDescriptor& field, const std::string& package) {
  std::string type = field.type_name();
  if (const pb::Descriptor* message = field.message_type())
    type = message->file()->package() == package
               ? std::string("[").append(title_of(*message)).append("](#" + anchor_of(*message) + ")")
               : code(message->full_name());
  else if (const pb::EnumDescriptor* enumeration = field.enum_type())
    type = code(enumeration->full_name());
  return field.is_repeated() ? std::string("repeated ").append(type) : type;
}

std::string default_of(const pb::FieldDescriptor& field) {
  if (!field.has_default_value()) return "";
  switch (field.cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_INT32: return std::to_string(field.default_value_int32());
    case pb::FieldDescriptor::CPPTYPE_INT64: return std::to_string(field.default_value_int64());
    case pb::FieldDescriptor::CPPTYPE_UINT32: return std::to_string(field.default_value_uint32());
    case pb::FieldDescriptor::CPPTYPE_UINT64: return std::to_string(field.default_value_uint64());
    case pb::FieldDescriptor::CPPTYPE_DOUBLE: return rockcut::scene::format_double(field.default_value_double());
    case pb::FieldDescriptor::CPPTYPE_FLOAT: return rockcut::scene::format_double(field.default_value_float());
    case pb::FieldDescriptor::CPPTYPE_BOOL: return field.default_value_bool() ? "true" : "false";
    case pb::FieldDescriptor::CPPTYPE_ENUM: return code(field.default_value_enum()->name());
    case pb::FieldDescriptor::CPPTYPE_STRING: return code("\"" + field.default_value_string() + "\"");
    case pb::FieldDescriptor::CPPTYPE_MESSAGE: break;
  }
  return "";
}

std::string allowed_of(const pb::FieldDescriptor& field, const pb::FieldOptions& options) {
  std::vector<std::string> values;
  if (options.HasExtension(rockcut::choices))
    for (const std::string& choice : rockcut::scene::split_choices(options.GetExtension(rockcut::choices)))
      values.push_back(code(choice));
  if (const pb::EnumDescriptor* enumeration = field.enum_type())
    for (int v = 0; v < enumeration->value_count(); ++v) values.push_back(code(enumeration->value(v)->name()));
  const std::string bounds = rockcut::scene::bounds_text(options);
  return bounds.empty() ? join(values, ", ") : bounds;
}

std::string field_row(const pb::FieldDescriptor& field) {
  const pb::FieldOptions options = options_of(field);
  std::string name = code(field.name());
  if (const pb::OneofDescriptor* oneof = field.real_containing_oneof())
    name += " (one of " + code(oneof->name()) + ")";
  const std::vector<std::string> cells{
      name,
      type_of(field, field.containing_type()->file()->package()),
      options.HasExtension(rockcut::unit) ? options.GetExtension(rockcut::unit) : "",
      default_of(field),
      allowed_of(field, options),
      options.GetExtension(rockcut::required) ? "yes" : "",
      comment_of(field)};
  std::vector<std::string> escaped;
  for (const std::string& c : cells) escaped.push_back(cell(c));
  return "| " + join(escaped, " | ") + " |\n";
}

std::string markdown(const pb::Descriptor& root) {
  std::string out =
      "# Scene file reference\n\n"
      "Generated from `" + join(sources_of(root), "`, `") + "` by `scene_reference`: do not edit by "
      "hand. After changing the schema, regenerate with\n`" + std::string(kRegenerate) + "`\n(a test fails while "
      "this file is out of date).\n\n"
      "A scene file (`*.pbtxt`) holds one `" + root.full_name() + "` in protobuf text format. Units are "
      "SI. The loader refuses values outside *allowed*, and a block that is present must give its "
      "*required* fields.\n";
  for (const pb::Descriptor* type : reachable(root)) {
    out += "\n## " + title_of(*type) + "\n\n";
    if (const std::string comment = comment_of(*type); !comment.empty()) out += comment + "\n\n";
    out += "| field | type | unit | default | allowed | required | description |\n"
           "|---|---|---|---|---|---|---|\n";
    for (int f = 0; f < type->field_count(); ++f) out += field_row(*type->field(f));
  }
  return out;
}

std::string cpp_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

std::string field_docs_cpp(const pb::Descriptor& root) {
  std::map<std::string, std::string> docs;  // sorted by full name, as field_doc() searches
  for (const pb::Descriptor* type : reachable(root))
    for (int f = 0; f < type->field_count(); ++f)
      if (std::string doc = comment_of(*type->field(f)); !doc.empty())
        docs[type->field(f)->full_name()] = std::move(doc);
  std::string out =
      "// Generated by scene_reference from " + join(sources_of(root), ", ") + ":\n"
      "// do not edit. Regenerate with\n"
      "//   " + std::string(kRegenerate) + "\n"
      "#include \"scene/field_docs.hpp\"\n\n#include <algorithm>\n#include <iterator>\n#include <utility>\n\n"
      "namespace rockcut::scene {\nnamespace {\n\n"
      "constexpr std::pair<std::string_view, std::string_view> kDocs[] = {\n";
  for (const auto& [name, doc] : docs) out += "    {" + cpp_string(name) + ",\n     " + cpp_string(doc) + "},\n";
  return out +
         "};\n\n}  // namespace\n\n"
         "std::string_view field_doc(std::string_view full_name) {\n"
         "  const auto* entry = std::lower_bound(std::begin(kDocs), std::end(kDocs), full_name,\n"
         "                                       [](const auto& e, std::string_view n) { return e.first < n; });\n"
         "  return entry != std::end(kDocs) && entry->first == full_name ? entry->second : std::string_view();\n"
         "}\n\n}  // namespace rockcut::scene\n";
}

bool write(const std::string& path, const std::string& text) {
  if (path.empty()) return static_cast<bool>(std::cout << text << std::flush);
  std::ofstream out(path, std::ios::binary);
  return static_cast<bool>(out << text);
}

int fail(const std::string& message) {
  std::cerr << "scene_reference: " << message << "\n";
  return 2;
}

// The descriptor set: an installation keeps it in ../share/rockcut/ beside bin/; a build tree
// reads it where protoc wrote it.
std::string default_descriptor_set() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path().parent_path() / "share" / "rockcut" / "scene_descriptor.pb";
    if (std::filesystem::is_regular_file(installed, ec)) return installed.string();
  }
  return ROCKCUT_SCENE_DESCRIPTOR_SET;
}

}  // namespace

int main(int argc, char** argv) {
  std::string set_path = default_descriptor_set(), output, field_docs;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "-o" || arg == "--field-docs") && i + 1 < argc) {
      (arg == "-o" ? output : field_docs) = argv[++i];
    } else if (arg == "-h" || arg == "--help") {
      std::cout << "usage: scene_reference [DESCRIPTOR_SET] [-o FILE] [--field-docs FILE]\n"
                   "Prints the scene field reference (Markdown); default set: "
                << default_descriptor_set() << "\n";
      return 0;
    } else if (!arg.empty() && arg[0] != '-') {
      set_path = arg;
    } else {
      return fail("unexpected argument \"" + arg + "\" (see --help)");
    }
  }

  pb::FileDescriptorSet set;
  std::ifstream in(set_path, std::ios::binary);
  if (!in || !set.ParseFromIstream(&in)) return fail("cannot read the descriptor set " + set_path);
  std::map<std::string, const pb::FileDescriptorProto*> files;
  for (const pb::FileDescriptorProto& file : set.file()) files[file.name()] = &file;
  pb::DescriptorPool pool;
  for (const auto& [name, file] : files)
    if (build(name, files, pool) == nullptr) return fail("cannot build " + name + " from " + set_path);
  const pb::Descriptor* scene = pool.FindMessageTypeByName("rockcut.Scene");
  if (scene == nullptr) return fail(set_path + " has no rockcut.Scene");

  if (!write(output, markdown(*scene))) return fail("cannot write " + output);
  if (!field_docs.empty() && !write(field_docs, field_docs_cpp(*scene)))
    return fail("cannot write " + field_docs);
  return 0;
}
