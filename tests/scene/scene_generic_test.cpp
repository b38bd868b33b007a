// Schema features Scene does not use yet (oneofs with two members, enums, bools, repeated numbers,
// required lists), on a message type built at run time: the loader must handle any schema.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/text_format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>

#include "rockcut/options.pb.h"
#include "scene/scene_loader.hpp"

namespace {

namespace pb = google::protobuf;
using rockcut::scene::parse_message;
using rockcut::scene::SceneError;
using testing::AllOf;
using testing::HasSubstr;
using testing::StartsWith;

constexpr const char* kSchema = R"(
name: "generic_test.proto" package: "generic" syntax: "proto2"
dependency: "rockcut/options.proto"
message_type {
  name: "Thing"
  field { name: "flag" number: 1 label: LABEL_OPTIONAL type: TYPE_BOOL }
  field { name: "color" number: 2 label: LABEL_OPTIONAL type: TYPE_ENUM type_name: ".generic.Color" }
  field { name: "circle" number: 3 label: LABEL_OPTIONAL type: TYPE_DOUBLE oneof_index: 0 }
  field { name: "square" number: 4 label: LABEL_OPTIONAL type: TYPE_DOUBLE oneof_index: 0 }
  field { name: "sizes" number: 5 label: LABEL_REPEATED type: TYPE_INT32 options { [rockcut.min]: 0 } }
  field { name: "tags" number: 6 label: LABEL_REPEATED type: TYPE_STRING options { [rockcut.required]: true } }
  oneof_decl { name: "shape" }
}
enum_type { name: "Color" value { name: "RED" number: 0 } value { name: "GREEN" number: 1 } }
)";

class GenericSchema : public testing::Test {
 protected:
  void SetUp() override {
    pb::FileDescriptorProto file;
    ASSERT_TRUE(pb::TextFormat::ParseFromString(kSchema, &file));
    ASSERT_NE(pool_.BuildFile(file), nullptr);
    thing_.reset(factory_.GetPrototype(pool_.FindMessageTypeByName("generic.Thing"))->New());
  }

  // Loads `text`; returns what() of the error, or "" when it loads.
  std::string errors(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
      parse_message(text, "thing", overrides, *thing_);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  }

  pb::DescriptorPool pool_{pb::DescriptorPool::generated_pool()};  // finds rockcut/options.proto
  pb::DynamicMessageFactory factory_{&pool_};
  std::unique_ptr<pb::Message> thing_;
};

TEST_F(GenericSchema, TwoMembersOfAOneof) {
  EXPECT_EQ(errors("tags: \"a\"\ncircle: 1\nsquare: 2\n"),
            "thing:3:1: Field \"square\" is specified along with field \"circle\", another member of "
            "oneof \"shape\".");
}

TEST_F(GenericSchema, UnknownEnumValueSuggestsNearest) {
  EXPECT_EQ(errors("tags: \"a\"\ncolor: GREN\n"),
            "thing:2:8: Unknown enumeration value of \"GREN\" for field \"color\" (did you mean \"GREEN\"?)");
}

TEST_F(GenericSchema, RequiredListMustNotBeEmpty) {
  EXPECT_EQ(errors("flag: true\n"), "thing:1:1: missing required field \"tags\"");
}

TEST_F(GenericSchema, EachValueOfARepeatedNumberIsChecked) {
  EXPECT_EQ(errors("tags: \"a\"\nsizes: 1\nsizes: -2\n"),
            "thing:3:1: sizes[1] = -2 is out of range: must be >= 0");
  // A list is located once for all its values.
  EXPECT_EQ(errors("tags: \"a\"\nsizes: [1, -2]\n"), "thing:2:1: sizes[1] = -2 is out of range: must be >= 0");
}

TEST_F(GenericSchema, BoolAndEnumOverrides) {
  ASSERT_EQ(errors("tags: \"a\"", {"flag=1", "color=GREEN"}), "");
  const pb::Reflection& r = *thing_->GetReflection();
  const pb::Descriptor& type = *thing_->GetDescriptor();
  EXPECT_TRUE(r.GetBool(*thing_, type.FindFieldByName("flag")));
  EXPECT_EQ(r.GetEnum(*thing_, type.FindFieldByName("color"))->name(), "GREEN");
  ASSERT_EQ(errors("tags: \"a\"", {"flag=false"}), "");
  EXPECT_FALSE(r.GetBool(*thing_, type.FindFieldByName("flag")));

  EXPECT_EQ(errors("tags: \"a\"", {"flag=yes"}),
            "--set:1:6: flag: \"yes\" is not a valid bool; use true, false, 1 or 0");
  EXPECT_THAT(errors("tags: \"a\"", {"color=GREN"}),
              AllOf(StartsWith("--set:1:7: color: \"GREN\" is not a value of generic.Color; choose one "
                               "of: RED, GREEN"),
                    HasSubstr("(did you mean \"GREEN\"?)")));
}

}  // namespace
