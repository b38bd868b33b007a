#include "scene/scene_loader.hpp"

#include <google/protobuf/text_format.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <tuple>

#include "scene/overrides.hpp"
#include "scene/source_map.hpp"
#include "scene/text_parser.hpp"
#include "scene/validation.hpp"

namespace rockcut::scene {
namespace {

namespace fs = std::filesystem;

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

namespace {

namespace pb = google::protobuf;

// The largest scene or base file read: the shipped scenes are under 5 kB.
constexpr std::uintmax_t kMaxSceneFileBytes = 4u << 20;  // 4 MiB

std::string read_file(const fs::path& path, std::string& error) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    error = "it is a directory";
    return {};
  }
  // A scene is a text file of kilobytes: a device (/dev/zero), a FIFO or a socket would be read
  // without end, and a huge file whole, so each is refused before a byte is read. The size is
  // checked again while reading, for a file that grows.
  const fs::file_status status = fs::status(path, ec);
  if (!ec && status.type() != fs::file_type::regular) {
    error = "it is not a regular file (a device, a pipe or a socket): a scene is a text file";
    return {};
  }
  if (!ec) {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxSceneFileBytes) {
      error = "it is " + std::to_string(size) + " bytes, more than a scene's limit of " +
              std::to_string(kMaxSceneFileBytes);
      return {};
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = std::strerror(errno);
    return {};
  }
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxSceneFileBytes) {
      error = "it grew past a scene's limit of " + std::to_string(kMaxSceneFileBytes) + " bytes";
      return {};
    }
  }
  if (in.bad()) error = std::strerror(errno);
  return text;
}

fs::path identity(const fs::path& path) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  return ec ? path.lexically_normal() : canonical;
}

// One file of a scene and, through its `base:` field, the files it starts from.
class Composer {
 public:
  explicit Composer(const pb::FieldDescriptor* base_field) : base_field_(base_field) {}

  // Parses `text` (the file `name`) into `message` with its bases laid under it, and the map of
  // where each value was written. `chain` holds the files that led here, for refusing a cycle.
  std::unique_ptr<SourceMap> compose(const std::string& text, const std::string& name, pb::Message& message,
                                     std::vector<fs::path> chain) {
    files.push_back(name);
    pb::TextFormat::ParseInfoTree tree;
    TextParse parsed = parse_text(text, name, message, tree);
    complete = complete && parsed.complete;
    for (Diagnostic& d : parsed.errors) diagnostics.push_back(std::move(d));
    std::unique_ptr<SourceMap> map = source_map(message, tree, name);
    const pb::Reflection& r = *message.GetReflection();
    if (base_field_ == nullptr || !r.HasField(message, base_field_)) return map;

    const std::string base = r.GetString(message, base_field_);
    const Location* at = map->find(base_field_, -1);
    const Location here = at ? *at : Location{name, 1, 1};
    auto report = [&](const std::string& why) {
      diagnostics.push_back({here.file, here.line, here.column, "base \"" + base + "\": " + why});
      complete = false;
    };
    if (base.empty()) {
      report("give the path of a scene file, relative to this one");
      return map;
    }
    const fs::path path = (fs::path(name).parent_path() / base).lexically_normal();
    chain.push_back(identity(name));
    if (std::find(chain.begin(), chain.end(), identity(path)) != chain.end()) {
      std::string cycle;
      for (const fs::path& p : chain) cycle += p.filename().string() + " -> ";
      report("the bases form a cycle (" + cycle + path.filename().string() +
             "); a scene cannot start from itself");
      return map;
    }
    std::string error;
    const std::string base_text = read_file(path, error);
    if (!error.empty()) {
      report("cannot read " + path.string() + ": " + error);
      return map;
    }

    std::unique_ptr<pb::Message> under(message.New());
    std::unique_ptr<SourceMap> under_map = compose(base_text, path.string(), *under, std::move(chain));
    overlay(*under, *under_map, message, *map);
    r.Swap(&message, under.get());
    r.ClearField(&message, base_field_);
    under_map->fields.erase(base_field_);
    return under_map;
  }

  std::vector<Diagnostic> diagnostics;
  std::vector<std::string> files;  // the scene's file first, then its bases in order
  bool complete = true;

 private:
  const pb::FieldDescriptor* base_field_;
};

void parse_composed(const std::string& text, const std::string& name, const std::vector<std::string>& overrides,
                    pb::Message& message, const pb::FieldDescriptor* base_field) {
  Composer composer(base_field);
  std::unique_ptr<SourceMap> map = composer.compose(text, name, message, {});
  std::vector<Diagnostic> diagnostics = std::move(composer.diagnostics);
  // After a syntax error the message is partial: its missing fields would only be noise.
  if (composer.complete) {
    // The bases are merged by now: a base named on the command line would be silently ignored.
    for (std::size_t k = 0; k < overrides.size(); ++k)
      if (base_field != nullptr && overrides[k].rfind(base_field->name() + "=", 0) == 0)
        diagnostics.push_back({"--set", static_cast<int>(k) + 1, 1,
                               "\"" + base_field->name() + "\" cannot be overridden: write `" +
                                   base_field->name() + ": \"FILE\"` in the scene file"});
    OverrideSites sites;
    for (Diagnostic& d : apply_overrides(overrides, message, sites)) diagnostics.push_back(std::move(d));
    for (Diagnostic& d : validate(message, name, map.get(), sites)) diagnostics.push_back(std::move(d));
  }
  if (diagnostics.empty()) return;
  // Validation walks the schema's order; the user reads the file top to bottom, then its bases, then
  // the overrides.
  auto rank = [&](const std::string& file) {
    const auto it = std::find(composer.files.begin(), composer.files.end(), file);
    return static_cast<std::size_t>(it - composer.files.begin());
  };
  std::stable_sort(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    return std::tuple(rank(a.file), a.line, a.column) < std::tuple(rank(b.file), b.line, b.column);
  });
  throw SceneError(std::move(diagnostics));
}

}  // namespace

void parse_message(const std::string& text, const std::string& name,
                   const std::vector<std::string>& overrides, google::protobuf::Message& message) {
  parse_composed(text, name, overrides, message, nullptr);
}

LoadedScene parse_scene(const std::string& text, const std::string& name,
                        const std::vector<std::string>& overrides) {
  LoadedScene loaded;
  loaded.path = name;
  loaded.source_text = text;
  loaded.overrides = overrides;
  parse_composed(text, name, overrides, loaded.scene, rockcut::Scene::descriptor()->FindFieldByName("base"));
  return loaded;
}

LoadedScene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  std::string error;
  const std::string text = read_file(path, error);
  if (!error.empty()) throw SceneError({{path.string(), 0, 0, "cannot read the scene file: " + error}});
  LoadedScene loaded = parse_scene(text, path.string(), overrides);
  loaded.path = path;
  return loaded;
}

}  // namespace rockcut::scene
