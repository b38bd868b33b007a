// Text-format parsing that reports every problem with its position and a hint.
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <string>
#include <vector>

#include "scene/scene_loader.hpp"

namespace rockcut::scene {

struct TextParse {
  std::vector<Diagnostic> errors;
  /// False when a syntax error stopped the parser: the message is then partial and not worth
  /// validating. Unknown fields do not stop it (they are skipped and reported).
  bool complete = false;
};

/// Parses `text` into `message`, recording where each field was written in `tree`.
TextParse parse_text(const std::string& text, const std::string& name,
                     google::protobuf::Message& message,
                     google::protobuf::TextFormat::ParseInfoTree& tree);

}  // namespace rockcut::scene
