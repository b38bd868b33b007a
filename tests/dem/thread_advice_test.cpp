// The note that warns when a scene gives the DEM more threads than its particles pay for.
#include <gtest/gtest.h>

#include "core/thread_advice.hpp"

namespace rockcut::dem {
namespace {

TEST(ThreadAdvice, SilentForOneThreadAndForEnoughParticles) {
  EXPECT_EQ(thread_advice(647, 1), "");
  EXPECT_EQ(thread_advice(2 * kMinParticlesPerThread, 2), "");
  EXPECT_EQ(thread_advice(55177, 2), "");  // the paper-scale block
}

TEST(ThreadAdvice, NamesTheFieldTheCountsAndAThreadCountThatFits) {
  // The reduced cutting scene on 2 threads: 52 s against 9.7 s on 1 (thread_advice.hpp).
  const std::string note = thread_advice(647, 2);
  EXPECT_NE(note.find("dem.threads 2 for 647 particles (323 per thread)"), std::string::npos) << note;
  EXPECT_NE(note.find("dem.threads: 1 is likely faster"), std::string::npos) << note;
  // Just below the threshold with 4 threads: 3 threads keep enough particles each.
  const std::string four = thread_advice(4 * kMinParticlesPerThread - 1, 4);
  EXPECT_NE(four.find("dem.threads: 3 is likely faster"), std::string::npos) << four;
}

}  // namespace
}  // namespace rockcut::dem
