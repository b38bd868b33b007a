// The proto comment of each schema field, for messages such as "missing required field".
// Generated descriptors carry no comments, so scene_reference writes them into field_docs.cpp
// (--field-docs) and a test keeps that file current.
#pragma once

#include <string_view>

namespace rockcut::scene {

/// The leading comment of a field on one line, by full name ("rockcut.Time.end_time_s");
/// "" when the field has none or is not in the scene schema.
std::string_view field_doc(std::string_view full_name);

}  // namespace rockcut::scene
