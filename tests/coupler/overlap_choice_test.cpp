// The coupler's choice of whether the DEM's forces overlap the fluid's step (coupling.overlap).
#include <gtest/gtest.h>

#include "run/overlap_choice.hpp"

namespace rockcut::coupler {
namespace {

TEST(OverlapChoice, AutoOverlapsOnlyWhereTheCoresWouldIdle) {
  // 1 + 1 threads on 2 cores: the DEM's forces run on the core the fluid leaves free.
  EXPECT_TRUE(choose_overlap("auto", Transport::ipc, 1, 1, 2).overlap);
  EXPECT_TRUE(choose_overlap("auto", Transport::inproc, 8, 8, 16).overlap);
  // 2 + 2 on 2 cores (the paper-scale scenes on this machine): they would take turns anyway.
  EXPECT_FALSE(choose_overlap("auto", Transport::ipc, 2, 2, 2).overlap);
  EXPECT_FALSE(choose_overlap("auto", Transport::inproc, 2, 1, 2).overlap);
  EXPECT_FALSE(choose_overlap("auto", Transport::ipc, 1, 1, 1).overlap);
  // From 16 cores the serial parts of each step cost more than time-sharing: 16 + 16 on 16 cores
  // overlapping took 0.79 of the wall of taking turns (docs/performance.md, "Overlap").
  EXPECT_TRUE(choose_overlap("auto", Transport::ipc, 16, 16, 16).overlap);
  EXPECT_TRUE(choose_overlap("auto", Transport::inproc, 32, 32, 16).overlap);
  EXPECT_FALSE(choose_overlap("auto", Transport::ipc, 8, 8, 8).overlap);
  // Over tcp the modules may have machines of their own: the local cores say nothing.
  EXPECT_TRUE(choose_overlap("auto", Transport::tcp, 2, 2, 2).overlap);
}

TEST(OverlapChoice, ExplicitSettingWinsAndTheReportSaysWhy) {
  const OverlapChoice on = choose_overlap("on", Transport::ipc, 2, 2, 2);
  EXPECT_TRUE(on.overlap);
  EXPECT_NE(on.report.find("coupling.overlap \"on\""), std::string::npos) << on.report;
  const OverlapChoice off = choose_overlap("off", Transport::tcp, 1, 1, 16);
  EXPECT_FALSE(off.overlap);
  EXPECT_NE(off.report.find("take turns"), std::string::npos) << off.report;
  const OverlapChoice a = choose_overlap("auto", Transport::ipc, 2, 2, 2);
  EXPECT_NE(a.report.find("dem.threads 2 + fluid.threads 2 on 2 cores)"), std::string::npos)
      << a.report;
  const OverlapChoice many = choose_overlap("auto", Transport::ipc, 16, 16, 16);
  EXPECT_NE(many.report.find("from 16 cores"), std::string::npos) << many.report;
}

TEST(OverlapChoice, UsableCoresIsAtLeastOne) { EXPECT_GE(usable_cores(), 1u); }

}  // namespace
}  // namespace rockcut::coupler
