// The progress a person sees during a long run: plain lines when the output is not a terminal,
// throttled, always a final line, and a readable time left.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "progress.hpp"

namespace dentsph {
namespace {

std::string read_all(std::FILE* f) {
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += char(c);
  return s;
}

TEST(Progress, PlainLinesThrottledWithAFinalLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  cli::ProgressReporter report(f);  // a file is not a terminal
  for (std::uint64_t k = 1; k <= 100; ++k) report({k, 100, 0.001 * k, 0.1 * k, 0.1 * (100 - k)});
  const std::string out = read_all(f);
  std::fclose(f);
  int lines = 0;
  for (char c : out) lines += c == '\n';
  EXPECT_EQ(lines, 3) << out;  // at 0.1 s, 5.1 s (every 5 s of wall time) and the last step
  EXPECT_NE(out.find("progress 100.0%  step 100/100"), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos) << "no terminal control in a log";
}

TEST(Progress, TimeLeftReadsAsAClock) {
  EXPECT_EQ(cli::ProgressReporter::clock(0), "0:00");
  EXPECT_EQ(cli::ProgressReporter::clock(65), "1:05");
  EXPECT_EQ(cli::ProgressReporter::clock(3725), "1:02:05");
}

}  // namespace
}  // namespace dentsph
