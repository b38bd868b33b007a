// docs/scene_reference.md and scene/field_docs.cpp are what scene_reference prints now.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;

constexpr const char* kRegenerate =
    "the schema (proto/rockcut/*.proto) changed; regenerate from the source folder with\n"
    "  build/bin/scene_reference -o docs/scene_reference.md --field-docs scene/field_docs.cpp";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SceneReference, IsCurrent) {
  const fs::path program = fs::path(ROCKCUT_BIN_DIR) / "scene_reference";
  ASSERT_TRUE(fs::exists(program)) << program << " is missing: build the scene_reference target";
  const fs::path dir = fs::path(ROCKCUT_TEST_TMP) / "scene";
  fs::create_directories(dir);
  const fs::path docs_cpp = dir / "field_docs.cpp";

  const std::string command = program.string() + " --field-docs " + docs_cpp.string();
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string markdown;
  char buffer[4096];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) markdown.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << command << " failed";

  const fs::path source = ROCKCUT_SOURCE_DIR;
  EXPECT_TRUE(markdown == read(source / "docs/scene_reference.md"))
      << "docs/scene_reference.md is out of date: " << kRegenerate;
  EXPECT_TRUE(read(docs_cpp) == read(source / "scene/field_docs.cpp"))
      << "scene/field_docs.cpp is out of date: " << kRegenerate;
}

}  // namespace
