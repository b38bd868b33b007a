#include "scene/scene_loader.hpp"

#include <google/protobuf/text_format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <tuple>

#include "scene/overrides.hpp"
#include "scene/text_parser.hpp"
#include "scene/validation.hpp"

namespace rockcut::scene {
namespace {

std::string join_lines(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics) text.append(text.empty() ? "" : "\n").append(d.to_string());
  return text;
}

}  // namespace

std::string Diagnostic::to_string() const {
  std::string where = file;
  if (line > 0) where.append(":").append(std::to_string(line));
  if (line > 0 && column > 0) where.append(":").append(std::to_string(column));
  return where.append(": ").append(message);
}

SceneError::SceneError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join_lines(diagnostics)), diagnostics_(std::move(diagnostics)) {}

std::string LoadedScene::effective_text() const {
  std::string text;
  google::protobuf::TextFormat::Printer().PrintToString(scene, &text);
  return text;
}

void parse_message(const std::string& text, const std::string& name,
                   const std::vector<std::string>& overrides, google::protobuf::Message& message) {
  google::protobuf::TextFormat::ParseInfoTree tree;
  TextParse parsed = parse_text(text, name, message, tree);
  std::vector<Diagnostic> diagnostics = std::move(parsed.errors);
  // After a syntax error the message is partial: its missing fields would only be noise.
  if (parsed.complete) {
    OverrideSites sites;
    for (Diagnostic& d : apply_overrides(overrides, message, sites)) diagnostics.push_back(std::move(d));
    for (Diagnostic& d : validate(message, name, &tree, sites)) diagnostics.push_back(std::move(d));
  }
  if (diagnostics.empty()) return;
  // Validation walks the schema's order; the user reads the file top to bottom, then the overrides.
  std::stable_sort(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    return std::tuple(a.file != name, a.line, a.column) < std::tuple(b.file != name, b.line, b.column);
  });
  throw SceneError(std::move(diagnostics));
}

LoadedScene parse_scene(const std::string& text, const std::string& name,
                        const std::vector<std::string>& overrides) {
  LoadedScene loaded;
  loaded.path = name;
  loaded.source_text = text;
  loaded.overrides = overrides;
  parse_message(text, name, overrides, loaded.scene);
  return loaded;
}

LoadedScene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  auto unreadable = [&](const std::string& why) {
    return SceneError({{path.string(), 0, 0, "cannot read the scene file: " + why}});
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw unreadable("it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw unreadable(std::strerror(errno));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw unreadable(std::strerror(errno));
  LoadedScene loaded = parse_scene(text, path.string(), overrides);
  loaded.path = path;
  return loaded;
}

}  // namespace rockcut::scene
