// A module's scalar names become run.h5 dataset names and summary.json keys: a name such as
// "../../evil" (or a thousand and one of them) is the module's fault, named as such (exit 3),
// not an output failure (exit 5).
#include <gtest/gtest.h>

#include "rockcut/wire.pb.h"
#include "run/reply_checks.hpp"

namespace rockcut::coupler {
namespace {

TEST(ReplyChecks, ScalarNamesAreLettersDigitsAndUnderscores) {
  wire::StepReport report;
  (*report.mutable_scalars())["tool_force_x_n_per_m"] = 1.0;
  (*report.mutable_scalars())["p1"] = 2.0;
  EXPECT_NO_THROW(check_scalar_names("dem_module", report.scalars()));
  for (const char* bad : {"../../evil", "", "a b", "x/y", "\x01"}) {
    wire::StepReport r = report;
    (*r.mutable_scalars())[bad] = 0.0;
    try {
      check_scalar_names("dem_module", r.scalars());
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const wire::ModuleFailure& e) {
      EXPECT_NE(std::string(e.what()).find("dem_module"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("scalar named"), std::string::npos) << e.what();
    }
  }
  wire::StepReport many;
  for (std::size_t k = 0; k <= kMaxReplyScalars; ++k) {
    std::string name = std::to_string(k);
    name.insert(0, 1, 's');
    (*many.mutable_scalars())[name] = 0.0;
  }
  EXPECT_THROW(check_scalar_names("fluid_module", many.scalars()), wire::ModuleFailure);
  (*report.mutable_scalars())[std::string(65, 'a')] = 0.0;
  EXPECT_THROW(check_scalar_names("dem_module", report.scalars()), wire::ModuleFailure);
}

}  // namespace
}  // namespace rockcut::coupler
