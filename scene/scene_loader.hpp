// Loading a scene file: protobuf text format, checked against proto/rockcut/scene.proto and its
// field options (required, min, max, greater_than, choices). Every problem found is reported with
// FILE:LINE:COL before anything starts.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcut/scene.pb.h"

namespace rockcut::scene {

/// One problem in a scene, located in the file (or in a --set override).
struct Diagnostic {
  std::string file;  ///< scene path, or "--set" for an override
  int line = 0;      ///< 1-based; 0 when unknown
  int column = 0;    ///< 1-based; 0 when unknown
  std::string message;
  /// "FILE:LINE:COL: message"
  std::string to_string() const;
};

/// Thrown when a scene has one or more problems; what() is every diagnostic, one per line.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

/// A parsed, overridden and validated scene.
struct LoadedScene {
  rockcut::Scene scene;
  std::filesystem::path path;
  std::string source_text;             ///< the file as written
  std::vector<std::string> overrides;  ///< the --set arguments applied, in order
  /// The effective scene (after overrides) in text format, as stored in run.h5.
  std::string effective_text() const;
};

/// Reads `path`, applies `overrides` ("dotted.path=value", any scalar field, checked against the
/// schema like the file), and validates. Throws SceneError listing every problem found.
LoadedScene load_scene(const std::filesystem::path& path,
                       const std::vector<std::string>& overrides = {});

/// Same, from text already in memory (`name` is used in diagnostics).
LoadedScene parse_scene(const std::string& text, const std::string& name,
                        const std::vector<std::string>& overrides = {});

/// What parse_scene does, for any message type: parse `text` into `message`, apply `overrides`,
/// validate against the field options. Lets tests exercise schema features Scene does not use yet.
void parse_message(const std::string& text, const std::string& name,
                   const std::vector<std::string>& overrides, google::protobuf::Message& message);

}  // namespace rockcut::scene
