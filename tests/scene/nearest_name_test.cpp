// The edit distance behind "did you mean".
#include <gtest/gtest.h>

#include "scene/nearest_name.hpp"

namespace {

using rockcut::scene::edit_distance;
using rockcut::scene::name_hint;
using rockcut::scene::nearest_name;

TEST(NearestName, EditDistance) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("model", "modle"), 1u);  // a swap of neighbours is one edit
  EXPECT_EQ(edit_distance("Dt_S", "dt_s"), 0u);    // case does not count
}

TEST(NearestName, OnlyCloseNamesAreSuggested) {
  const std::vector<std::string> names{"end_time_s", "dt_s", "dt_safety"};
  EXPECT_EQ(nearest_name("end_tme", names), "end_time_s");
  EXPECT_EQ(nearest_name("dt", names), "dt_s");
  EXPECT_EQ(nearest_name("frobnicate", names), "");
  EXPECT_EQ(name_hint("dt_safty", names), " (did you mean \"dt_safety\"?)");
  EXPECT_EQ(name_hint("frobnicate", names), "; valid names: end_time_s, dt_s, dt_safety");
}

}  // namespace
